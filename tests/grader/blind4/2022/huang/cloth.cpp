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
  positionBuffer.load(0, 4 * particlesPerEdge * particlesPerEdge * sizeof(GLfloat), _particles.getPositionData());
  const ElementArrayBuffer* indexBuffer = nullptr;
  GLenum primitive = GL_LINES;
  switch (type) {
    case DrawType::PARTICLE:
      glDrawArrays(GL_POINTS, 0, particlesPerEdge * particlesPerEdge);
      [[fallthrough]];
    case DrawType::FULL:
      indexBuffer = &ebo;
      primitive = GL_TRIANGLES;
      break;
    case DrawType::STRUCTURAL: indexBuffer = &structuralSpring; break;
    case DrawType::SHEAR: indexBuffer = &shearSpring; break;
    case DrawType::BEND: indexBuffer = &bendSpring; break;
  }
  if (type != DrawType::PARTICLE) {
    indexBuffer->bind();
    glDrawElements(primitive, static_cast<GLsizei>(indexBuffer->size() / sizeof(GLuint)), GL_UNSIGNED_INT, nullptr);
  }
  glBindVertexArray(0);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
}

void Cloth::initializeVertex() {
  int current = 0;
  float wStep = 2.0f * clothWidth / (particlesPerEdge - 1);
  float hStep = 2.0f * clothHeight / (particlesPerEdge - 1);
  for (int i = 0; i < particlesPerEdge; ++i) {
    for (int j = 0; j < particlesPerEdge; ++j) {
      _particles.position(current++) = Eigen::Vector4f(-clothWidth + j * wStep, 0, -clothHeight + i * hStep, 1);
    }
  }
  // Four corners are fixed.
  _particles.mass(0) = 0.0f;
  _particles.mass(particlesPerEdge - 1) = 0.0f;
  _particles.mass(particlesPerEdge * (particlesPerEdge - 1)) = 0.0f;
  _particles.mass(particlesPerEdge * particlesPerEdge - 1) = 0.0f;

  std::vector<GLuint> indices;
  indices.reserve((particlesPerEdge - 1) * (particlesPerEdge - 1) * 6);
  for (int i = 0; i < particlesPerEdge - 1; ++i) {
    for (int j = 0; j < particlesPerEdge - 1; ++j) {
      int topLeft = i * particlesPerEdge + j;
      indices.emplace_back(topLeft);
      indices.emplace_back(topLeft + particlesPerEdge);
      indices.emplace_back(topLeft + 1);
      indices.emplace_back(topLeft + 1);
      indices.emplace_back(topLeft + particlesPerEdge);
      indices.emplace_back(topLeft + particlesPerEdge + 1);
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
  //   1. Compute the rest length of each type of spring.
  //   2. Iterate over the particles and push Spring objects into `_springs`.
  // Note:
  //   1. The particles are stored row major:
  //       0   1   2   3 ...  24
  //      25  26  27  28 ...  49
  //      50  51  52  53 ...  74
  //     ...
  //     600 601 602 603 ... 624
  //   2. Each particle only connects to its own right / down neighbours, so no spring is added twice.
  // Example: the horizontal structural springs.
  float structrualLength = (_particles.position(0) - _particles.position(1)).norm();
  for (int i = 0; i < particlesPerEdge; ++i) {
    for (int j = 0; j < particlesPerEdge - 1; ++j) {
      int index = i * particlesPerEdge + j;
      _springs.emplace_back(index, index + 1, structrualLength, Spring::Type::STRUCTURAL);
    }
  }
  // Write code here!
  float shearLength = (_particles.position(0) - _particles.position(particlesPerEdge + 1)).norm();
  float bendLength = structrualLength * 2.0f;  // bend 跨兩格 = 兩倍長
  // vertical structural
  for (int i = 0; i < particlesPerEdge - 1; ++i) {
    for (int j = 0; j < particlesPerEdge; ++j) {
      int index = i * particlesPerEdge + j;
      _springs.emplace_back(index, index + particlesPerEdge, structrualLength, Spring::Type::STRUCTURAL);
    }
  }
  // shear
  for (int i = 0; i < particlesPerEdge - 1; ++i) {
    for (int j = 0; j < particlesPerEdge; ++j) {
      int index = i * particlesPerEdge + j;
      if (j < particlesPerEdge - 1) _springs.emplace_back(index, index + particlesPerEdge + 1, shearLength, Spring::Type::SHEAR);
      if (j > 0) _springs.emplace_back(index, index + particlesPerEdge - 1, shearLength, Spring::Type::SHEAR);
    }
  }
  // bend
  for (int i = 0; i < particlesPerEdge; ++i) {
    for (int j = 0; j < particlesPerEdge; ++j) {
      int index = i * particlesPerEdge + j;
      if (j < particlesPerEdge - 2) _springs.emplace_back(index, index + 2, bendLength, Spring::Type::BEND);
      if (i < particlesPerEdge - 2) _springs.emplace_back(index, index + 2 * particlesPerEdge, bendLength, Spring::Type::BEND);
    }
  }
  // printf("%zu\n", _springs.size());

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
  // TODO: Compute the spring force and the damper force of every spring.
  //   1. Read the start / end particle index of the spring.
  //   2. Use the positions for the spring force and the velocities for the damper force.
  //   3. Modify the particles' acceleration: a = F / m.
  // Note:
  //   1. Use `_particles.inverseMass(i)` to deal with m = 0 (fixed particles).
  //   2. Useful functions: norm(), normalize() (in place) vs normalized() (returns a copy), dot().
  //   3. springCoef and damperCoef are in configs.h.
  for (const auto& spring : _springs) {
    // Write code here!
    int a = spring.startParticleIndex();
    int b = spring.endParticleIndex();
    Eigen::Vector4f d = _particles.position(a) - _particles.position(b);
    float len = d.norm();
    d.normalize();
    float ks = springCoef * (len - spring.length());
    float kd = damperCoef * (_particles.velocity(a) - _particles.velocity(b)).dot(d);
    Eigen::Vector4f f = d * (kd + ks);
    _particles.acceleration(a) -= f * _particles.inverseMass(a);
    _particles.acceleration(b) += f * _particles.inverseMass(b);
  }
}

void Cloth::collide(Shape* shape) { shape->collide(this); }
void Cloth::collide(Spheres* sphere) { sphere->collide(this); }

void Cloth::computeNormal() {
  // Per-vertex normals for shading: the sum of the normals of the triangles around a vertex.
  static Eigen::Matrix<float, 4, particlesPerEdge * particlesPerEdge> normals;
  normals.setZero();
  for (int i = 0; i < particlesPerEdge - 1; ++i) {
    for (int j = 0; j < particlesPerEdge - 1; ++j) {
      int topLeft = i * particlesPerEdge + j;
      int topRight = topLeft + 1;
      int bottomLeft = topLeft + particlesPerEdge;
      int bottomRight = bottomLeft + 1;
      Eigen::Vector4f down = _particles.position(bottomLeft) - _particles.position(topLeft);
      Eigen::Vector4f right = _particles.position(topRight) - _particles.position(topLeft);
      Eigen::Vector4f normal = down.cross3(right);
      normals.col(topLeft) += normal;
      normals.col(topRight) += normal;
      normals.col(bottomLeft) += normal;
      Eigen::Vector4f up = _particles.position(topRight) - _particles.position(bottomRight);
      Eigen::Vector4f left = _particles.position(bottomLeft) - _particles.position(bottomRight);
      normal = up.cross3(left);
      normals.col(topRight) += normal;
      normals.col(bottomLeft) += normal;
      normals.col(bottomRight) += normal;
    }
  }
  normals.colwise().normalize();
  normalBuffer.load(0, particlesPerEdge * particlesPerEdge * sizeof(float) * 4, normals.data());
}
