// The collision groups' course side: Spheres::collide(Cloth*) and (2022) Spheres::collide() on
// the request's states.
// Included into probe_driver.cpp's one translation unit (driver_support.h says why), whose dispatch
// calls its function by the group's name.
#pragma once
#include "grader/driver/driver_support.h"

namespace {

// Both collision groups: three spheres added once (the singleton persists), then every case
// restores the whole state before the call, as the course's main restores its backups.
void collide(const ProbeMessage& in, ProbeMessage& out, bool sphereSphere) {
  Cloth cloth;
  Spheres& spheres = Spheres::initSpheres();
  const auto& radii = in.f(key::kSphereRadius);
  for (size_t s = 0; s < radii.size(); ++s)
    spheres.addSphere(Eigen::Vector4f(100.0f * float(s + 1), 100, 0, 1), radii[s]);
  const int cases = static_cast<int>(in.scalarInt(key::kCases));
  Particles& c = cloth.particles();
  Particles& s = spheres.particles();
  // addSphere grows the capacity by doubling and leaves the new columns unset (the course's
  // resize): the spare one is parked far away at rest, so that no answer holds bytes nobody set
  // (the two runs of a probe must agree to the bit) and a loop over the capacity meets nothing.
  for (int k = static_cast<int>(radii.size()); k < s.getCapacity(); ++k) {
    s.position(k) = Eigen::Vector4f(1000.0f * float(k + 1), 1000, 0, 1);
    s.velocity(k).setZero();
    s.acceleration(k).setZero();
  }
  for (int k = 0; k < cases; ++k) {
    load(c.position(), in.f(perCase(key::kClothPos, k)));
    load(c.velocity(), in.f(perCase(key::kClothVel, k)));
    // what simulateOneStep() computed before collide (the stub must leave it alone)
    c.acceleration().setZero();
    load(c.acceleration(), in.f(perCase(key::kClothAcc, k)));
    loadMass(c, in.f(perCase(key::kClothMass, k)));
    load(s.position(), in.f(perCase(key::kSpherePos, k)));
    load(s.velocity(), in.f(perCase(key::kSphereVel, k)));
    s.acceleration().setZero();
    load(s.acceleration(), in.f(perCase(key::kSphereAcc, k)));
    loadMass(s, in.f(perCase(key::kSphereMass, k)));
    fillStack();
#ifdef CLOTHREF_GRADER_EDITION_2024
    (void)sphereSphere;
    spheres.collide(&cloth);
#else
    if (sphereSphere)
      spheres.collide();
    else
      spheres.collide(&cloth);
#endif
    out.floats[perCase(key::kClothPos, k)] = save(c.position());
    out.floats[perCase(key::kClothVel, k)] = save(c.velocity());
    out.floats[perCase(key::kSpherePos, k)] = save(s.position());
    out.floats[perCase(key::kSphereVel, k)] = save(s.velocity());
    out.floats[perCase(key::kClothAcc, k)] = save(c.acceleration());
    out.floats[perCase(key::kSphereAcc, k)] = save(s.acceleration());
  }
}
void probeCollideCloth(const ProbeMessage& in, ProbeMessage& out) { collide(in, out, false); }
void probeCollideSpheres(const ProbeMessage& in, ProbeMessage& out) { collide(in, out, true); }

}  // namespace
