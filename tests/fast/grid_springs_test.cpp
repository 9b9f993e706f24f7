// The grid evaluation (external force, then the stencil sweeps) against the course-form code
// (core's computeExternalForce and per-spring computeSpringForce, the oracle), bit for bit: random
// states, every grid size shape, every SIMD path this CPU runs, float and double, one and several
// threads. Also: what matchCourseGrid accepts and refuses.
#include "clothref/fast/grid_springs.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "clothref/core/cloth.h"
#include "test_util.h"

namespace clothref {
namespace {

using test::bits;

// An n x n course cloth (initializeVertex + initializeSpring, corners fixed), then a random state:
// positions jittered around the grid, random velocities and accelerations, random masses.
template <typename T>
Cloth<T> randomCloth(int n, std::uint64_t seed) {
  Cloth<T> cloth;
  cloth.particles = initializeVertex<T>(n, T(1), T(0), T(0.01));
  initializeSpring(cloth, n);
  cloth.spring_coef = T(5000);
  cloth.damper_coef = T(0.5);
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> jitter(-0.05, 0.05), speed(-2, 2), mass(0.001, 0.1);
  Particles<T>& p = cloth.particles;
  for (int i = 0; i < p.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      p.position(k, i) += T(jitter(random));
      p.velocity(k, i) = T(speed(random));
      p.acceleration(k, i) = T(speed(random));
    }
    setMass(p, i, T(mass(random)));
  }
  for (int corner : {0, n - 1, n * (n - 1), n * n - 1}) setMass(p, corner, T(0));
  return cloth;
}

template <typename T>
bool matchCloth(const Cloth<T>& cloth, int threads, fast::GridSpringWorkspace<T>& workspace) {
  std::vector<std::uint32_t> start, end;
  std::vector<T> rest;
  for (const Spring<T>& s : cloth.springs) {
    start.push_back(s.start);
    end.push_back(s.end);
    rest.push_back(s.rest_length);
  }
  return fast::matchCourseGrid<T>(cloth.particles.size(), start, end, rest, threads, workspace);
}

// Runs the fast evaluation on a copy of `cloth` and the oracle on another; every bit of the
// accelerations (w lane included) must agree.
template <typename T>
void expectSameBits(const Cloth<T>& cloth, fast::SimdPath path, int threads) {
  const Vec4<T> gravity(T(0.1), T(-9.8), T(0.2), T(0));
  const T viscous_coef = T(0.3);
  Cloth<T> oracle = cloth;
  computeExternalForce(oracle.particles, gravity, viscous_coef);
  computeSpringForce(oracle);
  Cloth<T> swept = cloth;
  fast::GridSpringWorkspace<T> workspace;
  ASSERT_TRUE(matchCloth(swept, threads, workspace));
  fast::ThreadPool pool(threads);
  Particles<T>& p = swept.particles;
  fast::evaluateGridCloth(workspace, p.position.data(), p.velocity.data(), p.acceleration.data(),
                          p.mass.data(), p.inverse_mass.data(), gravity.data(), viscous_coef,
                          swept.spring_coef, swept.damper_coef, path,
                          threads > 1 ? &pool : nullptr);
  int differing = 0;
  for (int i = 0; i < p.size(); ++i)
    for (int k = 0; k < 4; ++k)
      if (bits(p.acceleration(k, i)) != bits(oracle.particles.acceleration(k, i))) ++differing;
  EXPECT_EQ(differing, 0) << "n^2 = " << p.size() << ", path " << fast::simdPathName(path)
                          << ", threads " << threads;
}

std::vector<fast::SimdPath> supportedPaths() {
  std::vector<fast::SimdPath> paths;
  for (fast::SimdPath path : fast::kAllSimdPaths)
    if (fast::simdPathSupported(path)) paths.push_back(path);
  return paths;
}

template <typename T>
class GridSprings : public ::testing::Test {};
using Precisions = ::testing::Types<float, double>;
TYPED_TEST_SUITE(GridSprings, Precisions);

TYPED_TEST(GridSprings, RandomStatesMatchTheOracleOnEveryPathAndSize) {
  // sizes around every lane count and the course's 25; 2 has no bend springs
  for (int n : {2, 3, 4, 5, 7, 8, 9, 16, 17, 25, 33})
    for (fast::SimdPath path : supportedPaths())
      for (std::uint64_t seed : {1u, 2u, 3u})
        expectSameBits(randomCloth<TypeParam>(n, seed), path, 1);
}

TYPED_TEST(GridSprings, ThreadSplitsMatchTheOracle) {
  for (int n : {25, 40, 101})
    for (fast::SimdPath path : supportedPaths())
      for (int threads : {2, 3, 4}) expectSameBits(randomCloth<TypeParam>(n, 7), path, threads);
}

TYPED_TEST(GridSprings, CoincidentParticlesGiveTheOraclesZeroForce) {
  // |d| = 0: Eigen's normalize leaves d alone, so the force is 0 rather than NaN
  Cloth<TypeParam> cloth = randomCloth<TypeParam>(6, 11);
  cloth.particles.position.col(8) = cloth.particles.position.col(9);
  cloth.particles.position.col(20) = cloth.particles.position.col(14);
  for (fast::SimdPath path : supportedPaths()) expectSameBits(cloth, path, 1);
}

TYPED_TEST(GridSprings, AtRestTheSignsOfZeroMatch) {
  // the unperturbed grid at rest: every stretch and relative velocity is exactly zero
  Cloth<TypeParam> cloth;
  cloth.particles = initializeVertex<TypeParam>(9, TypeParam(1), TypeParam(0), TypeParam(0.01));
  initializeSpring(cloth, 9);
  cloth.spring_coef = TypeParam(5000);
  cloth.damper_coef = TypeParam(0.5);
  for (fast::SimdPath path : supportedPaths()) expectSameBits(cloth, path, 1);
}

TYPED_TEST(GridSprings, OtherSpringListsKeepTheGeneralPath) {
  fast::GridSpringWorkspace<TypeParam> workspace;
  const Cloth<TypeParam> grid = randomCloth<TypeParam>(5, 1);
  EXPECT_TRUE(matchCloth(grid, 1, workspace));

  Cloth<TypeParam> swapped = grid;  // two springs of one family out of order
  std::swap(swapped.springs[3], swapped.springs[4]);
  EXPECT_FALSE(matchCloth(swapped, 1, workspace));

  Cloth<TypeParam> missing = grid;
  missing.springs.pop_back();
  EXPECT_FALSE(matchCloth(missing, 1, workspace));

  Cloth<TypeParam> extra = grid;
  extra.springs.push_back(grid.springs.front());
  EXPECT_FALSE(matchCloth(extra, 1, workspace));

  Cloth<TypeParam> rest = grid;  // one spring of a family with its own rest length
  rest.springs[7].rest_length *= TypeParam(1.5);
  EXPECT_FALSE(matchCloth(rest, 1, workspace));

  Cloth<TypeParam> interleaved = grid;  // the two shear passes interleaved, not separate
  const std::size_t first_shear = 2 * 5 * 4;
  std::swap(interleaved.springs[first_shear + 1], interleaved.springs[first_shear + 16]);
  EXPECT_FALSE(matchCloth(interleaved, 1, workspace));

  Cloth<TypeParam> not_square = grid;  // 24 particles cannot be a grid
  not_square.particles = makeParticles<TypeParam>(24, TypeParam(1));
  EXPECT_FALSE(matchCloth(not_square, 1, workspace));
}

}  // namespace
}  // namespace clothref
