// The integrator mistakes as switches on one course step (integrate_mistakes.h).
#include "grader/grade/mistakes/integrate_mistakes.h"

namespace clothref::grader::integrators {
namespace {

// The start state of `bodies`: a copy, or with `alias` the live state (what a pointer or
// Eigen::Ref "copy" reads later).
struct Backup {
  Backup(const std::vector<Particles<float>*>& of, bool alias_live)
      : bodies(of), alias(alias_live) {
    for (auto* p : bodies) x0.push_back(p->position), v0.push_back(p->velocity);
  }
  Mat4X<float> x(std::size_t b) const { return alias ? bodies[b]->position : x0[b]; }
  Mat4X<float> v(std::size_t b) const { return alias ? bodies[b]->velocity : v0[b]; }
  const std::vector<Particles<float>*>& bodies;
  bool alias;
  std::vector<Mat4X<float>> x0, v0;
};

// The course's explicit Euler (core/integrator.cpp's integrateExplicit, line for line).
void explicitEuler(System& s, const std::vector<Particles<float>*>& bodies, const StepSwitches& w) {
  const float dt = s.dt;
  for (auto* p : bodies) {
    if (w.position_half_acceleration)
      p->position += p->velocity * dt + p->acceleration * (0.5f * dt * dt);
    else if (w.updates_position)
      p->position += p->velocity * dt;
    if (w.updates_velocity) p->velocity += p->acceleration * dt;
  }
}

// The course's predictor-corrector (implicit h = 1, midpoint h = 1/2: core/integrator.cpp's
// predictEvaluateCorrect, operation for operation) for `bodies` only; the others keep their state.
void predictCorrect(System& s, const std::vector<Particles<float>*>& bodies, float h,
                    const StepSwitches& w) {
  const float dt = s.dt;
  const Backup backup(bodies, w.backup_follows_live);
  if (w.evaluates_before_predictor) simulate(s);
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
  if (!w.evaluates_before_predictor) simulate(s);
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    auto* p = bodies[b];
    if (w.corrector_new_velocity) {
      p->velocity = backup.v(b) + p->acceleration * dt;
      p->position = backup.x(b) + p->velocity * dt;
    } else {
      const Mat4X<float> x = backup.x(b) + p->velocity * dt;
      p->velocity = backup.v(b) + p->acceleration * dt;
      p->position = x;
    }
  }
}

// The course's RK4 (core/integrator.cpp's integrateRk4, operation for operation) for `bodies`
// only.
void rungeKutta(System& s, const std::vector<Particles<float>*>& bodies, const StepSwitches& w) {
  const float dt = s.dt;
  const Backup backup(bodies, w.backup_follows_live);
  std::vector<Mat4X<float>> kx[4], kv[4];
  const float stage[] = {0.5f, 0.5f, 1.0f};
  for (int k = 0; k < 4; ++k) {
    if (k > 0) simulate(s);
    for (auto* p : bodies) kx[k].push_back(p->velocity * dt), kv[k].push_back(p->acceleration * dt);
    if (k == 3) break;
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      const bool current = w.stage_from_current && k > 0;
      const Mat4X<float> x = current ? bodies[b]->position : backup.x(b);
      const Mat4X<float> v = current ? bodies[b]->velocity : backup.v(b);
      bodies[b]->velocity = v + kv[k][b] * stage[k];
      if (w.stage_position_from_new_velocity)
        bodies[b]->position = x + (bodies[b]->velocity * dt) * stage[k];
      else
        bodies[b]->position = x + (w.stage_position_from_kv == k ? kv[k][b] : kx[k][b]) * stage[k];
    }
  }
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const Mat4X<float> x = w.result_on_last_stage ? bodies[b]->position : backup.x(b);
    const Mat4X<float> v = w.result_on_last_stage ? bodies[b]->velocity : backup.v(b);
    if (w.result_first_stage_only) {
      bodies[b]->position = x + kx[0][b];
      bodies[b]->velocity = v + kv[0][b];
      continue;
    }
    const float weight = w.result_adds_nothing ? 0.0f : 1.0f;
    const auto& kxs = w.result_position_from_kv ? kv : kx;
    const Mat4X<float>& kv4 = w.result_velocity_k4_from_kx ? kx[3][b] : kv[3][b];
    bodies[b]->position =
        x + (kxs[0][b] + 2.0f * kxs[1][b] + 2.0f * kxs[2][b] + kxs[3][b]) / 6.0f * weight;
    bodies[b]->velocity = v + (kv[0][b] + 2.0f * kv[1][b] + 2.0f * kv[2][b] + kv4) / 6.0f * weight;
  }
}

}  // namespace

Step courseStep(Method method, const StepSwitches& switches) {
  return [method, switches](System& s) {
    std::vector<Particles<float>*> bodies{&s.cloth.particles, &s.spheres.particles};
    simulate(s);
    if (method == Method::Explicit || !switches.reevaluates) {
      explicitEuler(s, bodies, switches);
      return;
    }
    // A per-body loop: each body alone, later bodies after the earlier ones have moved; the
    // first body uses the derivatives evaluated before integrate(), each later one those of the
    // previous body's last simulateOneStep().
    std::vector<std::vector<Particles<float>*>> groups;
    if (switches.per_body)
      for (auto* p : bodies) groups.push_back({p});
    else
      groups.push_back(bodies);
    for (const auto& group : groups) {
      if (method == Method::Implicit || method == Method::Midpoint)
        predictCorrect(s, group, method == Method::Midpoint ? 0.5f : 1.0f, switches);
      else
        rungeKutta(s, group, switches);
    }
  };
}

StepSwitches switchesOf(Variant variant, int stage_index) {
  StepSwitches w;
  switch (variant) {
    case Variant::None:
      break;
    case Variant::ImplicitVNew:
      w.corrector_new_velocity = true;
      break;
    case Variant::SymplecticPredictor:
      w.predictor_symplectic = true;
      break;
    case Variant::Alias:
      w.backup_follows_live = true;
      break;
    case Variant::NoReevaluation:
      w.reevaluates = false;
      break;
    case Variant::NoReevaluationHalfVelocity:
      w.evaluates_before_predictor = true;
      break;
    case Variant::ZeroHalfStep:
      w.predictor_adds_nothing = true;
      break;
    case Variant::PerBody:
      w.per_body = true;
      break;
    case Variant::RkIntDivision:
      w.result_adds_nothing = true;
      break;
    case Variant::RkIntDivisionOnLastStage:
      w.result_adds_nothing = w.result_on_last_stage = true;
      break;
    case Variant::RkMixedFinal:
      w.result_position_from_kv = true;
      break;
    case Variant::RkK4xInVelocity:
      w.result_velocity_k4_from_kx = true;
      break;
    case Variant::RkMixedStage:
      w.stage_position_from_kv = stage_index;
      break;
    case Variant::RkStageFromCurrent:
      w.stage_from_current = true;
      break;
    case Variant::RkStageFromNewVelocity:
      w.stage_position_from_new_velocity = true;
      break;
    case Variant::RkStagesDiscarded:
      w.result_first_stage_only = true;
      break;
    case Variant::PositionUsesAcceleration:
      w.position_half_acceleration = true;
      break;
    case Variant::VelocityOnly:
      w.updates_position = false;
      break;
    case Variant::PositionOnly:
      w.updates_velocity = false;
      break;
  }
  return w;
}

Step variantStep(Method method, Variant variant, int stage_index) {
  return courseStep(method, switchesOf(variant, stage_index));
}

std::vector<std::pair<std::string, Step>> acceptedVariants(const Rubric& rubric, Method method) {
  std::vector<std::pair<std::string, Step>> accepted;
  if (method == Method::Explicit && rubric.accepts("explicit-as-symplectic"))
    accepted.push_back({"explicit written as symplectic Euler (v first, then x with the new v)",
                        clothrefStep(Method::Symplectic)});
  if (method == Method::Implicit && rubric.accepts("implicit-corrector-v-new"))
    accepted.push_back({"the corrector's position uses the new velocity",
                        variantStep(Method::Implicit, Variant::ImplicitVNew)});
  if ((method == Method::Implicit || method == Method::Midpoint) &&
      rubric.accepts("symplectic-predictor"))
    accepted.push_back(
        {"the predictor written as symplectic Euler (v first, then x with the new v)",
         variantStep(method, Variant::SymplecticPredictor)});
  return accepted;
}

}  // namespace clothref::grader::integrators
