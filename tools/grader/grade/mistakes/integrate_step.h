// The course's step with its lines switchable (the model of every integrator mistake,
// integrate_mistakes.h): the course's main loop step written once, with a switch per line a
// student's mistake changes, each switch's default the course's. Lines say which lines a reading
// changes (its row in integrate_mistakes.cpp); a new kind of line is a switch here and its use in
// integrate_step.cpp, a mistake on existing lines only its row.
#pragma once
#include <array>

#include "grader/grade/mistakes/integrate_mistakes.h"

namespace clothref::grader::integrators {

// The lines of the course's step a mistake changes; the defaults are the course's.
struct Lines {
  // every method
  bool backup_follows_live = false;  // x0, v0 read the live state (a pointer or Eigen::Ref "copy")
  bool reevaluates = true;           // integrate()'s own simulateOneStep() calls (off: explicit)
  bool evaluates_again = false;      // one more simulateOneStep() before an explicit step
  bool per_body = false;             // integrate() on one body at a time, each with its calls
  bool first_body_only = false;      // integrate() on particles[0] (the cloth) only
  bool updates_position = true, updates_velocity = true;  // the result's x and v
  // explicit Euler
  bool position_half_acceleration = false;  // x += v dt + a dt²/2
  bool velocity_first = false;              // v first, then x with the new v (symplectic)
  // the predictor-corrector (implicit h = 1, midpoint h = 1/2)
  bool predictor_full_step = false;         // midpoint's prediction with h = 1
  bool predictor_adds_nothing = false;      // h = 0 (1 / 2 == 0, or kept in locals)
  bool predictor_symplectic = false;        // v first, then x with the new v
  bool evaluates_before_predictor = false;  // simulateOneStep() before the prediction, not after
  bool corrector_new_velocity = false;      // x = x0 + v_new dt
  bool corrector_trapezoidal = false;       // x = x0 + (v0 + v1) dt / 2, v = v0 + (a0 + a1) dt / 2
  bool corrector_start_velocity = false;    // x = x0 + v0 dt
  // RK4
  std::array<float, 3> stage{0.5f, 0.5f, 1.0f};   // stage k + 1's state is x0 + k_k · stage[k]
  bool stage_increment_after_overwrite = false;   // k_k of x read after v = v0 + kv_k · c_k
  bool stage_from_current = false;                // stage k > 1 built on the previous stage
  bool stage_position_from_new_velocity = false;  // stage x = x0 + dt c (v0 + kv c)
  int stage_position_from_kv = -1;                // that stage's (0..2) x adds kv, not kx
  bool result_adds_nothing = false;               // 1 / 6 == 0
  bool result_on_last_stage = false;        // x += ... onto the state the last stage left, not x0
  bool result_position_from_kv = false;     // x0 + (kv1 + 2 kv2 + 2 kv3 + kv4) / 6
  bool result_velocity_k4_from_kx = false;  // v0 + (... + kx4) / 6
  bool result_first_stage_only = false;     // x0 + k1, v0 + k1v
  bool operator==(const Lines&) const = default;
};

// `into` with `from`'s switches that differ from the course's; false when both change one line
// differently.
bool merge(Lines& into, const Lines& from);

// The course's main loop step of `method` with `lines` and `overlay`: simulateOneStep(), then the
// method's integrate() (explicit Euler, the predictor-corrector or RK4), then what the overlay
// lays over it. With the defaults it is core/integrator.cpp's step, operation for operation.
Step linesStep(Method method, const Lines& lines, const Overlay& overlay);

}  // namespace clothref::grader::integrators
