// Reading an integrator probe's answer (grader/grade/probes/integrate/run.h): which non-finite
// numbers are an unstable method's overflow rather than a NaN of the stub's.
#include "grader/grade/probes/integrate/run.h"

#include <gtest/gtest.h>

#include <limits>

namespace clothref::grader::integrators {
namespace {

namespace key = probe::key;
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

TEST(IntegratorAnswer, OverflowAfterGrowthIsDivergenceAndASuddenNaNIsNot) {
  probe::ProbeMessage answer;
  answer.floats[key::perCase(key::kTrajectory, 4)] = {1.0f, 1.2f, 40.0f, 3e9f, 2e30f, kInf, kNaN};
  answer.floats[key::perCase(key::kClothPos, 4)] = {kNaN, kNaN, kNaN, 1.0f};
  answer.floats[key::perCase(key::kClothPos, 0)] = {0.5f, 1.0f};
  EXPECT_TRUE(onlyDivergedRuns(answer));
  // a NaN in another case's state (the one-step check's) is the stub's
  answer.floats[key::perCase(key::kClothVel, 0)] = {0.5f, kNaN};
  EXPECT_FALSE(onlyDivergedRuns(answer));
  answer.floats.erase(key::perCase(key::kClothVel, 0));
  // a trajectory that turns NaN without growing first is no divergence
  answer.floats[key::perCase(key::kTrajectory, 4)] = {1.0f, 1.2f, 1.1f, kNaN, kNaN};
  EXPECT_FALSE(onlyDivergedRuns(answer));
  // nothing non-finite at all: nothing to forgive
  answer.floats.erase(key::perCase(key::kClothPos, 4));
  answer.floats.erase(key::perCase(key::kTrajectory, 4));
  EXPECT_FALSE(onlyDivergedRuns(answer));
}

}  // namespace
}  // namespace clothref::grader::integrators
