#include "cloth.h"

#include <Eigen/Geometry>

#include "configs.h"
#include "sphere.h"

namespace {
// index of particle (row, col)
inline int idx(int row, int col) { return row * particlesPerEdge + col; }
}  // namespace

Cloth::Cloth() : Shape(particlesPerEdge * particlesPerEdge, particleMass) {
  initializeVertex();
  initializeSpring();
}

void Cloth::draw(DrawType type) const {
  vao.bind();
  positionBuffer.load(0, 4 * particlesPerEdge * particlesPerEdge * sizeof(GLfloat), _particles.getPositionData());
  const ElementArrayBuffer* currentEBO = nullptr;
  GLenum drawMode = GL_LINES;
  switch (type) {
    case DrawType::FULL:
      drawMode = GL_TRIANGLES;
      [[fallthrough]];
    case DrawType::PARTICLE:
      currentEBO = &ebo;
      break;
    case DrawType::STRUCTURAL:
      currentEBO = &structuralSpring;
      break;
    case DrawType::SHEAR:
      currentEBO = &shearSpring;
      break;
    case DrawType::BEND:
      currentEBO = &bendSpring;
      break;
  }
  currentEBO->bind();
  if (type == DrawType::PARTICLE) {
    glDrawArrays(GL_POINTS, 0, particlesPerEdge * particlesPerEdge);
  } else {
    GLsizei indexCount = static_cast<GLsizei>(currentEBO->size() / sizeof(GLuint));
    glDrawElements(drawMode, indexCount, GL_UNSIGNED_INT, nullptr);
  }
  glBindVertexArray(0);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
}

void Cloth::initializeVertex() {
  // Initialize particles' position
  float wStep = 2.0f * clothWidth / (particlesPerEdge - 1);
  float hStep = 2.0f * clothHeight / (particlesPerEdge - 1);
  int current = 0;
  for (int i = 0; i < particlesPerEdge; ++i) {
    for (int j = 0; j < particlesPerEdge; ++j) {
      _particles.position(current++) = Eigen::Vector4f(-clothWidth + j * wStep, 0, -clothHeight + i * hStep, 1);
    }
  }
  // Four corners are fixed (mass = 0)
  _particles.mass(0) = 0.0f;
  _particles.mass(particlesPerEdge - 1) = 0.0f;
  _particles.mass(particlesPerEdge * (particlesPerEdge - 1)) = 0.0f;
  _particles.mass(particlesPerEdge * particlesPerEdge - 1) = 0.0f;
  // Triangle indices for drawing the cloth surface
  std::vector<GLuint> indices;
  indices.reserve((particlesPerEdge - 1) * (particlesPerEdge - 1) * 6);
  for (int i = 0; i < particlesPerEdge - 1; ++i) {
    int offset = i * particlesPerEdge;
    for (int j = 0; j < particlesPerEdge - 1; ++j) {
      indices.emplace_back(offset + j);
      indices.emplace_back(offset + j + particlesPerEdge);
      indices.emplace_back(offset + j + 1);
      indices.emplace_back(offset + j + 1);
      indices.emplace_back(offset + j + particlesPerEdge);
      indices.emplace_back(offset + j + particlesPerEdge + 1);
    }
  }
  // Setup buffers
  int vboSize = particlesPerEdge * particlesPerEdge * sizeof(GLfloat);
  positionBuffer.allocate_load(vboSize * 4, _particles.getPositionData());
  normalBuffer.allocate(particlesPerEdge * particlesPerEdge * sizeof(float) * 4);
  ebo.allocate_load(indices.size() * sizeof(GLuint), indices.data());
  // Setup vao
  vao.bind();
  positionBuffer.bind();
  vao.enable(0);
  vao.setAttributePointer(0, 4, 4, 0);
  normalBuffer.bind();
  vao.enable(1);
  vao.setAttributePointer(1, 4, 4, 0);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
}

void Cloth::initializeSpring() {
  // TODO: Connect particles with springs.
  //   1. Compute spring length per type.
  //   2. Iterate the particles. Push spring objects into `_springs` vector
  // Note:
  //   1. The particles index is similar to pixel's index in a image.
  //   (0, 0) -> 0, (0, 1) -> 1, ...
  //   (1, 0) -> particlesPerEdge, (1, 1) -> particlesPerEdge + 1, ...
  //   2. See spring.h for the constructor of Spring.
  //   3. Each particle only needs to connect to part of its neighbors, otherwise springs are duplicated.
  // Example of horizontal structrual spring
  float structrualLength = (_particles.position(0) - _particles.position(1)).norm();
  for (int i = 0; i < particlesPerEdge; ++i) {
    for (int j = 0; j < particlesPerEdge - 1; ++j) {
      int index = i * particlesPerEdge + j;
      _springs.emplace_back(index, index + 1, structrualLength, Spring::Type::STRUCTURAL);
    }
  }
  // Write code here!
  const float shearLength = (_particles.position(idx(0, 0)) - _particles.position(idx(1, 1))).norm();
  const float bendLength = (_particles.position(idx(0, 0)) - _particles.position(idx(0, 2))).norm();
  for (int r = 0; r + 1 < particlesPerEdge; ++r)
    for (int c = 0; c < particlesPerEdge; ++c)
      _springs.emplace_back(idx(r, c), idx(r + 1, c), structrualLength, Spring::Type::STRUCTURAL);
  for (int r = 0; r + 1 < particlesPerEdge; ++r)
    for (int c = 0; c + 1 < particlesPerEdge; ++c)
      _springs.emplace_back(idx(r, c), idx(r + 1, c + 1), shearLength, Spring::Type::SHEAR);
  for (int r = 0; r + 1 < particlesPerEdge; ++r)
    for (int c = 1; c < particlesPerEdge; ++c)
      _springs.emplace_back(idx(r, c), idx(r + 1, c - 1), shearLength, Spring::Type::SHEAR);
  for (int r = 0; r < particlesPerEdge; ++r)
    for (int c = 0; c + 2 < particlesPerEdge; ++c)
      _springs.emplace_back(idx(r, c), idx(r, c + 2), bendLength, Spring::Type::BEND);
  for (int r = 0; r + 2 < particlesPerEdge; ++r)
    for (int c = 0; c < particlesPerEdge; ++c)
      _springs.emplace_back(idx(r, c), idx(r + 2, c), bendLength, Spring::Type::BEND);

  // Visualize springs
  std::vector<GLuint> structrualIndices, shearIndices, bendIndices;
  for (const auto& spring : _springs) {
    switch (spring.type()) {
      case Spring::Type::STRUCTURAL:
        structrualIndices.emplace_back(spring.startParticleIndex());
        structrualIndices.emplace_back(spring.endParticleIndex());
        break;
      case Spring::Type::SHEAR:
        shearIndices.emplace_back(spring.startParticleIndex());
        shearIndices.emplace_back(spring.endParticleIndex());
        break;
      case Spring::Type::BEND:
        bendIndices.emplace_back(spring.startParticleIndex());
        bendIndices.emplace_back(spring.endParticleIndex());
        break;
      default:
        break;
    }
  }
  structuralSpring.allocate_load(structrualIndices.size() * sizeof(GLuint), structrualIndices.data());
  shearSpring.allocate_load(shearIndices.size() * sizeof(GLuint), shearIndices.data());
  bendSpring.allocate_load(bendIndices.size() * sizeof(GLuint), bendIndices.data());
}

void Cloth::computeSpringForce() {
  // TODO: Compute spring force and damper force for each spring.
  //   1. Read the start and end index of the spring.
  //   2. Use the particles' position and velocity to compute the force.
  //   3. Modify the particles' acceleration a = F / m;
  // Note:
  //   1. Use _particles.inverseMass(index) to deal with m = 0 (fixed particles).
  //   2. Some useful functions: norm(), normalize(), normalized(), dot()
  //   3. normalize() modifies the vector itself, normalized() returns a new vector.
  for (const auto& spring : _springs) {
    const int a = spring.startParticleIndex();
    const int b = spring.endParticleIndex();
    Eigen::Vector4f d = _particles.position(a) - _particles.position(b);
    const float len = d.norm();
    d.normalize();
    const float hooke = springCoef * (len - spring.length());
    const float damp = damperCoef * (_particles.velocity(a) - _particles.velocity(b)).dot(d);
    Eigen::Vector4f force = d * (damp + hooke);
    // set acceleration to apply the force (a = F / m)
    _particles.acceleration(a) = -force * _particles.inverseMass(a);
    _particles.acceleration(b) = force * _particles.inverseMass(b);
  }
}

void Cloth::collide(Shape* shape) { shape->collide(this); }
void Cloth::collide(Spheres* sphere) { sphere->collide(this); }

void Cloth::computeNormal() {
  // Compute normals (for lighting), each vertex sums the normals of the triangles around it.
  static Eigen::Matrix<float, 4, particlesPerEdge * particlesPerEdge> normals;
  normals.setZero();
  for (int i = 0; i < particlesPerEdge - 1; ++i) {
    for (int j = 0; j < particlesPerEdge - 1; ++j) {
      int topLeft = i * particlesPerEdge + j;
      int topRight = topLeft + 1;
      int bottomLeft = topLeft + particlesPerEdge;
      int bottomRight = bottomLeft + 1;
      Eigen::Vector4f edge1 = _particles.position(bottomLeft) - _particles.position(topLeft);
      Eigen::Vector4f edge2 = _particles.position(topRight) - _particles.position(topLeft);
      Eigen::Vector4f faceNormal = edge1.cross3(edge2);
      normals.col(topLeft) += faceNormal;
      normals.col(bottomLeft) += faceNormal;
      normals.col(topRight) += faceNormal;
      edge1 = _particles.position(topRight) - _particles.position(bottomRight);
      edge2 = _particles.position(bottomLeft) - _particles.position(bottomRight);
      faceNormal = edge1.cross3(edge2);
      normals.col(topRight) += faceNormal;
      normals.col(bottomLeft) += faceNormal;
      normals.col(bottomRight) += faceNormal;
    }
  }
  normals.colwise().normalize();
  normalBuffer.load(0, particlesPerEdge * particlesPerEdge * sizeof(float) * 4, normals.data());
}
