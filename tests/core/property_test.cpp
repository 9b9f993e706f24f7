// Properties of the spring and collision stubs over many random states, in float and double.
// Seeds are fixed and doubles come from the top 53 bits of each draw (std distributions are not
// portable), so every run sees the same states.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "clothref/core/cloth.h"
#include "clothref/core/spheres.h"

namespace clothref {
namespace {

constexpr int kTrials = 1000;

double uniform(std::mt19937_64& random, double lo, double hi) {
  return lo + (hi - lo) * double(random() >> 11) * 0x1.0p-53;
}

template <typename T>
Vec4<T> randomVector(std::mt19937_64& random, double scale, T w) {
  return Vec4<T>(T(uniform(random, -scale, scale)), T(uniform(random, -scale, scale)),
                 T(uniform(random, -scale, scale)), w);
}

// Relative tolerance of a sum of a few rounded terms: float 1e-5, double 1e-12.
template <typename T>
double relativeTolerance() {
  return sizeof(T) == sizeof(float) ? 1e-5 : 1e-12;
}

// Sum of m a over a body, in double, and the sum of |m a| as its scale.
template <typename T>
std::pair<Eigen::Vector3d, double> massWeightedSum(const Particles<T>& p, bool use_acceleration) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double scale = 0;
  for (int i = 0; i < p.size(); ++i) {
    const Vec4<T>& column = use_acceleration ? p.acceleration.col(i) : p.velocity.col(i);
    const Eigen::Vector3d term =
        double(p.mass[i]) * column.template head<3>().template cast<double>();
    sum += term;
    scale += term.norm();
  }
  return {sum, scale};
}

template <typename T>
double kineticEnergy(const Particles<T>& p) {
  double energy = 0;
  for (int i = 0; i < p.size(); ++i)
    energy += 0.5 * double(p.mass[i]) *
              p.velocity.col(i).template head<3>().template cast<double>().squaredNorm();
  return energy;
}

template <typename T>
class Property : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(Property, Scalars);

// Equal masses: the force on the start is exactly minus the force on the end (the same product,
// negated); unequal masses: m_s a_s + m_e a_e = 0 up to rounding.
TYPED_TEST(Property, SpringForceIsAntisymmetric) {
  using T = TypeParam;
  std::mt19937_64 random(1);
  for (int trial = 0; trial < kTrials; ++trial) {
    Cloth<T> cloth;
    const bool equal = trial % 2 == 0;
    cloth.particles = makeParticles<T>(2, T(uniform(random, 0.5, 2)));
    if (!equal) setMass(cloth.particles, 1, T(uniform(random, 0.01, 100)));
    for (int i = 0; i < 2; ++i) {
      cloth.particles.position.col(i) = randomVector<T>(random, 1, T(1));
      cloth.particles.velocity.col(i) = randomVector<T>(random, 2, T(0));
    }
    cloth.springs = {Spring<T>{0, 1, T(uniform(random, 0.1, 2)), SpringType::Structural}};
    cloth.spring_coef = T(uniform(random, 1, 3e4));
    cloth.damper_coef = T(uniform(random, 0, 1000));
    computeSpringForce(cloth);
    const Particles<T>& p = cloth.particles;
    if (equal) {
      ASSERT_EQ(p.acceleration.col(0), (-p.acceleration.col(1)).eval()) << "trial " << trial;
    } else {
      const auto [sum, scale] = massWeightedSum(p, true);
      ASSERT_LE(sum.norm(), relativeTolerance<T>() * scale) << "trial " << trial;
    }
  }
}

// A random 5x5 cloth with random masses, jittered positions and velocities: the spring forces
// sum to zero over the whole body (fixed summation order, so only rounding remains).
TYPED_TEST(Property, SpringForcesSumToZeroOverACloth) {
  using T = TypeParam;
  std::mt19937_64 random(2);
  for (int trial = 0; trial < kTrials / 10; ++trial) {
    Cloth<T> cloth;
    cloth.particles = initializeVertex<T>(5, T(1), T(0), T(1));
    initializeSpring(cloth, 5);
    for (int i = 0; i < cloth.particles.size(); ++i) {
      setMass(cloth.particles, i, T(uniform(random, 0.1, 10)));
      cloth.particles.position.col(i) += randomVector<T>(random, 0.05, T(0));
      cloth.particles.velocity.col(i) = randomVector<T>(random, 1, T(0));
    }
    cloth.spring_coef = T(25000);
    cloth.damper_coef = T(750);
    computeSpringForce(cloth);
    const auto [sum, scale] = massWeightedSum(cloth.particles, true);
    ASSERT_LE(sum.norm(), relativeTolerance<T>() * scale) << "trial " << trial;
  }
}

// At its rest length and with no relative velocity a spring pulls on nothing, exactly.
TYPED_TEST(Property, NoForceAtRestLengthWithoutRelativeVelocity) {
  using T = TypeParam;
  std::mt19937_64 random(3);
  for (int trial = 0; trial < kTrials; ++trial) {
    Cloth<T> cloth;
    cloth.particles = makeParticles<T>(2, T(1));
    cloth.particles.position.col(0) = randomVector<T>(random, 1, T(1));
    cloth.particles.position.col(1) = randomVector<T>(random, 1, T(1));
    const Vec4<T> common = randomVector<T>(random, 3, T(0));
    cloth.particles.velocity.col(0) = common;
    cloth.particles.velocity.col(1) = common;
    const T rest = (cloth.particles.position.col(0) - cloth.particles.position.col(1)).norm();
    cloth.springs = {Spring<T>{0, 1, rest, SpringType::Structural}};
    cloth.spring_coef = T(uniform(random, 1, 3e4));
    cloth.damper_coef = T(uniform(random, 0, 1000));
    computeSpringForce(cloth);
    ASSERT_TRUE(cloth.particles.acceleration.isZero(0)) << "trial " << trial;
  }
}

// Random overlapping sphere pairs (masses 1..100x apart, random e, random velocities): total
// momentum is kept and kinetic energy never grows.
TYPED_TEST(Property, SphereSphereContactKeepsMomentumAndNeverGainsEnergy) {
  using T = TypeParam;
  std::mt19937_64 random(4);
  for (int trial = 0; trial < kTrials; ++trial) {
    Spheres<T> spheres;
    spheres.particles = makeParticles<T>(0, T(0));
    const double ra = uniform(random, 0.2, 1);
    const double rb = uniform(random, 0.2, 1);
    const Vec4<T> a = randomVector<T>(random, 1, T(1));
    // b within contact distance of a, in a random direction
    Vec4<T> direction = randomVector<T>(random, 1, T(0));
    direction.normalize();
    const Vec4<T> b = a + direction * T(uniform(random, 0.5, 0.999) * (ra + rb));
    addSphere(spheres, a, T(ra), T(1000));
    addSphere(spheres, b, T(rb), T(1000));
    setMass(spheres.particles, 1,
            T(double(spheres.particles.mass[0]) * uniform(random, 0.01, 100)));
    spheres.particles.velocity.col(0) = randomVector<T>(random, 3, T(0));
    spheres.particles.velocity.col(1) = randomVector<T>(random, 3, T(0));
    const auto [momentum_before, scale] = massWeightedSum(spheres.particles, false);
    const double energy_before = kineticEnergy(spheres.particles);
    collide(spheres, T(uniform(random, 0, 1)), T(0.15));
    const auto [momentum_after, unused] = massWeightedSum(spheres.particles, false);
    ASSERT_LE((momentum_after - momentum_before).norm(), relativeTolerance<T>() * scale)
        << "trial " << trial;
    ASSERT_LE(kineticEnergy(spheres.particles), energy_before * (1 + relativeTolerance<T>()))
        << "trial " << trial;
  }
}

// A sphere among random cloth particles, some inside it: free particles keep the total
// momentum; with some particles fixed, energy still never grows.
TYPED_TEST(Property, SphereClothContactKeepsMomentumAndNeverGainsEnergy) {
  using T = TypeParam;
  std::mt19937_64 random(5);
  for (int trial = 0; trial < kTrials / 4; ++trial) {
    const bool with_fixed = trial % 2 == 1;
    Spheres<T> spheres;
    spheres.particles = makeParticles<T>(0, T(0));
    addSphere(spheres, Vec4<T>(0, 0, 0, 1), T(uniform(random, 0.3, 1)), T(1000));
    spheres.particles.velocity.col(0) = randomVector<T>(random, 3, T(0));
    Cloth<T> cloth;
    cloth.particles = makeParticles<T>(8, T(1));
    for (int i = 0; i < 8; ++i) {
      cloth.particles.position.col(i) = randomVector<T>(random, 1, T(1));
      cloth.particles.velocity.col(i) = randomVector<T>(random, 3, T(0));
      setMass(cloth.particles, i, T(uniform(random, 0.1, 10)));
      if (with_fixed && i % 3 == 0) {
        setMass(cloth.particles, i, T(0));
        cloth.particles.velocity.col(i).setZero();
      }
    }
    auto total = [&]() {
      auto [p_sphere, s_sphere] = massWeightedSum(spheres.particles, false);
      auto [p_cloth, s_cloth] = massWeightedSum(cloth.particles, false);
      return std::make_pair(Eigen::Vector3d(p_sphere + p_cloth), s_sphere + s_cloth);
    };
    const auto [momentum_before, scale] = total();
    const double energy_before = kineticEnergy(spheres.particles) + kineticEnergy(cloth.particles);
    collide(spheres, cloth, T(uniform(random, 0, 1)), T(0.15));
    const double energy_after = kineticEnergy(spheres.particles) + kineticEnergy(cloth.particles);
    ASSERT_LE(energy_after, energy_before * (1 + relativeTolerance<T>())) << "trial " << trial;
    if (!with_fixed) {
      // each contact's impulse is bounded by the pair's momentum, so the scale bounds rounding
      ASSERT_LE((total().first - momentum_before).norm(), 8 * relativeTolerance<T>() * scale)
          << "trial " << trial;
    }
  }
}

}  // namespace
}  // namespace clothref
