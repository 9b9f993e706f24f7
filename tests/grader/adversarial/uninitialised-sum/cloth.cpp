// adversarial case uninitialised-sum (tests/grader/adversarial/make_suite.py)
#include "cloth.h"

#include <Eigen/Geometry>

#include "configs.h"
#include "sphere.h"

Cloth::Cloth() : Shape(particlesPerEdge * particlesPerEdge, particleMass) {
  initializeVertex();
  initializeSpring();
}

void Cloth::draw(DrawType type) const {
  vao.bind();
  positionBuffer.load(0, 4 * particlesPerEdge * particlesPerEdge * sizeof(GLfloat),
                      _particles.getPositionData());
  const ElementArrayBuffer* currentEBO = nullptr;
  switch (type) {
    case DrawType::PARTICLE:
      [[fallthrough]];
    case DrawType::FULL:
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
  GLsizei indexCount = static_cast<GLsizei>(currentEBO->size() / sizeof(GLuint));
  if (type == DrawType::PARTICLE) {
    glDrawArrays(GL_POINTS, 0, particlesPerEdge * particlesPerEdge);
  } else if (type == DrawType::FULL) {
    glDrawElements(GL_TRIANGLES, indexCount, GL_UNSIGNED_INT, nullptr);
  } else {
    glDrawElements(GL_LINES, indexCount, GL_UNSIGNED_INT, nullptr);
  }
  glBindVertexArray(0);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
}

void Cloth::initializeVertex() {
  // Cloth and sphere are both rendered in world coordinates, so position is the same as vertex.
  int current = 0;
  float wStep = 2.0f * clothWidth / (particlesPerEdge - 1);
  float hStep = 2.0f * clothHeight / (particlesPerEdge - 1);
  for (int i = 0; i < particlesPerEdge; ++i) {
    for (int j = 0; j < particlesPerEdge; ++j) {
      _particles.position(current++) = Eigen::Vector4f(-clothWidth + j * wStep, 0, -clothHeight + i * hStep, 1);
    }
  }
  // Four corners are fixed: infinite mass.
  _particles.mass(0) = 0.0f;
  _particles.mass(particlesPerEdge - 1) = 0.0f;
  _particles.mass(particlesPerEdge * (particlesPerEdge - 1)) = 0.0f;
  _particles.mass(particlesPerEdge * particlesPerEdge - 1) = 0.0f;

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
  int vboSize = particlesPerEdge * particlesPerEdge * sizeof(GLfloat);
  positionBuffer.allocate_load(vboSize * 4, _particles.getPositionData());
  normalBuffer.allocate(particlesPerEdge * particlesPerEdge * sizeof(float) * 4);
  ebo.allocate_load(indices.size() * sizeof(GLuint), indices.data());

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
  // 1. Compute spring length per type.
  // 2. Iterate the particles. Push spring objects into `_springs` vector
  // Note:
  //   1. The particles index:
  //   ===============================
  //   0      1      2      3 ...   particlesPerEdge - 1
  //   particlesPerEdge      ...
  //   ...                   ...    particlesPerEdge * particlesPerEdge - 1
  //   ===============================
  // Here is a simple example which connects the horizontal structural springs.
  float structrualLength = (_particles.position(0) - _particles.position(1)).norm();
  for (int i = 0; i < particlesPerEdge; ++i) {
    for (int j = 0; j < particlesPerEdge - 1; ++j) {
      int index = i * particlesPerEdge + j;
      _springs.emplace_back(index, index + 1, structrualLength, Spring::Type::STRUCTURAL);
    }
  }
  // Write code here!
  // Vertical structural springs reuse the horizontal rest length.
  for (int i = 0; i < particlesPerEdge - 1; ++i) {
    for (int j = 0; j < particlesPerEdge; ++j) {
      int index = i * particlesPerEdge + j;
      _springs.emplace_back(index, index + particlesPerEdge, structrualLength, Spring::Type::STRUCTURAL);
    }
  }
  // Shear: the down-right diagonal first, then the down-left one, each in its own pass.
  float shearLength = (_particles.position(0) - _particles.position(particlesPerEdge + 1)).norm();
  for (int i = 0; i < particlesPerEdge - 1; ++i) {
    for (int j = 0; j < particlesPerEdge - 1; ++j) {
      int index = i * particlesPerEdge + j;
      _springs.emplace_back(index, index + particlesPerEdge + 1, shearLength, Spring::Type::SHEAR);
    }
  }
  for (int i = 0; i < particlesPerEdge - 1; ++i) {
    for (int j = 1; j < particlesPerEdge; ++j) {
      int index = i * particlesPerEdge + j;
      _springs.emplace_back(index, index + particlesPerEdge - 1, shearLength, Spring::Type::SHEAR);
    }
  }
  // Bend: skip one particle, horizontally then vertically.
  float bendLength = (_particles.position(0) - _particles.position(2)).norm();
  for (int i = 0; i < particlesPerEdge; ++i) {
    for (int j = 0; j < particlesPerEdge - 2; ++j) {
      int index = i * particlesPerEdge + j;
      _springs.emplace_back(index, index + 2, bendLength, Spring::Type::BEND);
    }
  }
  for (int i = 0; i < particlesPerEdge - 2; ++i) {
    for (int j = 0; j < particlesPerEdge; ++j) {
      int index = i * particlesPerEdge + j;
      _springs.emplace_back(index, index + 2 * particlesPerEdge, bendLength, Spring::Type::BEND);
    }
  }

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
    }
  }
  structuralSpring.allocate_load(structrualIndices.size() * sizeof(GLuint), structrualIndices.data());
  shearSpring.allocate_load(shearIndices.size() * sizeof(GLuint), shearIndices.data());
  bendSpring.allocate_load(bendIndices.size() * sizeof(GLuint), bendIndices.data());
}

void Cloth::computeSpringForce() {
  for (const auto& spring : _springs) {
    // TODO: Compute spring force given current particle position and velocity.
    // Note:
    //   1. Use a = F / m to update acceleration, with inverseMass(i) for fixed (m = 0) particles.
    int start = spring.startParticleIndex();
    int end = spring.endParticleIndex();
    Eigen::Vector4f direction = _particles.position(start) - _particles.position(end);
    float length = direction.norm();
    direction.normalize();
    Eigen::Vector4f relativeVelocity = _particles.velocity(start) - _particles.velocity(end);
    // Damper first, then Hooke: the instructor's order of the two terms.
    Eigen::Vector4f force;  // spring + damper
    force += direction * (springCoef * (length - spring.length()));
    force += direction * (damperCoef * relativeVelocity.dot(direction));
    _particles.acceleration(start) -= force * _particles.inverseMass(start);
    _particles.acceleration(end) += force * _particles.inverseMass(end);
  }
}

void Cloth::collide(Shape* shape) { shape->collide(this); }
void Cloth::collide(Spheres* sphere) { sphere->collide(this); }

void Cloth::computeNormal() {
  // Compute normals of each vertex: sum of the face normals around it, then normalize.
  static Eigen::Matrix<float, 4, particlesPerEdge * particlesPerEdge> normals;
  normals.setZero();
  for (int i = 0; i < particlesPerEdge - 1; ++i) {
    int offset = i * particlesPerEdge;
    for (int j = 0; j < particlesPerEdge - 1; ++j) {
      int topLeft = offset + j;
      int topRight = topLeft + 1;
      int bottomLeft = topLeft + particlesPerEdge;
      int bottomRight = bottomLeft + 1;
      Eigen::Vector4f upper = (_particles.position(bottomLeft) - _particles.position(topLeft))
                                  .cross3(_particles.position(topRight) - _particles.position(topLeft));
      Eigen::Vector4f lower = (_particles.position(bottomLeft) - _particles.position(topRight))
                                  .cross3(_particles.position(bottomRight) - _particles.position(topRight));
      normals.col(topLeft) += upper;
      normals.col(topRight) += upper;
      normals.col(bottomLeft) += upper;
      normals.col(topRight) += lower;
      normals.col(bottomLeft) += lower;
      normals.col(bottomRight) += lower;
    }
  }
  normals.colwise().normalize();
  normalBuffer.load(0, particlesPerEdge * particlesPerEdge * sizeof(float) * 4, normals.data());
}
