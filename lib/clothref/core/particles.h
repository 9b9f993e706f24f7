// Particles: the state of one body (the course's `Particles` class, as plain data).
#pragma once

#include "clothref/core/types.h"

namespace clothref {

// N particles of one body.
//   position      4 x N, w = 1, metres
//   velocity      4 x N, w = 0, metres / second
//   acceleration  4 x N, w = 0, metres / second^2 (reset by computeExternalForce every evaluation)
//   mass          N, kilograms; 0 marks a fixed particle
//   inverse_mass  N, 1 / mass, or 0 for a fixed particle (the course's inverseMass(i))
// Set masses with setMass so the two mass arrays agree.
template <typename T>
struct Particles {
  Mat4X<T> position;
  Mat4X<T> velocity;
  Mat4X<T> acceleration;
  VecX<T> mass;
  VecX<T> inverse_mass;

  int size() const { return static_cast<int>(position.cols()); }
};

// Returns `count` particles at the origin (w = 1), at rest, with mass `mass`.
template <typename T>
Particles<T> makeParticles(int count, T mass);

// Sets the mass of particle i and its inverse (0 for a fixed particle, as the course's
// inverseMass).
template <typename T>
void setMass(Particles<T>& particles, int i, T mass);

// The course's Shape::computeExternalForce: every free particle's acceleration is *set* to
// gravity - velocity * viscous_coef * inverse_mass; a fixed particle's is set to zero.
//   gravity       4-vector, w = 0, metres / second^2
//   viscous_coef  linear drag coefficient, kilograms / second
template <typename T>
void computeExternalForce(Particles<T>& particles, const Vec4<T>& gravity, T viscous_coef);

}  // namespace clothref
