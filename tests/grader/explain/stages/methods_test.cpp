// The course integrators as coefficient tables (grader/grade/explain/stages/methods.h), proven by
// replay against the library: each course table, run on a system as the course's code runs it
// (simulateOneStep() before, backups x0 and v0, each evaluation's state from them and the
// derivatives met so far, then the result), is the library's step of that method. The table's sums
// of h v_k and h a_k round differently from the library's (k1 + 2 k2 + 2 k3 + k4) / 6 by design,
// so the replay agrees within a tolerance, not bit for bit (docs/design.md's table of copies).
#include "grader/grade/explain/stages/methods.h"

#include <gtest/gtest.h>

#include <array>

#include "grader/grade/mistakes/integrate_mistakes.h"
#include "grader/grade/mistakes/system.h"
#include "grader/grade/probes/integrate/systems.h"

namespace clothref::grader::integrators {
namespace {

using stages::kOwn;
using stages::MethodState;
using stages::MethodTerm;

// The state `st` of a table from the backups and the derivatives met so far: v first (a position
// may use its own new velocity).
void setState(const MethodState& st, float h, const std::array<Particles<float>*, 2>& bodies,
              const std::array<Mat4X<float>, 2>& x0, const std::array<Mat4X<float>, 2>& v0,
              const std::vector<std::array<Mat4X<float>, 2>>& vs,
              const std::vector<std::array<Mat4X<float>, 2>>& as) {
  const auto c = [](const MethodTerm& t) { return float(double(t.num) / t.den); };
  for (std::size_t b = 0; b < 2; ++b) {
    Mat4X<float> v = v0[b];
    for (const MethodTerm& t : st.v) v += (as[std::size_t(t.index)][b] * h) * c(t);
    Mat4X<float> x = x0[b];
    for (const MethodTerm& t : st.x)
      x += ((t.index == kOwn ? v : vs[std::size_t(t.index)][b]) * h) * c(t);
    bodies[b]->position = x;
    bodies[b]->velocity = v;
  }
}

Step tableStep(const stages::MethodTable& table) {
  return [&table](System& s) {
    simulate(s);
    const std::array<Particles<float>*, 2> bodies{&s.cloth.particles, &s.spheres.particles};
    std::array<Mat4X<float>, 2> x0{bodies[0]->position, bodies[1]->position};
    std::array<Mat4X<float>, 2> v0{bodies[0]->velocity, bodies[1]->velocity};
    std::vector<std::array<Mat4X<float>, 2>> vs{v0},
        as{{bodies[0]->acceleration, bodies[1]->acceleration}};
    for (const MethodState& e : table.evaluations) {
      setState(e, s.dt, bodies, x0, v0, vs, as);
      simulate(s);
      vs.push_back({bodies[0]->velocity, bodies[1]->velocity});
      as.push_back({bodies[0]->acceleration, bodies[1]->acceleration});
    }
    setState(table.result, s.dt, bodies, x0, v0, vs, as);
  };
}

TEST(StageMethods, EachCourseTableReplaysTheLibrarysMethod) {
  const std::vector<System> systems = {randomSystem(20221, 2022), randomSystem(20228, 2024),
                                       courseSystem(20221, 2022), courseSystem(20235, 2024)};
  for (int index = 0; index < 4; ++index) {
    const Method method = integratorMethod(index);
    for (const System& s : systems) {
      const System library = stepped(s, clothrefStep(method));
      EXPECT_LE(distance(stepped(s, tableStep(stages::courseTable(index))), library), 1e-6)
          << methodName(method) << " on " << s.cloth.particles.size() << " particles";
      // the replay sees a method's difference: another course method is far from it
      EXPECT_GT(distance(stepped(s, tableStep(stages::courseTable((index + 1) % 4))), library),
                1e-5)
          << methodName(method) << " against table " << (index + 1) % 4;
    }
  }
}

// Each accepted variant's table is that variant's reading of the one course step
// (mistakes/integrate_mistakes.h), so the stage fit and the replay mean the same code.
TEST(StageMethods, EachAcceptedTableIsItsReading) {
  const System s = randomSystem(20221, 2022);
  int accepted = 0;
  for (const stages::MethodTable& t : stages::methodTables()) {
    if (t.accepted.empty()) continue;
    ++accepted;
    const Method method = integratorMethod(t.stub);
    ASSERT_FALSE(readingsOf(t.accepted, method).empty()) << t.id;
    EXPECT_LE(distance(stepped(s, tableStep(t)), stepped(s, readingStep(t.accepted, method))), 1e-6)
        << t.id;
  }
  EXPECT_GT(accepted, 0);
}

// RK4 weights fitted on a student's k that are the course's on k of other stages read as such:
// k1 read after stage 4 (blind3 ko-big5) is k4 where k1 belongs; other weights are not.
TEST(StageMethods, CourseWeightsOnOtherStagesAreNamedByTheStageTheyCameFrom) {
  const double sixth = 1.0 / 6, third = 1.0 / 3;
  const auto k4ForK1 = stages::courseWeightsOnOtherStages({0, third, third, third});
  ASSERT_TRUE(k4ForK1.has_value());
  EXPECT_EQ(*k4ForK1, (std::array<int, 4>{3, 1, 2, 3}));
  EXPECT_EQ(stages::otherStagesText(*k4ForK1), "k4 where k1 belongs");
  const auto k3ForK4 = stages::courseWeightsOnOtherStages({sixth, third, 0.5, 0});
  ASSERT_TRUE(k3ForK4.has_value());
  EXPECT_EQ(stages::otherStagesText(*k3ForK4), "k3 where k4 belongs");
  // the course's own weights, other weights, and nothing added are no such reading
  EXPECT_FALSE(stages::courseWeightsOnOtherStages({sixth, third, third, sixth}));
  EXPECT_FALSE(stages::courseWeightsOnOtherStages({0.25, 0.25, 0.25, 0.25}));
  EXPECT_FALSE(stages::courseWeightsOnOtherStages({0, 0, 0, 0}));
  // a least-squares fit is read within its tolerance only
  EXPECT_TRUE(stages::courseWeightsOnOtherStages({1e-4, third, third, third + 1e-4}, 1e-3));
  EXPECT_FALSE(stages::courseWeightsOnOtherStages({1e-4, third, third, third + 1e-4}));
}

}  // namespace
}  // namespace clothref::grader::integrators
