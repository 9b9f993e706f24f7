// The stage fit (grade/explain/stages/stages.h) on records made here, as the probe driver makes
// them: a 4 x 4 cloth (corners fixed, k_s = 500, k_d = 5, randomly perturbed) and two spheres under
// gravity, no contact, one step of dt = 0.01 of a stub written the way students write
// (stage_students.h), in float and in double. Every course method is recognised with its rationals,
// each accepted variant as accepted, each known mistake with its catalogue id and its first
// departure, two mistakes at once as both.
#include "grader/grade/explain/stages/stages.h"

#include <gtest/gtest.h>

#include <iostream>
#include <random>
#include <set>

#include "clothref/core/cloth.h"
#include "clothref/core/spheres.h"
#include "explain/stages/stage_students.h"
#include "grader/bridge/probe_keys.h"
#include "grader/bridge/probe_protocol.h"
#include "grader/grade/cause_ids.h"
#include "grader/grade/explain/stages/methods.h"

namespace clothref::grader::stages {
namespace {

namespace st = clothref::test::students;

template <typename T>
struct World {
  Cloth<T> cloth;
  Spheres<T> spheres;
  void simulate() {
    const Vec4<T> g(0, T(-9.8), 0, 0);
    computeExternalForce(cloth.particles, g, T(3.4e-4));
    computeExternalForce(spheres.particles, g, T(3.4e-4));
    computeSpringForce(cloth);
  }
};

template <typename T>
World<T> makeWorld(unsigned seed) {
  World<T> w;
  constexpr int n = 4;
  w.cloth.particles = initializeVertex<T>(n, T(0.5), T(0), T(1));
  for (int corner : {0, n - 1, n * (n - 1), n * n - 1}) setMass(w.cloth.particles, corner, T(0));
  initializeSpring(w.cloth, n);
  w.cloth.spring_coef = 500;
  w.cloth.damper_coef = 5;
  addSphere(w.spheres, Vec4<T>(T(1.2), 1, 0, 1), T(0.5), T(1000));
  addSphere(w.spheres, Vec4<T>(T(-1.1), T(0.8), T(0.4), 1), T(0.5), T(1000));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  auto& p = w.cloth.particles;
  for (int i = 0; i < p.size(); ++i)
    for (int r = 0; r < 3; ++r) {
      p.position(r, i) += T(0.05 * u(rng));
      if (p.mass[i] != 0) p.velocity(r, i) = T(u(rng));
    }
  for (int i = 0; i < w.spheres.size(); ++i)
    for (int r = 0; r < 3; ++r) w.spheres.particles.velocity(r, i) = T(u(rng));
  return w;
}

template <typename T>
BodyState state(const Particles<T>& p, bool with_a) {
  BodyState s;
  for (int k = 0; k < p.position.size(); ++k) {
    s.x.push_back(double(p.position.data()[k]));
    s.v.push_back(double(p.velocity.data()[k]));
    if (with_a) s.a.push_back(double(p.acceleration.data()[k]));
  }
  return s;
}

// One step of `stub` recorded as the driver records it.
template <typename T, typename Stub>
StageRecord record(const Stub& stub, double step, unsigned seed = 7) {
  World<T> w = makeWorld<T>(seed);
  st::Bodies<T> bodies{&w.cloth.particles, &w.spheres.particles};
  StageRecord r;
  T dt = T(step);
  r.h = double(dt);
  w.simulate();
  r.start = {state(w.cloth.particles, true), state(w.spheres.particles, true)};
  std::function<void()> sim = [&] {
    ++r.calls;
    const bool keep = r.calls <= kMaxRecordedCalls;
    std::array<BodyState, 2> at{state(w.cloth.particles, false), state(w.spheres.particles, false)};
    w.simulate();
    at[0].a = state(w.cloth.particles, true).a;
    at[1].a = state(w.spheres.particles, true).a;
    if (keep) r.evaluations.push_back(at);
  };
  stub(bodies, sim, dt);
  r.h_after = double(dt);
  r.result = {state(w.cloth.particles, false), state(w.spheres.particles, false)};
  return r;
}

struct Expect {
  Expect(bool course_ = false, std::string accepted_ = "", std::string equals_ = "",
         int departure_ = 0, std::string what_ = "", std::set<std::string> likely_ = {},
         std::set<std::string> possible_ = {}, std::string yours_ = "", std::string theirs_ = "",
         bool fits_ = true)
      : course(course_),
        accepted(accepted_),
        equals(equals_),
        departure(departure_),
        what(what_),
        likely(likely_),
        possible(possible_),
        yours(yours_),
        theirs(theirs_),
        fits(fits_) {}
  bool course;
  std::string accepted, equals;
  int departure;  // the state of the first departure (0 none; recorded + 1 the result)
  std::string what;
  std::set<std::string> likely, possible;
  std::string yours, theirs;  // the departure's forms, when given
  bool fits;                  // every state an exact combination
};

struct Case {
  std::string name;
  int method;
  std::function<void(const st::Bodies<float>&, const std::function<void()>&, float&)> f;
  std::function<void(const st::Bodies<double>&, const std::function<void()>&, double&)> d;
  SourceHints hints;
  Expect expect;
};

template <typename F>
Case make(std::string name, int method, F stub, Expect expect, SourceHints hints = {}) {
  return {std::move(name), method, stub, stub, hints, std::move(expect)};
}

auto pc(double frac, st::Pc kind) {
  return [=](const auto& ps, const auto& sim, auto& dt) {
    using T = std::decay_t<decltype(dt)>;
    st::predictCorrect<T>(ps, sim, dt, T(frac), kind);
  };
}
auto rk(st::Rk kind) {
  return [=](const auto& ps, const auto& sim, auto& dt) {
    using T = std::decay_t<decltype(dt)>;
    st::rungeKutta<T>(ps, sim, dt, kind);
  };
}
auto ex(st::Ex kind) {
  return [=](const auto& ps, const auto&, auto& dt) {
    using T = std::decay_t<decltype(dt)>;
    st::explicitEuler<T>(ps, dt, kind);
  };
}

SourceHints alias() { return {.alias_backup = true}; }
SourceHints half() { return {.integer_half = true}; }
SourceHints sixth() { return {.integer_sixth = true}; }

const std::vector<Case>& cases() {
  using P = st::Pc;
  using R = st::Rk;
  using E = st::Ex;
  static const std::vector<Case> all = {
      make("explicit", 0, ex(E::Course), {true, "", "explicit"}),
      make("explicit symplectic", 0, ex(E::Symplectic),
           {false, "explicit-as-symplectic", "symplectic"}),
      make("explicit + a dt^2/2", 0, ex(E::Taylor),
           {false,
            "",
            "",
            1,
            "position",
            {cause::kPositionUsesAcceleration},
            {},
            "x0 + h·v0 + h²/2·a0",
            "x0 + h·v0"}),
      make("explicit, x only", 0, ex(E::PositionOnly),
           {false, "", "", 1, "velocity", {cause::kVelocityNotIntegrated}, {}, "v0", "v0 + h·a0"}),
      make("explicit, v only", 0, ex(E::VelocityOnly),
           {false, "", "", 1, "position", {cause::kPositionNotIntegrated}, {}, "x0", "x0 + h·v0"}),
      make("explicit, particles[0]", 0, ex(E::FirstOnly),
           {false, "", "", 1, "spheres", {cause::kOnlyFirstBody}}),
      make("explicit, v *= 0.9987 (pan)", 0, ex(E::Damped),
           {false, "", "", 1, "velocity", {cause::kVelocityDamped}, {}, "", "v0 + h·a0", false}),
      make("implicit", 1, pc(1, P::Course), {true, "", "implicit"}),
      make("implicit v new", 1, pc(1, P::VNew),
           {false, "implicit-corrector-v-new", "implicit-v-new"}),
      make("implicit symplectic predictor", 1, pc(1, P::SymplecticPredictor),
           {false, "symplectic-predictor", "implicit-symplectic-predictor"}),
      make("implicit alias difference (chen)", 1, pc(1, P::AliasDifference),
           {false,
            "",
            "explicit",
            2,
            "position",
            {cause::kBackupAlias},
            {cause::kNoReevaluation},
            "x0 + h·v0",
            "x0 + h·v1"},
           alias()),
      make("implicit alias difference, no pattern", 1, pc(1, P::AliasDifference),
           {false, "", "explicit", 2, "position", {cause::kNoReevaluation}, {cause::kBackupAlias}}),
      make("implicit simulate first (the issue's words)", 1, pc(1, P::SimulateFirst),
           {false, "", "explicit", 1, "position", {cause::kNoReevaluation}, {}, "x0", "x0 + h·v0"},
           alias()),
      make("implicit alias live (lee)", 1, pc(1, P::AliasLive),
           {false, "", "", 2, "position", {cause::kBackupAlias}, {}, "x1 + h·v1", "x0 + h·v1"}),
      make("implicit without simulateOneStep", 1, pc(1, P::NoSimulate),
           {false, "", "symplectic", 1, "calls", {cause::kNoReevaluation}}),
      make("implicit Heun", 1, pc(1, P::Heun),
           {false,
            "",
            "heun",
            2,
            "position",
            {cause::kHeunMethod},
            {},
            "x0 + h/2·v0 + h/2·v1",
            "x0 + h·v1"}),
      make("implicit per body", 1, pc(1, P::PerBody),
           {false, "", "", 1, "spheres", {cause::kPerBodyLoop}}),
      make("implicit particles[0]", 1, pc(1, P::FirstOnly),
           {false, "", "", 1, "spheres", {cause::kOnlyFirstBody}}),
      make("midpoint", 2, pc(0.5, P::Course), {true, "", "midpoint"}),
      make("midpoint symplectic predictor", 2, pc(0.5, P::SymplecticPredictor),
           {false, "symplectic-predictor", "midpoint-symplectic-predictor"}),
      make("midpoint full step", 2, pc(1, P::Course),
           {false,
            "",
            "implicit",
            1,
            "position",
            {cause::kMidpointFullStep},
            {},
            "x0 + h·v0",
            "x0 + h/2·v0"}),
      make("midpoint 1 / 2", 2, pc(0, P::Course),
           {false,
            "",
            "explicit",
            1,
            "position",
            {cause::kIntegerDivisionHalf},
            {cause::kNoReevaluation}},
           half()),
      make("midpoint zero half step, no pattern", 2, pc(0, P::Course),
           {false, "", "explicit", 1, "position", {cause::kNoReevaluation}}),
      make("midpoint prediction in locals", 2, pc(0.5, P::Locals),
           {false, "", "", 1, "position", {cause::kNoReevaluation}, {}, "x0", "x0 + h/2·v0"}),
      make("midpoint corrector h/2", 2, pc(0.5, P::HalfCorrector),
           {false,
            "",
            "",
            2,
            "position",
            {cause::kHalfStepCorrector},
            {},
            "x0 + h/2·v1",
            "x0 + h·v1"}),
      make("midpoint deltaTime = 1e-4f", 2, pc(0.5, P::HardCodedStep),
           {false, "", "", 2, "position", {cause::kDeltatimeMutated}, {}, "", "x0 + h·v1", false}),
      make("midpoint per body", 2, pc(0.5, P::PerBody),
           {false, "", "", 1, "spheres", {cause::kPerBodyLoop}}),
      make("rk4", 3, rk(R::Course), {true, "", "rk4"}),
      make("rk4 quarter weights", 3, rk(R::Quarter),
           {false,
            "",
            "",
            4,
            "position",
            {cause::kRk4WrongWeights},
            {},
            "x0 + h/4·(v0 + v1 + v2 + v3)",
            "x0 + h/6·(v0 + 2·v1 + 2·v2 + v3)"}),
      // the course's weights written out, k1 read after stage 4 overwrote the state (blind3
      // ko-big5): the weights fit 0, 1/3, 1/3, 1/3, which is k4 where k1 belongs, not wrong weights
      make("rk4 k1 read after stage 4", 3, rk(R::K1ReadLast),
           {false,
            "",
            "",
            4,
            "position",
            {cause::kRk4MixedIncrements},
            {},
            "x0 + h/3·(v1 + v2 + v3)",
            "x0 + h/6·(v0 + 2·v1 + 2·v2 + v3)"}),
      make("rk4 1 / 6", 3, rk(R::IntegerSixth),
           {false,
            "",
            "",
            4,
            "position",
            {cause::kIntegerDivisionRk4},
            {cause::kRk4WrongWeights},
            "x0"},
           sixth()),
      make("rk4 zero weights, no pattern", 3, rk(R::IntegerSixth),
           {false, "", "", 4, "position", {cause::kRk4WrongWeights}}),
      make("rk4 kv in the position", 3, rk(R::MixedFinal),
           {false,
            "",
            "",
            4,
            "position",
            {cause::kRk4MixedIncrements},
            {},
            "x0 + h/6·(a0 + 2·a1 + 2·a2 + a3)"}),
      make("rk4 k4x in the velocity", 3, rk(R::K4xInVelocity),
           {false,
            "",
            "",
            4,
            "velocity",
            {cause::kRk4MixedIncrements},
            {},
            "v0 + h/6·v3 + h/6·(a0 + 2·a1 + 2·a2)"}),
      make("rk4 kv in stage 2", 3, rk(R::MixedStage),
           {false,
            "",
            "",
            2,
            "position",
            {cause::kRk4MixedIncrements},
            {},
            "x0 + h/2·a1",
            "x0 + h/2·v1"}),
      make("rk4 stages from the current state (liu)", 3, rk(R::FromCurrent),
           {false,
            "",
            "",
            2,
            "position",
            {cause::kRk4StageNotFromBackup},
            {},
            "x1 + h/2·v1",
            "x0 + h/2·v1"}),
      make("rk4 Eigen::Ref backup (tang)", 3, rk(R::Alias),
           {false, "", "", 2, "position", {cause::kBackupAlias}, {cause::kRk4StageNotFromBackup}}),
      make("rk4 stage from the new velocity (yang)", 3, rk(R::FromNewVelocity),
           {false,
            "",
            "",
            1,
            "position",
            {cause::kRk4StageFromWrongIncrement},
            {},
            "x0 + h/2·v1",
            "x0 + h/2·v0"}),
      make("rk4 k1 only (lee)", 3, rk(R::Discarded),
           {false, "", "explicit", 4, "position", {cause::kRk4StagesDiscarded}, {}, "x0 + h·v0"}),
      make("rk4 position k from v0 (chang)", 3, rk(R::FromV0),
           {false,
            "",
            "",
            2,
            "position",
            {cause::kRk4MixedIncrements},
            {},
            "x0 + h/2·v0",
            "x0 + h/2·v1"}),
      make("rk4 per body", 3, rk(R::PerBody), {false, "", "", 1, "spheres", {cause::kPerBodyLoop}}),
      make("rk4 3/8 rule", 3, rk(R::ThreeEighths),
           {false, "", "rk4-three-eighths", 1, "position", {}}),
      make(
          "rk4 previous stages and 3/8 weights (kao)", 3, rk(R::KaoStyle),
          {false, "", "", 2, "position", {cause::kRk4StageNotFromBackup, cause::kRk4WrongWeights}}),
      make("rk4 deltaTime /= 2", 3, rk(R::HalfStep),
           {false,
            "",
            "",
            1,
            "position",
            {cause::kDeltatimeMutated},
            {},
            "x0 + h/4·v0",
            "x0 + h/2·v0"}),
      make("rk4 deltaTime /= 2 and quarter weights", 3, rk(R::HalfStepQuarter),
           {false, "", "", 1, "position", {cause::kDeltatimeMutated, cause::kRk4WrongWeights}}),
  };
  return all;
}

double worst_residual = 0;  // over every state that fits, of the cases checked so far

template <typename T>
void checkCase(const Case& c, double step) {
  const StageRecord r = [&] {
    if constexpr (std::is_same_v<T, float>)
      return record<float>(c.f, step);
    else
      return record<double>(c.d, step);
  }();
  const StageFit fit = fitStages(r);
  const StageExplanation e = explainStages(fit, c.method, c.hints);
  const std::string text = stageText(fit, e);
  SCOPED_TRACE(c.name + (std::is_same_v<T, float> ? " (float, h = " : " (double, h = ") +
               std::to_string(step) + ")\n" + text);
  const Expect& x = c.expect;
  EXPECT_EQ(e.fits, x.fits);
  for (const StageState& s : fit.states) {
    for (const Fitted* f : {&s.x, &s.v})
      if (f->fits) worst_residual = std::max(worst_residual, f->residual);
    if (!x.fits) break;
    EXPECT_TRUE(s.x.fits) << "position residual " << s.x.residual;
    EXPECT_TRUE(s.v.fits) << "velocity residual " << s.v.residual;
  }
  EXPECT_EQ(e.course, x.course);
  EXPECT_EQ(e.accepted, x.accepted);
  EXPECT_EQ(e.equals, x.equals);
  const int departure = x.departure == 0                 ? 0
                        : x.departure > fit.recorded + 1 ? fit.recorded + 1
                                                         : x.departure;
  if (!x.course && x.accepted.empty()) {
    EXPECT_EQ(e.departure.state, departure);
    EXPECT_EQ(e.departure.what, x.what);
    if (!x.yours.empty()) {
      EXPECT_EQ(e.departure.yours, x.yours);
    }
    if (!x.theirs.empty()) {
      EXPECT_EQ(e.departure.course, x.theirs);
    }
  }
  std::set<std::string> likely, possible;
  for (const StageCause& cause : e.causes) (cause.likely ? likely : possible).insert(cause.id);
  EXPECT_EQ(likely, x.likely);
  for (const std::string& id : x.possible) EXPECT_TRUE(possible.count(id)) << id;
}

TEST(StageFit, EveryStubInFloat) {
  worst_residual = 0;
  for (const Case& c : cases()) checkCase<float>(c, kStageStep);
  // The students' float arithmetic stays well inside the tolerance (kUlps roundings).
  std::cout << "worst residual of a fitting state: " << worst_residual << " tolerances\n";
  EXPECT_LT(worst_residual, 0.25);
}

TEST(StageFit, EveryStubInDouble) {
  for (const Case& c : cases()) checkCase<double>(c, kStageStep);
}

// At a round step a mix-up plus a natural term can equal another such pair exactly (1/6 h =
// 2/11 h - 1/66 h at h = 0.01): the simplest split is still the one taken.
TEST(StageFit, EveryStubInFloatAtARoundStep) {
  for (const Case& c : cases()) checkCase<float>(c, 0.01);
}

// The recorded stages lie far enough apart that one coefficient moved to its nearest other
// rational (a gap of at least 1/132 with denominators up to 12) misses the recorded numbers by many
// times the tolerance, while the right form reproduces them to well under it.
TEST(StageFit, NeighbouringRationalsMissByManyTolerances) {
  for (const Case& c : cases()) {
    if (c.name != "rk4" && c.name != "implicit" && c.name != "midpoint") continue;
    const StageFit fit = fitStages(record<float>(c.f, kStageStep));
    double worst_right = 0, closest_wrong = 1e300;
    for (int q = 1; q <= int(fit.states.size()); ++q) {
      const BodyState& at = recordedState(fit.record, q, kCloth);
      for (bool position : {true, false}) {
        const Fitted& f =
            position ? fit.states[std::size_t(q - 1)].x : fit.states[std::size_t(q - 1)].v;
        const std::vector<double>& recorded = position ? at.x : at.v;
        ASSERT_TRUE(f.fits) << c.name;
        worst_right = std::max(worst_right, formResidual(fit, kCloth, f.form, recorded));
        for (std::size_t t = 0; t < f.form.size(); ++t)
          for (const Rational delta : {Rational(1, 132), Rational(-1, 132)}) {
            Form moved = f.form;
            moved[t].coef = moved[t].coef + delta;
            closest_wrong = std::min(closest_wrong, formResidual(fit, kCloth, moved, recorded));
          }
      }
    }
    std::cout << c.name << ": the fit's worst residual " << worst_right
              << " tolerances; a coefficient off by 1/132 misses by at least " << closest_wrong
              << " tolerances\n";
    EXPECT_LT(worst_right, 0.25) << c.name;
    EXPECT_GT(closest_wrong, 100.0) << c.name;
  }
}

std::string explained(const std::string& name, const SourceHints& hints = {}) {
  for (const Case& c : cases())
    if (c.name == name) {
      const StageFit fit = fitStages(record<float>(c.f, kStageStep));
      const std::string text = stageText(fit, explainStages(fit, c.method, hints));
      std::cout << "---- " << name << "\n" << text;
      return text;
    }
  ADD_FAILURE() << name;
  return "";
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(StageText, SaysWhereTheStubLeavesTheCourseInItsTerms) {
  const std::string issue = explained("implicit simulate first (the issue's words)");
  EXPECT_TRUE(contains(issue, "Evaluation 1 position: yours x0, the course's x0 + h·v0.")) << issue;
  EXPECT_TRUE(contains(issue,
                       "This is forward Euler (the course's explicit Euler): "
                       "simulateOneStep() once, at the start state."))
      << issue;
  const std::string chen = explained("implicit alias difference (chen)");
  EXPECT_TRUE(contains(chen, "The result position: yours x0 + h·v0, the course's x0 + h·v1."))
      << chen;
  EXPECT_TRUE(contains(chen, "simulateOneStep() once, and what it computes is never used."))
      << chen;
  const std::string full = explained("midpoint full step");
  EXPECT_TRUE(contains(full, "This is the course's implicit Euler")) << full;
  const std::string kao = explained("rk4 previous stages and 3/8 weights (kao)");
  EXPECT_TRUE(contains(kao, "| evaluation 2 | x1 + h/2·v1 | v1 + h/2·a1 |")) << kao;
  EXPECT_TRUE(contains(kao, "| the result | x0 + h/8·(v0 + 3·v1 + 3·v2 + v3) |")) << kao;
  const std::string half = explained("rk4 deltaTime /= 2");
  EXPECT_TRUE(contains(half, "From there on your stages are the course's with a step of 0.5·h"))
      << half;
  const std::string ho = explained("midpoint corrector h/2");
  EXPECT_TRUE(contains(ho, "That state is the course's with a step of 0.5·h")) << ho;
  const std::string pan = explained("explicit, v *= 0.9987 (pan)");
  EXPECT_TRUE(contains(pan, "The result velocity is 0.9987·(v0 + h·a0)")) << pan;
  const std::string body = explained("midpoint per body");
  EXPECT_TRUE(contains(body, "| evaluation 1, spheres | at their start | at their start |"))
      << body;
}

// More calls than are recorded: the count is said, the first 16 are fitted.
TEST(StageText, ManyCallsAreCountedAndTheFirstSixteenFitted) {
  const auto busy = [](const auto& ps, const auto& sim, auto& dt) {
    for (int k = 0; k < 20; ++k) sim();
    for (auto* p : ps) {
      p->position += p->velocity * dt;
      p->velocity += p->acceleration * dt;
    }
  };
  const StageRecord r = record<float>(busy, kStageStep);
  EXPECT_EQ(r.calls, 20);
  const StageFit fit = fitStages(r);
  EXPECT_EQ(fit.recorded, kMaxRecordedCalls);
  const StageExplanation e = explainStages(fit, 1, {});
  const std::string text = stageText(fit, e);
  EXPECT_EQ(e.equals, "explicit") << text;
  EXPECT_TRUE(contains(text, "(Only the first 16 calls were recorded.)")) << text;
  EXPECT_TRUE(contains(text, "simulateOneStep() 20 times, at the start state.")) << text;
}

TEST(StageForms, RationalsAndTextAreExact) {
  EXPECT_EQ(Rational(2, -4), Rational(-1, 2));
  EXPECT_EQ(Rational(1, 6) + Rational(1, 3), Rational(1, 2));
  EXPECT_EQ(text(Rational(1, 6) * Rational(3)), "1/2");
  CourseForm rk4{'x',
                 0,
                 {{Rational(1, 6), 1, 'v', 0},
                  {Rational(1, 3), 1, 'v', 1},
                  {Rational(1, 3), 1, 'v', 2},
                  {Rational(1, 6), 1, 'v', 3}}};
  EXPECT_EQ(text(rk4, 3), "x0 + h/6·(v0 + 2·v1 + 2·v2 + v3)");
  CourseForm taylor{'x', 0, {{Rational(1), 1, 'v', 0}, {Rational(1, 2), 2, 'a', 0}}};
  EXPECT_EQ(text(taylor, 0), "x0 + h·v0 + h²/2·a0");
  CourseForm symplectic{'x', 0, {{Rational(1), 1, 'v', 1}}};
  EXPECT_EQ(text(symplectic, 0), "x0 + h·v_new");
  CourseForm alias{'v', 1, {{Rational(-3, 8), 1, 'a', 1}}};
  EXPECT_EQ(text(alias, 1), "v1 − 3h/8·a1");
}

// The driver's keys (bridge/probe_keys.h) read back into the record, sizes checked.
TEST(StageRecord, ReadsTheStageKeysOfTheAnswer) {
  namespace key = probe::key;
  const StageRecord r = record<float>(rk(st::Rk::Course), kStageStep);
  probe::ProbeMessage answer;
  const int k = 5;
  const auto put = [&](const char* name, const std::vector<double>& values) {
    auto& to = answer.floats[key::perCase(name, k)];
    for (double v : values) to.push_back(float(v));
  };
  const char* start[2][3] = {{key::kStartClothPos, key::kStartClothVel, key::kStartClothAcc},
                             {key::kStartSpherePos, key::kStartSphereVel, key::kStartSphereAcc}};
  const char* evals[2][3] = {{key::kEvalClothPos, key::kEvalClothVel, key::kEvalClothAcc},
                             {key::kEvalSpherePos, key::kEvalSphereVel, key::kEvalSphereAcc}};
  for (int b = 0; b < 2; ++b) {
    put(start[b][0], r.start[std::size_t(b)].x);
    put(start[b][1], r.start[std::size_t(b)].v);
    put(start[b][2], r.start[std::size_t(b)].a);
    for (const auto& e : r.evaluations) {
      put(evals[b][0], e[std::size_t(b)].x);
      put(evals[b][1], e[std::size_t(b)].v);
      put(evals[b][2], e[std::size_t(b)].a);
    }
  }
  put(key::kClothPos, r.result[0].x);
  put(key::kClothVel, r.result[0].v);
  put(key::kSpherePos, r.result[1].x);
  put(key::kSphereVel, r.result[1].v);
  answer.floats[key::perCase(key::kDtAfter, k)] = {float(r.h_after)};
  answer.ints[key::perCase(key::kCalls, k)] = {r.calls};
  StageRecord back;
  ASSERT_TRUE(stageRecordFrom(answer, k, r.h, back));
  EXPECT_EQ(back.calls, 3);
  ASSERT_EQ(back.evaluations.size(), 3u);
  EXPECT_EQ(back.evaluations[2][1].a, r.evaluations[2][1].a);
  EXPECT_EQ(back.result[0].x, r.result[0].x);
  EXPECT_TRUE(explainStages(fitStages(back), 3, {}).course);
  answer.floats[key::perCase(key::kEvalClothVel, k)].pop_back();  // sizes disagree
  EXPECT_FALSE(stageRecordFrom(answer, k, r.h, back));
  EXPECT_FALSE(stageRecordFrom(answer, k + 1, r.h, back));  // no such case
}

}  // namespace
}  // namespace clothref::grader::stages
