// Sphere-cloth contacts with a conservative broad phase. The course tests every sphere against
// every cloth particle, in order, and most pairs are far apart. Here a SIMD filter
// (contact_filter.h), on a structure-of-arrays copy of the cloth's positions, flags the particles
// whose squared distance to the sphere centre is within the radius plus a margin far above the
// rounding of the exact test; the pairs it passes over would all be rejected by the exact test,
// so skipping them changes no bit. Every flagged pair runs the course's exact test and contact, in
// the course's order, with the sphere's current (already corrected) centre, so the bits are those
// of the per-pair loop.
#pragma once

#include <vector>

#include "clothref/fast/simd_path.h"

namespace clothref::fast {

// The bodies, in the course's layout.
//   sphere_position, sphere_velocity  4 x spheres (x, y, z, w per sphere)
//   sphere_inverse_mass, radius       spheres; 1 / kg and metres
//   cloth_position, cloth_velocity    4 x particles
//   cloth_inverse_mass                particles
template <typename T>
struct ContactBodies {
  T* sphere_position;
  T* sphere_velocity;
  const T* sphere_inverse_mass;
  const T* radius;
  int spheres;
  T* cloth_position;
  T* cloth_velocity;
  const T* cloth_inverse_mass;
  int particles;
};

// Scratch for collideSpheresWithCloth: the filter's copy of the cloth's positions (metres, x, y
// and z arrays; float runs only). Sized on first use and reused, so keep one per world: later
// calls for the same cloth allocate nothing.
struct ContactWorkspace {
  std::vector<float> x, y, z;
};

// The course's Spheres::collide(Cloth*): for each sphere i, for each particle j in order, the
// contact of the course (restitution `restitution`, position correction factor `correction`),
// skipping only pairs that cannot touch. Returns the number of pairs the exact test ran on (for
// benchmarks and tests).
template <typename T>
long collideSpheresWithCloth(const ContactBodies<T>& bodies, T restitution, T correction,
                             SimdPath path, ContactWorkspace& workspace);

// The exact per-pair contact between sphere i and particle j, as the course writes it (both
// vectors 4 lanes, evaluated as Eigen does for a Vector4). Returns whether the pair touched.
template <typename T>
bool resolveSphereParticleContact(const ContactBodies<T>& bodies, int i, int j, T restitution,
                                  T correction);

}  // namespace clothref::fast
