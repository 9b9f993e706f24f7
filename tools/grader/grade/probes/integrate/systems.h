// The integrator probe's test systems (docs/grading-reference.md, "Integrators"; the system itself
// and clothref's step of it are mistakes/system.h): the states tried, the encoding of a system into
// the probe's request and of the answer back, and the distances and errors the checks compare.
#pragma once
#include <cstdint>
#include <vector>

#include "clothref/core/method.h"
#include "grader/grade/mistakes/system.h"

namespace probe {
struct ProbeMessage;
}

namespace clothref::grader::integrators {

// The library's method of course integrator `index`: the row of clothref's method table (how the
// probe protocol names it, key::kMethod), 0 explicit .. 3 RK4 as the course's currentIntegrator
// (IntegrateSystems.IntegratorsAreTheLibrarysCourseRows checks each row's class is the stub's).
Method integratorMethod(int index);

// Random small perturbations of a 4 x 4 cloth at rest and two spheres, sphere 0 pressing on a
// free cloth particle (contact on); dt = 0.01 s; the course's gravity, drag, sphere density and
// contact constants of `edition` (the same in both).
System randomSystem(std::uint64_t seed, int edition = 2022);
// The same on the course's own cloth and spheres (25 x 25, the edition's scene), no contact;
// `corners_free`: its fixed corners unpinned (a free particle's mass, as the 2024 program's keys
// 1-4 leave an unpinned corner), so that a step holding them still shows.
System courseSystem(std::uint64_t seed, int edition, bool corners_free = false);
// clothref's `spring` scene: a unit mass on a spring to an anchor (k = 100 N/m, c = 2 N s/m, rest
// 1 m, released at 1.2 m); `particles` the cloth's size (the others fixed and parked far away).
System springSystem(float dt, int particles = 2, int edition = 2022);
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
