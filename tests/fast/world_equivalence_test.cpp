// Whole steps with the fast kernels against the course-form loops (setExecution(world, false, ..)),
// bit for bit at every step: every built-in scene, every method, float and double, every SIMD
// path this CPU runs; spheres pushed into the cloth so contacts happen from the first step; and a
// 100 x 100 cloth (big enough for threads) at 1, 2 and 3 threads. The golden check (ctest
// `golden`, and GoldenOnEveryPath below) covers the full-length runs.
#include <gtest/gtest.h>

#include <cstdlib>
#include <vector>

#include "clothref/core/world.h"
#include "clothref/scene/make_world.h"
#include "test_util.h"

namespace clothref {
namespace {

std::vector<fast::SimdPath> supportedPaths() {
  std::vector<fast::SimdPath> paths;
  for (fast::SimdPath path : fast::kAllSimdPaths)
    if (fast::simdPathSupported(path)) paths.push_back(path);
  return paths;
}

// Drops every sphere onto the cloth (centre half a radius above a cloth particle), moving down.
template <typename T>
void pushSpheresIntoCloth(World<T>& world) {
  if (!world.spheres || !world.cloth) return;
  Particles<T>& s = world.spheres->particles;
  const Particles<T>& c = world.cloth->particles;
  for (int i = 0; i < s.size(); ++i) {
    const int j = (c.size() / 2 + 7 * i) % c.size();
    s.position.col(i) = c.position.col(j);
    s.position(1, i) += world.spheres->radius[std::size_t(i)] / T(2);
    s.velocity.col(i) = Vec4<T>(T(0.1), T(-1), T(0.05), T(0));
  }
}

// Whether every bit of every body's positions and velocities (w lanes included) agrees.
template <typename T>
bool sameState(const World<T>& a, const World<T>& b) {
  auto same = [](const Mat4X<T>& x, const Mat4X<T>& y) {
    for (Eigen::Index i = 0; i < x.size(); ++i)
      if (test::bits(x.data()[i]) != test::bits(y.data()[i])) return false;
    return true;
  };
  auto sameBody = [&same](const Particles<T>& x, const Particles<T>& y) {
    return same(x.position, y.position) && same(x.velocity, y.velocity);
  };
  return (!a.cloth || sameBody(a.cloth->particles, b.cloth->particles)) &&
         (!a.spheres || sameBody(a.spheres->particles, b.spheres->particles));
}

// Steps an oracle world and a fast one side by side; returns the first step whose states differ
// in any bit, or -1.
template <typename T>
long firstDifferentStep(const Scene& scene, Method method, fast::SimdPath path, int threads,
                        int steps, bool push) {
  World<T> oracle = makeWorld<T>(scene, method);
  World<T> fast = makeWorld<T>(scene, method);
  setExecution(oracle, false, path, 1);
  setExecution(fast, true, path, threads);
  if (push) {
    pushSpheresIntoCloth(oracle);
    pushSpheresIntoCloth(fast);
  }
  for (int k = 1; k <= steps; ++k) {
    step(oracle);
    step(fast);
    if (!sameState(oracle, fast)) return k;
  }
  return -1;
}

template <typename T>
class WorldEquivalence : public ::testing::Test {};
using Precisions = ::testing::Types<float, double>;
TYPED_TEST_SUITE(WorldEquivalence, Precisions);

TYPED_TEST(WorldEquivalence, EveryBuiltinSceneMethodAndPath) {
  for (const Scene& scene : builtinScenes())
    for (Method method : kAllMethods)
      for (fast::SimdPath path : supportedPaths())
        for (bool push : {false, true})
          EXPECT_EQ((firstDifferentStep<TypeParam>(scene, method, path, 1, 60, push)), -1)
              << scene.name << ' ' << methodName(method) << ' ' << fast::simdPathName(path)
              << (push ? " spheres pushed into the cloth" : "");
}

TYPED_TEST(WorldEquivalence, BigClothAtEveryThreadCount) {
  Scene scene = *findBuiltinScene("course2022");
  scene.cloth->grid->particles_per_edge = 100;
  const int n = 100;
  scene.cloth->fixed = {0, n - 1, n * (n - 1), n * n - 1};
  for (int threads : {1, 2, 3})
    for (fast::SimdPath path : supportedPaths())
      EXPECT_EQ((firstDifferentStep<TypeParam>(scene, Method::Rk4, path, threads, 4, true)), -1)
          << fast::simdPathName(path) << ", threads " << threads;
}

TEST(WorldEquivalence, GridDetectionFollowsTheScene) {
  World<float> course = makeWorld<float>(*findBuiltinScene("course2022"), Method::Explicit);
  EXPECT_FALSE(course.execution.prepared);
  step(course);  // the first step detects the grid
  EXPECT_TRUE(course.execution.prepared);
  EXPECT_TRUE(course.execution.grid);
  EXPECT_EQ(course.execution.pool, nullptr);  // 25 x 25: one thread whatever is asked
  setExecution(course, true, fast::SimdPath::Sse2, 2);
  EXPECT_EQ(course.execution.pool, nullptr);
  World<float> spring = makeWorld<float>(*findBuiltinScene("spring"), Method::Explicit);
  step(spring);
  EXPECT_FALSE(spring.execution.grid);  // explicit springs: the general path
}

// The golden data (full-length runs with contacts) on every SIMD path, through the CLI, which
// takes its path from CLOTHREF_SIMD.
TEST(WorldEquivalence, GoldenOnEveryPath) {
  for (fast::SimdPath path : supportedPaths()) {
    ::setenv("CLOTHREF_SIMD", std::string(fast::simdPathName(path)).c_str(), 1);
    const test::CommandResult result =
        test::runCli(std::string("golden --golden ") + CLOTHREF_SOURCE_DIR + "/golden");
    ::unsetenv("CLOTHREF_SIMD");
    EXPECT_EQ(result.exit_code, 0) << fast::simdPathName(path) << ":\n" << result.output;
  }
}

}  // namespace
}  // namespace clothref
