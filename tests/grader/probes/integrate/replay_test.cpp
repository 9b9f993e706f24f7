// The integrators' replays (grader/grade/probes/integrate/replay.h): a model with nothing fitted
// is the library's method, on the random state with its contact too; a mistake's model is the
// code it stands for; the fitted changes (pinned particles, a velocity factor) are read from the
// run.
#include "grader/grade/probes/integrate/replay.h"

#include <gtest/gtest.h>

#include "grader/grade/cause_ids.h"
#include "grader/grade/mistakes/integrate_mistakes.h"

namespace clothref::grader::integrators {
namespace {

constexpr double kRel = 2e-5;  // the rubric's integrate_rel
const Rubric kRubric = defaultRubric(2022);

TEST(IntegratorReplay, AnEmptyOverlayIsTheLibrarysMethod) {
  for (int index = 0; index < 4; ++index) {
    const Method method = integratorMethod(index);
    for (const System& start :
         {randomSystem(20221), randomSystem(7), stageSystem(20221, false, 2022)}) {
      const System model = stepped(start, integratorModel({}, "", StepModel{method}).step);
      const System library = stepped(start, clothrefStep(method));
      EXPECT_EQ(distance(model, library), 0) << index;
      // a mistake is far beyond the check's tolerance
      EXPECT_GT(distance(stepped(start, readingStep(cause::kNoReevaluation, method)), library),
                index == 0 ? -1.0 : kRel)
          << index;
    }
  }
}

// RK4 whose increments are read after each stage overwrote the velocity with v0 + c·h·a of its
// own stage (the example, written as students write it): the model of
// rk4-stage-from-wrong-increment is that code, to the probe's tolerance.
void overwrittenRk4(System& s) {
  simulate(s);
  const float dt = s.dt;
  std::vector<Particles<float>*> bodies{&s.cloth.particles, &s.spheres.particles};
  std::vector<Particles<float>> start;
  for (auto* p : bodies) start.push_back(*p);
  std::vector<Mat4X<float>> dx[4], dv[4];
  const float w[3] = {0.5f, 0.5f, 1.0f};
  for (int st = 0; st < 4; ++st) {
    if (st > 0) simulate(s);
    for (std::size_t k = 0; k < bodies.size(); ++k) {
      Particles<float>* p = bodies[k];
      dv[st].push_back(p->acceleration * dt);
      if (st > 0) p->velocity = start[k].velocity + dv[st][k] * w[st - 1];
      dx[st].push_back(p->velocity * dt);
      if (st < 3) {
        p->position = start[k].position + dx[st][k] * w[st];
        p->velocity = start[k].velocity + dv[st][k] * w[st];
      }
    }
  }
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    bodies[k]->position =
        start[k].position + (dx[0][k] + 2.0f * dx[1][k] + 2.0f * dx[2][k] + dx[3][k]) / 6.0f;
    bodies[k]->velocity =
        start[k].velocity + (dv[0][k] + 2.0f * dv[1][k] + 2.0f * dv[2][k] + dv[3][k]) / 6.0f;
  }
}

IntegratorRun runOf(int index, const Step& student) {
  IntegratorRun run;
  run.index = index;
  run.method = integratorMethod(index);
  run.rel = kRel;
  run.random = randomSystem(20221);
  run.actual = stepped(run.random, student);
  run.expected = stepped(run.random, clothrefStep(run.method));
  run.start = run.random;
  simulate(run.start);
  return run;
}

TEST(IntegratorReplay, OverwrittenIncrementsAreTheirModel) {
  const IntegratorRun run = runOf(3, overwrittenRk4);
  ASSERT_GT(distance(run.actual, run.expected), kRel);  // a mistake the check sees
  const std::vector<IntegratorModel> models =
      modelsOf(cause::kRk4StageFromWrongIncrement, kRubric, run, RunStages{});
  ASSERT_EQ(models.size(), 2u);
  EXPECT_GT(distance(stepped(run.random, models[0].step), run.actual), kRel);
  EXPECT_LE(distance(stepped(run.random, models[1].step), run.actual), kRel);
  // RK4 with other weights on the course's stages is no model of it: the fit has no weights
  // without a stage record, and a variant of the stages is far.
  EXPECT_TRUE(modelsOf(cause::kRk4WrongWeights, kRubric, run, RunStages{}).empty());
  for (const IntegratorModel& m : modelsOf(cause::kRk4MixedIncrements, kRubric, run, RunStages{}))
    EXPECT_GT(distance(stepped(run.random, m.step), run.actual), kRel) << m.text;
}

// RK4 as a student writes it whose fourth stage, like the two before it, starts from a half step
// (blind 2024/peng's stages: `old + kx3 * 0.5f`, the velocity too), with the course's weights.
void halfStepFourthStageRk4(System& s) {
  simulate(s);
  const float dt = s.dt;
  std::vector<Particles<float>*> bodies{&s.cloth.particles, &s.spheres.particles};
  std::vector<Particles<float>> old;
  for (auto* p : bodies) old.push_back(*p);
  std::vector<Mat4X<float>> kx[4], kv[4];
  for (int st = 0; st < 4; ++st) {
    if (st > 0) simulate(s);
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      kx[st].push_back(bodies[i]->velocity * dt);
      kv[st].push_back(bodies[i]->acceleration * dt);
      if (st == 3) continue;
      bodies[i]->position = old[i].position + kx[st][i] * 0.5f;
      bodies[i]->velocity = old[i].velocity + kv[st][i] * 0.5f;
    }
  }
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    bodies[i]->position =
        old[i].position + (kx[0][i] + 2.0f * kx[1][i] + 2.0f * kx[2][i] + kx[3][i]) / 6.0f;
    bodies[i]->velocity =
        old[i].velocity + (kv[0][i] + 2.0f * kv[1][i] + 2.0f * kv[2][i] + kv[3][i]) / 6.0f;
  }
}

TEST(IntegratorReplay, AFourthStageFromAHalfStepIsItsModel) {
  const IntegratorRun run = runOf(3, halfStepFourthStageRk4);
  ASSERT_GT(distance(run.actual, run.expected), kRel);  // a mistake the check sees
  const std::vector<IntegratorModel> models =
      modelsOf(cause::kRk4FourthStageHalfStep, kRubric, run, RunStages{});
  ASSERT_EQ(models.size(), 1u);
  EXPECT_LE(distance(stepped(run.random, models[0].step), run.actual), kRel);
  // no other RK4 stage mistake is that code
  for (const auto& id : {cause::kRk4StageNotFromBackup, cause::kRk4StageFromWrongIncrement,
                         cause::kRk4MixedIncrements})
    for (const IntegratorModel& m : modelsOf(id, kRubric, run, RunStages{}))
      EXPECT_GT(distance(stepped(run.random, m.step), run.actual), kRel) << m.text;
}

// RK4 as a student writes it whose update sets the velocity first and then reads the position's k4
// from the live velocity, the new one (blind3 2024/hsia-big5): `x0 + (k1x + 2 * k2x + 2 * k3x +
// p->velocity() * deltaTime) / 6` after `v = v0 + (... + p->acceleration() * deltaTime) / 6`.
void k4AfterVelocityRk4(System& s) {
  simulate(s);
  const float dt = s.dt;
  std::vector<Particles<float>*> bodies{&s.cloth.particles, &s.spheres.particles};
  std::vector<Mat4X<float>> x0, v0, kx[3], kv[3];
  for (auto* p : bodies) x0.push_back(p->position), v0.push_back(p->velocity);
  const float c[3] = {0.5f, 0.5f, 1.0f};
  for (int st = 0; st < 3; ++st) {
    if (st > 0) simulate(s);
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      kx[st].push_back(bodies[i]->velocity * dt);
      kv[st].push_back(bodies[i]->acceleration * dt);
      bodies[i]->position = x0[i] + kx[st][i] * c[st];
      bodies[i]->velocity = v0[i] + kv[st][i] * c[st];
    }
  }
  simulate(s);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    Particles<float>& p = *bodies[i];
    p.velocity = v0[i] + (kv[0][i] + 2 * kv[1][i] + 2 * kv[2][i] + p.acceleration * dt) / 6;
    p.position = x0[i] + (kx[0][i] + 2 * kx[1][i] + 2 * kx[2][i] + p.velocity * dt) / 6;
  }
}

TEST(IntegratorReplay, AK4ReadAfterTheVelocityUpdateIsItsModel) {
  const IntegratorRun run = runOf(3, k4AfterVelocityRk4);
  ASSERT_GT(distance(run.actual, run.expected), kRel);  // a mistake the check sees
  int reproduce = 0;
  for (const IntegratorModel& m : modelsOf(cause::kRk4MixedIncrements, kRubric, run, RunStages{}))
    reproduce += distance(stepped(run.random, m.step), run.actual) <= kRel;
  EXPECT_EQ(reproduce, 1);  // that reading, and no other of the cause
}

// A helper that stops hard-coded cloth particles after the step: read from the numbers, replayed.
TEST(IntegratorReplay, PinnedParticlesAreReadAndReplayed) {
  const Step pinning = [](System& s) {
    clothrefStep(Method::Midpoint)(s);
    for (int j : {1, 2, 6}) s.cloth.particles.velocity.col(j).setZero();
  };
  const IntegratorRun run = runOf(2, pinning);
  const std::vector<IntegratorModel> models =
      modelsOf(cause::kIntegratorPinsParticles, kRubric, run, {});
  // after the course's midpoint, also after its prediction, and after its accepted variant (a
  // symplectic predictor): only the first is this code
  ASSERT_EQ(models.size(), 3u);
  EXPECT_TRUE(models[1].model.overlay.pins_at_stages);
  EXPECT_GT(distance(stepped(run.random, models[1].step), run.actual), kRel);
  EXPECT_GT(distance(stepped(run.random, models[2].step), run.actual), kRel);
  ASSERT_TRUE(models[0].model.rows.empty());
  ASSERT_EQ(models[0].model.overlay.pinned.size(), 1u);
  EXPECT_EQ(models[0].model.overlay.pinned[0].cloth_size, run.random.cloth.particles.size());
  EXPECT_EQ(models[0].model.overlay.pinned[0].particles, (std::vector<int>{1, 2, 6}));
  EXPECT_FALSE(models[0].model.overlay.pinned[0].positions);
  EXPECT_LE(distance(stepped(run.random, models[0].step), run.actual), kRel);
  EXPECT_NE(models[0].text.find("particles 1-2, 6 stopped"), std::string::npos) << models[0].text;
}

// The same helper called in RK4's stage loop too (blind3 2024/liang's pinCorners): each stage state
// has those particles stopped before its simulateOneStep(), so the model that stops them after
// the step only is not this code, and the one that stops them at every stage is.
TEST(IntegratorReplay, ParticlesPinnedAtEveryStageAreReplayedSo) {
  const Step pinning = [](System& s) {
    simulate(s);
    const float dt = s.dt;
    std::vector<Particles<float>*> bodies{&s.cloth.particles, &s.spheres.particles};
    std::vector<Particles<float>> start;
    for (auto* p : bodies) start.push_back(*p);
    const auto pin = [&] {
      for (int j : {1, 6}) s.cloth.particles.velocity.col(j).setZero();
    };
    std::vector<Mat4X<float>> kx[4], kv[4];
    const float c[3] = {0.5f, 0.5f, 1.0f};
    for (int st = 0; st < 4; ++st) {
      if (st > 0) simulate(s);
      for (auto* p : bodies)
        kx[st].push_back(p->velocity * dt), kv[st].push_back(p->acceleration * dt);
      if (st == 3) break;
      for (std::size_t i = 0; i < bodies.size(); ++i) {
        bodies[i]->position = start[i].position + kx[st][i] * c[st];
        bodies[i]->velocity = start[i].velocity + kv[st][i] * c[st];
      }
      pin();
    }
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      bodies[i]->position =
          start[i].position + (kx[0][i] + 2 * kx[1][i] + 2 * kx[2][i] + kx[3][i]) / 6;
      bodies[i]->velocity =
          start[i].velocity + (kv[0][i] + 2 * kv[1][i] + 2 * kv[2][i] + kv[3][i]) / 6;
    }
    pin();
  };
  const IntegratorRun run = runOf(3, pinning);
  const std::vector<IntegratorModel> models =
      modelsOf(cause::kIntegratorPinsParticles, kRubric, run, {});
  ASSERT_GE(models.size(), 2u);
  EXPECT_GT(distance(stepped(run.random, models[0].step), run.actual), kRel) << models[0].text;
  EXPECT_TRUE(models[1].model.overlay.pins_at_stages);
  EXPECT_LE(distance(stepped(run.random, models[1].step), run.actual), kRel) << models[1].text;
  EXPECT_NE(models[1].text.find("after each stage state and after the step"), std::string::npos)
      << models[1].text;
}

// A helper that stops the top row only on the course's 25 x 25 cloth, after explicit Euler written
// as symplectic Euler (accepted): invisible on the small random state, read on the course's cloth
// with its corners unpinned, and replayed on both after the accepted variant.
TEST(IntegratorReplay, PinsOnTheCoursesClothOnlyAreReadThereAfterAnAcceptedVariant) {
  const Step curtain = [](System& s) {
    clothrefStep(Method::Symplectic)(s);
    if (s.cloth.particles.size() == 625)
      for (int j = 0; j < 25; ++j) s.cloth.particles.velocity.col(j).setZero();
  };
  IntegratorRun run = runOf(0, curtain);
  ASSERT_LE(distance(run.actual, stepped(run.random, clothrefStep(Method::Symplectic))), kRel);
  OneStep course_cloth;
  course_cloth.state = courseSystem(20221, 2024, true);
  ASSERT_EQ(course_cloth.state.cloth.particles.size(), 625);
  for (int corner : {0, 24, 600, 624})
    ASSERT_GT(course_cloth.state.cloth.particles.mass[corner], 0);
  course_cloth.actual = stepped(course_cloth.state, curtain);
  completeOneStep(course_cloth, Method::Explicit);
  run.course_cloth = course_cloth;
  const std::vector<IntegratorModel> models =
      modelsOf(cause::kIntegratorPinsParticles, kRubric, run, {});
  ASSERT_EQ(models.size(), 2u);  // after the course's explicit Euler, after symplectic Euler
  ASSERT_TRUE(!models[1].model.rows.empty());
  ASSERT_EQ(models[1].model.overlay.pinned.size(), 1u);
  EXPECT_EQ(models[1].model.overlay.pinned[0].cloth_size, 625);
  std::vector<int> top_row(25);
  for (int j = 0; j < 25; ++j) top_row[std::size_t(j)] = j;
  EXPECT_EQ(models[1].model.overlay.pinned[0].particles, top_row);
  EXPECT_NE(models[1].text.find("particles 0-24 stopped (of a 625-particle cloth)"),
            std::string::npos)
      << models[1].text;
  for (std::size_t m = 0; m < models.size(); ++m) {
    const bool symplectic = m == 1;
    EXPECT_EQ(distance(stepped(run.random, models[m].step), run.actual) <= kRel, symplectic);
    EXPECT_EQ(distance(stepped(course_cloth.state, models[m].step), course_cloth.actual) <= kRel,
              symplectic);
  }
}

// Velocities scaled after the step, on one body only (a helper that damps the spheres).
TEST(IntegratorReplay, AVelocityFactorIsReadPerBody) {
  const Step damped = [](System& s) {
    clothrefStep(Method::Explicit)(s);
    s.spheres.particles.velocity *= 0.999f;
  };
  const IntegratorRun run = runOf(0, damped);
  const std::vector<IntegratorModel> models = modelsOf(cause::kVelocityDamped, kRubric, run, {});
  ASSERT_EQ(models.size(), 1u);
  EXPECT_EQ(models[0].model.overlay.velocity_factor[0], 1);
  EXPECT_NEAR(models[0].model.overlay.velocity_factor[1], 0.999, 1e-6);
  EXPECT_LE(distance(stepped(run.random, models[0].step), run.actual), kRel);
}

}  // namespace
}  // namespace clothref::grader::integrators
