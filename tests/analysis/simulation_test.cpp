// The analysis's method list (analysis/simulation.h): every core method plus backward Euler,
// names that parse back, evaluation counts, and a Simulation that steps with the chosen method.
#include "clothref/analysis/simulation.h"

#include <gtest/gtest.h>

namespace clothref {
namespace {

TEST(MethodChoice, NamesParseBackAndCountEvaluations) {
  const std::vector<MethodChoice> methods = analysisMethods();
  ASSERT_EQ(methods.size(), (std::size(kAllMethods) + 1));
  EXPECT_TRUE(methods.back().backward_euler);
  for (const MethodChoice& method : methods) {
    MethodChoice parsed;
    ASSERT_TRUE(parseMethodChoice(method.name(), parsed)) << method.name();
    EXPECT_EQ(parsed, method);
  }
  MethodChoice unknown;
  EXPECT_FALSE(parseMethodChoice("backward", unknown));
  EXPECT_EQ(methods.back().name(), "backward-euler");
  EXPECT_EQ(methods.back().evaluationsPerStep(), 1);
  EXPECT_EQ((MethodChoice{Method::Rk4, false}.evaluationsPerStep()), 4);
}

TEST(Simulation, StepsWithTheChosenMethod) {
  const Scene& scene = *findBuiltinScene("spring");
  Simulation<double> core = makeSimulation<double>(scene, MethodChoice{Method::Explicit, false});
  Simulation<double> implicit = makeSimulation<double>(scene, MethodChoice{Method::Explicit, true});
  World<double> reference = makeWorld<double>(scene, Method::Explicit);
  for (int s = 0; s < 10; ++s) {
    core.advance();
    implicit.advance();
    step(reference);
  }
  // the core method is the world's own step, bit for bit; backward Euler is a different step
  EXPECT_EQ(core.world.cloth->particles.position, reference.cloth->particles.position);
  EXPECT_NE(implicit.world.cloth->particles.position, reference.cloth->particles.position);
  EXPECT_EQ(implicit.world.step, 10);
  EXPECT_EQ(implicit.solver.stats.solves, 10);
}

}  // namespace
}  // namespace clothref
