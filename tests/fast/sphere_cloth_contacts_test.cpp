// The filtered sphere-cloth contacts against core's per-pair collide (the oracle), bit for bit, on
// every SIMD path this CPU runs: random configurations with spheres inside, touching and far from
// the cloth, pairs placed within a few units in the last place of the contact distance,
// restitution 0 and 0.8, fixed particles, and non-finite states. Plus: far pairs are skipped.
#include "clothref/fast/sphere_cloth_contacts.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "clothref/core/spheres.h"
#include "test_util.h"

namespace clothref {
namespace {

using test::bits;

template <typename T>
fast::ContactBodies<T> contactBodies(Spheres<T>& s, Cloth<T>& c) {
  return {s.particles.position.data(),
          s.particles.velocity.data(),
          s.particles.inverse_mass.data(),
          s.radius.data(),
          s.size(),
          c.particles.position.data(),
          c.particles.velocity.data(),
          c.particles.inverse_mass.data(),
          c.particles.size()};
}

template <typename T>
int differingBits(const Particles<T>& a, const Particles<T>& b) {
  int differing = 0;
  for (int i = 0; i < a.size(); ++i)
    for (int k = 0; k < 4; ++k) {
      differing += bits(a.position(k, i)) != bits(b.position(k, i));
      differing += bits(a.velocity(k, i)) != bits(b.velocity(k, i));
    }
  return differing;
}

std::vector<fast::SimdPath> supportedPaths() {
  std::vector<fast::SimdPath> paths;
  for (fast::SimdPath path : fast::kAllSimdPaths)
    if (fast::simdPathSupported(path)) paths.push_back(path);
  return paths;
}

// Returns the number of pairs the fast path tested (the same on every path).
template <typename T>
long expectSameBits(const Spheres<T>& spheres, const Cloth<T>& cloth, T restitution) {
  Spheres<T> oracle_spheres = spheres;
  Cloth<T> oracle_cloth = cloth;
  collide(oracle_spheres, oracle_cloth, restitution, T(0.15));
  // one workspace per path for the whole test program, reused across cloth sizes as a world's is
  static fast::ContactWorkspace workspaces[std::size(fast::kAllSimdPaths)];
  long tested = -1;
  for (fast::SimdPath path : supportedPaths()) {
    Spheres<T> fast_spheres = spheres;
    Cloth<T> fast_cloth = cloth;
    const long path_tested = fast::collideSpheresWithCloth(
        contactBodies(fast_spheres, fast_cloth), restitution, T(0.15), path, workspaces[int(path)]);
    EXPECT_EQ(differingBits(fast_spheres.particles, oracle_spheres.particles), 0)
        << fast::simdPathName(path);
    EXPECT_EQ(differingBits(fast_cloth.particles, oracle_cloth.particles), 0)
        << fast::simdPathName(path);
    if (tested >= 0) {
      EXPECT_EQ(path_tested, tested) << fast::simdPathName(path);
    }
    tested = path_tested;
  }
  return tested;
}

// A jittered n x n cloth (some particles fixed) and `count` spheres around it.
template <typename T>
void randomScene(std::mt19937_64& random, int n, int count, Spheres<T>& spheres, Cloth<T>& cloth) {
  std::uniform_real_distribution<double> unit(-1, 1), radius(0.05, 0.6), mass(0.001, 0.1);
  cloth = Cloth<T>{};
  cloth.particles = initializeVertex<T>(n, T(1), T(0), T(0.01));
  for (int i = 0; i < cloth.particles.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      cloth.particles.position(k, i) += T(0.05 * unit(random));
      cloth.particles.velocity(k, i) = T(unit(random));
    }
    setMass(cloth.particles, i, random() % 10 == 0 ? T(0) : T(mass(random)));
  }
  spheres = Spheres<T>{};
  spheres.particles = makeParticles<T>(0, T(0));
  for (int s = 0; s < count; ++s) {
    const T r = T(radius(random));
    addSphere(spheres,
              Vec4<T>(T(1.2 * unit(random)), T(0.4 * unit(random)), T(1.2 * unit(random)), T(1)), r,
              T(1000));
    spheres.particles.velocity.col(s) =
        Vec4<T>(T(unit(random)), T(unit(random)), T(unit(random)), T(0));
  }
}

template <typename T>
class SphereClothContacts : public ::testing::Test {};
using Precisions = ::testing::Types<float, double>;
TYPED_TEST_SUITE(SphereClothContacts, Precisions);

TYPED_TEST(SphereClothContacts, RandomScenesMatchTheOracle) {
  std::mt19937_64 random(42);
  for (int trial = 0; trial < 200; ++trial) {
    Spheres<TypeParam> spheres;
    Cloth<TypeParam> cloth;
    randomScene(random, 3 + trial % 20, 1 + trial % 5, spheres, cloth);
    for (TypeParam restitution : {TypeParam(0), TypeParam(0.8)}) {
      SCOPED_TRACE(::testing::Message() << "trial " << trial << ", restitution " << restitution);
      expectSameBits(spheres, cloth, restitution);
    }
  }
}

TYPED_TEST(SphereClothContacts, PairsAtTheContactDistanceMatchTheOracle) {
  // every particle within a few ulps of the sphere's surface: the broad phase's margin decides
  using T = TypeParam;
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int trial = 0; trial < 50; ++trial) {
    Spheres<T> spheres;
    Cloth<T> cloth;
    randomScene(random, 9, 1, spheres, cloth);
    const Vec4<T> centre = spheres.particles.position.col(0);
    const T r = spheres.radius[0];
    for (int j = 0; j < cloth.particles.size(); ++j) {
      Vec4<double> direction(unit(random), unit(random), unit(random), 0);
      direction.normalize();
      Vec4<T> x = centre - (direction * double(r)).template cast<T>();
      x[3] = T(1);
      for (int ulps = int(random() % 9) - 4, k = 0; k < 3; ++k)
        for (int u = 0; u < std::abs(ulps); ++u)
          x[k] = std::nextafter(x[k], ulps > 0 ? std::numeric_limits<T>::infinity() : T(0));
      cloth.particles.position.col(j) = x;
    }
    expectSameBits(spheres, cloth, T(0));
  }
}

TYPED_TEST(SphereClothContacts, NonFiniteStatesMatchTheOracle) {
  using T = TypeParam;
  std::mt19937_64 random(3);
  Spheres<T> spheres;
  Cloth<T> cloth;
  randomScene(random, 8, 3, spheres, cloth);
  cloth.particles.position(1, 5) = std::numeric_limits<T>::quiet_NaN();
  cloth.particles.position(0, 20) = std::numeric_limits<T>::infinity();
  spheres.particles.position(2, 1) = std::numeric_limits<T>::quiet_NaN();
  expectSameBits(spheres, cloth, T(0));
}

TYPED_TEST(SphereClothContacts, NonFiniteWLanesMatchTheOracle) {
  // the float filter folds w into x, y and z (x + w * 0) instead of squaring it: a NaN or infinite
  // w must still reach the exact test, which takes a NaN length as a contact
  using T = TypeParam;
  for (T bad : {std::numeric_limits<T>::quiet_NaN(), std::numeric_limits<T>::infinity(),
                -std::numeric_limits<T>::infinity()}) {
    std::mt19937_64 random(11);
    Spheres<T> spheres;
    Cloth<T> cloth;
    randomScene(random, 9, 2, spheres, cloth);
    // far from both spheres, so only the w lane can make these pairs reach the exact test
    cloth.particles.position.col(3) = Vec4<T>(T(50), T(50), T(50), bad);
    cloth.particles.position.col(70) = Vec4<T>(T(-50), T(50), T(50), bad);
    SCOPED_TRACE(::testing::Message() << "cloth w " << bad);
    expectSameBits(spheres, cloth, T(0.8));
    spheres.particles.position(3, 1) = bad;
    SCOPED_TRACE("and sphere 1's w");
    expectSameBits(spheres, cloth, T(0.8));
  }
}

TYPED_TEST(SphereClothContacts, LongRunsOfTouchingPairsMatchTheOracle) {
  // touching pairs one after another, in full filter blocks and the last, partial one: a sphere
  // under a flat cloth reaching every particle at first; each contact moves the centre down, so
  // the filter re-flags after each (about 40 of 64 to 108 of 529 pairs touch)
  using T = TypeParam;
  std::mt19937_64 random(13);
  for (int n : {8, 11, 16, 23}) {
    Spheres<T> spheres;
    Cloth<T> cloth;
    randomScene(random, n, 1, spheres, cloth);
    spheres.radius[0] = T(3.5);
    spheres.particles.position.col(0) = Vec4<T>(T(0), T(-2.5), T(0), T(0));
    SCOPED_TRACE(::testing::Message() << n << " x " << n);
    EXPECT_GT(expectSameBits(spheres, cloth, T(0.8)), 2 * n);  // more than two cloth rows' worth
  }
}

TYPED_TEST(SphereClothContacts, FarPairsAreSkipped) {
  using T = TypeParam;
  std::mt19937_64 random(5);
  Spheres<T> spheres;
  Cloth<T> cloth;
  randomScene(random, 25, 4, spheres, cloth);
  for (int s = 0; s < 4; ++s) spheres.radius[std::size_t(s)] = T(0.2);
  const long pairs = 4L * cloth.particles.size();
  const long tested = expectSameBits(spheres, cloth, T(0));
  EXPECT_LT(tested, pairs / 4);
  // spheres far above the cloth: the filter passes over every pair
  for (int s = 0; s < 4; ++s) spheres.particles.position(1, s) = T(10);
  EXPECT_EQ(expectSameBits(spheres, cloth, T(0)), 0);
}

}  // namespace
}  // namespace clothref
