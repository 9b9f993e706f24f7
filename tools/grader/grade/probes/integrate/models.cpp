// The models of the integrators' causes (models.h).
#include "grader/grade/probes/integrate/models.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "grader/grade/cause_ids.h"
#include "grader/grade/explain/stages/methods.h"

namespace clothref::grader::integrators {

IntegratorModel integratorModel(std::vector<std::string> ids, std::string text, StepModel model) {
  Step step = courseStep(model);
  return {std::move(ids), std::move(text), std::move(model), std::move(step)};
}

namespace {

std::string number(double value) { return util::num(value); }

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

// For result weights `w` that are the course's on k of other stages, or the course's weights while
// `other` is not: what stands where ("k4 where k1 belongs", "every k in place").
std::optional<std::string> restaged(const std::vector<double>& w,
                                    const std::vector<double>& other) {
  const std::array<double, 4> weights = {w[0], w[1], w[2], w[3]};
  if (const auto from = stages::courseWeightsOnOtherStages(weights))
    return stages::otherStagesText(*from);
  if (!stages::areRk4Weights(weights) || w == other) return std::nullopt;
  return "every k in place";
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
  std::vector<IntegratorModel> models;
  // The mistake's readings: rows of the one course step.
  for (const Reading& r : readingsOf(id, method))
    models.push_back(integratorModel({id}, r.text, StepModel{method, {r.row}, {}}));
  const auto fitted = [&](const Overlay& o, const std::string& text) {
    models.push_back(integratorModel({id}, text, StepModel{method, {}, o}));
  };
  const std::string the =
      "the course's " + std::string(method == Method::Explicit   ? "explicit Euler"
                                    : method == Method::Implicit ? "implicit Euler"
                                    : method == Method::Midpoint ? "midpoint"
                                                                 : "RK4");
  // The causes whose model is fitted from the student's numbers.
  if (id == cause::kVelocityDamped) {
    Overlay t;
    t.velocity_factor = {velocityFactorOf(run, 0), velocityFactorOf(run, 1)};
    // A factor 0 is no damping: the body is held still (integrator-pins-particles).
    const bool stopped =
        std::abs(t.velocity_factor[0]) < 1e-6 || std::abs(t.velocity_factor[1]) < 1e-6;
    if (!stopped && (t.velocity_factor[0] != 1 || t.velocity_factor[1] != 1))
      fitted(t, the + " with the velocities then multiplied by " + number(t.velocity_factor[0]) +
                    " (the cloth) and " + number(t.velocity_factor[1]) + " (the spheres)");
  } else if (id == cause::kDeltatimeMutated) {
    // The course's step at h first, then at the stage fit's scale: a midpoint whose halved
    // deltaTime also shortens its corrector is the course's prediction with a half-step corrector
    // (half-step-corrector, with its own row) before it is implicit Euler at h/2. The two give
    // the same numbers; the first is what the student wrote (the prediction is x0 + h/2 v0).
    const double scale = stages.recorded ? stages.explanation.scale : 1;
    const auto& after = run.answer.f(key::perCase(key::kDtAfter, 0));
    for (const double step : scale != 1 ? std::vector<double>{1, scale} : std::vector<double>{1}) {
      Overlay t;
      t.step = step;
      std::string text = the + (step != 1 ? " at a step of " + number(step) + "·h" : "");
      if (!after.empty() && after[0] != run.random.dt) {
        const double ratio = double(after[0]) / double(run.random.dt);
        const bool constant = stages.recorded && stages.fit.record.h_after != stages.fit.record.h &&
                              float(stages.fit.record.h_after) == after[0];
        if (constant) {
          t.dt_after = after[0];
          fitted(t, text + ", leaving deltaTime at " + number(after[0]) + " s after the call");
          // ... restored to that constant before the corrector, which then steps it (at step 1:
          // the stages before it keep the call's h).
          t.result_dt = after[0];
          text += " whose corrector steps deltaTime = " + number(after[0]) +
                  " s (restored to a constant), left so after the call";
        } else {
          t.dt_after_factor = ratio;
          text += ", leaving deltaTime at " + number(ratio) + " x its value after the call";
        }
      }
      if (step != 1 || t.dt_after || t.dt_after_factor) fitted(t, text);
    }
  } else if ((id == cause::kRk4WrongWeights || id == cause::kRk4MixedIncrements) &&
             method == Method::Rk4) {
    // Fitted weights that are the course's on k of other stages are a k read from the wrong
    // stage (rk4-mixed-increments), other weights are wrong weights: one reading each.
    Overlay t;
    fittedWeights(stages, t.weights_x, t.weights_v);
    if (!t.weights_x.empty() && !t.weights_v.empty()) {
      const auto x = restaged(t.weights_x, t.weights_v), v = restaged(t.weights_v, t.weights_x);
      const bool course_weights_on_other_k = x && v;
      if (id == cause::kRk4WrongWeights && !course_weights_on_other_k)
        fitted(t, "the course's RK4 stages with the weights " + weightText(t.weights_x) +
                      " (positions) and " + weightText(t.weights_v) + " (velocities)");
      if (id == cause::kRk4MixedIncrements && course_weights_on_other_k)
        fitted(t, "the course's RK4 whose result reads " +
                      (*x == *v ? *x + " (positions and velocities)"
                                : *x + " (positions) and " + *v + " (velocities)"));
    }
  } else if (id == cause::kIntegratorPinsParticles) {
    Overlay t;
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
      fitted(t, the + " with " + held + " after the step");
      Overlay staged = t;  // a helper called in the stage loop too
      staged.pins_at_stages = method != Method::Explicit;
      if (staged.pins_at_stages)
        fitted(staged, the + " with " + held + " after each stage state and after the step");
      // The same after a variant the rubric accepts (explicit written as symplectic Euler, ...).
      for (const stages::MethodTable& accepted : stages::methodTables())
        if (accepted.stub == run.index && !accepted.accepted.empty() &&
            rubric.accepts(accepted.accepted))
          for (const Reading& r : readingsOf(accepted.accepted, method))
            models.push_back(integratorModel({id}, r.text + " with " + held + " after the step",
                                             StepModel{method, {r.row}, t}));
    }
  }
  return models;
}

}  // namespace clothref::grader::integrators
