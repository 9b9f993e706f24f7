// One run of the integrator probe: the request (the random state, the convergence ladder, the
// stability run and the stage record) built for one course integrator, the child's answer, and
// what the checks compare it with.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "grader/bridge/probe_protocol.h"
#include "grader/grade/probes/integrate/systems.h"
#include "grader/grade/probes/util.h"

namespace clothref::grader::integrators {

// One step of one state: the state sent, after the simulateOneStep() that precedes integrate(),
// the student's answer and the course method's.
struct OneStep {
  System state, start, actual, expected;
  int case_index = 0;
  double distance = 0;  // actual against expected
};

struct IntegratorRun {
  int index = 0;  // the course's currentIntegrator: 0 explicit .. 3 RK4
  Method method = Method::Explicit;
  std::string stub;
  double rel = 0;
  System random;
  std::vector<double> dts;
  std::vector<std::int64_t> strides;
  double end_time = 1.0;
  int spring_particles = 2;  // cloth size of the spring systems
  double limit = 0, stable_dt = 0;
  int stable_case = 0;
  int stage_case = 0;  // the contact-free case whose stages are recorded (stages.h)
  probe::ProbeMessage answer;
  System start;  // the random state after the simulateOneStep() that precedes integrate()
  System actual, expected;
  double distance = 0;  // actual against the course method after one step
  // One step on the course's cloth as the course's program can have it (courseSystem; 2024: its
  // corners unpinned, as keys 1-4 do): a step that holds particles of its own still (the top row,
  // hard-coded corners) shows only there. Part of the one-step check; none in a run put together
  // by hand.
  std::optional<OneStep> course_cloth;
};

// Fills `step`'s expected (the course's `method`), start and distance from its state and actual.
void completeOneStep(OneStep& step, Method method);

// Builds the request for `index` (small systems, or the course's cloth when `course_size`) and
// runs it; `log` records a failed child's verdict. Returns false with `failure` set when the
// child did not answer.
bool runIntegrator(const ProbeContext& context, int index, bool course_size, IntegratorRun& run,
                   util::ProbeFailure& failure, ChildRun& child, bool log);

// Whether every non-finite number of `answer` belongs to a case whose trajectory first grew past
// 1e6 m (the probe's systems are about 1 m): an unstable method overflows so, where a NaN of the
// stub's (0 / 0) comes without growing first. An answer with none: false.
bool onlyDivergedRuns(const probe::ProbeMessage& answer);

}  // namespace clothref::grader::integrators
