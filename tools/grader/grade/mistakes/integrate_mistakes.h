// The integrator mistakes as switches on one course step: the course's main loop step
// (simulateOneStep(), then the method's integrate()) written once here with a switch per line a
// student's mistake changes, each switch's default the course's. With every switch at its default
// the step is the library's (core/integrator.cpp), bit for bit
// (IntegrateMistakes.NoSwitchIsTheLibrarysStep, per method, on both editions' systems). A
// mistake's model is its switches (Variant names the sets the probe tries); the rubric's accepted
// variants are steps too.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "grader/grade/mistakes/system.h"
#include "grader/grade/rubric.h"

namespace clothref::grader::integrators {

// The lines of the course's step a mistake changes; the defaults are the course's.
struct StepSwitches {
  // every method
  bool backup_follows_live = false;  // x0, v0 read the live state (a pointer or Eigen::Ref "copy")
  bool reevaluates = true;           // integrate()'s own simulateOneStep() calls (off: explicit)
  bool per_body = false;             // integrate() on one body at a time, each with its calls
  // explicit Euler
  bool position_half_acceleration = false;  // x += v dt + a dt²/2
  bool updates_position = true, updates_velocity = true;
  // the predictor-corrector (implicit h = 1, midpoint h = 1/2)
  bool predictor_adds_nothing = false;      // h = 0 (1 / 2 == 0, or kept in locals)
  bool predictor_symplectic = false;        // v first, then x with the new v
  bool evaluates_before_predictor = false;  // simulateOneStep() before the prediction, not after
  bool corrector_new_velocity = false;      // x = x0 + v_new dt
  // RK4
  bool stage_from_current = false;                // stage k > 1 built on the previous stage
  bool stage_position_from_new_velocity = false;  // stage x = x0 + dt c (v0 + kv c)
  int stage_position_from_kv = -1;                // that stage's (0..2) x adds kv, not kx
  bool result_adds_nothing = false;               // 1 / 6 == 0
  bool result_on_last_stage = false;        // x += ... onto the state the last stage left, not x0
  bool result_position_from_kv = false;     // x0 + (kv1 + 2 kv2 + 2 kv3 + kv4) / 6
  bool result_velocity_k4_from_kx = false;  // v0 + (... + kx4) / 6
  bool result_first_stage_only = false;     // x0 + k1, v0 + k1v
};

// The course's main loop step with `method` and `switches` (Explicit, Implicit, Midpoint, Rk4;
// a switch of another method's line is ignored).
Step courseStep(Method method, const StepSwitches& switches);

// The mistakes the probe tries, each a set of switches (switchesOf).
enum class Variant {
  None,  // no switch: the course's method
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

// The switches of `variant`. `stage_index`: for RkMixedStage, the stage (0..2) whose position
// uses the velocity increment.
StepSwitches switchesOf(Variant variant, int stage_index = -1);

// courseStep(method, switchesOf(variant, stage_index)).
Step variantStep(Method method, Variant variant, int stage_index = -1);

// The accepted variants of `method` that the rubric switches on: (description, step).
std::vector<std::pair<std::string, Step>> acceptedVariants(const Rubric& rubric, Method method);

}  // namespace clothref::grader::integrators
