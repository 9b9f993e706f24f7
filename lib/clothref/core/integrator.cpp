#include "clothref/core/integrator.h"

#include <cstddef>

namespace clothref {

namespace {

// Copies x and v of every body into its scratch (no allocation once sized).
template <typename T>
void backUp(Bodies<T> bodies, IntegratorScratch<T>& scratch) {
  scratch.resize(bodies.size());
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    scratch[b].x0 = bodies[b]->position;
    scratch[b].v0 = bodies[b]->velocity;
  }
}

// The predictor/corrector shape shared by implicit and midpoint: predict with `fraction` of the
// step, evaluate there, then take the full step from x0, v0 with the derivatives just evaluated.
template <typename T>
void predictEvaluateCorrect(Bodies<T> bodies, T dt, bool half_step,
                            FunctionRef<void()> simulateOneStep, IntegratorScratch<T>& scratch) {
  backUp(bodies, scratch);
  for (Particles<T>* p : bodies) {
    if (half_step) {
      p->position += p->velocity * dt * T(0.5);
      p->velocity += p->acceleration * dt * T(0.5);
    } else {
      p->position += p->velocity * dt;
      p->velocity += p->acceleration * dt;
    }
  }
  simulateOneStep();
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    Particles<T>& p = *bodies[b];
    p.position = scratch[b].x0 + p.velocity * dt;
    p.velocity = scratch[b].v0 + p.acceleration * dt;
  }
}

}  // namespace

template <typename T>
void integrateExplicit(Bodies<T> bodies, T dt) {
  for (Particles<T>* p : bodies) {
    p->position += p->velocity * dt;
    p->velocity += p->acceleration * dt;
  }
}

template <typename T>
void integrateSymplectic(Bodies<T> bodies, T dt) {
  for (Particles<T>* p : bodies) {
    p->velocity += p->acceleration * dt;
    p->position += p->velocity * dt;
  }
}

template <typename T>
void integrateImplicit(Bodies<T> bodies, T dt, FunctionRef<void()> simulateOneStep,
                       IntegratorScratch<T>& scratch) {
  predictEvaluateCorrect(bodies, dt, false, simulateOneStep, scratch);
}

template <typename T>
void integrateMidpoint(Bodies<T> bodies, T dt, FunctionRef<void()> simulateOneStep,
                       IntegratorScratch<T>& scratch) {
  predictEvaluateCorrect(bodies, dt, true, simulateOneStep, scratch);
}

template <typename T>
void integrateRk4(Bodies<T> bodies, T dt, FunctionRef<void()> simulateOneStep,
                  IntegratorScratch<T>& scratch) {
  backUp(bodies, scratch);
  // stage s reads the derivatives of the current state, then moves every body to the next
  // stage state x0 + k * weight (weight 0.5, 0.5, 1); the last stage only records k4
  constexpr T kStageWeight[3] = {T(0.5), T(0.5), T(1)};
  for (int stage = 0; stage < 4; ++stage) {
    if (stage > 0) simulateOneStep();
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      Particles<T>& p = *bodies[b];
      BodyScratch<T>& s = scratch[b];
      s.kx[stage] = p.velocity * dt;
      s.kv[stage] = p.acceleration * dt;
      if (stage == 3) continue;
      if (stage == 2) {
        p.position = s.x0 + s.kx[stage];
        p.velocity = s.v0 + s.kv[stage];
      } else {
        p.position = s.x0 + s.kx[stage] * kStageWeight[stage];
        p.velocity = s.v0 + s.kv[stage] * kStageWeight[stage];
      }
    }
  }
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    Particles<T>& p = *bodies[b];
    const BodyScratch<T>& s = scratch[b];
    p.position = s.x0 + (s.kx[0] + T(2) * s.kx[1] + T(2) * s.kx[2] + s.kx[3]) / T(6);
    p.velocity = s.v0 + (s.kv[0] + T(2) * s.kv[1] + T(2) * s.kv[2] + s.kv[3]) / T(6);
  }
}

template <typename T>
void integrate(Method method, Bodies<T> bodies, T dt, FunctionRef<void()> simulateOneStep,
               IntegratorScratch<T>& scratch) {
  switch (method) {
    case Method::Explicit:
      return integrateExplicit(bodies, dt);
    case Method::Symplectic:
      return integrateSymplectic(bodies, dt);
    case Method::Implicit:
      return integrateImplicit(bodies, dt, simulateOneStep, scratch);
    case Method::Midpoint:
      return integrateMidpoint(bodies, dt, simulateOneStep, scratch);
    case Method::Rk4:
      return integrateRk4(bodies, dt, simulateOneStep, scratch);
    case Method::BackwardEuler:  // stepped by World::stepper (clothref/solver), never from here
      return;
  }
}

#define CLOTHREF_INSTANTIATE(T)                                                              \
  template void integrateExplicit(Bodies<T>, T);                                             \
  template void integrateSymplectic(Bodies<T>, T);                                           \
  template void integrateImplicit(Bodies<T>, T, FunctionRef<void()>, IntegratorScratch<T>&); \
  template void integrateMidpoint(Bodies<T>, T, FunctionRef<void()>, IntegratorScratch<T>&); \
  template void integrateRk4(Bodies<T>, T, FunctionRef<void()>, IntegratorScratch<T>&);      \
  template void integrate(Method, Bodies<T>, T, FunctionRef<void()>, IntegratorScratch<T>&);
CLOTHREF_INSTANTIATE(float)
CLOTHREF_INSTANTIATE(double)
#undef CLOTHREF_INSTANTIATE

}  // namespace clothref
