// World: one simulation, the state of every body plus the parameters its step uses. Two worlds
// share nothing, so any number can run in one process (the course's Spheres singleton is gone).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "clothref/core/cloth.h"
#include "clothref/core/integrator.h"
#include "clothref/core/spheres.h"
#include "clothref/fast/grid_springs.h"
#include "clothref/fast/sphere_cloth_contacts.h"

namespace clothref {

// The scene's parameters in the world's precision.
template <typename T>
struct Physics {
  T dt = T(0);
  Vec4<T> gravity = Vec4<T>::Zero();  // w = 0
  T viscous_coef = T(0);
  bool sphere_external_force = false;
  bool sphere_sphere_collision = false;
  T restitution_cloth = T(0);
  T restitution_sphere = T(0);
  T correction = T(0);
};

// The 2024 course program's per-frame work, done before the first step of every frame.
//   steps_per_frame  0 = none (the 2022 loop)
//   sphere_velocity  4-vector, w = 0, metres / second, given to sphere 0 (setVelocity(0, vel))
//   pinned           cloth particle indices given mass 0 and zero velocity and acceleration
template <typename T>
struct FrameLoop {
  int steps_per_frame = 0;
  Vec4<T> sphere_velocity = Vec4<T>::Zero();
  std::vector<int> pinned;
};

// How a world's step runs: the fast kernels (clothref/fast) or the course-form loops alone. The
// results are the same bits either way; only the speed differs.
template <typename T>
struct Execution {
  bool use_fast = true;  // false: the course-form loops only (the oracle)
  fast::SimdPath simd = fast::defaultSimdPath();
  int threads = 1;    // spring sweep threads; only grids of N >= 100 use more
  bool grid = false;  // the cloth's springs are the course grid's stencils
  fast::GridSpringWorkspace<T> springs;
  fast::ContactWorkspace contacts;  // the sphere-cloth contact filter's copy of the positions
  std::shared_ptr<fast::ThreadPool> pool;  // when threads > 1 and the grid is big enough
  bool prepared = false;                   // grid detection and buffers done (setExecution)
};

// Cloths with fewer particles per edge keep one thread: below this, waking a thread costs more
// than the sweep it would share.
inline constexpr int kThreadedGridEdge = 100;

template <typename T>
struct World;

// How a world steps a method the core does not implement (a method-table row with
// `stepped_by_solver`, e.g. backward Euler in clothref/solver). The area that implements the method
// installs one in the world; step() calls it in place of integrate().
template <typename T>
struct MethodStepper {
  virtual ~MethodStepper() = default;
  // Calls simulateOneStep(world) as often as the method needs and advances every body by one
  // dt; step() does the frame's work before and counts the step after.
  virtual void integrate(World<T>& world) = 0;
};

template <typename T>
struct World {
  std::optional<Cloth<T>> cloth;
  std::optional<Spheres<T>> spheres;
  Physics<T> physics;
  FrameLoop<T> frame_loop;
  Method method = Method::Explicit;
  std::int64_t step = 0;         // steps taken
  IntegratorScratch<T> scratch;  // integrator backups, reused every step
  Execution<T> execution;        // fast kernels on, default SIMD path, one thread
  // For a method stepped by the solver (see MethodStepper). Copies of a world share it: it holds
  // only work buffers rebuilt every step (and running statistics), never state.
  std::shared_ptr<MethodStepper<T>> stepper;
};

// Sets how `world` steps: the fast kernels (`use_fast`) or the course-form loops alone, the
// kernels' SIMD path (one this CPU supports) and the spring sweep's threads (>= 1; only grids of
// kThreadedGridEdge or more particles per edge use more than one). Never changes the results.
// The first step calls it with the defaults (fast, defaultSimdPath(), one thread) if nobody has.
template <typename T>
void setExecution(World<T>& world, bool use_fast, fast::SimdPath simd, int threads);

// The bodies in the course's order (cloth, then spheres); `storage` holds the pointers.
template <typename T>
Bodies<T> bodies(World<T>& world, std::array<Particles<T>*, 2>& storage);

// The course's simulateOneStep, running only the parts the scene has: external forces on the
// cloth, on the spheres (when enabled), spring forces, sphere-cloth and sphere-sphere contacts.
template <typename T>
void simulateOneStep(World<T>& world);

// One step of the main loop: the frame's work when a frame begins (frame_loop), simulateOneStep,
// then the integrator (or, for a method stepped by the solver, world.stepper, which throws
// std::logic_error when missing). Allocates nothing once the first step has sized the scratch.
template <typename T>
void step(World<T>& world);

// Total kinetic energy, sum of 1/2 m |v|^2 over every particle, in double, in particle order.
template <typename T>
double kineticEnergy(const World<T>& world);

// Total linear momentum, sum of m v, in double, in particle order.
template <typename T>
std::array<double, 3> momentum(const World<T>& world);

// True when every position and velocity is finite.
template <typename T>
bool isFinite(const World<T>& world);

}  // namespace clothref
