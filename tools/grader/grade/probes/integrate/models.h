// The models of the integrators' causes (issue 38, "likely means proven"; replayed in replay.h):
// the course's step with a mistake's switch (mistakes/integrate_mistakes.h), or a course method
// table (explain/stages/methods.h) run as the course's code runs it, with the mistake's change:
// another step, result weights, a velocity factor, pinned particles or stopped spheres.
#pragma once
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "grader/grade/explain/stages/methods.h"
#include "grader/grade/probes/integrate/run.h"
#include "grader/grade/probes/integrate/stages.h"

namespace clothref::grader::integrators {

// A course method table run on a System as the course's code runs it: simulateOneStep() before,
// backups x0, v0 of every body, each evaluation's state from them and the derivatives met so far
// (velocities and accelerations read after each simulateOneStep(), so a contact inside it counts
// as in the course's code), then the result; with a mistake's changes.
struct TableModel {
  const stages::MethodTable* table = nullptr;
  double step = 1;         // every term's h is step x deltaTime
  double result_step = 1;  // the result's terms are taken at result_step x h
  // The result's weights on the evaluations' v (positions) and a (velocities), replacing the
  // table's: RK4 with other weights. Empty: the table's.
  std::vector<double> weights_x, weights_v;
  std::array<double, 2> velocity_factor{1, 1};  // the result's velocity of each body times this
  std::vector<int> pinned;                      // cloth particles held still after the step
  bool pinned_position = false;                 // ... put back where they were, not only stopped
  std::vector<int> pinned_spheres;              // spheres whose velocity is zeroed after the step
  std::optional<double> dt_after_factor;        // deltaTime x this after the call
  std::optional<float> dt_after;                // or this constant
  // The result's terms at this deltaTime, whatever the call's (a constant the stub restored
  // deltaTime to before its corrector, e.g. `deltaTime = 0.0001f;`).
  std::optional<float> result_dt;
};
Step tableStep(const TableModel& model);

// One model of a cause: a step and its text ("the course's RK4 with weights 1/6, 1/6, 1/3, 1/3").
struct IntegratorModel {
  std::vector<std::string> ids;
  std::string text;
  Step step;
  std::optional<TableModel> table;  // a table model: it combines with another's changes
};

// Every model of cause `id` for this run (none when the cause has no model).
std::vector<IntegratorModel> modelsOf(const std::string& id, const IntegratorRun& run,
                                      const RunStages& stages);

}  // namespace clothref::grader::integrators
