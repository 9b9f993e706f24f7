// The models of the integrators' causes (models.h).
#include "grader/grade/probes/integrate/models.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "grader/grade/cause_ids.h"
#include "grader/grade/mistakes/integrate_mistakes.h"

namespace clothref::grader::integrators {
namespace {

using stages::kOwn;
using stages::MethodState;
using stages::MethodTable;
using stages::MethodTerm;

float coefficient(const MethodTerm& t, double scale) {
  return float(double(t.num) / t.den * scale);
}

std::string number(double value) { return util::num(value); }

// The state `st` of a table from the backups and the derivatives met so far: v first (a
// position may use its own new velocity), both from the backups.
void setState(const MethodState& st, double scale, float h,
              const std::array<Particles<float>*, 2>& bodies, const std::array<Mat4X<float>, 2>& x0,
              const std::array<Mat4X<float>, 2>& v0,
              const std::vector<std::array<Mat4X<float>, 2>>& vs,
              const std::vector<std::array<Mat4X<float>, 2>>& as) {
  for (std::size_t b = 0; b < 2; ++b) {
    Mat4X<float> v = v0[b];
    for (const MethodTerm& t : st.v)
      if (t.index >= 0 && std::size_t(t.index) < as.size())
        v += (as[std::size_t(t.index)][b] * h) * coefficient(t, scale);
    Mat4X<float> x = x0[b];
    for (const MethodTerm& t : st.x) {
      if (t.index != kOwn && (t.index < 0 || std::size_t(t.index) >= vs.size())) continue;
      if (t.block == 'a') {  // a position term h²·a_k (a velocity formed from a_k, then times h)
        x += (as[std::size_t(t.index)][b] * (h * h)) * coefficient(t, scale * scale);
        continue;
      }
      const Mat4X<float>& velocity = t.index == kOwn ? v : vs[std::size_t(t.index)][b];
      x += (velocity * h) * coefficient(t, scale);
    }
    bodies[b]->position = x;
    bodies[b]->velocity = v;
  }
}

}  // namespace

Step tableStep(const TableModel& m) {
  return [m](System& s) {
    simulate(s);
    const std::array<Particles<float>*, 2> bodies{&s.cloth.particles, &s.spheres.particles};
    const float h = float(double(s.dt) * m.step);
    std::array<Mat4X<float>, 2> x0, v0;
    std::vector<std::array<Mat4X<float>, 2>> vs, as;  // each state met: its v and a
    for (std::size_t b = 0; b < 2; ++b) x0[b] = bodies[b]->position, v0[b] = bodies[b]->velocity;
    vs.push_back(v0);
    as.push_back({bodies[0]->acceleration, bodies[1]->acceleration});
    for (const MethodState& e : m.table->evaluations) {
      setState(e, 1, h, bodies, x0, v0, vs, as);
      simulate(s);
      vs.push_back({bodies[0]->velocity, bodies[1]->velocity});
      as.push_back({bodies[0]->acceleration, bodies[1]->acceleration});
    }
    MethodState result = m.table->result;
    if (!m.weights_x.empty() || !m.weights_v.empty()) {
      // Weights as rationals of 1/720 (the stage fit's are small rationals): w·h·v_k, u·h·a_k.
      const auto terms = [](const std::vector<double>& w, char block) {
        std::vector<MethodTerm> out;
        for (std::size_t k = 0; k < w.size(); ++k)
          if (w[k] != 0) out.push_back({int(std::lround(w[k] * 720)), 720, block, int(k)});
        return out;
      };
      if (!m.weights_x.empty()) result.x = terms(m.weights_x, 'v');
      if (!m.weights_v.empty()) result.v = terms(m.weights_v, 'a');
    }
    const float result_h = m.result_dt ? float(double(*m.result_dt) * m.step) : h;
    setState(result, m.result_step, result_h, bodies, x0, v0, vs, as);
    for (std::size_t b = 0; b < 2; ++b)
      if (m.velocity_factor[b] != 1) bodies[b]->velocity *= float(m.velocity_factor[b]);
    holdStill(m.pinned, m.pinned_spheres, s, x0[0]);
    if (m.dt_after_factor) s.dt = float(double(s.dt) * *m.dt_after_factor);
    if (m.dt_after) s.dt = *m.dt_after;
  };
}

namespace {

// The course's factor c such that the body's velocity after one step is c times the course's.
double velocityFactorOf(const IntegratorRun& run, int body) {
  const Mat4X<float>& a =
      body == 0 ? run.actual.cloth.particles.velocity : run.actual.spheres.particles.velocity;
  const Mat4X<float>& e =
      body == 0 ? run.expected.cloth.particles.velocity : run.expected.spheres.particles.velocity;
  double along = 0, norm = 0;
  for (int k = 0; k < a.size(); ++k) {
    along += double(a.data()[k]) * double(e.data()[k]);
    norm += double(e.data()[k]) * double(e.data()[k]);
  }
  if (!(norm > 0) || !std::isfinite(along)) return 1;
  const double c = along / norm;
  return std::abs(c - 1) < 1e-6 ? 1 : c;
}

// The stage fit's result weights on the student's evaluations (x0 + sum w_k h v_k, v0 + sum
// u_k h a_k), when the result is such a sum; empty otherwise.
void fittedWeights(const RunStages& stages, std::vector<double>& wx, std::vector<double>& wv) {
  wx.clear();
  wv.clear();
  if (!stages.recorded || stages.fit.states.empty()) return;
  const stages::StageState& r = stages.fit.result();
  const auto weights = [](const stages::Fitted& f, char block, std::vector<double>& w) {
    if (!f.fits || f.course.base_index != 0) return;
    std::vector<double> out(4, 0.0);
    for (const stages::CourseTerm& t : f.course.terms) {
      if (t.power != 1 || t.block != block || t.index < 0 || t.index > 3) return;
      out[std::size_t(t.index)] += t.coef.value();
    }
    w = out;
  };
  weights(r.x, 'v', wx);
  weights(r.v, 'a', wv);
}

std::string weightText(const std::vector<double>& w) {
  std::string out;
  for (double x : w) out += (out.empty() ? "" : ", ") + number(x);
  return out;
}

}  // namespace

std::vector<IntegratorModel> modelsOf(const std::string& id, const Rubric& rubric,
                                      const IntegratorRun& run, const RunStages& stages) {
  const Method method = run.method;
  const stages::MethodTable& course = stages::courseTable(run.index);
  std::vector<IntegratorModel> models;
  const auto variant = [&](Variant v, const std::string& text, int k = -1) {
    models.push_back({{id}, text, variantStep(method, v, k), std::nullopt});
  };
  const auto table = [&](const TableModel& t, const std::string& text) {
    models.push_back({{id}, text, tableStep(t), t});
  };
  const std::string the =
      "the course's " + std::string(method == Method::Explicit   ? "explicit Euler"
                                    : method == Method::Implicit ? "implicit Euler"
                                    : method == Method::Midpoint ? "midpoint"
                                                                 : "RK4");
  TableModel base;
  base.table = &course;
  if (id == cause::kOnlyFirstBody) {
    models.push_back(
        {{id}, the + " on particles[0] (the cloth) only", clothrefStep(method, 1), std::nullopt});
    if (method == Method::Explicit)
      models.push_back({{id},
                        "symplectic Euler on particles[0] (the cloth) only",
                        clothrefStep(Method::Symplectic, 1),
                        std::nullopt});
  } else if (id == cause::kPositionUsesAcceleration && method == Method::Explicit) {
    variant(Variant::PositionUsesAcceleration, "explicit Euler with x += v dt + a dt²/2");
  } else if (id == cause::kVelocityNotIntegrated || id == cause::kPositionNotIntegrated) {
    const bool velocity = id == cause::kVelocityNotIntegrated;
    if (method == Method::Explicit) {
      variant(velocity ? Variant::PositionOnly : Variant::VelocityOnly,
              "explicit Euler without the " + std::string(velocity ? "velocity" : "position") +
                  " update");
    } else {
      TableModel t = base;
      t.weights_x = velocity ? std::vector<double>{} : std::vector<double>(4, 0.0);
      t.weights_v = velocity ? std::vector<double>(4, 0.0) : std::vector<double>{};
      // A zero weight vector is "no term": x = x0 (or v = v0).
      table(t, the + " without the " + std::string(velocity ? "velocity" : "position") + " update");
    }
  } else if (id == cause::kBackupAlias && method != Method::Explicit) {
    variant(Variant::Alias, the + " with a backup that follows the live state");
  } else if (id == cause::kCorrectorFromPrediction &&
             (method == Method::Implicit || method == Method::Midpoint)) {
    // The same step as a backup that follows the live state: the corrector adds onto the
    // prediction. Which one the student wrote is the source's to say (backupCause).
    variant(Variant::Alias, the + " whose corrector steps from the predicted state");
  } else if (id == cause::kNoReevaluation && method != Method::Explicit) {
    variant(Variant::NoReevaluation, "explicit Euler (what simulateOneStep() computes unused)");
    // The same step taken from the live state after the stub's own simulateOneStep() (no
    // backups, or "backups" that follow the live state): the course's explicit Euler after a
    // second call, which resolves a contact a second time.
    const Step explicit_step = clothrefStep(Method::Explicit);
    models.push_back({{id},
                      "explicit Euler from the state your own simulateOneStep() leaves (the "
                      "step starts after that call, not from backups taken before it)",
                      [explicit_step](System& s) {
                        simulate(s);
                        explicit_step(s);
                      },
                      std::nullopt});
    if (method == Method::Midpoint) {
      variant(Variant::NoReevaluationHalfVelocity,
              "the course's midpoint with simulateOneStep() before the half step");
      variant(Variant::ZeroHalfStep, "the course's midpoint whose half step adds nothing");
    }
  } else if (id == cause::kIntegerDivisionHalf && method == Method::Midpoint) {
    variant(Variant::ZeroHalfStep,
            "the course's midpoint with 1 / 2 = 0 (the half step adds "
            "nothing)");
  } else if (id == cause::kPerBodyLoop && method != Method::Explicit) {
    variant(Variant::PerBody,
            the + " run on each body in turn, each with its own simulateOneStep() calls");
  } else if (id == cause::kMidpointFullStep && method == Method::Midpoint) {
    models.push_back({{id},
                      "the course's implicit Euler (a full-step prediction)",
                      clothrefStep(Method::Implicit),
                      std::nullopt});
  } else if (id == cause::kHeunMethod) {
    for (const stages::MethodTable& t : stages::methodTables())
      if (t.id == "heun") {
        TableModel heun;
        heun.table = &t;
        table(heun, "Heun's method (the trapezoidal corrector)");
      }
  } else if (id == cause::kHalfStepCorrector && method != Method::Explicit) {
    TableModel t = base;
    t.result_step = 0.5;
    table(t, the + " whose corrector takes h/2");
  } else if (id == cause::kVelocityDamped) {
    TableModel t = base;
    t.velocity_factor = {velocityFactorOf(run, 0), velocityFactorOf(run, 1)};
    // A factor 0 is no damping: the body is held still (integrator-pins-particles).
    const bool stopped =
        std::abs(t.velocity_factor[0]) < 1e-6 || std::abs(t.velocity_factor[1]) < 1e-6;
    if (!stopped && (t.velocity_factor[0] != 1 || t.velocity_factor[1] != 1))
      table(t, the + " with the velocities then multiplied by " + number(t.velocity_factor[0]) +
                   " (the cloth) and " + number(t.velocity_factor[1]) + " (the spheres)");
  } else if (id == cause::kDeltatimeMutated) {
    TableModel t = base;
    const double scale = stages.recorded ? stages.explanation.scale : 1;
    t.step = scale;
    const auto& after = run.answer.f(key::perCase(key::kDtAfter, 0));
    std::string text = the + (scale != 1 ? " at a step of " + number(scale) + "·h" : "");
    if (!after.empty() && after[0] != run.random.dt) {
      const double ratio = double(after[0]) / double(run.random.dt);
      const bool constant = stages.recorded && stages.fit.record.h_after != stages.fit.record.h &&
                            float(stages.fit.record.h_after) == after[0];
      if (constant) {
        t.dt_after = after[0];
        table(t, text + ", leaving deltaTime at " + number(after[0]) + " s after the call");
        // ... restored to that constant before the corrector, which then steps it; the stages
        // before it keep the call's h (the fit's scale is the corrector's).
        TableModel restored = base;
        restored.dt_after = after[0];
        restored.result_dt = after[0];
        table(restored, the + " whose corrector steps deltaTime = " + number(after[0]) +
                            " s (restored to a constant), left so after the call");
        t.result_dt = after[0];
        text += " whose corrector steps deltaTime = " + number(after[0]) +
                " s (restored to a constant), left so after the call";
      } else {
        t.dt_after_factor = ratio;
        text += ", leaving deltaTime at " + number(ratio) + " x its value after the call";
      }
    }
    table(t, text);
  } else if (id == cause::kIntegerDivisionRk4 && method == Method::Rk4) {
    variant(Variant::RkIntDivision, "the course's RK4 with 1 / 6 = 0 in the update");
    variant(Variant::RkIntDivisionOnLastStage,
            "the course's RK4 with 1 / 6 = 0 in an update added (+=) to the state the last stage "
            "left");
  } else if (id == cause::kRk4MixedIncrements && method == Method::Rk4) {
    variant(Variant::RkMixedFinal, "the course's RK4 whose position update adds the velocity k's");
    variant(Variant::RkK4xInVelocity, "the course's RK4 whose velocity update takes k4 of x");
    for (int k = 0; k < 3; ++k)
      variant(
          Variant::RkMixedStage,
          "the course's RK4 whose stage " + std::to_string(k + 2) + " position adds a velocity k",
          k);
  } else if (id == cause::kRk4StageNotFromBackup && method == Method::Rk4) {
    variant(Variant::RkStageFromCurrent,
            "the course's RK4 with each stage built on the previous "
            "stage instead of the backup");
  } else if (id == cause::kRk4StageFromWrongIncrement && method == Method::Rk4) {
    variant(Variant::RkStageFromNewVelocity,
            "the course's RK4 with each stage position from that stage's new velocity");
    // Each increment read after the velocity was overwritten with v0 + c·h·a_k of its own stage:
    // the stage positions x0 + c·h·(v0 + c'·h·a_k) and the update's k's (v0 + c'·h·a_k)·h.
    static const MethodTable overwritten = [] {
      MethodTable t = stages::courseTable(3);
      t.evaluations[1].x = {{1, 2, 'v', 0}, {1, 4, 'a', 1}};
      t.evaluations[2].x = {{1, 1, 'v', 0}, {1, 2, 'a', 2}};
      t.result.x = {{1, 1, 'v', 0}, {1, 6, 'a', 1}, {1, 6, 'a', 2}, {1, 6, 'a', 3}};
      return t;
    }();
    TableModel t;
    t.table = &overwritten;
    table(t,
          "the course's RK4 with each position increment read after the stage's velocity was "
          "overwritten with v0 + c·h·a of that stage");
  } else if (id == cause::kRk4StagesDiscarded && method == Method::Rk4) {
    variant(Variant::RkStagesDiscarded, "the course's RK4 whose update uses k1 only");
  } else if (id == cause::kRk4WrongWeights && method == Method::Rk4) {
    TableModel t = base;
    fittedWeights(stages, t.weights_x, t.weights_v);
    if (!t.weights_x.empty() && !t.weights_v.empty())
      table(t, "the course's RK4 stages with the weights " + weightText(t.weights_x) +
                   " (positions) and " + weightText(t.weights_v) + " (velocities)");
  } else if (id == cause::kCorrectorStartVelocity &&
             (method == Method::Implicit || method == Method::Midpoint)) {
    static const MethodTable implicit_start = [] {
      MethodTable t = stages::courseTable(1);
      t.result = MethodState{{{1, 1, 'v', 0}}, {{1, 1, 'a', 1}}};
      return t;
    }();
    static const MethodTable midpoint_start = [] {
      MethodTable t = stages::courseTable(2);
      t.result = MethodState{{{1, 1, 'v', 0}}, {{1, 1, 'a', 1}}};
      return t;
    }();
    TableModel t;
    t.table = method == Method::Implicit ? &implicit_start : &midpoint_start;
    table(t, the + " whose corrector moves the positions with the start velocity v0");
  } else if (id == cause::kIntegratorPinsParticles) {
    TableModel t = base;
    t.pinned = pinnedParticles(run);
    t.pinned_spheres = stoppedSpheres(run);
    std::string held;
    for (const Pins& pins : t.pinned)
      held += (held.empty() ? "" : " and ") + std::string("the cloth's particles ") +
              indexRanges(pins.particles) +
              (pins.positions ? " put back and stopped" : " stopped") +
              (t.pinned.size() > 1 || pins.cloth_size != run.random.cloth.particles.size()
                   ? " (of a " + std::to_string(pins.cloth_size) + "-particle cloth)"
                   : "");
    if (!t.pinned_spheres.empty())
      held += (held.empty() ? "" : " and ") + std::string("the spheres ") +
              indexRanges(t.pinned_spheres) + " stopped";
    if (!held.empty()) {
      table(t, the + " with " + held + " after the step");
      // The same after a variant the rubric accepts (explicit written as symplectic Euler, ...).
      for (const MethodTable& accepted : stages::methodTables())
        if (accepted.stub == run.index && !accepted.accepted.empty() &&
            rubric.accepts(accepted.accepted)) {
          TableModel v = t;
          v.table = &accepted;
          table(v, accepted.name + " with " + held + " after the step");
        }
    }
  }
  return models;
}

}  // namespace clothref::grader::integrators
