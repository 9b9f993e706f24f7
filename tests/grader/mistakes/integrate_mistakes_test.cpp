// The integrator mistakes as switches on one course step (grader/grade/mistakes/
// integrate_mistakes.h): with no row and no overlay, the step is the library's, bit for bit; each
// reading changes the step (so a student's numbers equal to it name it); the readings that are a
// library method on other bodies are that method, bit for bit.
#include "grader/grade/mistakes/integrate_mistakes.h"

#include <gtest/gtest.h>

#include <cstring>

#include "grader/grade/cause_ids.h"
#include "grader/grade/probes/integrate/systems.h"

namespace clothref::grader::integrators {
namespace {

bool bitEqual(const System& a, const System& b) {
  const auto same = [](const Mat4X<float>& x, const Mat4X<float>& y) {
    return x.cols() == y.cols() &&
           std::memcmp(x.data(), y.data(), sizeof(float) * std::size_t(x.size())) == 0;
  };
  return same(a.cloth.particles.position, b.cloth.particles.position) &&
         same(a.cloth.particles.velocity, b.cloth.particles.velocity) &&
         same(a.spheres.particles.position, b.spheres.particles.position) &&
         same(a.spheres.particles.velocity, b.spheres.particles.velocity) && a.dt == b.dt;
}

std::vector<System> systems() {
  return {randomSystem(20221, 2022), randomSystem(20228, 2024),       courseSystem(20221, 2022),
          courseSystem(20235, 2024), stageSystem(20221, false, 2022), stageSystem(7, true, 2024)};
}

// Every switch at its course value is the library's step, per method, on random and course-size
// states of both editions (the step is written once with its switches, so this is the proof that
// "no mistake" is the course).
TEST(IntegrateMistakes, NoSwitchIsTheLibrarysStep) {
  for (int index = 0; index < 4; ++index) {
    const Method method = integratorMethod(index);
    for (const System& s : systems()) {
      EXPECT_TRUE(bitEqual(stepped(s, courseStep(method)), stepped(s, clothrefStep(method))))
          << methodName(method) << " on " << s.cloth.particles.size() << " particles";
      EXPECT_TRUE(bitEqual(stepped(s, courseStep(StepModel{method, {}, Overlay{}})),
                           stepped(s, clothrefStep(method))));
      // the cloth alone is the library's method on particles[0] only
      EXPECT_TRUE(bitEqual(stepped(s, readingStep(cause::kOnlyFirstBody, method)),
                           stepped(s, clothrefStep(method, 1))))
          << methodName(method);
    }
  }
  for (const System& s : systems()) {
    // Re-evaluating nothing is the library's explicit Euler, whatever the method.
    EXPECT_TRUE(bitEqual(stepped(s, readingStep(cause::kNoReevaluation, Method::Rk4)),
                         stepped(s, clothrefStep(Method::Explicit))));
    // Midpoint with a full-step prediction is the library's implicit Euler.
    EXPECT_TRUE(bitEqual(stepped(s, readingStep(cause::kMidpointFullStep, Method::Midpoint)),
                         stepped(s, clothrefStep(Method::Implicit))));
    // Explicit written velocity first is the library's symplectic Euler.
    EXPECT_TRUE(bitEqual(stepped(s, readingStep("explicit-as-symplectic", Method::Explicit)),
                         stepped(s, clothrefStep(Method::Symplectic))));
    const std::vector<Reading> first = readingsOf(cause::kOnlyFirstBody, Method::Explicit);
    ASSERT_EQ(first.size(), 2u);
    EXPECT_TRUE(bitEqual(stepped(s, courseStep(StepModel{Method::Explicit, {first[1].row}, {}})),
                         stepped(s, clothrefStep(Method::Symplectic, 1))));
  }
}

// Every reading of every method changes the step, and each id is a catalogue entry or a variant
// the rubric may accept.
TEST(IntegrateMistakes, EveryReadingChangesTheStep) {
  const System s = randomSystem(20221);
  int readings = 0;
  for (int index = 0; index < 4; ++index) {
    const Method method = integratorMethod(index);
    const System course = stepped(s, clothrefStep(method));
    for (const Reading& r : readingsOf(method)) {
      ++readings;
      EXPECT_GT(distance(stepped(s, courseStep(StepModel{method, {r.row}, {}})), course), 1e-6)
          << methodName(method) << ": " << r.text;
    }
  }
  EXPECT_GT(readings, 0);
  for (const std::string& id : readingIds()) {
    bool known = false;
    for (const std::string& name : acceptedVariantNames()) known = known || id == name;
    for (const cause::Entry& entry : cause::entries()) known = known || id == entry.id;
    EXPECT_TRUE(known) << id;
  }
}

// Two readings at once: their lines together; one line set two ways is no model.
TEST(IntegrateMistakes, CombinedReadingsSetBothLines) {
  const System s = randomSystem(20221);
  const std::vector<Reading> alias = readingsOf(cause::kBackupAlias, Method::Rk4);
  const std::vector<Reading> discarded = readingsOf(cause::kRk4StagesDiscarded, Method::Rk4);
  ASSERT_FALSE(alias.empty());
  ASSERT_FALSE(discarded.empty());
  const StepModel a{Method::Rk4, {alias[0].row}, {}}, b{Method::Rk4, {discarded[0].row}, {}};
  const std::optional<StepModel> both = combined(a, b);
  ASSERT_TRUE(both.has_value());
  EXPECT_EQ(both->rows.size(), 2u);
  const System ab = stepped(s, courseStep(*both));
  EXPECT_GT(distance(ab, stepped(s, courseStep(a))), 1e-6);
  EXPECT_GT(distance(ab, stepped(s, courseStep(b))), 1e-6);
  const std::vector<Reading> mixed = readingsOf(cause::kRk4MixedIncrements, Method::Rk4);
  ASSERT_GE(mixed.size(), 4u);  // stage positions from kv, stages 2 and 3: one switch, two values
  EXPECT_FALSE(combined(StepModel{Method::Rk4, {mixed[2].row}, {}},
                        StepModel{Method::Rk4, {mixed[3].row}, {}})
                   .has_value());
}

}  // namespace
}  // namespace clothref::grader::integrators
