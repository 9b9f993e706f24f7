// The forces group's course side: Cloth::computeSpringForce on the request's states and our
// spring set.
// Included into probe_driver.cpp's one translation unit (driver_support.h says why), whose dispatch
// calls its function by the group's name.
#pragma once
#include "grader/driver/driver_support.h"

namespace {

void probeForces(const ProbeMessage& in, ProbeMessage& out) {
  Cloth cloth;
  // Our spring set, never the student's: a wrong initializeSpring must not fail the forces.
  cloth.springs() = springsFrom(in, -1);
  springCoef = in.scalar(key::kSpringCoef);
  damperCoef = in.scalar(key::kDamperCoef);
  const int cases = static_cast<int>(in.scalarInt(key::kCases));
  Particles& p = cloth.particles();
  for (int k = 0; k < cases; ++k) {
    load(p.position(), in.f(perCase(key::kClothPos, k)));
    load(p.velocity(), in.f(perCase(key::kClothVel, k)));
    load(p.acceleration(), in.f(perCase(key::kClothAcc, k)));
    loadMass(p, in.f(perCase(key::kClothMass, k)));
    fillStack();
    cloth.computeSpringForce();
    out.floats[perCase(key::kClothAcc, k)] = save(p.acceleration());
  }
}

}  // namespace
