// Our definitions of the course framework's non-stub members and globals, shared by both editions
// (the student files define Cloth::*, Spheres::* and the integrators). Compiled once per edition,
// against that edition's headers, into the probe driver library.
#include <glad/gl.h>

#include <Eigen/LU>

#include "buffer.h"
#include "configs.h"
#include "particles.h"
#include "shape.h"
#include "vertexarray.h"

// No-op GL: the grader never draws.
void glDrawElements(GLenum, GLsizei, GLenum, const void*) {}
void glDrawArrays(GLenum, GLint, GLsizei) {}
void glBindVertexArray(GLuint) {}
void glBindBuffer(GLenum, GLuint) {}
void glVertexAttribDivisor(GLuint, GLuint) {}
void glDrawElementsInstanced(GLenum, GLsizei, GLenum, const void*, GLsizei) {}

Buffer::Buffer() noexcept : _handle(0), _size(0) {}
Buffer::~Buffer() = default;
void Buffer::bind() const noexcept {}
// allocate and allocate_load remember the byte count: the draw code divides size() by it.
void Buffer::allocate(GLsizeiptr size, GLenum) const noexcept { _size = size; }
void Buffer::load(GLintptr, GLsizeiptr, const void*) const noexcept {}
void Buffer::allocate_load(GLsizeiptr size, const void*, GLenum) const noexcept { _size = size; }
void UniformBuffer::bindUniformBlockIndex(GLuint, GLuint, GLuint) const noexcept {}
void UniformBuffer::bindUniformBlockIndex(GLuint) const noexcept {}

VertexArray::VertexArray() : handle(0) {}
VertexArray::~VertexArray() = default;
void VertexArray::enable(int) const {}
void VertexArray::bind() const {}
void VertexArray::setAttributePointer(int, int, int, int) const {}

Particles::Particles(int size, float mass_) noexcept
    : _position(4, size), _velocity(4, size), _acceleration(4, size), _mass(size, mass_) {
  setZero();
}

void Particles::resize(int newSize) {
  // New columns are left uninitialised, as in the course.
  _position.conservativeResize(Eigen::NoChange, newSize);
  _velocity.conservativeResize(Eigen::NoChange, newSize);
  _acceleration.conservativeResize(Eigen::NoChange, newSize);
  _mass.resize(newSize, 0.0f);
}

void Particles::setZero() {
  _position.setZero();
  _velocity.setZero();
  _acceleration.setZero();
}

Shape::Shape(int size, float mass_) noexcept
    : _particles(size, mass_),
      modelMatrix(Eigen::Matrix4f::Identity()),
      normalMatrix(Eigen::Matrix4f::Identity()) {}

void Shape::setModelMatrix(const Eigen::Ref<const Eigen::Matrix4f>& _modelMatrix) {
  modelMatrix = _modelMatrix;
  normalMatrix = modelMatrix.inverse().transpose();
}

void Shape::computeExternalForce() {
  for (size_t i = 0; i < _particles.mass().size(); ++i) {
    const int k = static_cast<int>(i);
    if (_particles.mass(k) == 0.0f) {
      _particles.acceleration(k).setZero();
    } else {
      _particles.acceleration(k) = Eigen::Vector4f(0, -9.8f, 0, 0);
      _particles.acceleration(k) -=
          _particles.velocity(k) * viscousCoef * _particles.inverseMass(k);
    }
  }
}

// Globals with the course's defaults (configs.cpp); springCoef differs by edition.
int windowWidth = 0;
int windowHeight = 0;
int speedMultiplier = 1;
float mouseMoveSpeed = 0.001f;
float keyboardMoveSpeed = 0.1f;
float deltaTime = 1e-4f;
int simulationPerFrame = static_cast<int>(baseSpeed / deltaTime);
#ifdef CLOTHREF_GRADER_EDITION_2024
float springCoef = 20000.0f;
#else
float springCoef = 25000.0f;
#endif
float damperCoef = 750.0f;
float viscousCoef = 3.4e-4f;
Eigen::Vector4f sphereColor(0.28f, 0.65f, 0.8f, 1.0f);
Eigen::Vector4f clothColor(0.88f, 0.17f, 0.17f, 1.0f);
bool isSphereColorChange = false;
#ifndef CLOTHREF_GRADER_EDITION_2024
bool isClothColorChange = false;
#endif
bool isDrawingParticles = false;
#ifdef CLOTHREF_GRADER_EDITION_2024
bool isDrawingStructuralSprings = false;
bool isDrawingShearSprings = false;
bool isDrawingCloth = true;
#else
bool isDrawingStructuralSprings = true;
bool isDrawingShearSprings = true;
bool isDrawingCloth = false;
#endif
bool isDrawingBendSprings = false;
bool isPaused = true;
bool isStateSwitched = false;
int currentIntegrator = 0;
