#include "clothref/analysis/simulation.h"

namespace clothref {

std::string_view MethodChoice::name() const {
  return backward_euler ? std::string_view("backward-euler") : methodName(core);
}

int MethodChoice::evaluationsPerStep() const {
  return backward_euler ? 1 : methodInfo(core).evaluations;
}

std::vector<MethodChoice> analysisMethods() {
  std::vector<MethodChoice> methods;
  for (Method method : kAllMethods) methods.push_back(MethodChoice{method, false});
  methods.push_back(MethodChoice{Method::Explicit, true});
  return methods;
}

bool parseMethodChoice(std::string_view name, MethodChoice& method) {
  for (const MethodChoice& candidate : analysisMethods()) {
    if (candidate.name() == name) {
      method = candidate;
      return true;
    }
  }
  return false;
}

template <typename T>
Simulation<T> makeSimulation(const Scene& scene, MethodChoice method, std::optional<double> dt) {
  Simulation<T> simulation{makeWorld<T>(scene, method.core, dt), method, {}};
  if (method.backward_euler && simulation.world.cloth)
    prepareBackwardEuler(*simulation.world.cloth, simulation.solver);
  return simulation;
}

template Simulation<float> makeSimulation(const Scene&, MethodChoice, std::optional<double>);
template Simulation<double> makeSimulation(const Scene&, MethodChoice, std::optional<double>);

}  // namespace clothref
