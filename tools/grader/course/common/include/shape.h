// Stand-in for the course's shape.h: the base of Cloth and Spheres, owning their Particles, with
// the gravity-and-drag external force and the collision double dispatch.
#pragma once
#include <Eigen/Core>
#include <functional>

#include "particles.h"

class Cloth;
class Spheres;
class Integrator;

class Shape {
 public:
  explicit Shape(int size, float mass_) noexcept;
  virtual ~Shape() = default;
  void setModelMatrix(const Eigen::Ref<const Eigen::Matrix4f>& _modelMatrix);
  Particles& particles() { return _particles; }
  Eigen::Matrix4f getModelMatrix() const { return modelMatrix; }
  Eigen::Matrix4f getNormalMatrix() const { return normalMatrix; }
  // Sets every acceleration to gravity - v * viscousCoef / m (zero for a fixed particle).
  void computeExternalForce();
  virtual void collide(Shape* shape) = 0;
  virtual void collide(Cloth*) {}
  virtual void collide(Spheres*) {}
  virtual void collide() {}

 protected:
  Particles _particles;
  Eigen::Matrix4f modelMatrix;
  Eigen::Matrix4f normalMatrix;
};
