// Particles a step holds still (grader/grade/probes/integrate/held_still.h): read per cloth size
// from both one-step states, laid over a step only on cloths of their size, and named as runs.
#include "grader/grade/probes/integrate/held_still.h"

#include <gtest/gtest.h>

namespace clothref::grader::integrators {
namespace {

// A run whose student step is `student` on the small random state and on the course's cloth with
// its corners unpinned.
IntegratorRun runOf(const Step& student) {
  IntegratorRun run;
  run.method = Method::Explicit;
  run.random = randomSystem(20221);
  run.actual = stepped(run.random, student);
  run.expected = stepped(run.random, clothrefStep(run.method));
  run.start = run.random;
  simulate(run.start);
  OneStep course;
  course.state = courseSystem(20221, 2024, true);
  course.actual = stepped(course.state, student);
  completeOneStep(course, run.method);
  run.course_cloth = course;
  return run;
}

TEST(HeldStill, PinsAreReadPerClothSize) {
  // particle 1 of every cloth stopped; the four corners put back only on a 625-particle cloth
  const IntegratorRun run = runOf([](System& s) {
    const Mat4X<float> before = s.cloth.particles.position;
    clothrefStep(Method::Explicit)(s);
    s.cloth.particles.velocity.col(1).setZero();
    if (s.cloth.particles.size() == 625)
      for (int c : {0, 24, 600, 624}) {
        s.cloth.particles.velocity.col(c).setZero();
        s.cloth.particles.position.col(c) = before.col(c);
      }
  });
  const std::vector<Pins> pins = pinnedParticles(run);
  ASSERT_EQ(pins.size(), 2u);
  EXPECT_EQ(pins[0].cloth_size, 16);
  EXPECT_EQ(pins[0].particles, (std::vector<int>{1}));
  EXPECT_FALSE(pins[0].positions);  // particle 1 moved by the step, then stopped
  EXPECT_EQ(pins[1].cloth_size, 625);
  EXPECT_EQ(pins[1].particles, (std::vector<int>{0, 1, 24, 600, 624}));
  EXPECT_FALSE(pins[1].positions);  // 1 is only stopped, so not all were put back
  EXPECT_TRUE(stoppedSpheres(run).empty());
}

TEST(HeldStill, PinsApplyOnlyToClothsOfTheirSize) {
  System small = randomSystem(3), course = courseSystem(3, 2024, true);
  ASSERT_EQ(small.cloth.particles.size(), 16);
  ASSERT_EQ(course.cloth.particles.size(), 625);
  const std::vector<Pins> pins = {{625, {0, 24}, false}};
  for (System* s : {&small, &course}) {
    clothrefStep(Method::Explicit)(*s);
    s->cloth.particles.velocity.col(0).setConstant(1);
    s->cloth.particles.velocity.col(2).setConstant(1);
  }
  holdStill(pins, {}, small, small.cloth.particles.position);
  holdStill(pins, {}, course, course.cloth.particles.position);
  EXPECT_FALSE(small.cloth.particles.velocity.col(0).isZero(0));  // not its size
  EXPECT_TRUE(course.cloth.particles.velocity.col(0).isZero(0));
  EXPECT_FALSE(course.cloth.particles.velocity.col(2).isZero(0));  // not pinned
}

TEST(HeldStill, IndicesReadAsRuns) {
  EXPECT_EQ(indexRanges({}), "");
  EXPECT_EQ(indexRanges({3}), "3");
  EXPECT_EQ(indexRanges({0, 1, 2, 6}), "0-2, 6");
  EXPECT_EQ(indexRanges({0, 24, 600, 624}), "0, 24, 600, 624");  // no even run of four
  std::vector<int> column;
  for (int row = 0; row < 25; ++row) column.push_back(24 + 25 * row);
  EXPECT_EQ(indexRanges(column), "24 to 624 in steps of 25");
  column.insert(column.begin(), {0, 1});
  EXPECT_EQ(indexRanges(column), "0-1, 24 to 624 in steps of 25");
}

}  // namespace
}  // namespace clothref::grader::integrators
