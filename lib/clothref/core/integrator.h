// Integrators: stubs 5 to 8 of the course (explicit, implicit, midpoint, RK4) and the symplectic
// Euler variant many students write as their explicit Euler.
//
// Each acts on every body in `bodies` (the course's std::vector<Particles*>: cloth first, then
// spheres) and expects the accelerations, impulses and corrections of the current state to exist
// already: the step calls simulateOneStep() once before integrate(), as the course's main loop
// does. Methods that need more derivatives call `simulateOneStep` again on a modified state.
#pragma once

#include <span>
#include <string_view>
#include <vector>

#include "clothref/base/function_ref.h"
#include "clothref/core/method.h"
#include "clothref/core/particles.h"

namespace clothref {

// The bodies an integrator acts on.
template <typename T>
using Bodies = std::span<Particles<T>* const>;

// Backups and stage derivatives of one body, kept between steps so a step allocates nothing.
template <typename T>
struct BodyScratch {
  Mat4X<T> x0, v0;        // state at the start of the step
  Mat4X<T> kx[4], kv[4];  // RK4 stage increments v * dt and a * dt
};

// One BodyScratch per body, sized on first use.
template <typename T>
using IntegratorScratch = std::vector<BodyScratch<T>>;

// Forward Euler: x += v * dt, then v += a * dt (the position uses the old velocity).
template <typename T>
void integrateExplicit(Bodies<T> bodies, T dt);

// Symplectic (semi-implicit) Euler: v += a * dt, then x += v * dt.
template <typename T>
void integrateSymplectic(Bodies<T> bodies, T dt);

// The course's "implicit" Euler: one predictor-corrector pass, not a backward-Euler solve.
// Predict x = x0 + v0 dt, v = v0 + a0 dt; simulateOneStep(); then x = x0 + v dt, v = v0 + a dt
// with v and a read at the predicted state (after any collision there).
template <typename T>
void integrateImplicit(Bodies<T> bodies, T dt, FunctionRef<void()> simulateOneStep,
                       IntegratorScratch<T>& scratch);

// The course's midpoint: predict with (v dt) * 0.5 and (a dt) * 0.5, simulateOneStep(), then
// x = x0 + v dt, v = v0 + a dt at the midpoint state.
template <typename T>
void integrateMidpoint(Bodies<T> bodies, T dt, FunctionRef<void()> simulateOneStep,
                       IntegratorScratch<T>& scratch);

// Classical RK4 as the course writes it: k = (v dt, a dt) at x0, x0 + k1 / 2, x0 + k2 / 2,
// x0 + k3; then x = x0 + (k1 + 2 k2 + 2 k3 + k4) / 6, and the same for v.
template <typename T>
void integrateRk4(Bodies<T> bodies, T dt, FunctionRef<void()> simulateOneStep,
                  IntegratorScratch<T>& scratch);

// Dispatches to one of the above (a method stepped by the solver is not stepped here: World::step
// calls its MethodStepper).
template <typename T>
void integrate(Method method, Bodies<T> bodies, T dt, FunctionRef<void()> simulateOneStep,
               IntegratorScratch<T>& scratch);

}  // namespace clothref
