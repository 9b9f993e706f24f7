// The integrator mistakes as switches on one course step (grader/grade/mistakes/
// integrate_mistakes.h): with no switch on, the step is the library's, bit for bit; each mistake
// changes the step (so a student's numbers equal to it name it).
#include "grader/grade/mistakes/integrate_mistakes.h"
#include "grader/grade/probes/integrate/systems.h"

#include <gtest/gtest.h>

#include <cstring>

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
         same(a.spheres.particles.velocity, b.spheres.particles.velocity);
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
      EXPECT_TRUE(bitEqual(stepped(s, courseStep(method, StepSwitches{})),
                           stepped(s, clothrefStep(method))))
          << methodName(method) << " on " << s.cloth.particles.size() << " particles";
      EXPECT_TRUE(bitEqual(stepped(s, variantStep(method, Variant::None)),
                           stepped(s, clothrefStep(method))));
    }
  }
  // Re-evaluating nothing is the library's explicit Euler, whatever the method.
  for (const System& s : systems())
    EXPECT_TRUE(bitEqual(stepped(s, variantStep(Method::Rk4, Variant::NoReevaluation)),
                         stepped(s, clothrefStep(Method::Explicit))));
}

TEST(IntegrateMistakes, EveryMistakeChangesTheStep) {
  const System s = randomSystem(20221);
  const std::vector<std::pair<Method, std::vector<Variant>>> mistakes = {
      {Method::Explicit,
       {Variant::PositionUsesAcceleration, Variant::VelocityOnly, Variant::PositionOnly}},
      {Method::Implicit,
       {Variant::ImplicitVNew, Variant::SymplecticPredictor, Variant::Alias,
        Variant::NoReevaluation, Variant::PerBody}},
      {Method::Midpoint,
       {Variant::SymplecticPredictor, Variant::Alias, Variant::NoReevaluationHalfVelocity,
        Variant::ZeroHalfStep, Variant::PerBody}},
      {Method::Rk4,
       {Variant::Alias, Variant::RkIntDivision, Variant::RkIntDivisionOnLastStage,
        Variant::RkMixedFinal, Variant::RkK4xInVelocity, Variant::RkStageFromCurrent,
        Variant::RkStageFromNewVelocity, Variant::RkStagesDiscarded, Variant::PerBody}}};
  for (const auto& [method, variants] : mistakes) {
    const System course = stepped(s, clothrefStep(method));
    for (Variant v : variants)
      EXPECT_GT(distance(stepped(s, variantStep(method, v)), course), 1e-6)
          << methodName(method) << " variant " << int(v);
  }
  for (int stage = 0; stage < 3; ++stage)
    EXPECT_GT(distance(stepped(s, variantStep(Method::Rk4, Variant::RkMixedStage, stage)),
                       stepped(s, clothrefStep(Method::Rk4))),
              1e-6)
        << "mixed stage " << stage;
}

}  // namespace
}  // namespace clothref::grader::integrators
