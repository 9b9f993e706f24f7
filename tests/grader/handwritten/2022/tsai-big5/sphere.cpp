#include "sphere.h"

#include <Eigen/Dense>

#include "cloth.h"
#include "configs.h"

namespace {
void generateVertices(std::vector<GLfloat>& vertices, std::vector<GLuint>& indices) {
  // See http://www.songho.ca/opengl/gl_sphere.html#sphere if you don't know how to create a sphere.
  vertices.reserve(6 * (sphereStack + 1) * (sphereSlice + 1));
  indices.reserve(6 * sphereStack * sphereSlice);
  float x, y, z, xy;  // vertex position

  float sectorStep = static_cast<float>(2 * EIGEN_PI / sphereSlice);
  float stackStep = static_cast<float>(EIGEN_PI / sphereStack);
  float sectorAngle, stackAngle;

  for (int i = 0; i <= sphereStack; ++i) {
    stackAngle = static_cast<float>(EIGEN_PI / 2 - i * stackStep);  // starting from pi/2 to -pi/2
    xy = cosf(stackAngle);                                           // r * cos(u)
    z = sinf(stackAngle);                                            // r * sin(u)
    // add (sectorCount+1) vertices per stack
    // the first and last vertices have same position and normal, but different tex coords
    for (int j = 0; j <= sphereSlice; ++j) {
      sectorAngle = j * sectorStep;  // starting from 0 to 2pi
      // vertex position (x, y, z)
      x = xy * cosf(sectorAngle);  // r * cos(u) * cos(v)
      y = xy * sinf(sectorAngle);  // r * cos(u) * sin(v)
      // position and normal are the same for a unit sphere
      vertices.insert(vertices.end(), {x, y, z, x, y, z});
    }
  }

  unsigned int k1, k2;  // EBO index
  for (int i = 0; i < sphereStack; ++i) {
    k1 = i * (sphereSlice + 1);  // beginning of current stack
    k2 = k1 + sphereSlice + 1;   // beginning of next stack
    for (int j = 0; j < sphereSlice; ++j, ++k1, ++k2) {
      // 2 triangles per sector excluding 1st and last stacks
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
  // Position
  vao.enable(0);
  vao.setAttributePointer(0, 3, 6, 0);
  glVertexAttribDivisor(0, 0);
  // Normal
  vao.enable(1);
  vao.setAttributePointer(1, 3, 6, 3);
  glVertexAttribDivisor(1, 0);
  // Offset (per instance)
  offsets.bind();
  vao.enable(2);
  vao.setAttributePointer(2, 3, 4, 0);
  glVertexAttribDivisor(2, 1);
  // Size (per instance)
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
  //   2. If collided, update impulse directly to particles' velocity
  //   3. (Bonus) You can add friction, which updates particles' acceleration a = F / m
  // Note:
  //   1. There are `sphereCount` spheres.
  //   2. There are particlesPerEdge * particlesPerEdge particles.
  //   3. See TA's slide if you don't know how to update impulse.
  //   4. Hint: You can push particles apart to prevent penetration. e.g.
  //      _particles.position(i) += penetration * normal * 0.15f;
  //      cloth->particles().position(j) -= penetration * normal * 0.15f;
  // Write code here!
	Particles& p = cloth->particles();
	for (int i = 0; i < sphereCount; i++) {
		for (int j = 0; j < particlesPerEdge * particlesPerEdge; j++) {
			Eigen::Vector4f n = _particles.position(i) - p.position(j);
			float pen = _radius[i] - n.norm();
			if (pen < 0) continue;  // 沒碰到
			n.normalize();
			float vn = (_particles.velocity(i) - p.velocity(j)).dot(n);
			if (vn < 0) {
				Eigen::Vector4f J = -(1 + coefRestitution) * (vn * n) / (_particles.inverseMass(i) + p.inverseMass(j));
				_particles.velocity(i) += J * _particles.inverseMass(i);
				p.velocity(j) -= J * p.inverseMass(j);
			}
			_particles.position(i) += pen * n * 0.15f;
			p.position(j) -= pen * n * 0.15f;
		}
	}
}

void Spheres::collide() {
  constexpr float coefRestitution = 0.8f;
  // TODO: Collide with another sphere (Rigidbody collision)
  //   1. Detect collision.
  //   2. If collided, update impulse directly to particles' velocity
  //   3. (Bonus) You can add friction, which updates particles' acceleration a = F / m
  // Note:
  //   1. There are `sphereCount` spheres.
  //   2. You may not want to calculate one pair twice.
  //   3. See TA's slide if you don't know how to update impulse.
  //   4. Hint: You can push particles apart to prevent penetration.
  // Write code here!
	for (int i = 0; i < sphereCount; i++) {
		for (int j = i + 1; j < sphereCount; j++) {
			Eigen::Vector4f n = _particles.position(i) - _particles.position(j);
			float pen = _radius[i] + _radius[j] - n.norm();
			if (pen < 0) continue;
			n.normalize();
			float vn = (_particles.velocity(i) - _particles.velocity(j)).dot(n);
			if (vn < 0) {
				Eigen::Vector4f J = -(1 + coefRestitution) * (vn * n) / (_particles.inverseMass(i) + _particles.inverseMass(j));
				_particles.velocity(i) += J * _particles.inverseMass(i);
				_particles.velocity(j) -= J * _particles.inverseMass(j);
			}
			// 把後面那顆推開
			_particles.position(j) -= pen * n * 0.15f;
		}
	}
}
