#include "clothref/core/cloth.h"

#include <cmath>

#include <gtest/gtest.h>

#include "test_util.h"

namespace clothref {
namespace {

template <typename T>
Cloth<T> gridCloth(int n) {
  Cloth<T> cloth;
  cloth.particles = initializeVertex<T>(n, T(2), T(0), T(1));
  initializeSpring(cloth, n);
  return cloth;
}

std::array<int, 3> countByType(const Cloth<float>& cloth) {
  std::array<int, 3> counts{};
  for (const auto& spring : cloth.springs) ++counts[static_cast<int>(spring.type)];
  return counts;
}

TEST(InitializeSpring, CourseCountsAtN25) {
  const auto counts = countByType(gridCloth<float>(25));
  EXPECT_EQ(counts[0], 1200);
  EXPECT_EQ(counts[1], 1152);
  EXPECT_EQ(counts[2], 1150);
}

TEST(InitializeSpring, CountsFollowTheFormulasForOtherSizes) {
  for (int n : {2, 3, 4, 7, 10, 31}) {
    const auto counts = countByType(gridCloth<float>(n));
    EXPECT_EQ(counts[0], 2 * n * (n - 1)) << "n = " << n;
    EXPECT_EQ(counts[1], 2 * (n - 1) * (n - 1)) << "n = " << n;
    EXPECT_EQ(counts[2], 2 * n * (n - 2)) << "n = " << n;
  }
}

TEST(InitializeSpring, RestLengthsAtN25) {
  const Cloth<float> cloth = gridCloth<float>(25);
  for (const auto& spring : cloth.springs) {
    const float expected = spring.type == SpringType::Structural ? 1.0f / 6
                           : spring.type == SpringType::Shear    ? std::sqrt(2.0f) / 6
                                                                 : 1.0f / 3;
    ASSERT_NEAR(spring.rest_length, expected, 1e-6f);
  }
  // the course's float bits (docs/course.md §5): |p0-p1|, |p0-p26|, |p0-p2|
  EXPECT_EQ(test::bits(cloth.springs.front().rest_length), 0x3e2aaaa8u);
  EXPECT_EQ(test::bits(cloth.springs[1200].rest_length), 0x3e715bebu);
  EXPECT_EQ(test::bits(cloth.springs.back().rest_length), 0x3eaaaaacu);
}

TEST(InitializeSpring, SixPassesInTheCourseOrder) {
  const int n = 25;
  const Cloth<float> cloth = gridCloth<float>(n);
  // first spring of each pass, and its (start, end) offset
  struct Pass {
    int first;
    int start;
    int end;
    SpringType type;
  };
  const Pass passes[] = {{0, 0, 1, SpringType::Structural},   {600, 0, n, SpringType::Structural},
                         {1200, 0, n + 1, SpringType::Shear}, {1776, 1, n, SpringType::Shear},
                         {2352, 0, 2, SpringType::Bend},      {2927, 0, 2 * n, SpringType::Bend}};
  for (const Pass& pass : passes) {
    const auto& spring = cloth.springs[pass.first];
    EXPECT_EQ(spring.start, static_cast<std::uint32_t>(pass.start)) << pass.first;
    EXPECT_EQ(spring.end, static_cast<std::uint32_t>(pass.end)) << pass.first;
    EXPECT_EQ(spring.type, pass.type) << pass.first;
  }
  for (const auto& spring : cloth.springs) ASSERT_LT(spring.start, spring.end);
}

TEST(InitializeVertex, CourseGridBits) {
  const Particles<float> p = initializeVertex<float>(25, 2.0f, 0.0f, 1.0f);
  // 4.0f / 24 = 0x3e2aaaab; x_j = -2 + j * step, two roundings, no FMA (docs/course.md §5)
  const float step = 4.0f / 24;
  EXPECT_EQ(test::bits(step), 0x3e2aaaabu);
  for (int j = 0; j < 25; ++j) {
    volatile float product = float(j) * step;  // volatile keeps the two roundings apart
    EXPECT_EQ(test::bits(p.position(0, j)), test::bits(-2.0f + product)) << j;
  }
  EXPECT_EQ(p.position(0, 12), 0.0f);  // the centre column is exactly 0 without FMA
  EXPECT_EQ(p.position(2, 312), 0.0f);
  EXPECT_EQ(p.position(3, 100), 1.0f);
}

TEST(ComputeSpringForce, HookeAndDamperAlongTheAxis) {
  Cloth<double> cloth;
  cloth.particles = makeParticles<double>(2, 2.0);
  cloth.particles.position.col(1) = Vec4<double>(1.5, 0, 0, 1);
  cloth.particles.velocity.col(0) = Vec4<double>(0.3, 0.7, 0, 0);
  cloth.springs = {Spring<double>{0, 1, 1.0, SpringType::Structural}};
  cloth.spring_coef = 10;
  cloth.damper_coef = 2;
  computeSpringForce(cloth);
  // d = x0 - x1 = (-1.5, 0, 0), n = (-1, 0, 0): s = k_d (v0 - v1).n + k_s (L - L0) = -0.6 + 5
  const double s = 2 * -0.3 + 10 * 0.5;
  EXPECT_DOUBLE_EQ(cloth.particles.acceleration(0, 0), s / 2.0);   // a_s -= F / m, F = s n
  EXPECT_DOUBLE_EQ(cloth.particles.acceleration(0, 1), -s / 2.0);  // a_e += F / m
  // the perpendicular velocity component produces no force
  EXPECT_EQ(cloth.particles.acceleration(1, 0), 0.0);
  EXPECT_EQ(cloth.particles.acceleration(1, 1), 0.0);
}

TEST(ComputeSpringForce, AccumulatesAndSparesFixedParticles) {
  Cloth<float> cloth = gridCloth<float>(5);
  cloth.spring_coef = 100;
  cloth.damper_coef = 1;
  setMass(cloth.particles, 0, 0.0f);
  cloth.particles.position(1, 6) = 0.1f;  // lift one particle
  cloth.particles.acceleration.setConstant(7.0f);
  cloth.particles.acceleration.row(3).setZero();
  computeSpringForce(cloth);
  EXPECT_EQ(cloth.particles.acceleration(1, 0), 7.0f);   // fixed: invM = 0, untouched
  EXPECT_LT(cloth.particles.acceleration(1, 6), 7.0f);   // pulled back down, on top of 7
  EXPECT_EQ(cloth.particles.acceleration(1, 24), 7.0f);  // no spring reaches the far corner
}

}  // namespace
}  // namespace clothref
