// The analytic checks (verify.h) pass for the library's stubs, their machinery decides correctly,
// and `clothref verify` reports them with the documented exit codes and JSON shape.
#include "clothref/verify/verify.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "test_util.h"

namespace clothref {
namespace {

void expectAllPass(const std::vector<CheckRow>& rows) {
  ASSERT_FALSE(rows.empty());
  for (const CheckRow& row : rows)
    EXPECT_TRUE(row.pass) << row.check << " [" << row.method << ", " << precisionName(row.precision)
                          << "]: expected " << row.expected << ", observed " << row.observed
                          << ", tolerance " << row.tolerance;
}

TEST(MakeRow, AppliesItsRule) {
  EXPECT_TRUE(makeRow("c", "-", Precision::Double, 1, 1.15, 0.2).pass);
  EXPECT_FALSE(makeRow("c", "-", Precision::Double, 1, 1.25, 0.2).pass);
  EXPECT_FALSE(makeRow("c", "-", Precision::Double, 1, 0.75, 0.2).pass);
  // one-sided: anything below passes, above by more than the tolerance fails
  EXPECT_TRUE(makeRow("c", "-", Precision::Double, 0, -5, 1e-6, CheckRule::AtMost).pass);
  EXPECT_FALSE(makeRow("c", "-", Precision::Double, 0, 2e-6, 1e-6, CheckRule::AtMost).pass);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(makeRow("c", "-", Precision::Double, 0, nan, 1).pass);
  EXPECT_FALSE(makeRow("c", "-", Precision::Double, 0, nan, 1, CheckRule::AtMost).pass);
}

TEST(FitOrder, RecoversThePowerOfAnExactPowerLaw) {
  const std::array<double, 6> dts = {0.1, 0.05, 0.025, 0.0125, 0.00625, 0.003125};
  for (double p : {1.0, 2.0, 4.0}) {
    std::array<double, 6> errors{};
    for (std::size_t i = 0; i < dts.size(); ++i) errors[i] = 3.7 * std::pow(dts[i], p);
    EXPECT_NEAR(fitOrder(dts, errors), p, 1e-12);
  }
  // least squares, not the end points: a kink in the middle moves the slope
  const std::array<double, 3> kinked_dts = {1, 0.5, 0.25};
  const std::array<double, 3> kinked = {1, 0.25, 0.125};
  EXPECT_NEAR(fitOrder(kinked_dts, kinked), 1.5, 1e-12);
}

TEST(ClosedForm, EveryMethodSceneAndPrecisionIsWithinItsBound) {
  const std::vector<CheckRow> rows = closedFormChecks();
  // 3 scenes x 2 precisions x every method
  EXPECT_EQ(rows.size(), 3 * 2 * kAllMethods.size());
  expectAllPass(rows);
  // the bounds are not vacuous: every error is a measurable fraction of its bound in double
  for (const CheckRow& row : rows) {
    if (row.precision == Precision::Double) {
      EXPECT_GT(row.observed, 1e-4 * row.tolerance) << row.check;
    }
  }
}

TEST(Convergence, DoubleOrdersMatchTheMethods) {
  const std::vector<ConvergenceStudy> studies = convergenceStudies();
  ASSERT_EQ(studies.size(), 2 * kAllMethods.size());
  for (const ConvergenceStudy& study : studies) {
    SCOPED_TRACE(std::string(methodName(study.method)) + " " +
                 std::string(precisionName(study.precision)));
    EXPECT_GE(study.dts.size(), 6u);  // at least five halvings
    for (std::size_t i = 1; i < study.dts.size(); ++i)
      EXPECT_NEAR(study.dts[i - 1] / study.dts[i], 2, 1e-6);
    if (study.precision == Precision::Double) {
      ASSERT_TRUE(study.order.has_value());
      EXPECT_NEAR(*study.order, study.expected_order, 0.2);
      continue;
    }
    // float: every fitted point lies above 10x its round-off; the first-order methods and
    // midpoint have enough of them
    for (std::size_t i = 0; i < study.dts.size(); ++i) {
      if (study.fitted[i]) {
        EXPECT_GE(study.errors[i], 10 * study.roundoff[i]);
      }
    }
    if (study.method != Method::Rk4) {
      ASSERT_TRUE(study.order.has_value());
      EXPECT_NEAR(*study.order, study.expected_order, 0.2);
    }
  }
  expectAllPass(convergenceChecks(studies));
}

// Where contacts put the bodies: every row passes, each case has a position and a velocity row
// in both precisions, and a separating pair's velocity row is exact.
TEST(Contact, PositionsAndVelocitiesAreTheCoursesEquations) {
  const std::vector<CheckRow> rows = contactChecks();
  expectAllPass(rows);
  // 9 cases (4 particle-sphere, 4 sphere-pair, 1 fixed particle) x 2 rows x 2 precisions
  EXPECT_EQ(rows.size(), 9u * 2 * 2);
  int separating = 0;
  for (const CheckRow& row : rows) {
    if (row.check.find("separating") != std::string::npos &&
        row.check.find("v_before") != std::string::npos) {
      EXPECT_EQ(row.tolerance, 0.0) << row.check;
      ++separating;
    }
    EXPECT_LT(row.tolerance, row.precision == Precision::Float ? 1e-5 : 1e-13) << row.check;
  }
  EXPECT_EQ(separating, 4 * 2);
}

// The odeint peer agrees with the library's explicit, RK4 and symplectic Euler, and the bounds are
// round-off sized: far below what a changed stage would move (docs/verification.md).
TEST(Peer, LibraryMethodsAgreeWithOdeint) {
  const std::vector<CheckRow> rows = peerChecks();
  expectAllPass(rows);
  // cloth: 3 steppers x 2 precisions; sphere: 2 steppers x double
  EXPECT_EQ(rows.size(), 3u * 2 + 2);
  for (const CheckRow& row : rows) {
    EXPECT_NE(row.check.find("1000 steps"), std::string::npos) << row.check;
    EXPECT_LT(row.tolerance, row.precision == Precision::Float ? 1e-3 : 1e-11) << row.check;
  }
}

TEST(FreeCloth, EveryMethodKeepsMomentum) { expectAllPass(freeClothMomentumChecks()); }

TEST(Energy, EveryMethodBehavesAsItsAmplificationFactorSays) { expectAllPass(energyChecks()); }

// The fast kernels give the course-form stubs' bits on both course scenes, every method (so a bug
// in a stub that the fast paths shadow still fails verify).
TEST(CourseForm, FastKernelsMatchTheCourseFormStubs) {
  const std::vector<CheckRow> rows = courseFormChecks();
  EXPECT_EQ(rows.size(), 2 * kAllMethods.size());
  expectAllPass(rows);
  for (const CheckRow& row : rows) EXPECT_EQ(row.tolerance, 0.0) << row.check;
}

TEST(CourseFacts, BothCourseScenesHaveEveryFact) {
  const std::vector<CheckRow> rows = courseFactChecks();
  expectAllPass(rows);
  int per_scene[2] = {0, 0};
  for (const CheckRow& row : rows) per_scene[row.check.rfind("course2024", 0) == 0]++;
  EXPECT_GE(per_scene[0], 20);
  EXPECT_GE(per_scene[1], 20);
}

// The expected values tell the methods apart by far more than the tolerances: explicit grows,
// implicit decays, midpoint grows slowly, rk4 decays slowly (in double), symplectic is bounded,
// backward Euler decays as 1 / (1 + theta^2) per step: close to the course's implicit
// (1 - theta^2 + theta^4) but theta^6 per step apart.
TEST(Energy, ExpectationsSeparateTheMethods) {
  std::map<std::string, CheckRow> doubles;
  for (const CheckRow& row : energyChecks())
    if (row.precision == Precision::Double) doubles[row.method] = row;
  ASSERT_EQ(doubles.size(), kAllMethods.size());
  EXPECT_GT(doubles["explicit"].expected, 5.0);
  EXPECT_LT(doubles["implicit"].expected, 0.2);
  EXPECT_GT(doubles["midpoint"].expected - 1, 100 * doubles["midpoint"].tolerance);
  EXPECT_GT(1 - doubles["rk4"].expected, 100 * doubles["rk4"].tolerance);
  EXPECT_EQ(doubles["symplectic"].rule, CheckRule::AtMost);
  EXPECT_LT(doubles["symplectic"].expected, 0.2);
  EXPECT_LT(doubles["backward-euler"].expected, doubles["implicit"].expected);
  EXPECT_GT(doubles["implicit"].expected - doubles["backward-euler"].expected,
            100 * doubles["implicit"].tolerance);
  // a forward-Euler-like growth would be far outside the symplectic bound
  EXPECT_GT(std::pow(1.04, 1000) - 1, 10 * doubles["symplectic"].expected);
}

}  // namespace
}  // namespace clothref
