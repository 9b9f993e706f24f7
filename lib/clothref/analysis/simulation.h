// The methods the analysis compares, and one run of any of them: the core's five integrators
// (core/integrator.h) and backward Euler (solver/backward_euler.h), which the core cannot call
// because the solver depends on the core, not the other way round.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "clothref/core/world.h"
#include "clothref/scene/make_world.h"
#include "clothref/scene/scene.h"
#include "clothref/solver/backward_euler.h"

namespace clothref {

// One method: a core integrator, or backward Euler.
struct MethodChoice {
  Method core = Method::Explicit;
  bool backward_euler = false;

  // "explicit", ..., "symplectic", "backward-euler"
  std::string_view name() const;
  // Derivative evaluations (simulateOneStep calls) per step; backward Euler makes one, plus
  // one Jacobian assembly and its CG iterations (reported apart).
  int evaluationsPerStep() const;
  bool operator==(const MethodChoice&) const = default;
};

// The core's methods in their order, then backward Euler.
std::vector<MethodChoice> analysisMethods();

// Parses a name of analysisMethods(); false for an unknown one.
bool parseMethodChoice(std::string_view name, MethodChoice& method);

// A world and, for backward Euler, its solver.
template <typename T>
struct Simulation {
  World<T> world;
  MethodChoice method;
  BackwardEulerSolver<T> solver;

  void advance() {
    if (method.backward_euler)
      stepBackwardEuler(world, solver);
    else
      step(world);
  }
};

// A simulation of `scene` with `method` at `dt` (the scene's when not given).
template <typename T>
Simulation<T> makeSimulation(const Scene& scene, MethodChoice method,
                             std::optional<double> dt = std::nullopt);

}  // namespace clothref
