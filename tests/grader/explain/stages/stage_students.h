// Integrator stubs written the way students write them (right, accepted, and each known mistake),
// in float or double, for the stage-fit tests (stages_test.cpp). Each is a generic callable
// (bodies, simulateOneStep, deltaTime) on clothref Particles: the course's integrate() with the
// global deltaTime passed by reference.
#pragma once
#include <functional>
#include <vector>

#include "clothref/core/particles.h"

namespace clothref::test::students {

template <typename T>
using Bodies = std::vector<Particles<T>*>;

enum class Pc {  // implicit (fraction 1) and midpoint (1/2) shapes
  Course,
  VNew,                 // corrector: v first, then x with the new v (accepted)
  SymplecticPredictor,  // predictor: v first, then x (accepted)
  AliasDifference,      // `auto tmp = particles;` then x += (v - tmp.v) dt, v += (a - tmp.a) dt
  SimulateFirst,        // `auto tmp = particles;` simulateOneStep() at the start, then explicit
  AliasLive,            // pointer backup: the corrector starts from the live (predicted) state
  NoSimulate,           // predictor and corrector, simulateOneStep() never called
  Locals,               // the prediction kept in local matrices, evaluated at the start
  Heun,                 // corrector averages the start and predicted derivatives
  HalfCorrector,        // the corrector also takes h/2 (a local h)
  HardCodedStep,        // deltaTime /= 2 for the prediction, then deltaTime = 1e-4f
  PerBody,              // each body alone: predict, simulate, correct
  FirstOnly             // particles[0] only
};

template <typename T>
void predictCorrect(const Bodies<T>& ps, const std::function<void()>& sim, T& dt, T frac, Pc kind) {
  using M = Mat4X<T>;
  if (kind == Pc::PerBody) {
    for (auto* p : ps) {
      const Particles<T> old = *p;
      p->position += p->velocity * dt * frac;
      p->velocity += p->acceleration * dt * frac;
      sim();
      p->position = old.position + p->velocity * dt;
      p->velocity = old.velocity + p->acceleration * dt;
    }
    return;
  }
  Bodies<T> bodies = ps;
  if (kind == Pc::FirstOnly) bodies.resize(1);
  std::vector<M> x0, v0, a0;
  for (auto* p : bodies)
    x0.push_back(p->position), v0.push_back(p->velocity), a0.push_back(p->acceleration);
  if (kind == Pc::SimulateFirst) {
    const Bodies<T> tmp = ps;  // "backup"
    sim();
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      bodies[i]->position +=
          bodies[i]->velocity * dt + (bodies[i]->velocity - tmp[i]->velocity) * dt;
      bodies[i]->velocity += bodies[i]->acceleration * dt;
    }
    return;
  }
  if (kind == Pc::Locals) {
    std::vector<M> midv;
    for (auto* p : bodies) midv.push_back(p->velocity + p->acceleration * dt * frac);
    sim();
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      bodies[i]->position += midv[i] * dt;
      bodies[i]->velocity += bodies[i]->acceleration * dt;
    }
    return;
  }
  const T step = kind == Pc::HardCodedStep ? (dt /= 2) : dt * frac;
  for (auto* p : bodies) {
    if (kind == Pc::SymplecticPredictor) {
      p->velocity += p->acceleration * step;
      p->position += p->velocity * step;
    } else {
      p->position += p->velocity * step;
      p->velocity += p->acceleration * step;
    }
  }
  const Bodies<T> tmp = bodies;  // a pointer "backup" taken late: it follows the live state
  std::vector<M> vt, at;
  for (auto* p : tmp) vt.push_back(p->velocity), at.push_back(p->acceleration);
  if (kind != Pc::NoSimulate) sim();
  if (kind == Pc::HardCodedStep) dt = T(1e-4);
  const T full = kind == Pc::HalfCorrector ? dt * frac : dt;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    Particles<T>& p = *bodies[i];
    switch (kind) {
      case Pc::VNew:
        p.velocity = v0[i] + p.acceleration * full;
        p.position = x0[i] + p.velocity * full;
        break;
      case Pc::AliasDifference:
        p.position += (p.velocity - tmp[i]->velocity) * full;
        p.velocity += (p.acceleration - tmp[i]->acceleration) * full;
        break;
      case Pc::AliasLive: {
        const M v = p.velocity, a = p.acceleration;
        p.position += v * full;  // "*p = *backup" was a self-assignment
        p.velocity += a * full;
        break;
      }
      case Pc::Heun: {
        const M x = x0[i] + (v0[i] + p.velocity) / T(2) * full;
        p.velocity = v0[i] + (a0[i] + p.acceleration) / T(2) * full;
        p.position = x;
        break;
      }
      default: {
        const M x = x0[i] + p.velocity * full;
        p.velocity = v0[i] + p.acceleration * full;
        p.position = x;
      }
    }
  }
}

enum class Rk {
  Course,
  Quarter,          // weights 1/4 each
  IntegerSixth,     // (1 / 6) * (k1 + 2 k2 + 2 k3 + k4): nothing added
  MixedFinal,       // the position adds the velocity k's
  MixedStage,       // stage 2's position adds kv1 / 2
  K4xInVelocity,    // the velocity update adds k4x (h·v3) instead of k4v
  FromCurrent,      // stages from the live (previous stage) state, result from the backup
  Alias,            // Eigen::Ref backup: stages and result from the live state
  FromNewVelocity,  // stage x = x0 + dt c (v0 + kv c)
  Discarded,        // result x0 + k1
  FromV0,           // every position k from v0
  PerBody,          // each body with its own stages
  ThreeEighths,     // the 3/8-rule Runge-Kutta method
  KaoStyle,         // stages from the previous stage, weights 1/8 3/8 3/8 1/8
  HalfStep,         // deltaTime /= 2 at the start, never restored
  HalfStepQuarter,  // deltaTime /= 2 and weights 1/4
  K1ReadLast        // k1 read at the end from the live state: after stage 4, so it is k4
};

template <typename T>
void rungeKutta(const Bodies<T>& ps, const std::function<void()>& sim, T& dt, Rk kind) {
  using M = Mat4X<T>;
  if (kind == Rk::PerBody) {
    for (auto* p : ps) rungeKutta(Bodies<T>{p}, sim, dt, Rk::Course);
    return;
  }
  if (kind == Rk::HalfStep || kind == Rk::HalfStepQuarter) dt /= 2;
  const std::size_t n = ps.size();
  std::vector<M> x0, v0, kx[4], kv[4];
  for (auto* p : ps) x0.push_back(p->position), v0.push_back(p->velocity);
  const bool live = kind == Rk::FromCurrent || kind == Rk::Alias || kind == Rk::KaoStyle;
  const T third = T(1) / T(3);
  for (int s = 0; s < 4; ++s) {
    if (s > 0) sim();
    for (std::size_t i = 0; i < n; ++i) {
      kx[s].push_back((kind == Rk::FromV0 ? v0[i] : ps[i]->velocity) * dt);
      kv[s].push_back(ps[i]->acceleration * dt);
    }
    if (s == 3) break;
    for (std::size_t i = 0; i < n; ++i) {
      Particles<T>& p = *ps[i];
      const M bx = live ? M(p.position) : x0[i], bv = live ? M(p.velocity) : v0[i];
      if (kind == Rk::ThreeEighths) {
        const M dx = s == 0   ? M(kx[0][i] * third)
                     : s == 1 ? M(kx[1][i] - kx[0][i] * third)
                              : M(kx[0][i] - kx[1][i] + kx[2][i]);
        const M dv = s == 0   ? M(kv[0][i] * third)
                     : s == 1 ? M(kv[1][i] - kv[0][i] * third)
                              : M(kv[0][i] - kv[1][i] + kv[2][i]);
        p.position = x0[i] + dx;
        p.velocity = v0[i] + dv;
        continue;
      }
      const T c = s == 2 ? T(1) : T(0.5);
      const M v = bv + kv[s][i] * c;
      if (kind == Rk::FromNewVelocity)
        p.position = bx + dt * v * c;
      else
        p.position = bx + (kind == Rk::MixedStage && s == 1 ? kv[s][i] : kx[s][i]) * c;
      p.velocity = v;
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    Particles<T>& p = *ps[i];
    const M bx = kind == Rk::Alias ? M(p.position) : x0[i],
            bv = kind == Rk::Alias ? M(p.velocity) : v0[i];
    const auto& kxs = kind == Rk::MixedFinal ? kv : kx;
    if (kind == Rk::Discarded) {
      p.position = bx + kx[0][i];
      p.velocity = bv + kv[0][i];
    } else if (kind == Rk::Quarter || kind == Rk::HalfStepQuarter) {
      p.position = bx + (kxs[0][i] + kxs[1][i] + kxs[2][i] + kxs[3][i]) / T(4);
      p.velocity = bv + (kv[0][i] + kv[1][i] + kv[2][i] + kv[3][i]) / T(4);
    } else if (kind == Rk::ThreeEighths || kind == Rk::KaoStyle) {
      p.position = bx + (kxs[0][i] + T(3) * kxs[1][i] + T(3) * kxs[2][i] + kxs[3][i]) / T(8);
      p.velocity = bv + (kv[0][i] + T(3) * kv[1][i] + T(3) * kv[2][i] + kv[3][i]) / T(8);
    } else if (kind == Rk::K1ReadLast) {
      // `(particles[i]->velocity() * deltaTime + 2 * k2x[i] + ...) / 6`, the velocity likewise
      // (updated after the position, from the acceleration the state still holds)
      p.position = bx + (p.velocity * dt + T(2) * kx[1][i] + T(2) * kx[2][i] + kx[3][i]) / T(6);
      p.velocity = bv + (p.acceleration * dt + T(2) * kv[1][i] + T(2) * kv[2][i] + kv[3][i]) / T(6);
    } else {
      const T sixth = kind == Rk::IntegerSixth ? T(1 / 6) : T(1) / T(6);
      p.position = bx + (kxs[0][i] + T(2) * kxs[1][i] + T(2) * kxs[2][i] + kxs[3][i]) * sixth;
      const M& kv4 = kind == Rk::K4xInVelocity ? kx[3][i] : kv[3][i];
      p.velocity = bv + (kv[0][i] + T(2) * kv[1][i] + T(2) * kv[2][i] + kv4) * sixth;
    }
  }
}

enum class Ex { Course, Symplectic, Taylor, PositionOnly, VelocityOnly, FirstOnly, Damped };

template <typename T>
void explicitEuler(const Bodies<T>& ps, T dt, Ex kind) {
  for (auto* p : ps) {
    if (kind == Ex::FirstOnly && p != ps[0]) continue;
    if (kind == Ex::Symplectic) {
      p->velocity += p->acceleration * dt;
      p->position += p->velocity * dt;
      continue;
    }
    if (kind == Ex::Taylor)
      p->position += p->velocity * dt + p->acceleration * (T(0.5) * dt * dt);
    else if (kind != Ex::VelocityOnly)
      p->position += p->velocity * dt;
    if (kind != Ex::PositionOnly) p->velocity += p->acceleration * dt;
    // damping added by hand (pan's 0.999 is 1 - h/10 at the round step h = 0.01: a combination)
    if (kind == Ex::Damped) p->velocity *= T(0.9987);
  }
}

}  // namespace clothref::test::students
