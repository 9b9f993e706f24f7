// The integrator probe's mistake simulators: the course's predictor-corrector and RK4 written the
// way students write them, with one known mistake switched on, so that a student's numbers equal
// to one name that mistake; and the accepted variants the rubric switches on, as steps.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "grader/grade/mistakes/system.h"
#include "grader/grade/rubric.h"

namespace clothref::grader::integrators {

// `Alias`: every read of "the backup" sees the live state (a pointer or Eigen::Ref "copy").
enum class Variant {
  None,  // no mistake: the course's method (the copies below are proven bit-equal to it)
  ImplicitVNew,
  SymplecticPredictor,  // predictor v first, then x with the new v (implicit and midpoint)
  Alias,
  NoReevaluation,
  NoReevaluationHalfVelocity,  // simulateOneStep() before the half step: x0 + (v0 + a0 h) dt
  ZeroHalfStep,  // the prediction adds nothing (1 / 2 == 0, or kept in locals): re-evaluated at x0
  PerBody,       // one body at a time, each with its own simulateOneStep() calls
  RkIntDivision,
  RkIntDivisionOnLastStage,  // x += (1 / 6) * (...) on the last stage's state: returns that stage
  RkMixedFinal,
  RkK4xInVelocity,
  RkMixedStage,
  RkStageFromCurrent,
  RkStageFromNewVelocity,  // stage x = x0 + dt h (v0 + kv h)
  RkStagesDiscarded,       // x = x0 + k1, v = v0 + k1v
  PositionUsesAcceleration,
  VelocityOnly,
  PositionOnly
};

// The course's main loop step with `method` written with `variant`. `stage_index`: for
// RkMixedStage, the stage (0..2) whose position uses the velocity increment. Explicit Euler
// without a mistake, and a method that never re-evaluates (NoReevaluation), are the library's
// integrateExplicit; the predictor-corrector and RK4 are copies with switches
// (IntegrateMistakes.NoMistakeIsBitEqualToTheLibrary).
Step variantStep(Method method, Variant variant, int stage_index = -1);

// The accepted variants of `method` that the rubric switches on: (description, step).
std::vector<std::pair<std::string, Step>> acceptedVariants(const Rubric& rubric, Method method);

}  // namespace clothref::grader::integrators
