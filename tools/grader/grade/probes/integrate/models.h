// The models of the integrators' causes (issue 38, "likely means proven"; replayed in replay.h):
// the course's step with a mistake's rows (mistakes/integrate_mistakes.h, one table named by the
// catalogue's ids), and for the causes whose model is fitted from the student's numbers the
// course's step with that fit laid over it (an Overlay: a step size, result weights, a velocity
// factor, particles held still, deltaTime after the call).
#pragma once
#include <string>
#include <vector>

#include "grader/grade/mistakes/integrate_mistakes.h"
#include "grader/grade/probes/integrate/held_still.h"
#include "grader/grade/probes/integrate/run.h"
#include "grader/grade/probes/integrate/stages.h"

namespace clothref::grader::integrators {

// One model of a cause: the step model, its step and its text ("the course's RK4 with weights
// 1/6, 1/6, 1/3, 1/3").
struct IntegratorModel {
  std::vector<std::string> ids;
  std::string text;
  StepModel model;
  Step step;
};
IntegratorModel integratorModel(std::vector<std::string> ids, std::string text, StepModel model);

// Every model of cause `id` for this run (none when the cause has no model): its rows on the
// stub's method, then what is fitted from the run; the rubric's accepted variants are the steps a
// pinning helper may follow.
std::vector<IntegratorModel> modelsOf(const std::string& id, const Rubric& rubric,
                                      const IntegratorRun& run, const RunStages& stages);

}  // namespace clothref::grader::integrators
