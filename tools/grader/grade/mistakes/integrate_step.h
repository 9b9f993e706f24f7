// The course's step with its lines switchable (the model of every integrator mistake,
// integrate_mistakes.h): the course's main loop step written once, with a switch per line a
// student's mistake changes, each switch's default the course's, and the Overlay a fitted model
// lays over it. Lines say which lines a reading changes (its row in integrate_mistakes.cpp); a
// new kind of line is a switch here and its use in integrate_step.cpp, a mistake on existing lines
// only its row.
#pragma once
#include <array>
#include <optional>
#include <vector>

#include "grader/grade/mistakes/system.h"

namespace clothref::grader::integrators {

// Cloth particles a step holds still, on cloths of one size (code that pins hard-coded indices
// only on the course's 25 x 25 cloth leaves the small probe cloth alone).
struct Pins {
  int cloth_size = 0;  // particles of the cloths they apply to
  std::vector<int> particles;
  bool positions = false;  // put back where they were, not only stopped
};

// `pinned` (those of s's cloth size) and `spheres` held still in `s` after a step that began at
// cloth positions `cloth_x0` (after the first simulateOneStep()).
void holdStill(const std::vector<Pins>& pinned, const std::vector<int>& spheres, System& s,
               const Mat4X<float>& cloth_x0);

// What a model fits from the student's numbers, laid over the step's lines; the defaults change
// nothing.
struct Overlay {
  double step = 1;         // every h of the call is step x deltaTime (deltaTime scaled before it)
  double result_step = 1;  // the result's (corrector's) terms at result_step x h
  // The result's terms at this deltaTime, whatever the call's (a constant the stub restored
  // deltaTime to before its corrector, e.g. `deltaTime = 0.0001f;`).
  std::optional<float> result_dt{};
  // RK4's result weights on k1..k4 of x (positions) and of v (velocities), replacing
  // 1/6, 1/3, 1/3, 1/6; empty: the course's.
  std::vector<double> weights_x{}, weights_v{};
  std::array<double, 2> velocity_factor{1, 1};  // each body's velocity times this after the step
  std::vector<Pins> pinned{};                   // cloth particles held still after the step
  std::vector<int> pinned_spheres{};            // spheres whose velocity is zeroed after the step
  // ... and after each stage state is written, before its simulateOneStep() (a helper called in
  // the stage loop too)
  bool pins_at_stages = false;
  std::optional<double> dt_after_factor{};  // deltaTime x this after the call
  std::optional<float> dt_after{};          // or this constant
};

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
  bool result_k4x_after_velocity = false;   // v first, then x's k4 read as v_new dt
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
