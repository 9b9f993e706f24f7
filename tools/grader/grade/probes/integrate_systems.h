// The integrator probe's test systems (docs/grading.md, "Integrators"): small cloths and spheres
// with the course's step parts, clothref's own step of a course method (the library's method
// table and integrators), the encoding of a system into the probe's request and of the answer
// back, and the distances and errors the checks compare.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "clothref/core/cloth.h"
#include "clothref/core/method.h"
#include "clothref/core/spheres.h"

namespace probe {
struct ProbeMessage;
}

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
  float dt = 0;
  bool course_size = false;  // the course's 25 x 25 cloth and spheres (retry after a crash)
};

// The course's simulateOneStep on `s` (its parts switched by the system's flags): the library's
// course-form functions in the course's order. A copy of clothref::simulateOneStep's order, which
// has no switch for contact; IntegrateSystems.SimulateIsTheLibrarysSimulateOneStep proves it
// bit-equal.
void simulate(System& s);

// The library's method of course integrator `index`: the row of clothref's method table (how the
// probe protocol names it, key::kMethod), 0 explicit .. 3 RK4 as the course's currentIntegrator
// (IntegrateSystems.IntegratorsAreTheLibrarysCourseRows checks each row's class is the stub's).
Method integratorMethod(int index);

using Step = std::function<void(System&)>;

// The course's main loop step with clothref's integrator: simulate, then integrate() of the
// library on the first `bodies_integrated` bodies.
Step clothrefStep(Method method, int bodies_integrated = 2);

// Random small perturbations of a 4 x 4 cloth at rest and two spheres, sphere 0 pressing on a
// free cloth particle (contact on); dt = 0.01 s.
System randomSystem(std::uint64_t seed);
// The same on the course's own cloth and spheres (25 x 25, the edition's scene), no contact.
System courseSystem(std::uint64_t seed, int edition);
// clothref's `spring` scene: a unit mass on a spring to an anchor (k = 100 N/m, c = 2 N s/m, rest
// 1 m, released at 1.2 m); `particles` the cloth's size (the others fixed and parked far away).
System springSystem(float dt, int particles = 2);
// The largest stable dt of `method` on springSystem (analysis::theoryLimit on its one mode).
double stabilityLimit(Method method);
// The stage record's system (stages.h): the random state with another seed and no contact, at the
// step stages::kStageStep.
System stageSystem(std::uint64_t seed, bool course_size, int edition);

// Case k of the request: the system, `steps` steps, a trajectory record every `stride` steps.
void addSystem(probe::ProbeMessage& m, int k, const System& s, std::int64_t steps,
               std::int64_t stride);
// The state of case k in the answer, on the shape of `like`.
System answerSystem(const probe::ProbeMessage& a, int k, const System& like);

// Largest |a - b| / (1 + |b|) over positions and velocities of body 0, 1 or both (-1).
double distance(const System& a, const System& b, int body = -1);
// `s` after one `step`.
System stepped(const System& s, const Step& step);

// Errors |x - x_exact| of the spring's free particle, max over a recorded trajectory.
double trajectoryError(const std::vector<float>& trajectory, double dt, std::int64_t stride,
                       int particles = 2);
// The same trajectory error for clothref's method (the expected observed order).
double referenceError(Method method, double dt, std::int64_t steps, std::int64_t stride);

}  // namespace clothref::grader::integrators
