#include "clothref/core/world.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace clothref {

template <typename T>
void setExecution(World<T>& world, bool use_fast, fast::SimdPath simd, int threads) {
  Execution<T>& execution = world.execution;
  execution.use_fast = use_fast;
  execution.simd = simd;
  execution.threads = std::max(threads, 1);
  execution.grid = false;
  execution.pool.reset();
  execution.prepared = true;
  if (!use_fast || !world.cloth) return;
  const Cloth<T>& cloth = *world.cloth;
  std::vector<std::uint32_t> start, end;
  std::vector<T> rest;
  for (const Spring<T>& spring : cloth.springs) {
    start.push_back(spring.start);
    end.push_back(spring.end);
    rest.push_back(spring.rest_length);
  }
  const int count = cloth.particles.size();
  const bool big = count >= kThreadedGridEdge * kThreadedGridEdge;
  const int sweep_threads = big ? execution.threads : 1;
  execution.grid =
      fast::matchCourseGrid<T>(count, start, end, rest, sweep_threads, execution.springs);
  if (execution.grid && sweep_threads > 1)
    execution.pool = std::make_shared<fast::ThreadPool>(sweep_threads);
}

template <typename T>
Bodies<T> bodies(World<T>& world, std::array<Particles<T>*, 2>& storage) {
  std::size_t count = 0;
  if (world.cloth) storage[count++] = &world.cloth->particles;
  if (world.spheres) storage[count++] = &world.spheres->particles;
  return Bodies<T>(storage.data(), count);
}

template <typename T>
void simulateOneStep(World<T>& world) {
  const Physics<T>& physics = world.physics;
  Execution<T>& execution = world.execution;
  if (!execution.prepared)
    setExecution(world, execution.use_fast, execution.simd, execution.threads);
  // a course grid cloth gets its external and spring forces from one fast evaluation
  const bool grid_cloth = world.cloth && execution.use_fast && execution.grid;
  if (world.cloth && !grid_cloth)
    computeExternalForce(world.cloth->particles, physics.gravity, physics.viscous_coef);
  if (world.spheres && physics.sphere_external_force)
    computeExternalForce(world.spheres->particles, physics.gravity, physics.viscous_coef);
  if (grid_cloth) {
    Cloth<T>& cloth = *world.cloth;
    Particles<T>& p = cloth.particles;
    fast::evaluateGridCloth(execution.springs, p.position.data(), p.velocity.data(),
                            p.acceleration.data(), p.mass.data(), p.inverse_mass.data(),
                            physics.gravity.data(), physics.viscous_coef, cloth.spring_coef,
                            cloth.damper_coef, execution.simd, execution.pool.get());
  } else if (world.cloth && !world.cloth->springs.empty()) {
    computeSpringForce(*world.cloth);
  }
  if (world.spheres && world.cloth) {
    if (execution.use_fast) {
      Particles<T>& s = world.spheres->particles;
      Particles<T>& c = world.cloth->particles;
      const fast::ContactBodies<T> contact{
          s.position.data(), s.velocity.data(), s.inverse_mass.data(), world.spheres->radius.data(),
          s.size(),          c.position.data(), c.velocity.data(),     c.inverse_mass.data(),
          c.size()};
      fast::collideSpheresWithCloth(contact, physics.restitution_cloth, physics.correction,
                                    execution.simd, execution.contacts);
    } else {
      collide(*world.spheres, *world.cloth, physics.restitution_cloth, physics.correction);
    }
  }
  if (world.spheres && physics.sphere_sphere_collision)
    collide(*world.spheres, physics.restitution_sphere, physics.correction);
}

namespace {

// The 2024 main loop's work before a frame's steps: pinned corners get mass 0 and zero velocity
// and acceleration, then spheres.setVelocity(0, vel).
template <typename T>
void beginFrame(World<T>& world) {
  if (world.cloth)
    for (int i : world.frame_loop.pinned) {
      setMass(world.cloth->particles, i, T(0));
      world.cloth->particles.velocity.col(i).setZero();
      world.cloth->particles.acceleration.col(i).setZero();
    }
  if (world.spheres && world.spheres->size() > 0)
    world.spheres->particles.velocity.col(0) = world.frame_loop.sphere_velocity;
}

}  // namespace

template <typename T>
void step(World<T>& world) {
  if (world.frame_loop.steps_per_frame > 0 && world.step % world.frame_loop.steps_per_frame == 0)
    beginFrame(world);
  if (methodInfo(world.method).stepped_by_solver) {
    if (!world.stepper)
      throw std::logic_error(std::string(methodName(world.method)) +
                             " needs its solver: build the world with makeWorld");
    world.stepper->integrate(world);
  } else {
    std::array<Particles<T>*, 2> storage{};
    simulateOneStep(world);
    integrate(
        world.method, bodies(world, storage), world.physics.dt,
        [&world] { simulateOneStep(world); }, world.scratch);
  }
  ++world.step;
}

namespace {

// Calls f(particles) for each body in order.
template <typename T, typename F>
void forEachBody(const World<T>& world, F&& f) {
  if (world.cloth) f(world.cloth->particles);
  if (world.spheres) f(world.spheres->particles);
}

}  // namespace

template <typename T>
double kineticEnergy(const World<T>& world) {
  double energy = 0;
  forEachBody(world, [&energy](const Particles<T>& p) {
    for (int i = 0; i < p.size(); ++i) {
      double v2 = 0;
      for (int k = 0; k < 3; ++k) v2 += double(p.velocity(k, i)) * double(p.velocity(k, i));
      energy += 0.5 * double(p.mass[i]) * v2;
    }
  });
  return energy;
}

template <typename T>
std::array<double, 3> momentum(const World<T>& world) {
  std::array<double, 3> total{0, 0, 0};
  forEachBody(world, [&total](const Particles<T>& p) {
    for (int i = 0; i < p.size(); ++i)
      for (int k = 0; k < 3; ++k) total[k] += double(p.mass[i]) * double(p.velocity(k, i));
  });
  return total;
}

template <typename T>
bool isFinite(const World<T>& world) {
  bool finite = true;
  forEachBody(world, [&finite](const Particles<T>& p) {
    finite = finite && p.position.allFinite() && p.velocity.allFinite();
  });
  return finite;
}

#define CLOTHREF_INSTANTIATE(T)                                        \
  template void setExecution(World<T>&, bool, fast::SimdPath, int);    \
  template Bodies<T> bodies(World<T>&, std::array<Particles<T>*, 2>&); \
  template void simulateOneStep(World<T>&);                            \
  template void step(World<T>&);                                       \
  template double kineticEnergy(const World<T>&);                      \
  template std::array<double, 3> momentum(const World<T>&);            \
  template bool isFinite(const World<T>&);
CLOTHREF_INSTANTIATE(float)
CLOTHREF_INSTANTIATE(double)
#undef CLOTHREF_INSTANTIATE

}  // namespace clothref
