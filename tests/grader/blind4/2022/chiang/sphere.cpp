#include "sphere.h"

#include <Eigen/Dense>

#include "cloth.h"
#include "configs.h"

namespace {
void generateVertices(std::vector<GLfloat>& vertices, std::vector<GLuint>& indices) {
  // See http://www.songho.ca/opengl/gl_sphere.html#sphere if you don't know how to create a sphere.
  vertices.reserve(6 * (sphereStack + 1) * (sphereSlice + 1));
  indices.reserve(6 * sphereStack * sphereSlice);
  float x, y, z, xy;  // position
  float sectorStep = static_cast<float>(EIGEN_PI * 2 / sphereSlice);
  float stackStep = static_cast<float>(EIGEN_PI / sphereStack);
  for (int i = 0; i <= sphereStack; ++i) {
    float stackAngle = static_cast<float>(EIGEN_PI / 2 - i * stackStep);  // from pi/2 to -pi/2
    xy = cosf(stackAngle);
    z = sinf(stackAngle);
    for (int j = 0; j <= sphereSlice; ++j) {
      float sectorAngle = j * sectorStep;  // from 0 to 2pi
      x = xy * cosf(sectorAngle);
      y = xy * sinf(sectorAngle);
      vertices.insert(vertices.end(), {x, y, z, x, y, z});  // unit sphere: the normal is the position
    }
  }
  for (int i = 0; i < sphereStack; ++i) {
    unsigned int k1 = i * (sphereSlice + 1);
    unsigned int k2 = k1 + sphereSlice + 1;
    for (int j = 0; j < sphereSlice; ++j, ++k1, ++k2) {
      if (i != 0) indices.insert(indices.end(), {k1, k2, k1 + 1});
      if (i != (sphereStack - 1)) indices.insert(indices.end(), {k1 + 1, k2, k2 + 1});
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
  offsets.allocate(4 * sizeof(float));
  sizes.allocate(sizeof(float));
  std::vector<GLfloat> vertices;
  std::vector<GLuint> indices;
  generateVertices(vertices, indices);
  vbo.allocate_load(vertices.size() * sizeof(GLfloat), vertices.data());
  ebo.allocate_load(indices.size() * sizeof(GLuint), indices.data());

  vao.bind();
  vbo.bind();
  ebo.bind();
  // Position
  vao.enable(0);
  vao.setAttributePointer(0, 3, 6, 0);
  glVertexAttribDivisor(0, 0);
  // Normal
  vao.enable(1);
  vao.setAttributePointer(1, 3, 6, 3);
  glVertexAttribDivisor(1, 0);
  // Sphere centers
  offsets.bind();
  vao.enable(2);
  vao.setAttributePointer(2, 3, 4, 0);
  glVertexAttribDivisor(2, 1);
  // Sphere radius
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
  // TODO: Collide with the cloth particles (a simple approach to soft body collision).
  //   1. Detect the collisions.
  //   2. If two bodies collide, apply the impulse directly to their velocities.
  //   3. (Bonus) Add friction, which updates the particles' acceleration a = F / m.
  // Note:
  //   1. There are `sphereCount` spheres.
  //   2. There are particlesPerEdge * particlesPerEdge cloth particles.
  //   3. See the slides if you do not know how to compute the impulse.
  //   4. Hint: push the particles apart a little to prevent penetration, e.g.
  //        _particles.position(i) += penetration * normal * 0.15f;
  //        cloth->particles().position(j) -= penetration * normal * 0.15f;
  // Write code here!
  Particles& cloths = cloth->particles();
  const int total = particlesPerEdge * particlesPerEdge;
  for (int i = 0; i < sphereCount; ++i) {
    for (int j = 0; j < total; ++j) {
      Eigen::Vector4f normal = _particles.position(i) - cloths.position(j);
      float penetration = _radius[i] - normal.norm();
      if (penetration < 0) continue;
      normal.normalize();
      float approach = (_particles.velocity(i) - cloths.velocity(j)).dot(normal);
      if (approach < 0) {
        Eigen::Vector4f impulse = (-(1 + coefRestitution)) * (normal * approach) / (cloths.inverseMass(j) + _particles.inverseMass(i));
        _particles.velocity(i) += impulse * _particles.inverseMass(i);
        cloths.velocity(j) -= impulse * cloths.inverseMass(j);
        // 推開一點避免穿透
        _particles.position(i) += penetration * normal * 0.15f;
        cloths.position(j) -= penetration * normal * 0.15f;
      }
    }
  }
}

void Spheres::collide() {
  constexpr float coefRestitution = 0.8f;
  // TODO: Collide with the other spheres (rigid body collision).
  //   1. Detect the collisions.
  //   2. If two spheres collide, apply the impulse directly to their velocities.
  //   3. (Bonus) Add friction, which updates the spheres' acceleration a = F / m.
  // Note:
  //   1. There are `sphereCount` spheres.
  //   2. Do not process a pair of spheres twice.
  //   3. Hint: push the spheres apart a little to prevent penetration, as in collide(Cloth*).
  // Write code here!
  constexpr float friction = 0.2f;  // bonus
  for (int i = 0; i < sphereCount; ++i) {
    for (int j = i + 1; j < sphereCount; ++j) {
      Eigen::Vector4f normal = _particles.position(i) - _particles.position(j);
      float penetration = (_radius[i] + _radius[j]) - normal.norm();
      if (penetration < 0) continue;
      normal.normalize();
      Eigen::Vector4f relative = _particles.velocity(i) - _particles.velocity(j);
      float approach = relative.dot(normal);
      if (approach < 0) {
        Eigen::Vector4f impulse = (-(1 + coefRestitution)) * (normal * approach) / (_particles.inverseMass(j) + _particles.inverseMass(i));
        _particles.velocity(i) += impulse * _particles.inverseMass(i);
        _particles.velocity(j) -= impulse * _particles.inverseMass(j);
      }
      // 摩擦力：切線方向的相對速度
      Eigen::Vector4f tangent = relative - normal * approach;
      _particles.acceleration(i) -= tangent * friction * _particles.inverseMass(i);
      _particles.acceleration(j) += tangent * friction * _particles.inverseMass(j);
      _particles.position(i) += penetration * normal * 0.15f;
      _particles.position(j) -= penetration * normal * 0.15f;
    }
  }
}
