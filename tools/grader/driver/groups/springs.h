// The springs group's course side: Cloth() and its springs, as this build's N makes them.
// Included into probe_driver.cpp's one translation unit (driver_support.h says why), whose dispatch
// calls its function by the group's name.
#pragma once
#include "grader/driver/driver_support.h"

namespace {

void probeSprings(const ProbeMessage&, ProbeMessage& out) {
  fillStack();  // Cloth() calls initializeSpring
  Cloth cloth;
  std::vector<std::int64_t> start, end, type;
  std::vector<float> rest;
  for (const Spring& spring : cloth.springs()) {
    start.push_back(spring.startParticleIndex());
    end.push_back(spring.endParticleIndex());
    type.push_back(static_cast<std::int64_t>(spring.type()));
    rest.push_back(spring.length());
  }
  out.ints[key::kParticlesPerEdge] = {particlesPerEdge};
  out.ints[key::kSpringStart] = start;
  out.ints[key::kSpringEnd] = end;
  out.ints[key::kSpringType] = type;
  out.floats[key::kSpringRest] = rest;
  out.floats[key::kClothPos] = save(cloth.particles().position());
}

}  // namespace
