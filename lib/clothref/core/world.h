// World: one simulation, the state of every body plus the parameters its step uses. Two worlds
// share nothing, so any number can run in one process (the course's Spheres singleton is gone).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "clothref/core/cloth.h"
#include "clothref/core/integrator.h"
#include "clothref/core/spheres.h"

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

template <typename T>
struct World {
  std::optional<Cloth<T>> cloth;
  std::optional<Spheres<T>> spheres;
  Physics<T> physics;
  FrameLoop<T> frame_loop;
  Method method = Method::Explicit;
  std::int64_t step = 0;           // steps taken
  IntegratorScratch<T> scratch;    // integrator backups, reused every step
};

// The bodies in the course's order (cloth, then spheres); `storage` holds the pointers.
template <typename T>
Bodies<T> bodies(World<T>& world, std::array<Particles<T>*, 2>& storage);

// The course's simulateOneStep, running only the parts the scene has: external forces on the
// cloth, on the spheres (when enabled), spring forces, sphere-cloth and sphere-sphere contacts.
template <typename T>
void simulateOneStep(World<T>& world);

// One step of the main loop: the frame's work when a frame begins (frame_loop), simulateOneStep,
// then the integrator. Allocates nothing once the first step has sized the integrator scratch.
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
