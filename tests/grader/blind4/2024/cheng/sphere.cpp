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
  constexpr float coefRestitution = 1.0f;
  // TODO: Collide with the cloth particles (a simple approach to soft body collision).
  //   1. Detect the collisions.
  //   2. If two bodies collide, apply the impulse directly to their velocities.
  // Note:
  //   1. There are `sphereCount` spheres (sphereCount is 1 in the default scene).
  //   2. There are particlesPerEdge * particlesPerEdge cloth particles.
  //   3. See the slides if you do not know how to compute the impulse.
  // only one sphere in the scene
  const int s = 0;
  Particles& cp = cloth->particles();
  for (int j = 0; j < particlesPerEdge * particlesPerEdge; ++j)
  {
    Eigen::Vector4f normal = _particles.position(s) - cp.position(j);
    const float penetration = _radius[s] - normal.norm();
    if (penetration < 0) continue;
    normal.normalize();
    const float vn = (_particles.velocity(s) - cp.velocity(j)).dot(normal);
    if (vn < 0)
    {
      const Eigen::Vector4f J = (-(1 + coefRestitution)) * (normal * vn) / (cp.inverseMass(j) + _particles.inverseMass(s));
      _particles.velocity(s) += J * _particles.inverseMass(s);
      cp.velocity(j) -= J * cp.inverseMass(j);
    }
    _particles.position(s) += penetration * normal * 0.15f;
    cp.position(j) -= penetration * normal * 0.15f;
  }
}

void Spheres::setVelocity(int i, const Eigen::Vector4f vel) { _particles.velocity(i) = vel; }
