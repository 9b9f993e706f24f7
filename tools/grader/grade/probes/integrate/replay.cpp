// The integrators' causes proven by replay (replay.h).
#include "grader/grade/probes/integrate/replay.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "clothref/verify/verify.h"
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
    for (int j : m.pinned)
      if (j >= 0 && j < s.cloth.particles.size()) {
        s.cloth.particles.velocity.col(j).setZero();
        if (m.pinned_position) s.cloth.particles.position.col(j) = x0[0].col(j);
      }
    for (int j : m.pinned_spheres)
      if (j >= 0 && j < s.spheres.particles.size()) s.spheres.particles.velocity.col(j).setZero();
    if (m.dt_after_factor) s.dt = float(double(s.dt) * *m.dt_after_factor);
    if (m.dt_after) s.dt = *m.dt_after;
  };
}

namespace {

// A body's positions or velocities of `a` against `b` within rel (1 + |b|); not-finite matches
// not-finite only.
bool close(const Mat4X<float>& a, const Mat4X<float>& b, double rel) {
  if (a.size() != b.size()) return false;
  for (int k = 0; k < a.size(); ++k) {
    const double x = a.data()[k], y = b.data()[k];
    if (!std::isfinite(x) || !std::isfinite(y)) {
      if (std::isfinite(x) != std::isfinite(y)) return false;
      continue;
    }
    if (std::abs(x - y) > rel * (1 + std::abs(y))) return false;
  }
  return true;
}

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

// The cloth particles the student's step leaves at rest where the course's moves them.
std::vector<int> pinnedParticles(const IntegratorRun& run, bool& positions) {
  std::vector<int> pinned;
  positions = true;
  const auto& a = run.actual.cloth.particles;
  const auto& e = run.expected.cloth.particles;
  for (int j = 0; j < a.size(); ++j)
    if (a.velocity.col(j).isZero(0) && !e.velocity.col(j).isZero(0)) {
      pinned.push_back(j);
      positions = positions && a.position.col(j) == run.start.cloth.particles.position.col(j);
    }
  return pinned;
}

// The spheres the student's step leaves without velocity where the course's gives them one (a
// helper that holds them still).
std::vector<int> stoppedSpheres(const IntegratorRun& run) {
  std::vector<int> stopped;
  const auto& a = run.actual.spheres.particles;
  const auto& e = run.expected.spheres.particles;
  for (int j = 0; j < a.size() && j < e.size(); ++j)
    if (a.velocity.col(j).isZero(0) && !e.velocity.col(j).isZero(0)) stopped.push_back(j);
  return stopped;
}

std::string ranges(const std::vector<int>& indices) {
  std::string out;
  for (std::size_t k = 0; k < indices.size();) {
    std::size_t e = k;
    while (e + 1 < indices.size() && indices[e + 1] == indices[e] + 1) ++e;
    out += (out.empty() ? "" : ", ") + std::to_string(indices[k]) +
           (e > k ? "-" + std::to_string(indices[e]) : "");
    k = e + 1;
  }
  return out;
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

std::vector<IntegratorModel> modelsOf(const std::string& id, const IntegratorRun& run,
                                      const RunStages& stages) {
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
  if (id == "only-first-body") {
    models.push_back(
        {{id}, the + " on particles[0] (the cloth) only", clothrefStep(method, 1), std::nullopt});
    if (method == Method::Explicit)
      models.push_back({{id},
                        "symplectic Euler on particles[0] (the cloth) only",
                        clothrefStep(Method::Symplectic, 1),
                        std::nullopt});
  } else if (id == "position-uses-acceleration" && method == Method::Explicit) {
    variant(Variant::PositionUsesAcceleration, "explicit Euler with x += v dt + a dt²/2");
  } else if (id == "velocity-not-integrated" || id == "position-not-integrated") {
    const bool velocity = id == "velocity-not-integrated";
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
  } else if (id == "backup-alias" && method != Method::Explicit) {
    variant(Variant::Alias, the + " with a backup that follows the live state");
  } else if (id == "no-reevaluation" && method != Method::Explicit) {
    variant(Variant::NoReevaluation, "explicit Euler (what simulateOneStep() computes unused)");
    if (method == Method::Midpoint) {
      variant(Variant::NoReevaluationHalfVelocity,
              "the course's midpoint with simulateOneStep() before the half step");
      variant(Variant::ZeroHalfStep, "the course's midpoint whose half step adds nothing");
    }
  } else if (id == "integer-division-half" && method == Method::Midpoint) {
    variant(Variant::ZeroHalfStep,
            "the course's midpoint with 1 / 2 = 0 (the half step adds "
            "nothing)");
  } else if (id == "per-body-loop" && method != Method::Explicit) {
    variant(Variant::PerBody,
            the + " run on each body in turn, each with its own simulateOneStep() calls");
  } else if (id == "midpoint-full-step" && method == Method::Midpoint) {
    models.push_back({{id},
                      "the course's implicit Euler (a full-step prediction)",
                      clothrefStep(Method::Implicit),
                      std::nullopt});
  } else if (id == "heun-method") {
    for (const stages::MethodTable& t : stages::methodTables())
      if (t.id == "heun") {
        TableModel heun;
        heun.table = &t;
        table(heun, "Heun's method (the trapezoidal corrector)");
      }
  } else if (id == "half-step-corrector" && method != Method::Explicit) {
    TableModel t = base;
    t.result_step = 0.5;
    table(t, the + " whose corrector takes h/2");
  } else if (id == "velocity-damped") {
    TableModel t = base;
    t.velocity_factor = {velocityFactorOf(run, 0), velocityFactorOf(run, 1)};
    // A factor 0 is no damping: the body is held still (integrator-pins-particles).
    const bool stopped =
        std::abs(t.velocity_factor[0]) < 1e-6 || std::abs(t.velocity_factor[1]) < 1e-6;
    if (!stopped && (t.velocity_factor[0] != 1 || t.velocity_factor[1] != 1))
      table(t, the + " with the velocities then multiplied by " + number(t.velocity_factor[0]) +
                   " (the cloth) and " + number(t.velocity_factor[1]) + " (the spheres)");
  } else if (id == "deltatime-mutated") {
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
        // ... restored to that constant before the corrector, which then steps it.
        t.result_dt = after[0];
        text += " whose corrector steps deltaTime = " + number(after[0]) +
                " s (restored to a constant), left so after the call";
      } else {
        t.dt_after_factor = ratio;
        text += ", leaving deltaTime at " + number(ratio) + " x its value after the call";
      }
    }
    table(t, text);
  } else if (id == "integer-division-rk4" && method == Method::Rk4) {
    variant(Variant::RkIntDivision, "the course's RK4 with 1 / 6 = 0 in the update");
  } else if (id == "rk4-mixed-increments" && method == Method::Rk4) {
    variant(Variant::RkMixedFinal, "the course's RK4 whose position update adds the velocity k's");
    variant(Variant::RkK4xInVelocity, "the course's RK4 whose velocity update takes k4 of x");
    for (int k = 0; k < 3; ++k)
      variant(
          Variant::RkMixedStage,
          "the course's RK4 whose stage " + std::to_string(k + 2) + " position adds a velocity k",
          k);
  } else if (id == "rk4-stage-not-from-backup" && method == Method::Rk4) {
    variant(Variant::RkStageFromCurrent,
            "the course's RK4 with each stage built on the previous "
            "stage instead of the backup");
  } else if (id == "rk4-stage-from-wrong-increment" && method == Method::Rk4) {
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
  } else if (id == "rk4-stages-discarded" && method == Method::Rk4) {
    variant(Variant::RkStagesDiscarded, "the course's RK4 whose update uses k1 only");
  } else if (id == "rk4-wrong-weights" && method == Method::Rk4) {
    TableModel t = base;
    fittedWeights(stages, t.weights_x, t.weights_v);
    if (!t.weights_x.empty() && !t.weights_v.empty())
      table(t, "the course's RK4 stages with the weights " + weightText(t.weights_x) +
                   " (positions) and " + weightText(t.weights_v) + " (velocities)");
  } else if (id == "corrector-start-velocity" &&
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
  } else if (id == "integrator-pins-particles") {
    TableModel t = base;
    t.pinned = pinnedParticles(run, t.pinned_position);
    t.pinned_spheres = stoppedSpheres(run);
    std::string held;
    if (!t.pinned.empty())
      held = "the cloth's particles " + ranges(t.pinned) +
             (t.pinned_position ? " put back and stopped" : " stopped");
    if (!t.pinned_spheres.empty())
      held += (held.empty() ? "" : " and ") + std::string("the spheres ") +
              ranges(t.pinned_spheres) + " stopped";
    if (!held.empty()) table(t, the + " with " + held + " after the step");
  }
  return models;
}

Replay replayIntegrator(const IntegratorModel& model, const ProbeContext& context,
                        const IntegratorRun& run, const std::vector<TestResult>& tests) {
  Replay replay;
  replay.model = model.text;
  const double rel = run.rel;
  const auto name = [&](std::size_t k) {
    return k < tests.size() ? tests[k].check : std::string("check ") + std::to_string(k + 1);
  };
  std::size_t k = 0;
  // The one-step check, on the random state.
  const System one = stepped(run.random, model.step);
  const bool positions =
      close(one.cloth.particles.position, run.actual.cloth.particles.position, rel) &&
      close(one.spheres.particles.position, run.actual.spheres.particles.position, rel);
  const bool velocities =
      close(one.cloth.particles.velocity, run.actual.cloth.particles.velocity, rel) &&
      close(one.spheres.particles.velocity, run.actual.spheres.particles.velocity, rel);
  replay.checks.push_back({name(k++), {{"positions", positions}, {"velocities", velocities}}});
  // Every body integrated: the same bodies stand still.
  bool same_bodies = true;
  for (int body : {0, 1})
    same_bodies = same_bodies && (distance(one, run.start, body) <= rel) ==
                                     (distance(run.actual, run.start, body) <= rel);
  replay.checks.push_back({name(k++), {{"bodies that move", same_bodies}}});
  // deltaTime after the call.
  const auto& after = run.answer.f(key::perCase(key::kDtAfter, 0));
  replay.checks.push_back(
      {name(k++), {{"deltaTime after the call", !after.empty() && after[0] == one.dt}}});
  if (run.method != Method::Explicit)
    replay.checks.push_back({name(k++), {{"result", positions && velocities}}});
  // The convergence ladder and the stability run, as the driver runs them (deltaTime reset
  // before every step), recorded every stride.
  const auto trajectory = [&](float dt, std::int64_t steps, std::int64_t stride) {
    System s = springSystem(dt, run.spring_particles);
    std::vector<float> record;
    for (std::int64_t n = 1; n <= steps; ++n) {
      s.dt = dt;
      model.step(s);
      if (n % stride == 0) {
        const auto x = util::flat(s.cloth.particles.position);
        record.insert(record.end(), x.begin(), x.end());
      }
    }
    return record;
  };
  std::vector<double> model_errors, student_errors;
  bool model_usable = true, student_usable = true;
  for (std::size_t d = 0; d < run.dts.size(); ++d) {
    const std::int64_t steps = std::llround(run.end_time / run.dts[d]);
    const double m = trajectoryError(trajectory(float(run.dts[d]), steps, run.strides[d]),
                                     run.dts[d], run.strides[d], run.spring_particles);
    const double s = trajectoryError(run.answer.f(key::perCase(key::kTrajectory, int(d) + 1)),
                                     run.dts[d], run.strides[d], run.spring_particles);
    model_errors.push_back(m);
    student_errors.push_back(s);
    model_usable = model_usable && std::isfinite(m) && m > 0 && m < 1e299;
    student_usable = student_usable && std::isfinite(s) && s > 0 && s < 1e299;
  }
  const double tolerance = context.rubric.tolerances.order;
  const bool same_order =
      model_usable == student_usable &&
      (!model_usable ||
       std::abs(fitOrder(run.dts, model_errors) - fitOrder(run.dts, student_errors)) <= tolerance);
  replay.checks.push_back({name(k++), {{"convergence order", same_order}}});
  const std::int64_t stable_steps = static_cast<std::int64_t>(20.0 / run.stable_dt);
  const std::int64_t stable_stride = std::max<std::int64_t>(1, stable_steps / 100);
  const std::vector<float> stable = trajectory(float(run.stable_dt), stable_steps, stable_stride);
  const auto amplitude = [&](const std::vector<float>& record) {
    const std::size_t per_record = 4 * std::size_t(run.spring_particles);
    double a = 0;
    for (std::size_t r = 0; r + per_record <= record.size(); r += per_record) {
      const double u = std::abs(double(record[r + 4]) - 1.0);
      a = std::isfinite(u) ? std::max(a, u) : 1e300;
    }
    return a;
  };
  const double model_amplitude = amplitude(stable);
  const double student_amplitude =
      amplitude(run.answer.f(key::perCase(key::kTrajectory, run.stable_case)));
  replay.checks.push_back(
      {name(k++), {{"stability", (model_amplitude <= 0.3) == (student_amplitude <= 0.3)}}});
  return replay;
}

namespace {

// Two table models' changes together (the same table): a mistake of each at once.
std::optional<IntegratorModel> combine(const IntegratorModel& a, const IntegratorModel& b) {
  if (!a.table || !b.table || a.table->table != b.table->table) return std::nullopt;
  TableModel t = *a.table;
  const TableModel& o = *b.table;
  if (o.step != 1) t.step = o.step;
  if (o.result_step != 1) t.result_step = o.result_step;
  if (!o.weights_x.empty()) t.weights_x = o.weights_x;
  if (!o.weights_v.empty()) t.weights_v = o.weights_v;
  for (std::size_t b2 = 0; b2 < 2; ++b2)
    if (o.velocity_factor[b2] != 1) t.velocity_factor[b2] = o.velocity_factor[b2];
  if (!o.pinned.empty()) t.pinned = o.pinned, t.pinned_position = o.pinned_position;
  if (!o.pinned_spheres.empty()) t.pinned_spheres = o.pinned_spheres;
  if (o.dt_after_factor) t.dt_after_factor = o.dt_after_factor;
  if (o.dt_after) t.dt_after = o.dt_after;
  if (o.result_dt) t.result_dt = o.result_dt;
  IntegratorModel both;
  both.ids = a.ids;
  both.ids.insert(both.ids.end(), b.ids.begin(), b.ids.end());
  both.text = a.text + "; and " + b.text.substr(b.text.find(' ', 4) + 1);
  both.step = tableStep(t);
  both.table = t;
  return both;
}

}  // namespace

void proveIntegratorCauses(const ProbeContext& context, const IntegratorRun& run,
                           const RunStages& stages, std::vector<TestResult>& tests) {
  if (std::all_of(tests.begin(), tests.end(), [](const TestResult& t) { return t.passed(); }))
    return;
  // The causes named likely, then possible, then the stage fit's, then every other with a model.
  std::vector<std::string> ids, named;
  const auto add = [&](std::vector<std::string>& to, const std::string& id) {
    if (std::find(to.begin(), to.end(), id) == to.end()) to.push_back(id);
  };
  for (bool likely : {true, false})
    for (const TestResult& t : tests)
      for (const Cause& c : t.causes)
        if (c.likely == likely) add(ids, c.id), add(named, c.id);
  for (bool likely : {true, false})
    for (const std::string& id : stages.causes(likely)) add(ids, id);
  for (const char* id :
       {"only-first-body", "position-uses-acceleration", "velocity-not-integrated",
        "position-not-integrated", "backup-alias", "no-reevaluation", "per-body-loop",
        "midpoint-full-step", "heun-method", "half-step-corrector", "corrector-start-velocity",
        "velocity-damped", "integrator-pins-particles", "deltatime-mutated", "rk4-mixed-increments",
        "rk4-stage-not-from-backup", "rk4-stage-from-wrong-increment", "rk4-stages-discarded"})
    add(ids, id);
  std::vector<IntegratorModel> models;
  std::vector<Replay> replays;
  std::string winner;  // the cause the first proving model names
  for (const std::string& id : ids)
    for (IntegratorModel& m : modelsOf(id, run, stages)) {
      replays.push_back(replayIntegrator(m, context, run, tests));
      models.push_back(std::move(m));
      if (!replays.back().proven()) continue;
      if (winner.empty()) {
        applyReplay(replays.back(), models.back().ids, tests);
        winner = models.back().ids.front();
      } else if (models.back().ids.front() != winner &&
                 std::find(named.begin(), named.end(), id) != named.end()) {
        alternative(replays.back(), models.back().ids, winner, tests);
      }
    }
  for (std::size_t i = 0; i < models.size() && winner.empty(); ++i)
    for (std::size_t j = i + 1; j < models.size() && winner.empty(); ++j) {
      if (models[i].ids == models[j].ids) continue;
      const std::optional<IntegratorModel> both = combine(models[i], models[j]);
      if (!both) continue;
      const Replay pair = replayIntegrator(*both, context, run, tests);
      if (!pair.proven()) continue;
      applyReplay(pair, both->ids, tests);
      winner = both->ids.front();
    }
  // A cause named that no model proves: its best model's line, as a guess.
  for (std::size_t m = 0; m < models.size(); ++m) {
    if (std::find(named.begin(), named.end(), models[m].ids.front()) == named.end()) continue;
    std::size_t best = m;
    for (std::size_t q = 0; q < models.size(); ++q)
      if (models[q].ids == models[m].ids && replays[q].reproduced() > replays[best].reproduced())
        best = q;
    if (best == m && !replays[m].proven()) applyReplay(replays[m], models[m].ids, tests);
  }
  requireProofs(tests, {"deltatime-mutated", "unstable", "wrong-order"});
}

}  // namespace clothref::grader::integrators
