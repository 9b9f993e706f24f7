// RK4's lines of the course's step (integrate_step.h): its switches, its integrate() and the
// readings of its mistakes. A new mistake here is its row; a new line its switch in Rk4Switches,
// its use in rungeKutta and its row.
#include <cmath>

#include "grader/grade/cause_ids.h"
#include "grader/grade/mistakes/integrate_step.h"

namespace clothref::grader::integrators {
namespace {

// The lines of RK4 a mistake changes; the defaults are the course's.
struct Rk4Switches {
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
};

// The rational weight of a fitted RK4 result (a small rational: 1/720 steps).
float weight(double w, float scale) {
  return float(double(std::lround(w * 720)) / 720 * double(scale));
}

// The course's RK4 (core/integrator.cpp's integrateRk4, operation for operation) for the call's
// bodies only.
void rungeKutta(const Call& c, const Rk4Switches& w) {
  System& s = c.s;
  const auto& bodies = c.bodies;
  const Sizes& z = c.z;
  const Overlay& o = c.o;
  const float dt = z.dt;
  const Backup backup(bodies, c.every.backup_follows_live);
  // vk, ak: the velocity and acceleration each kx, kv was read from
  std::vector<Mat4X<float>> kx[4], kv[4], vk[4], ak[4];
  const float node[] = {0.5f, 0.5f, 1.0f};  // stage k + 1's time, in h
  for (int k = 0; k < 4; ++k) {
    if (k > 0) simulate(s);
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      auto* p = bodies[b];
      if (w.stage_increment_after_overwrite && k > 0)
        p->velocity = backup.v(b) + (p->acceleration * dt) * node[k - 1];
      vk[k].push_back(p->velocity), ak[k].push_back(p->acceleration);
      kx[k].push_back(p->velocity * dt), kv[k].push_back(p->acceleration * dt);
    }
    if (k == 3) break;
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      const bool current = w.stage_from_current && k > 0;
      const Mat4X<float> x = current ? bodies[b]->position : backup.x(b);
      const Mat4X<float> v = current ? bodies[b]->velocity : backup.v(b);
      bodies[b]->velocity = v + kv[k][b] * w.stage[std::size_t(k)];
      if (w.stage_position_from_new_velocity)
        bodies[b]->position = x + (bodies[b]->velocity * dt) * w.stage[std::size_t(k)];
      else
        bodies[b]->position =
            x + (w.stage_position_from_kv == k ? kv[k][b] : kx[k][b]) * w.stage[std::size_t(k)];
    }
    c.at_stage();
  }
  // The result's increments at the result's h.
  if (z.result_dt != dt)
    for (int k = 0; k < 4; ++k)
      for (std::size_t b = 0; b < bodies.size(); ++b) {
        kx[k][b] = vk[k][b] * z.result_dt;
        kv[k][b] = ak[k][b] * z.result_dt;
      }
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const Mat4X<float> x = w.result_on_last_stage ? bodies[b]->position : backup.x(b);
    const Mat4X<float> v = w.result_on_last_stage ? bodies[b]->velocity : backup.v(b);
    if (w.result_first_stage_only) {
      bodies[b]->position = x + kx[0][b];
      bodies[b]->velocity = v + kv[0][b];
      continue;
    }
    const float factor = (w.result_adds_nothing ? 0.0f : 1.0f) * z.result_scale;
    const auto& kxs = w.result_position_from_kv ? kv : kx;
    const Mat4X<float>& kv4 = w.result_velocity_k4_from_kx ? kx[3][b] : kv[3][b];
    Mat4X<float> nv = v + (kv[0][b] + 2.0f * kv[1][b] + 2.0f * kv[2][b] + kv4) / 6.0f * factor;
    // x's k4 read from the live velocity after v was updated: v_new dt
    const Mat4X<float> kx4 =
        w.result_k4x_after_velocity ? Mat4X<float>(nv * z.result_dt) : Mat4X<float>(kxs[3][b]);
    Mat4X<float> nx = x + (kxs[0][b] + 2.0f * kxs[1][b] + 2.0f * kxs[2][b] + kx4) / 6.0f * factor;
    // Fitted weights, term by term (x0 + w1 k1 + ...; a zero weight adds nothing).
    if (!o.weights_x.empty()) {
      nx = x;
      for (std::size_t k = 0; k < 4 && k < o.weights_x.size(); ++k)
        if (o.weights_x[k] != 0) nx += kx[k][b] * weight(o.weights_x[k], z.result_scale);
    }
    if (!o.weights_v.empty()) {
      nv = v;
      for (std::size_t k = 0; k < 4 && k < o.weights_v.size(); ++k)
        if (o.weights_v[k] != 0) nv += kv[k][b] * weight(o.weights_v[k], z.result_scale);
    }
    bodies[b]->position = c.every.updates_position ? nx : backup.x(b);
    bodies[b]->velocity = c.every.updates_velocity ? nv : backup.v(b);
  }
}

// Every reading of an RK4 stub on its lines, in the order the prover tries them (the first-pass
// ones in the order the one-step check tries them), after every method's.
// clang-format off
const std::vector<Row<Rk4Switches>>& rk4Rows() {
  static const std::vector<Row<Rk4Switches>> table = {
    {cause::kIntegerDivisionRk4, kR, true, "the course's RK4 with 1 / 6 = 0 in the update",
     {.result_adds_nothing = true}},
    {cause::kIntegerDivisionRk4, kR, false,
     "the course's RK4 with 1 / 6 = 0 in an update added (+=) to the state the last stage left",
     {.result_adds_nothing = true, .result_on_last_stage = true}},
    {cause::kRk4MixedIncrements, kR, true,
     "the course's RK4 whose position update adds the velocity k's",
     {.result_position_from_kv = true}},
    {cause::kRk4MixedIncrements, kR, true, "the course's RK4 whose velocity update takes k4 of x",
     {.result_velocity_k4_from_kx = true}},
    {cause::kRk4MixedIncrements, kR, true,
     "the course's RK4 whose stage 2 position adds a velocity k", {.stage_position_from_kv = 0}},
    {cause::kRk4MixedIncrements, kR, true,
     "the course's RK4 whose stage 3 position adds a velocity k", {.stage_position_from_kv = 1}},
    {cause::kRk4MixedIncrements, kR, true,
     "the course's RK4 whose stage 4 position adds a velocity k", {.stage_position_from_kv = 2}},
    {cause::kRk4MixedIncrements, kR, true,
     "the course's RK4 whose position update reads k4 after the velocity update (v_new·h)",
     {.result_k4x_after_velocity = true}},
    {cause::kRk4StageNotFromBackup, kR, true,
     "the course's RK4 with each stage built on the previous stage instead of the backup",
     {.stage_from_current = true}},
    {cause::kRk4StageFromWrongIncrement, kR, true,
     "the course's RK4 with each stage position from that stage's new velocity",
     {.stage_position_from_new_velocity = true}},
    // Each increment read after the velocity was overwritten with v0 + c·h·a_k of its own stage:
    // the stage positions x0 + c·h·(v0 + c'·h·a_k), the update's k's (v0 + c'·h·a_k)·h.
    {cause::kRk4StageFromWrongIncrement, kR, false,
     "the course's RK4 with each position increment read after the stage's velocity was "
     "overwritten with v0 + c·h·a of that stage",
     {.stage_increment_after_overwrite = true}},
    {cause::kRk4StagesDiscarded, kR, true, "the course's RK4 whose update uses k1 only",
     {.result_first_stage_only = true}},
    {cause::kRk4FourthStageHalfStep, kR, true,
     "the course's RK4 whose fourth stage is taken from a half step (x0 + k3/2, v0 + k3v/2)",
     {.stage = {0.5f, 0.5f, 0.5f}}},
  };
  return table;
}
// clang-format on

}  // namespace

const Family& rungeKutta4Family() {
  static const Family rows = familyOf(rk4Rows(), rungeKutta);
  return rows;
}

}  // namespace clothref::grader::integrators
