#include "clothref/core/spheres.h"

namespace clothref {

template <typename T>
void addSphere(Spheres<T>& spheres, const Vec4<T>& center, T radius, T density) {
  Particles<T>& p = spheres.particles;
  const int i = p.size();
  p.position.conservativeResize(Eigen::NoChange, i + 1);
  p.velocity.conservativeResize(Eigen::NoChange, i + 1);
  p.acceleration.conservativeResize(Eigen::NoChange, i + 1);
  p.mass.conservativeResize(i + 1);
  p.inverse_mass.conservativeResize(i + 1);
  p.position.col(i) = center;
  p.velocity.col(i).setZero();
  p.acceleration.col(i).setZero();
  setMass(p, i, density * radius * radius * radius);
  spheres.radius.push_back(radius);
}

namespace {

// One contact between body a (the sphere, index i) and body b (index j), normal from b to a.
// Shared by both collide stubs: the course writes the same lines in each.
template <typename T>
void resolveContact(Particles<T>& a, int i, Particles<T>& b, int j, T contact_distance,
                    T restitution, T correction) {
  Vec4<T> normal = a.position.col(i) - b.position.col(j);
  const T penetration = contact_distance - normal.norm();
  if (penetration < T(0)) return;
  normal.normalize();
  const Vec4<T> relative_velocity = a.velocity.col(i) - b.velocity.col(j);
  const T approach = relative_velocity.dot(normal);
  if (approach < T(0)) {
    // the course's order: the normal velocity n * (v_rel . n) first, then scaled by -(1 + e);
    // -(1 + e) * n * s would round differently whenever e != 0
    const Vec4<T> normal_velocity = normal * approach;
    const Vec4<T> impulse =
        (-(T(1) + restitution) * normal_velocity) / (b.inverse_mass[j] + a.inverse_mass[i]);
    a.velocity.col(i) += impulse * a.inverse_mass[i];
    b.velocity.col(j) -= impulse * b.inverse_mass[j];
  }
  const Vec4<T> shift = penetration * normal * correction;
  a.position.col(i) += shift;
  b.position.col(j) -= shift;
}

}  // namespace

template <typename T>
void collide(Spheres<T>& spheres, Cloth<T>& cloth, T restitution, T correction) {
  for (int i = 0; i < spheres.size(); ++i)
    for (int j = 0; j < cloth.particles.size(); ++j)
      resolveContact(spheres.particles, i, cloth.particles, j, spheres.radius[i], restitution,
                     correction);
}

template <typename T>
void collide(Spheres<T>& spheres, T restitution, T correction) {
  for (int i = 0; i < spheres.size(); ++i)
    for (int j = i + 1; j < spheres.size(); ++j)
      resolveContact(spheres.particles, i, spheres.particles, j,
                     spheres.radius[i] + spheres.radius[j], restitution, correction);
}

template void addSphere(Spheres<float>&, const Vec4<float>&, float, float);
template void addSphere(Spheres<double>&, const Vec4<double>&, double, double);
template void collide(Spheres<float>&, Cloth<float>&, float, float);
template void collide(Spheres<double>&, Cloth<double>&, double, double);
template void collide(Spheres<float>&, float, float);
template void collide(Spheres<double>&, double, double);

}  // namespace clothref
