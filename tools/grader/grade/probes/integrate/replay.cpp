// The integrators' causes proven by replay (replay.h).
#include "grader/grade/probes/integrate/replay.h"

#include <algorithm>
#include <cmath>
#include <string_view>

#include "clothref/verify/verify.h"
#include "grader/grade/cause_ids.h"
#include "grader/grade/probes/util.h"

namespace clothref::grader::integrators {

Replay replayIntegrator(const IntegratorModel& model, const ProbeContext& context,
                        const IntegratorRun& run, const std::vector<TestResult>& tests) {
  Replay replay;
  replay.model = model.text;
  const double rel = run.rel;
  const auto name = [&](std::size_t k) {
    return k < tests.size() ? tests[k].check : std::string("check ") + std::to_string(k + 1);
  };
  std::size_t k = 0;
  // The one-step check, on the random state and on the course's cloth.
  const System one = stepped(run.random, model.step);
  bool positions = true, velocities = true;
  const auto compare = [&](const System& model_state, const System& actual) {
    positions =
        positions &&
        util::closeTo(model_state.cloth.particles.position, actual.cloth.particles.position, rel) &&
        util::closeTo(model_state.spheres.particles.position, actual.spheres.particles.position,
                      rel);
    velocities =
        velocities &&
        util::closeTo(model_state.cloth.particles.velocity, actual.cloth.particles.velocity, rel) &&
        util::closeTo(model_state.spheres.particles.velocity, actual.spheres.particles.velocity,
                      rel);
  };
  compare(one, run.actual);
  if (run.course_cloth)
    compare(stepped(run.course_cloth->state, model.step), run.course_cloth->actual);
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

// What a model's text says it changes, without the method it changes ("the course's midpoint
// whose corrector takes h/2" -> "whose corrector takes h/2"): the second of two models joined.
std::string changeOf(const std::string& text) {
  std::size_t at = std::string::npos;
  for (const char* word :
       {" with ", " whose ", " without ", " at a step", " on particles", " run on ", " leaving "})
    at = std::min(at, text.find(word));
  return at == std::string::npos ? text : text.substr(at + 1);
}

// A model whose only change is particles held still after the course's own lines.
bool onlyHoldsStill(const IntegratorModel& m) {
  const Overlay& o = m.model.overlay;
  return m.model.rows.empty() && o.step == 1 && o.result_step == 1 && !o.result_dt &&
         o.weights_x.empty() && o.weights_v.empty() && o.velocity_factor[0] == 1 &&
         o.velocity_factor[1] == 1 && !o.dt_after_factor && !o.dt_after &&
         (!o.pinned.empty() || !o.pinned_spheres.empty());
}

// Two models' switches together (mistakes/integrate_mistakes.h, combined): a mistake of each at
// once, the one that changes the course's lines first.
std::optional<IntegratorModel> combine(const IntegratorModel& a, const IntegratorModel& b) {
  if (a.model.rows.empty() && !b.model.rows.empty()) return combine(b, a);
  const std::optional<StepModel> both = combined(a.model, b.model);
  if (!both) return std::nullopt;
  std::vector<std::string> ids = a.ids;
  ids.insert(ids.end(), b.ids.begin(), b.ids.end());
  return integratorModel(std::move(ids),
                         a.text + (onlyHoldsStill(b) ? ", then " : "; and ") + changeOf(b.text),
                         *both);
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
  for (const cause::Entry& entry : cause::entries())  // the catalogue's integrator models
    if (std::string_view(entry.model) == "integrator step") add(ids, entry.id);
  std::vector<IntegratorModel> models;
  std::vector<Replay> replays;
  std::string winner;  // the cause the first proving model names
  for (const std::string& id : ids)
    for (IntegratorModel& m : modelsOf(id, context.rubric, run, stages)) {
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
      // RK4 weights fitted on the student's own evaluations absorb any change of the stages:
      // they pair only with a reading of a cause the probes named, not with every row.
      const auto fishing = [&](const IntegratorModel& weights, const IntegratorModel& other) {
        return !weights.model.overlay.weights_x.empty() && !other.model.rows.empty() &&
               std::find(named.begin(), named.end(), other.ids.front()) == named.end();
      };
      if (fishing(models[i], models[j]) || fishing(models[j], models[i])) continue;
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
  requireProofs(tests, {cause::kDeltatimeMutated, cause::kUnstable, cause::kWrongOrder});
}

}  // namespace clothref::grader::integrators
