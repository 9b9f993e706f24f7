// Stability limits (analysis/stability.h): the amplification theory gives the textbook limits,
// the measured limits on the spring scenes agree with it within 1 % for every method in float
// and double, course2022's explicit limit matches the linearised cloth, and the CLI prints the
// documented JSON.
#include "clothref/analysis/stability.h"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "test_util.h"

namespace clothref {
namespace {

Method method(const char* name) {
  const std::optional<Method> m = parseMethod(name);
  EXPECT_TRUE(m) << name;
  return m.value_or(Method::Explicit);
}

TEST(StabilityTheory, TextbookLimitsOnOneMode) {
  const double omega = 10, zeta = 0.1;
  const Mode undamped{omega * omega, 0};
  const Mode damped{omega * omega, 2 * zeta * omega};
  const auto limit = [](const char* name, const Mode& mode) {
    return theoryLimit(method(name), {mode});
  };
  EXPECT_NEAR(limit("explicit", damped).dt, 2 * zeta / omega, 1e-9);
  EXPECT_EQ(limit("explicit", undamped).kind, TheoryKind::NeverStable);
  EXPECT_EQ(limit("midpoint", undamped).kind, TheoryKind::NeverStable);
  EXPECT_EQ(limit("midpoint", damped).kind, TheoryKind::Limit);
  EXPECT_NEAR(limit("symplectic", undamped).dt, 2 / omega, 1e-9);
  EXPECT_NEAR(limit("rk4", undamped).dt, 2 * std::sqrt(2.0) / omega, 1e-9);
  // 1 + z + z^2 on the imaginary axis: |R|^2 = 1 - z^2 + z^4 <= 1 up to z = 1
  EXPECT_NEAR(limit("implicit", undamped).dt, 1 / omega, 1e-9);
  EXPECT_EQ(limit("backward-euler", undamped).kind, TheoryKind::AlwaysStable);
  EXPECT_EQ(limit("backward-euler", damped).kind, TheoryKind::AlwaysStable);
  // a scene's limit is its most restrictive mode's
  const Mode stiff{4 * omega * omega, 0};
  EXPECT_NEAR(theoryLimit(method("rk4"), {undamped, stiff}).dt, std::sqrt(2.0) / omega, 1e-9);
}

TEST(StabilityTheory, SpectralRadiusCrossesOneAtTheLimit) {
  const Mode undamped{100, 0};
  EXPECT_LT(stepSpectralRadius(method("symplectic"), undamped, 0.199), 1 + 1e-12);
  EXPECT_GT(stepSpectralRadius(method("symplectic"), undamped, 0.201), 1.01);
  // a drag-only mode has radius 1 exactly at every h (no cancellation noise)
  const Mode drag{0, 3.4e-4};
  for (double h : {1e-3, 1.0, 100.0})
    EXPECT_LE(stepSpectralRadius(method("symplectic"), drag, h), 1.0);
}

// The measured limits on the spring scenes agree with the amplification theory within 1 %.
class SpringStability : public ::testing::TestWithParam<std::tuple<const char*, const char*>> {};

TEST_P(SpringStability, MeasuredAgreesWithTheoryWithinOnePercent) {
  const auto [scene_name, method_name] = GetParam();
  const Scene& scene = *findBuiltinScene(scene_name);
  const Method m = method(method_name);
  const TheoryLimit theory = theoryLimit(m, sceneModes(scene));
  for (Precision precision : {Precision::Float, Precision::Double}) {
    const MeasuredLimit measured =
        measureLimit(scene, m, precision, stabilityCriterion(scene), searchRange(scene));
    switch (theory.kind) {
      case TheoryKind::Limit:
        ASSERT_EQ(measured.kind, MeasuredKind::Limit) << precisionName(precision);
        EXPECT_NEAR(measured.dt / theory.dt, 1.0, 0.01) << precisionName(precision);
        break;
      case TheoryKind::NeverStable:
        EXPECT_EQ(measured.kind, MeasuredKind::UnstableAtLow) << precisionName(precision);
        break;
      case TheoryKind::AlwaysStable:
        EXPECT_EQ(measured.kind, MeasuredKind::StableAtHigh) << precisionName(precision);
        break;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, SpringStability,
                         ::testing::Combine(::testing::Values("spring", "spring-undamped"),
                                            ::testing::Values("explicit", "implicit", "midpoint",
                                                              "rk4", "symplectic",
                                                              "backward-euler")),
                         [](const auto& info) {
                           std::string name =
                               std::string(std::get<0>(info.param)) + "_" + std::get<1>(info.param);
                           for (char& c : name)
                             if (c == '-') c = '_';
                           return name;
                         });

TEST(StabilityMeasured, TheCriterionFiresOnlyAboveTheLimit) {
  const Scene& scene = *findBuiltinScene("spring-undamped");
  const StabilityCriterion criterion = stabilityCriterion(scene);
  EXPECT_TRUE(runIsStable(scene, method("symplectic"), Precision::Double, 0.198, criterion));
  EXPECT_FALSE(runIsStable(scene, method("symplectic"), Precision::Double, 0.202, criterion));
}

TEST(StabilityCourse2022, ExplicitLimitMatchesTheLinearisedCloth) {
  const Scene& scene = *findBuiltinScene("course2022");
  const std::vector<Mode> modes = sceneModes(scene);
  // 621 free particles x 3
  EXPECT_EQ(modes.size(), 1863u);
  const TheoryLimit theory = theoryLimit(method("explicit"), modes);
  ASSERT_EQ(theory.kind, TheoryKind::Limit);
  const MeasuredLimit measured = measureLimit(scene, method("explicit"), Precision::Float,
                                              stabilityCriterion(scene), searchRange(scene));
  ASSERT_EQ(measured.kind, MeasuredKind::Limit);
  // the bisection stops within 1 %, so 2 % covers it
  EXPECT_NEAR(measured.dt / theory.dt, 1.0, 0.02);
}

TEST(StabilityJson, NullWhereThereIsNoLimit) {
  StabilityResult none;
  none.scene = "spring-undamped";
  none.method = "explicit";
  none.measured.kind = MeasuredKind::UnstableAtLow;
  none.theory.kind = TheoryKind::NeverStable;
  none.criterion = "c";
  StabilityResult some = none;
  some.method = "rk4";
  some.measured.kind = MeasuredKind::Limit;
  some.measured.dt = 0.28;
  some.measured.runs = 10;
  some.theory = {TheoryKind::Limit, 0.2828};
  const nlohmann::ordered_json json = stabilityToJson({none, some});
  ASSERT_EQ(json["results"].size(), 2u);
  EXPECT_TRUE(json["results"][0]["dt_max_measured"].is_null());
  EXPECT_TRUE(json["results"][0]["dt_max_theory"].is_null());
  EXPECT_DOUBLE_EQ(json["results"][1]["dt_max_measured"].get<double>(), 0.28);
  EXPECT_NEAR(json["results"][1]["ratio"].get<double>(), 0.28 / 0.2828, 1e-12);
}

}  // namespace
}  // namespace clothref
