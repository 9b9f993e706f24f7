// Explicit Euler's lines of the course's step (integrate_step.h): its switches, its integrate()
// and the readings of its mistakes. A new mistake here is its row; a new line its switch in
// EulerSwitches, its use in integrateEuler and its row.
#include "grader/grade/cause_ids.h"
#include "grader/grade/mistakes/integrate_step.h"

namespace clothref::grader::integrators {
namespace {

// The lines of explicit Euler a mistake changes; the defaults are the course's.
struct EulerSwitches {
  bool position_half_acceleration = false;  // x += v dt + a dt²/2
  bool velocity_first = false;              // v first, then x with the new v (symplectic)
};

// The course's explicit Euler (core/integrator.cpp's integrateExplicit, line for line).
void integrateEuler(const Call& c, const EulerSwitches& w) {
  const float dt = c.z.dt;
  const EveryMethod& e = c.every;
  for (auto* p : c.bodies) {
    if (w.velocity_first) {
      if (e.updates_velocity) p->velocity += increment(p->acceleration, dt, c.z.result_scale);
      if (e.updates_position) p->position += increment(p->velocity, dt, c.z.result_scale);
      continue;
    }
    if (w.position_half_acceleration)
      p->position += p->velocity * dt + p->acceleration * (0.5f * dt * dt);
    else if (e.updates_position)
      p->position += increment(p->velocity, dt, c.z.result_scale);
    if (e.updates_velocity) p->velocity += increment(p->acceleration, dt, c.z.result_scale);
  }
}

// Every reading of an explicit Euler stub on its lines, in the order the prover tries them (the
// first-pass ones in the order the one-step check tries them), after every method's.
// clang-format off
const std::vector<Row<EulerSwitches>>& eulerRows() {
  static const std::vector<Row<EulerSwitches>> table = {
    {cause::kOnlyFirstBody, kE, true, "symplectic Euler on particles[0] (the cloth) only",
     {.velocity_first = true}, {}, std::nullopt, {}, cause::kOnlyFirstBody},
    {cause::kPositionUsesAcceleration, kE, true, "explicit Euler with x += v dt + a dt²/2",
     {.position_half_acceleration = true}},
    {cause::kVelocityNotIntegrated, kE, true, "explicit Euler without the velocity update", {},
     {.updates_velocity = false}},
    {cause::kPositionNotIntegrated, kE, true, "explicit Euler without the position update", {},
     {.updates_position = false}},
    // A variant the rubric may accept (stages::methodTables' `accepted`), which a fitted overlay
    // (particles held still) may follow.
    {"explicit-as-symplectic", kE, false, "symplectic Euler (v first, then x with the new v)",
     {.velocity_first = true}},
  };
  return table;
}
// clang-format on

}  // namespace

const Family& explicitEulerFamily() {
  static const Family rows = familyOf(eulerRows(), integrateEuler);
  return rows;
}

}  // namespace clothref::grader::integrators
