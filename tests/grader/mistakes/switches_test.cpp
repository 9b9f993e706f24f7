// Structs of switches read field by field without a list of their fields (grader/grade/mistakes/
// switches.h): every field is visited in order, and merging two models takes each switch one of
// them changes, failing when both change one switch differently.
#include "grader/grade/mistakes/switches.h"

#include <gtest/gtest.h>

#include <array>
#include <tuple>

namespace clothref::grader::integrators {
namespace {

// The kinds of field the step's switches have, each default "the course's".
struct Lines {
  std::array<float, 3> stage{0.5f, 0.5f, 1.0f};
  bool first = false;
  int from = -1;
  bool second = false, on = true;
};

TEST(Switches, EveryFieldIsVisitedInOrder) {
  Lines lines;
  EXPECT_EQ(std::tuple_size_v<decltype(switches::fields(lines))>, 5u);
  std::get<2>(switches::fields(lines)) = 7;
  std::get<4>(switches::fields(lines)) = false;
  EXPECT_EQ(lines.from, 7);
  EXPECT_FALSE(lines.on);
}

TEST(Switches, MergeTakesWhatEitherChangesAndFailsOnOneSwitchSetTwoWays) {
  Lines both;
  EXPECT_TRUE(switches::merge(both, Lines{.first = true}));
  EXPECT_TRUE(switches::merge(both, Lines{.stage = {0.5f, 0.5f, 0.5f}, .on = false}));
  EXPECT_TRUE(switches::merge(both, Lines{.first = true, .from = 1}));  // the same value again
  EXPECT_TRUE(both.first);
  EXPECT_EQ(both.from, 1);
  EXPECT_FALSE(both.on);
  EXPECT_EQ(both.stage[2], 0.5f);
  EXPECT_FALSE(both.second);
  Lines other = both;
  EXPECT_FALSE(switches::merge(other, Lines{.from = 2}));  // from: 1 and 2
  EXPECT_FALSE(switches::merge(other, Lines{.stage = {1.0f, 1.0f, 1.0f}}));
  EXPECT_TRUE(switches::merge(other, Lines{}));  // the course's changes nothing
}

}  // namespace
}  // namespace clothref::grader::integrators
