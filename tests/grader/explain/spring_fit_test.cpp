// Reading a spring force back in the course's terms (grader/grade/explain/spring_fit.h): forces
// made here on a perturbed, moving cloth with the course's formula (clothref::formula::springForce,
// in float as a student's code runs) and with one thing changed; the course's reads as the
// course's, and each change is named (a constant with the value that fits).
#include "grader/grade/explain/spring_fit.h"

#include <gtest/gtest.h>

#include <random>

#include "clothref/formula/course_formulas.h"
#include "grader/grade/cause_ids.h"

namespace clothref::grader {
namespace {

constexpr double kSpring = 25000, kDamper = 750;

enum class Change {
  None,
  SpringHalved,
  SpringSign,
  DamperSign,
  NoDamper,
  Unnormalised,
  OneEnd,
  MassNotInverse,
  WholeSign,  // the ends or += and -= swapped: both terms flipped
  EndOnly,
  UnnormalisedTwice  // k_d ((v_s - v_e) . d) d
};

// A 6 x 6 cloth of the course's grid, perturbed and moving (`moving` false: at rest), with fixed,
// heavy and light particles, and the change a student's computeSpringForce makes to it.
SpringCase makeCase(Change change, bool moving, unsigned seed) {
  constexpr int n = 6;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1, 1);
  SpringCase c;
  std::vector<std::array<float, 4>> x, v;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      x.push_back(
          {0.2f * float(j) + 0.01f * u(rng), 0.01f * u(rng), 0.2f * float(i) + 0.01f * u(rng), 1});
      v.push_back(
          {moving ? 0.5f * u(rng) : 0, moving ? 0.5f * u(rng) : 0, moving ? 0.5f * u(rng) : 0, 0});
      const int k = i * n + j;
      c.mass.push_back(k == 0 || k == n - 1 ? 0.0 : k % 7 == 3 ? 4.0 : k % 5 == 2 ? 0.25 : 1.0);
    }
  formula::forEachGridSpring(n, [&](int family, int s, int e) {
    const double rest = family < 2 ? 0.2 : family < 4 ? 0.2 * std::sqrt(2.0) : 0.4;
    c.springs.push_back({s, e, rest});
  });
  std::vector<std::array<float, 4>> a(x.size(), {0, 0, 0, 0});
  for (const auto& s : c.springs) {
    const std::size_t i = std::size_t(s.start), j = std::size_t(s.end);
    const float ks = change == Change::SpringHalved ? float(kSpring / 2)
                     : change == Change::SpringSign || change == Change::WholeSign ? float(-kSpring)
                                                                                   : float(kSpring);
    const float kd = change == Change::DamperSign || change == Change::WholeSign ? float(-kDamper)
                     : change == Change::NoDamper                                ? 0.0f
                                                                                 : float(kDamper);
    float force[4];
    formula::springForce(
        x[i].data(), x[j].data(), v[i].data(), v[j].data(), float(s.rest), ks,
        change == Change::Unnormalised || change == Change::UnnormalisedTwice ? 0.0f : kd, force);
    if (change == Change::UnnormalisedTwice) {  // k_d (dv . d) d
      float d[4], dv[4];
      for (int k = 0; k < 4; ++k) d[k] = x[i][k] - x[j][k], dv[k] = v[i][k] - v[j][k];
      const float along = formula::dot4(dv, d);
      for (int k = 0; k < 4; ++k) force[k] += d[k] * (kd * along);
    }
    if (change == Change::Unnormalised) {  // k_d (dv . d) along the unit direction
      float d[4], dv[4];
      for (int k = 0; k < 4; ++k) d[k] = x[i][k] - x[j][k], dv[k] = v[i][k] - v[j][k];
      const float length = std::sqrt(formula::dot4(d, d)), along = formula::dot4(dv, d);
      for (int k = 0; k < 4; ++k) force[k] += d[k] / length * (kd * along);
    }
    const auto weight = [&](std::size_t p) {
      const float m = float(c.mass[p]);
      return change == Change::MassNotInverse ? m : m == 0 ? 0.0f : 1.0f / m;
    };
    for (int k = 0; k < 4; ++k) {
      if (change != Change::EndOnly) a[i][k] -= force[k] * weight(i);
      if (change != Change::OneEnd) a[j][k] += force[k] * weight(j);
    }
  }
  for (std::size_t p = 0; p < x.size(); ++p) {
    c.x.push_back({x[p][0], x[p][1], x[p][2]});
    c.v.push_back({v[p][0], v[p][1], v[p][2]});
    c.change.push_back({a[p][0], a[p][1], a[p][2]});
  }
  return c;
}

std::vector<SpringFinding> explain(Change change) {
  std::vector<SpringReading> readings;
  for (unsigned seed : {1u, 2u})
    readings.push_back(readSprings(makeCase(change, seed == 2, seed), 1e-4));
  return explainSprings(readings, kSpring, kDamper);
}

TEST(SpringFit, TheCoursesForceReadsAsTheCourses) {
  const SpringReading moving = readSprings(makeCase(Change::None, true, 3), 1e-4);
  EXPECT_TRUE(moving.fits) << moving.residual;
  EXPECT_EQ(moving.form, SpringForm::Course);
  EXPECT_NEAR(moving.spring_coef, kSpring, 1e-3 * kSpring);
  EXPECT_NEAR(moving.damper_coef, kDamper, 1e-3 * kDamper);
  const SpringReading still = readSprings(makeCase(Change::None, false, 4), 1e-4);
  EXPECT_TRUE(still.fits);
  EXPECT_TRUE(std::isnan(still.damper_coef));  // at rest the damper says nothing
  EXPECT_TRUE(explain(Change::None).empty());
}

TEST(SpringFit, EachChangeIsNamed) {
  const struct {
    Change change;
    const char* cause;
    const char* text;  // part of the text
  } expected[] = {
      {Change::SpringHalved, cause::kSpringCoefficient, "k_s = 12500 N/m"},
      {Change::SpringSign, cause::kSpringForceSign, "pushes its ends apart"},
      {Change::DamperSign, cause::kDamperSign, "adds energy"},
      {Change::NoDamper, cause::kMissingDamper, "k_d fits as 0"},
      {Change::Unnormalised, cause::kDamperNotNormalised, "unit direction"},
      {Change::OneEnd, cause::kForceOneEndOnly, "start particle"},
      {Change::MassNotInverse, cause::kMassNotInverse, "not the inverse mass"},
      {Change::WholeSign, cause::kSpringForceSign, "the whole force has the wrong sign"},
      {Change::EndOnly, cause::kForceOneEndOnly, "end particle"},
      {Change::UnnormalisedTwice, cause::kDamperNotNormalised, "in both places"}};
  for (const auto& e : expected) {
    const auto findings = explain(e.change);
    ASSERT_EQ(findings.size(), 1u) << e.cause;
    EXPECT_EQ(findings[0].cause, e.cause);
    EXPECT_NE(findings[0].text.find(e.text), std::string::npos) << findings[0].text;
  }
}

}  // namespace
}  // namespace clothref::grader
