// The predictor-corrector's lines of the course's step (integrate_step.h; implicit Euler h = 1,
// midpoint h = 1/2): its switches, its integrate() and the readings of its mistakes. A new
// mistake here is its row; a new line its switch in PredictorSwitches, its use in
// predictCorrect and its row.
#include "grader/grade/cause_ids.h"
#include "grader/grade/mistakes/integrate_step.h"

namespace clothref::grader::integrators {
namespace {

// The lines of the predictor-corrector a mistake changes; the defaults are the course's.
struct PredictorSwitches {
  bool predictor_full_step = false;         // midpoint's prediction with h = 1
  bool predictor_adds_nothing = false;      // h = 0 (1 / 2 == 0, or kept in locals)
  bool predictor_symplectic = false;        // v first, then x with the new v
  bool evaluates_before_predictor = false;  // simulateOneStep() before the prediction, not after
  bool corrector_new_velocity = false;      // x = x0 + v_new dt
  bool corrector_trapezoidal = false;       // x = x0 + (v0 + v1) dt / 2, v = v0 + (a0 + a1) dt / 2
  bool corrector_start_velocity = false;    // x = x0 + v0 dt
};

// The course's predictor-corrector (core/integrator.cpp's predictEvaluateCorrect, operation for
// operation) for the call's bodies only; the others keep their state.
void predictCorrect(const Call& c, const PredictorSwitches& w) {
  System& s = c.s;
  const auto& bodies = c.bodies;
  const float dt = c.z.dt, rdt = c.z.result_dt, scale = c.z.result_scale;
  float h = c.method == Method::Midpoint ? 0.5f : 1.0f;
  const Backup backup(bodies, c.every.backup_follows_live);
  std::vector<Mat4X<float>> a0;
  for (auto* p : bodies) a0.push_back(p->acceleration);
  if (w.evaluates_before_predictor) simulate(s);
  if (w.predictor_full_step) h = 1;
  if (w.predictor_adds_nothing) h = 0;
  for (auto* p : bodies) {
    if (w.predictor_symplectic) {
      p->velocity += (p->acceleration * dt) * h;
      p->position += (p->velocity * dt) * h;
    } else {
      p->position += (p->velocity * dt) * h;
      p->velocity += (p->acceleration * dt) * h;
    }
  }
  c.at_stage();
  if (!w.evaluates_before_predictor) simulate(s);
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    auto* p = bodies[b];
    Mat4X<float> x, v;
    if (w.corrector_trapezoidal) {
      const float half = float(0.5 * double(scale));
      v = backup.v(b);
      v += (a0[b] * rdt) * half;
      v += (p->acceleration * rdt) * half;
      x = backup.x(b);
      x += (backup.v0[b] * rdt) * half;
      x += (p->velocity * rdt) * half;
    } else if (w.corrector_new_velocity) {
      v = backup.v(b) + increment(p->acceleration, rdt, scale);
      x = backup.x(b) + increment(v, rdt, scale);
    } else {
      const Mat4X<float>& along = w.corrector_start_velocity ? backup.v0[b] : p->velocity;
      x = backup.x(b) + increment(along, rdt, scale);
      v = backup.v(b) + increment(p->acceleration, rdt, scale);
    }
    p->velocity = c.every.updates_velocity ? v : backup.v(b);
    p->position = c.every.updates_position ? x : backup.x(b);
  }
}

// Every reading of an implicit Euler or midpoint stub on its lines (and Heun's on any stub), in
// the order the prover tries them (the first-pass ones in the order the one-step check tries
// them), after every method's and explicit Euler's.
// clang-format off
const std::vector<Row<PredictorSwitches>>& predictorRows() {
  static const std::vector<Row<PredictorSwitches>> table = {
    {cause::kMidpointFullStep, kM, true, "the course's implicit Euler (a full-step prediction)",
     {.predictor_full_step = true}},
    {cause::kNoReevaluation, kM, true,
     "the course's midpoint with simulateOneStep() before the half step",
     {.evaluates_before_predictor = true}},
    // simulateOneStep() at the unchanged start state; a contact in it is applied a second time,
    // so this is not explicit Euler's result.
    {cause::kNoReevaluation, kM, true, "the course's midpoint whose half step adds nothing",
     {.predictor_adds_nothing = true}},
    {cause::kIntegerDivisionHalf, kM, false,
     "the course's midpoint with 1 / 2 = 0 (the half step adds nothing)",
     {.predictor_adds_nothing = true}},
    {cause::kHeunMethod, kAll, false, "Heun's method (the trapezoidal corrector)",
     {.corrector_trapezoidal = true}, {}, Method::Implicit},
    {cause::kCorrectorStartVelocity, kI | kM, false,
     "{method} whose corrector moves the positions with the start velocity v0",
     {.corrector_start_velocity = true}},
    // Variants the rubric may accept (stages::methodTables' `accepted`), which a fitted overlay
    // (particles held still) may follow.
    {"implicit-corrector-v-new", kI, false, "implicit Euler whose corrector uses the new v",
     {.corrector_new_velocity = true}},
    {"symplectic-predictor", kI, false,
     "implicit Euler with a symplectic predictor (v first, then x)", {.predictor_symplectic = true}},
    {"symplectic-predictor", kM, false, "midpoint with a symplectic predictor (v first, then x)",
     {.predictor_symplectic = true}},
  };
  return table;
}
// clang-format on

}  // namespace

const Family& predictorCorrectorFamily() {
  static const Family rows = familyOf(predictorRows(), predictCorrect);
  return rows;
}

}  // namespace clothref::grader::integrators
