// Work-precision sweeps (analysis/work_precision.h): errors converge at each method's order
// against the closed form, unstable points are flagged and kept, counts and timing statistics
// are consistent, and `clothref sweep` writes its CSV and JSON (or nothing, on bad input).
#include "clothref/analysis/work_precision.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "clothref/verify/verify.h"
#include "test_util.h"

namespace clothref {
namespace {

Method method(const char* name) {
  const std::optional<Method> m = parseMethod(name);
  EXPECT_TRUE(m) << name;
  return m.value_or(Method::Explicit);
}

SweepSettings springSettings(std::vector<int> substeps, int repeats = 1) {
  SweepSettings settings = defaultSweepSettings(*findBuiltinScene("spring"));
  settings.substeps = std::move(substeps);
  settings.repeats = repeats;
  return settings;
}

double observedOrder(const char* name, std::vector<int> substeps) {
  const Scene& scene = *findBuiltinScene("spring");
  const SweepSettings settings = springSettings(substeps);
  const SweepReference reference = sweepReference(scene, settings);
  std::vector<double> dts, errors;
  for (int s : substeps) {
    const SweepPoint p = sweepPoint(scene, method(name), Precision::Double, s, settings, reference);
    EXPECT_TRUE(p.stable);
    dts.push_back(p.dt);
    errors.push_back(*p.error_final);
  }
  return fitOrder(dts, errors);
}

TEST(WorkPrecision, ErrorsConvergeAtEachMethodsOrder) {
  EXPECT_NEAR(observedOrder("explicit", {80, 160, 320, 640}), 1.0, 0.2);
  EXPECT_NEAR(observedOrder("backward-euler", {80, 160, 320, 640}), 1.0, 0.2);
  EXPECT_NEAR(observedOrder("midpoint", {40, 80, 160, 320}), 2.0, 0.2);
  EXPECT_NEAR(observedOrder("rk4", {10, 20, 40, 80}), 4.0, 0.2);
}

TEST(WorkPrecision, UnstablePointsAreFlaggedAndKept) {
  const Scene& scene = *findBuiltinScene("spring");
  const SweepSettings settings = springSettings({1, 10}, 3);
  const SweepReference reference = sweepReference(scene, settings);
  // dt = 0.1 s is five times explicit Euler's limit on this spring: it grows, but stays within
  // the bounds over 1 s, so it keeps its (large) errors
  const SweepPoint p =
      sweepPoint(scene, method("explicit"), Precision::Float, 1, settings, reference);
  EXPECT_FALSE(p.stable);
  EXPECT_GT(*p.error_final, 0.2);
  // and dt = 0.01 s is stable
  EXPECT_TRUE(
      sweepPoint(scene, method("explicit"), Precision::Float, 10, settings, reference).stable);

  // course2022 at 5 ms blows up: the run stops, errors are null, it is timed once
  const Scene& course = *findBuiltinScene("course2022");
  SweepSettings course_settings = defaultSweepSettings(course);
  course_settings.horizon = 0.1;
  course_settings.reference_substeps = 50;  // 2e-4 s, inside RK4's limit
  const SweepReference course_reference = sweepReference(course, course_settings);
  const SweepPoint blown = sweepPoint(course, method("explicit"), Precision::Float, 2,
                                      course_settings, course_reference);
  EXPECT_FALSE(blown.stable);
  EXPECT_FALSE(blown.error_final.has_value());
  EXPECT_FALSE(blown.error_rms.has_value());
  EXPECT_EQ(blown.runs, 1);
  EXPECT_GT(blown.seconds_median, 0.0);
}

TEST(WorkPrecision, CountsAndTimingStatisticsAreConsistent) {
  const Scene& scene = *findBuiltinScene("spring");
  const SweepSettings settings = springSettings({20}, 5);
  const SweepReference reference = sweepReference(scene, settings);
  for (const char* name : {"explicit", "implicit", "rk4", "backward-euler"}) {
    const Method m = method(name);
    const SweepPoint p = sweepPoint(scene, m, Precision::Double, 20, settings, reference);
    EXPECT_EQ(p.steps, 200);  // 1 s at 5 ms
    EXPECT_EQ(p.evaluations, 200 * methodInfo(m).evaluations) << name;
    EXPECT_EQ(p.runs, 5);
    EXPECT_LE(p.seconds_min, p.seconds_median);
    EXPECT_LE(p.seconds_median, p.seconds_max);
    EXPECT_LE(p.cpu_seconds_min, p.cpu_seconds_median);
    EXPECT_LE(p.cpu_seconds_median, p.cpu_seconds_max);
    EXPECT_GT(p.cpu_seconds_min, 0.0);
    // the RMS over time of the max error is at most its maximum over time, which is at least
    // the final error's size order; both are positive
    EXPECT_GT(*p.error_final, 0.0);
    EXPECT_GT(*p.error_rms, 0.0);
    EXPECT_EQ(p.cg_iterations.has_value(), m == Method::BackwardEuler) << name;
  }
}

// The odeint peer's points: named after the stepper, counted as the counterpart method, and (the
// same step map) at the counterpart's error up to round-off, on the spring and on course2022
// (contacts included).
TEST(WorkPrecision, PeerPointsSitOnTheirCounterparts) {
  const Scene& scene = *findBuiltinScene("spring");
  const SweepSettings settings = springSettings({20, 40}, 1);
  const SweepReference reference = sweepReference(scene, settings);
  for (PeerStepper stepper : {PeerStepper::Euler, PeerStepper::Rk4}) {
    for (int substeps : {20, 40}) {
      const SweepPoint ours = sweepPoint(scene, peerCounterpart(stepper), Precision::Double,
                                         substeps, settings, reference);
      const SweepPoint peer =
          sweepPeerPoint(scene, stepper, Precision::Double, substeps, settings, reference);
      EXPECT_EQ(peer.method, peerStepperName(stepper));
      EXPECT_EQ(peer.evaluations, ours.evaluations);
      EXPECT_EQ(peer.stable, ours.stable);
      ASSERT_TRUE(peer.error_final && ours.error_final);
      EXPECT_GT(*peer.error_final, 1e-9);
      EXPECT_NEAR(*peer.error_final, *ours.error_final, 1e-12) << peer.method;
    }
  }
  const Scene& course = *findBuiltinScene("course2022");
  SweepSettings course_settings = defaultSweepSettings(course);
  course_settings.horizon = 0.05;
  course_settings.repeats = 1;
  course_settings.reference_substeps = 50;
  const SweepReference course_reference = sweepReference(course, course_settings);
  const SweepPoint ours =
      sweepPoint(course, method("rk4"), Precision::Double, 40, course_settings, course_reference);
  const SweepPoint peer = sweepPeerPoint(course, PeerStepper::Rk4, Precision::Double, 40,
                                         course_settings, course_reference);
  ASSERT_TRUE(peer.error_final && ours.error_final);
  EXPECT_NEAR(*peer.error_final, *ours.error_final, 1e-9);
}

TEST(WorkPrecision, FloatErrorsStopAtTheFloatFloor) {
  const Scene& scene = *findBuiltinScene("spring");
  const SweepSettings settings = springSettings({10240});
  const SweepReference reference = sweepReference(scene, settings);
  const SweepPoint f =
      sweepPoint(scene, method("rk4"), Precision::Float, 10240, settings, reference);
  const SweepPoint d =
      sweepPoint(scene, method("rk4"), Precision::Double, 10240, settings, reference);
  // RK4 at 1e-5 s is far below float's resolution: float sees round-off, double does not
  EXPECT_GT(*f.error_final, 1e-8);
  EXPECT_LT(*d.error_final, 1e-12);
}

}  // namespace
}  // namespace clothref
