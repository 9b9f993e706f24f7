// The integrator probe's mistake simulators (integrate_mistakes.h).
#include "grader/grade/mistakes/integrate_mistakes.h"

#include <array>

#include "clothref/core/integrator.h"

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

// The course's predictor-corrector (implicit h = 1, midpoint h = 1/2) for `bodies` only; the
// others keep their state (a per-body loop). With Variant::None it is the library's
// integrateImplicit / integrateMidpoint, operation for operation.
void predictCorrect(System& s, const std::vector<Particles<float>*>& bodies, float h,
                    Variant variant) {
  const float dt = s.dt;
  const Backup backup(bodies, variant == Variant::Alias);
  const auto X0 = [&](std::size_t b) { return backup.x(b); };
  const auto V0 = [&](std::size_t b) { return backup.v(b); };
  if (variant == Variant::NoReevaluationHalfVelocity) simulate(s);
  if (variant == Variant::ZeroHalfStep) h = 0;
  for (auto* p : bodies) {
    if (variant == Variant::SymplecticPredictor) {
      p->velocity += (p->acceleration * dt) * h;
      p->position += (p->velocity * dt) * h;
    } else {
      p->position += (p->velocity * dt) * h;
      p->velocity += (p->acceleration * dt) * h;
    }
  }
  if (variant != Variant::NoReevaluationHalfVelocity) simulate(s);
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    auto* p = bodies[b];
    if (variant == Variant::ImplicitVNew) {
      p->velocity = V0(b) + p->acceleration * dt;
      p->position = X0(b) + p->velocity * dt;
    } else {
      const Mat4X<float> x = X0(b) + p->velocity * dt;
      p->velocity = V0(b) + p->acceleration * dt;
      p->position = x;
    }
  }
}

// RK4 in the course's form for `bodies` only, with one mistake switched on (Variant::None: the
// library's integrateRk4, operation for operation).
void rungeKutta(System& s, const std::vector<Particles<float>*>& bodies, Variant variant,
                int stage_index) {
  const float dt = s.dt;
  const Backup backup(bodies, variant == Variant::Alias);
  const auto X0 = [&](std::size_t b) { return backup.x(b); };
  const auto V0 = [&](std::size_t b) { return backup.v(b); };
  std::vector<Mat4X<float>> kx[4], kv[4];
  const float stage[] = {0.5f, 0.5f, 1.0f};
  for (int k = 0; k < 4; ++k) {
    if (k > 0) simulate(s);
    for (auto* p : bodies) kx[k].push_back(p->velocity * dt), kv[k].push_back(p->acceleration * dt);
    if (k == 3) break;
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      const bool current = variant == Variant::RkStageFromCurrent && k > 0;
      const Mat4X<float> x = current ? bodies[b]->position : X0(b);
      const Mat4X<float> v = current ? bodies[b]->velocity : V0(b);
      const bool mixed = variant == Variant::RkMixedStage && stage_index == k;
      bodies[b]->velocity = v + kv[k][b] * stage[k];
      if (variant == Variant::RkStageFromNewVelocity)
        bodies[b]->position = x + (bodies[b]->velocity * dt) * stage[k];
      else
        bodies[b]->position = x + (mixed ? kv[k][b] : kx[k][b]) * stage[k];
    }
  }
  // `x += (1 / 6) * (...)` adds to the state the last stage left, not to the backup.
  const bool on_last_stage = variant == Variant::RkIntDivisionOnLastStage;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const Mat4X<float> x = on_last_stage ? bodies[b]->position : X0(b);
    const Mat4X<float> v = on_last_stage ? bodies[b]->velocity : V0(b);
    if (variant == Variant::RkStagesDiscarded) {
      bodies[b]->position = x + kx[0][b];
      bodies[b]->velocity = v + kv[0][b];
      continue;
    }
    const float w = variant == Variant::RkIntDivision || on_last_stage ? 0.0f : 1.0f;
    const auto& kxs = variant == Variant::RkMixedFinal ? kv : kx;
    const Mat4X<float>& kv4 = variant == Variant::RkK4xInVelocity ? kx[3][b] : kv[3][b];
    bodies[b]->position =
        x + (kxs[0][b] + 2.0f * kxs[1][b] + 2.0f * kxs[2][b] + kxs[3][b]) / 6.0f * w;
    bodies[b]->velocity = v + (kv[0][b] + 2.0f * kv[1][b] + 2.0f * kv[2][b] + kv4) / 6.0f * w;
  }
}

}  // namespace

Step variantStep(Method method, Variant variant, int stage_index) {
  return [method, variant, stage_index](System& s) {
    std::vector<Particles<float>*> bodies{&s.cloth.particles, &s.spheres.particles};
    const float dt = s.dt;
    simulate(s);
    if (variant == Variant::NoReevaluation ||
        (method == Method::Explicit && variant == Variant::None)) {
      integrateExplicit(Bodies<float>(bodies.data(), bodies.size()), dt);
      return;
    }
    if (method == Method::Explicit) {
      for (auto* p : bodies) {
        if (variant == Variant::PositionUsesAcceleration)
          p->position += p->velocity * dt + p->acceleration * (0.5f * dt * dt);
        else if (variant != Variant::VelocityOnly)
          p->position += p->velocity * dt;
        if (variant != Variant::PositionOnly) p->velocity += p->acceleration * dt;
      }
      return;
    }
    // A per-body loop: each body alone, later bodies after the earlier ones have moved.
    std::vector<std::vector<Particles<float>*>> groups;
    if (variant == Variant::PerBody)
      for (auto* p : bodies) groups.push_back({p});
    else
      groups.push_back(bodies);
    for (std::size_t g = 0; g < groups.size(); ++g) {
      // A per-body loop's first body uses the derivatives evaluated before integrate(); each later
      // one those of the previous body's last simulateOneStep().
      if (method == Method::Implicit || method == Method::Midpoint)
        predictCorrect(s, groups[g], method == Method::Midpoint ? 0.5f : 1.0f, variant);
      else
        rungeKutta(s, groups[g], variant, stage_index);
    }
  };
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
