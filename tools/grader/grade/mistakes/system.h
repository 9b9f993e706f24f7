// The state the integrator mistakes run on (mistakes/integrate_mistakes.h) and the probe tests
// (probes/integrate/): small cloths and spheres with the course's step parts, the course's
// simulateOneStep on them, and clothref's own step of a course method (the library's method table
// and integrators).
#pragma once
#include <functional>

#include "clothref/core/cloth.h"
#include "clothref/core/method.h"
#include "clothref/core/spheres.h"

namespace clothref::grader::integrators {

// A small system: a cloth (any particles and springs) and spheres, the course's step parts.
struct System {
  Cloth<float> cloth;
  Spheres<float> spheres;
  float viscous = 0;
  Vec4<float> gravity = Vec4<float>::Zero();
  bool sphere_gravity = false;
  // Sphere-cloth contact inside simulateOneStep, as the course's: it couples the bodies, so a
  // method that advances them one at a time gives another result.
  bool contact = false;
  // The contacts' constants: coefRestitution of Spheres::collide(Cloth*) and of
  // Spheres::collide(), and the correction factor; set with the system from the Edition record.
  float restitution_cloth = 0, restitution_sphere = 0, correction = 0;
  float dt = 0;
  bool course_size = false;  // the course's 25 x 25 cloth and spheres (retry after a crash)
};

// The course's simulateOneStep on `s` (its parts switched by the system's flags): the library's
// course-form functions in the course's order. A copy of clothref::simulateOneStep's order, which
// has no switch for contact; IntegrateSystems.SimulateIsTheLibrarysSimulateOneStep proves it
// bit-equal.
void simulate(System& s);

using Step = std::function<void(System&)>;

// The course's main loop step with clothref's integrator: simulate, then integrate() of the
// library on the first `bodies_integrated` bodies.
Step clothrefStep(Method method, int bodies_integrated = 2);

}  // namespace clothref::grader::integrators
