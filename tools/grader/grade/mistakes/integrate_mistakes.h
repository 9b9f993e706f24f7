// The integrator mistakes as switches on one course step: the course's main loop step
// (simulateOneStep(), then the method's integrate()) written once (integrate_step.h), split by
// method family, with a switch per line a student's mistake changes, each switch's default the
// course's. A mistake's readings are rows of its family's table (integrate_euler.cpp,
// integrate_predictor.cpp, integrate_rk4.cpp, or integrate_step.cpp for the lines every method
// shares), named by the catalogue's id (cause::k…) and setting the lines they change; what a model
// fits from the student's numbers (a step size, weights, a velocity factor, particles held still,
// deltaTime after the call) is an Overlay laid over those lines. With no row and no overlay the
// step is the library's (core/integrator.cpp), bit for bit (IntegrateMistakes.
// NoSwitchIsTheLibrarysStep, per method, on both editions' systems). A new mistake is its
// catalogue entry and its row in one family's file, with a new switch and its use there when it
// changes a line no switch has.
#pragma once
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "grader/grade/mistakes/integrate_step.h"
#include "grader/grade/mistakes/system.h"
#include "grader/grade/rubric.h"

namespace clothref::grader::integrators {

// A model of the step: the stub's method, rows (numbered through the families' tables in order;
// none: the course's), an overlay.
struct StepModel {
  Method method = Method::Explicit;  // the stub's (a row may run another method: Heun)
  std::vector<int> rows{};
  Overlay overlay{};
};

// The course's main loop step as `model` changes it.
Step courseStep(const StepModel& model);
inline Step courseStep(Method method) { return courseStep(StepModel{method}); }

// A reading of a mistake (or of a variant the rubric accepts): a row of a family's table.
struct Reading {
  std::string id;    // the catalogue's cause (cause::k…), or the rubric's accepted variant
  std::string text;  // what the model computes, in a student's words
  int row = -1;
  bool first_pass = false;  // tried on the first step before any fit (oneStepSignatures)
};

// The readings of `id` on a stub of `method`, in the tables' order (every method's rows, then
// explicit Euler's, the predictor-corrector's, RK4's; none: not a row's id).
std::vector<Reading> readingsOf(std::string_view id, Method method);
// Every reading of a stub of `method`, in the tables' order.
std::vector<Reading> readingsOf(Method method);
// Every id the tables name (the catalogue test checks each is an entry or an accepted variant).
std::vector<std::string> readingIds();

// `id`'s first reading on `method` as a step (the course's step when `id` has none there).
Step readingStep(std::string_view id, Method method);

// Both models at once: the rows of both (none when two set one line differently, or run
// different methods) and both overlays (b's values where it changes one).
std::optional<StepModel> combined(const StepModel& a, const StepModel& b);

// The accepted variants of `method` that the rubric switches on: (description, step).
std::vector<std::pair<std::string, Step>> acceptedVariants(const Rubric& rubric, Method method);

}  // namespace clothref::grader::integrators
