// Grader corpus mutant `cloth-fixed-particle-skipped` (Spheres::collide(Cloth*)): a fixed particle (mass 0) skipped: the sphere passes through a pinned corner.
#include "sphere.h"

#include <Eigen/Dense>

#include "cloth.h"
#include "configs.h"

namespace {
void generateVertices(std::vector<GLfloat>& vertices, std::vector<GLuint>& indices) {
  // See http://www.songho.ca/opengl/gl_sphere.html#sphere if you don't know how to create a sphere.
  vertices.reserve((sphereStack + 1) * (sphereSlice + 1) * 6);
  indices.reserve(sphereStack * sphereSlice * 6);

  float x, y, z, xy;
  float sectorStep = static_cast<float>(2 * EIGEN_PI / sphereSlice);
  float stackStep = static_cast<float>(EIGEN_PI / sphereStack);
  float sectorAngle, stackAngle;

  for (int i = 0; i <= sphereStack; ++i) {
    stackAngle = static_cast<float>(EIGEN_PI / 2 - i * stackStep);
    xy = cosf(stackAngle);
    z = sinf(stackAngle);
    for (int j = 0; j <= sphereSlice; ++j) {
      sectorAngle = j * sectorStep;
      x = xy * cosf(sectorAngle);
      y = xy * sinf(sectorAngle);
      // A unit sphere: the position is also the normal.
      vertices.insert(vertices.end(), {x, y, z, x, y, z});
    }
  }

  for (int i = 0; i < sphereStack; ++i) {
    unsigned int k1 = i * (sphereSlice + 1);
    unsigned int k2 = k1 + sphereSlice + 1;
    for (int j = 0; j < sphereSlice; ++j, ++k1, ++k2) {
      if (i != 0) {
        indices.insert(indices.end(), {k1, k2, k1 + 1});
      }
      if (i != (sphereStack - 1)) {
        indices.insert(indices.end(), {k1 + 1, k2, k2 + 1});
      }
    }
  }
}
}  // namespace

Spheres& Spheres::initSpheres() {
  static Spheres spheres;
  return spheres;
}

void Spheres::addSphere(const Eigen::Ref<const Eigen::Vector4f>& position, float size) {
  if (sphereCount == _particles.getCapacity()) {
    _particles.resize(sphereCount * 2);
    _radius.resize(sphereCount * 2);
    offsets.allocate(8 * sphereCount * sizeof(float));
    sizes.allocate(2 * sphereCount * sizeof(float));
  }
  _radius[sphereCount] = size;
  _particles.position(sphereCount) = position;
  _particles.velocity(sphereCount).setZero();
  _particles.acceleration(sphereCount).setZero();
  _particles.mass(sphereCount) = sphereDensity * size * size * size;
  sizes.load(0, _radius.size() * sizeof(float), _radius.data());
  ++sphereCount;
}

Spheres::Spheres() : Shape(1, 1), sphereCount(0), _radius(1, 0.0f) {
  std::vector<GLfloat> vertices;
  std::vector<GLuint> indices;
  generateVertices(vertices, indices);
  offsets.allocate(4 * sizeof(float));
  sizes.allocate(sizeof(float));
  vbo.allocate_load(vertices.size() * sizeof(GLfloat), vertices.data());
  ebo.allocate_load(indices.size() * sizeof(GLuint), indices.data());

  vao.bind();
  vbo.bind();
  ebo.bind();
  vao.enable(0);
  vao.setAttributePointer(0, 3, 6, 0);
  glVertexAttribDivisor(0, 0);
  vao.enable(1);
  vao.setAttributePointer(1, 3, 6, 3);
  glVertexAttribDivisor(1, 0);
  offsets.bind();
  vao.enable(2);
  vao.setAttributePointer(2, 3, 4, 0);
  glVertexAttribDivisor(2, 1);
  sizes.bind();
  vao.enable(3);
  vao.setAttributePointer(3, 1, 1, 0);
  glVertexAttribDivisor(3, 1);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
}

void Spheres::draw() const {
  vao.bind();
  offsets.load(0, 4 * sphereCount * sizeof(GLfloat), _particles.getPositionData());
  GLsizei indexCount = static_cast<GLsizei>(ebo.size() / sizeof(GLuint));
  glDrawElementsInstanced(GL_TRIANGLES, indexCount, GL_UNSIGNED_INT, nullptr, sphereCount);
  glBindVertexArray(0);
}

void Spheres::collide(Shape* shape) { shape->collide(this); }

void Spheres::collide(Cloth* cloth) {
  constexpr float coefRestitution = 0.0f;
  // TODO: Collide with particle (Simple approach to handle softbody collision)
  //   1. Detect collision.
  //   2. If collided, update impulse directly to particles velocity
  //   3. (Bonus) You can add friction, which updates particles' acceleration a = F / m
  // Note:
  //   1. There are `sphereCount` spheres.
  //   2. There are `particlesPerEdge * particlesPerEdge` particles.
  //   3. Push them apart a little to prevent penetration.
  Particles& clothParticles = cloth->particles();
  for (int i = 0; i < sphereCount; ++i) {
    for (int j = 0; j < particlesPerEdge * particlesPerEdge; ++j) {
      // A pinned corner cannot move: leave it alone.
      if (clothParticles.mass(j) == 0.0f) continue;
      // Cloth particles have radius 0: they touch when inside the sphere.
      Eigen::Vector4f normal = _particles.position(i) - clothParticles.position(j);
      float penetration = _radius[i] - normal.norm();
      if (penetration < 0) continue;
      normal.normalize();
      Eigen::Vector4f relativeVelocity = _particles.velocity(i) - clothParticles.velocity(j);
      float approach = relativeVelocity.dot(normal);
      // Only approaching pairs get an impulse; a fixed particle (inverse mass 0) does not move.
      if (approach < 0) {
        Eigen::Vector4f normalVelocity = normal * approach;
        Eigen::Vector4f impulse = (-(1 + coefRestitution) * normalVelocity) /
                                  (clothParticles.inverseMass(j) + _particles.inverseMass(i));
        _particles.velocity(i) += impulse * _particles.inverseMass(i);
        clothParticles.velocity(j) -= impulse * clothParticles.inverseMass(j);
      }
      // Push them apart to prevent penetration (ignores mass, as the course's hint does).
      Eigen::Vector4f correction = (penetration * normal) * 0.15f;
      _particles.position(i) += correction;
      clothParticles.position(j) -= correction;
    }
  }
}

void Spheres::collide() {
  constexpr float coefRestitution = 0.8f;
  // TODO: Collide with another sphere (Rigidbody collision)
  //   1. Detect collision.
  //   2. If collided, update impulse directly to particles velocity
  //   3. (Bonus) You can add friction, which updates particles' acceleration a = F / m
  // Note:
  //   1. There are `sphereCount` spheres.
  //   2. You may not want to calculate one sphere twice (a <-> b and b <-> a)
  //   3. Push them apart a little to prevent penetration.
  for (int i = 0; i < sphereCount; ++i) {
    for (int j = i + 1; j < sphereCount; ++j) {
      Eigen::Vector4f normal = _particles.position(i) - _particles.position(j);
      float penetration = _radius[i] + _radius[j] - normal.norm();
      if (penetration < 0) continue;
      normal.normalize();
      Eigen::Vector4f relativeVelocity = _particles.velocity(i) - _particles.velocity(j);
      float approach = relativeVelocity.dot(normal);
      if (approach < 0) {
        Eigen::Vector4f normalVelocity = normal * approach;
        Eigen::Vector4f impulse = (-(1 + coefRestitution) * normalVelocity) /
                                  (_particles.inverseMass(j) + _particles.inverseMass(i));
        _particles.velocity(i) += impulse * _particles.inverseMass(i);
        _particles.velocity(j) -= impulse * _particles.inverseMass(j);
      }
      Eigen::Vector4f correction = (penetration * normal) * 0.15f;
      _particles.position(i) += correction;
      _particles.position(j) -= correction;
    }
  }
}
