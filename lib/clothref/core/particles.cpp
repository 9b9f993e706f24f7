#include "clothref/core/particles.h"

#include "clothref/formula/course_formulas.h"

namespace clothref {

template <typename T>
Particles<T> makeParticles(int count, T mass) {
  Particles<T> particles;
  particles.position = Mat4X<T>::Zero(4, count);
  particles.position.row(3).setOnes();
  particles.velocity = Mat4X<T>::Zero(4, count);
  particles.acceleration = Mat4X<T>::Zero(4, count);
  particles.mass = VecX<T>::Zero(count);
  particles.inverse_mass = VecX<T>::Zero(count);
  for (int i = 0; i < count; ++i) setMass(particles, i, mass);
  return particles;
}

template <typename T>
void setMass(Particles<T>& particles, int i, T mass) {
  particles.mass[i] = mass;
  particles.inverse_mass[i] = mass == T(0) ? T(0) : T(1) / mass;
}

template <typename T>
void computeExternalForce(Particles<T>& particles, const Vec4<T>& gravity, T viscous_coef) {
  // the course's expression, written once for clothref and the grader's driver alike
  for (int i = 0; i < particles.size(); ++i)
    formula::externalAcceleration(particles.velocity.col(i).data(), particles.mass[i],
                                  particles.inverse_mass[i], gravity.data(), viscous_coef,
                                  particles.acceleration.col(i).data());
}

template struct Particles<float>;
template struct Particles<double>;
template Particles<float> makeParticles(int, float);
template Particles<double> makeParticles(int, double);
template void setMass(Particles<float>&, int, float);
template void setMass(Particles<double>&, int, double);
template void computeExternalForce(Particles<float>&, const Vec4<float>&, float);
template void computeExternalForce(Particles<double>&, const Vec4<double>&, double);

}  // namespace clothref
