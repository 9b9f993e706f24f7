#include "clothref/core/spheres.h"

#include "clothref/formula/course_formulas.h"

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

// One contact between body a (the sphere, index i) and body b (index j), normal from b to a: the
// course writes the same lines in both collide stubs, course_formulas.h writes them once (the
// impulse's association order and the correction included).
template <typename T>
void resolveContact(Particles<T>& a, int i, Particles<T>& b, int j, T contact_distance,
                    T restitution, T correction) {
  formula::resolveContact(a.position.col(i).data(), a.velocity.col(i).data(), a.inverse_mass[i],
                          b.position.col(j).data(), b.velocity.col(j).data(), b.inverse_mass[j],
                          contact_distance, restitution, correction);
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
