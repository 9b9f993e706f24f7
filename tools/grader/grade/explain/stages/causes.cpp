// explainStages (stages.h): a stage fit against the course's method of the stub, its accepted
// variants and the known methods (stages/methods.h), turned into the first departure and catalogue
// ids. A cause is likely only when the fit shows it; a source pattern only refines a finding the
// fit made (integer division, an aliasing backup), never makes one.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "grader/grade/cause_ids.h"
#include "grader/grade/explain/stages/methods.h"
#include "grader/grade/submission/source_patterns.h"

namespace clothref::grader::stages {
namespace {

void addCause(StageExplanation& e, const std::string& id, bool likely, const std::string& why) {
  for (StageCause& c : e.causes)
    if (c.id == id) {
      c.likely = c.likely || likely;
      return;
    }
  e.causes.push_back({id, likely, why});
}

bool isStart(const Form& form, bool position) {
  return form == Form{Term{position ? kGenX0 : kGenV0, 0, Rational(1)}};
}

// The student's form of state q minus the form of the state `base` (0 = x0 / v0).
bool increment(const StageFit& fit, int q, bool position, int base, Form& out) {
  const StageState& s = fit.states[std::size_t(q - 1)];
  const Fitted& f = position ? s.x : s.v;
  CourseForm at;
  at.base = position ? 'x' : 'v';
  at.base_index = base;
  Form base_form;
  if (!f.fits || !toForm(fit, at, base_form)) return false;
  out = add(f.form, scaled(base_form, Rational(-1)));
  return true;
}

// The course's increment of method state `method` at the student's state q (identity map).
bool courseIncrement(const StageFit& fit, int q, const MethodState& method, bool position,
                     Form& out) {
  std::vector<int> map;
  for (int k = 0; k <= fit.recorded + 1; ++k) map.push_back(k);
  CourseForm c = methodForm(method, position, map, q);
  Form whole;
  if (!toForm(fit, c, whole)) return false;
  out = add(whole, scaled(Form{Term{position ? kGenX0 : kGenV0, 0, Rational(1)}}, Rational(-1)));
  return true;
}

// Findings of one state against the course's state: built on the previous state, dimensional
// mix-ups, a block of the wrong evaluation (RK4).
void stateFindings(const StageFit& fit, int q, const MethodState& course, int method,
                   bool& on_previous, bool& mixed, bool& wrong_stage, bool& own_velocity) {
  for (bool position : {true, false}) {
    const StageState& s = fit.states[std::size_t(q - 1)];
    const Fitted& f = position ? s.x : s.v;
    Form want, have, prev;
    if (!f.fits || !courseIncrement(fit, q, course, position, want)) continue;
    if (increment(fit, q, position, 0, have) && have == want) continue;
    if (q > 1 && increment(fit, q, position, q - 1, prev) && prev == want) on_previous = true;
    for (const CourseTerm& t : f.course.terms) {
      if ((position && t.block == 'a' && t.power == 1) ||
          (!position && t.block == 'v' && t.power >= 1))
        mixed = true;
      // RK4: a stage (or the result) whose blocks come from another evaluation than the course's.
      const std::vector<MethodTerm>& terms = position ? course.x : course.v;
      if (method != 3 || terms.size() != 1 || t.power != 1 || f.course.terms.size() != 1 ||
          f.course.base_index != 0)
        continue;
      const int expected = terms[0].index;
      if (t.block == (position ? 'v' : 'a') && t.index != expected) {
        if (position && t.index == q)
          own_velocity = true;
        else
          wrong_stage = true;
      }
    }
  }
}

// The factor c for which the result's velocity of `body` is c times the course's result velocity
// (v = c·(v0 + h·a0) for forward Euler), to rounding; 0 when there is none.
double velocityFactor(const StageFit& fit, const MethodState& course_result) {
  std::vector<int> map;
  for (int k = 0; k <= fit.recorded + 1; ++k) map.push_back(k);
  Form want;
  if (!toForm(fit, methodForm(course_result, false, map, fit.recorded + 1), want)) return 0;
  const std::vector<double>& recorded = recordedState(fit.record, fit.recorded + 1, kCloth).v;
  std::vector<double> value(recorded.size(), 0.0), magnitude(recorded.size(), 0.0);
  for (const Term& t : want) {
    const std::vector<double>& col = column(fit, kCloth, t.gen);
    if (col.size() != recorded.size()) return 0;
    const double c = t.coef.value() * std::pow(fit.record.h, t.power);
    for (std::size_t i = 0; i < col.size(); ++i) {
      value[i] += c * col[i];
      magnitude[i] += std::abs(c * col[i]);
    }
  }
  double along = 0, norm = 0;
  for (std::size_t i = 0; i < recorded.size(); ++i) {
    along += recorded[i] * value[i];
    norm += value[i] * value[i];
  }
  if (!(norm > 0)) return 0;
  const double c = along / norm;
  for (std::size_t i = 0; i < recorded.size(); ++i)
    if (!(std::abs(recorded[i] - c * value[i]) <=
          kUlps * kUnit * (std::abs(recorded[i]) + std::abs(c) * magnitude[i])))
      return 0;
  return c;
}

}  // namespace

StageExplanation explainStages(const StageFit& fit, int method, const SourceHints& hints) {
  StageExplanation e;
  e.method = method;
  e.calls = fit.record.calls;
  const MethodTable& course = courseTable(method);
  e.course_calls = int(course.evaluations.size());
  e.fits = std::all_of(fit.states.begin(), fit.states.end(),
                       [](const StageState& s) { return s.x.fits && s.v.fits; });
  e.departure = departure(fit, course);
  e.course = e.departure.state == 0;
  for (const MethodTable& t : methodTables())
    if (!e.course && t.stub == method && !t.accepted.empty() && departure(fit, t).state == 0)
      e.accepted = t.accepted;
  // The known method the whole stub equals: the stub's own first, then its variants, then others.
  std::vector<const MethodTable*> order = {&course};
  for (const MethodTable& t : methodTables())
    if (&t != &course && t.stub == method) order.push_back(&t);
  for (const MethodTable& t : methodTables())
    if (t.stub != method) order.push_back(&t);
  // (of the whole stub: every body at every state the same stage)
  const bool together = std::all_of(fit.states.begin(), fit.states.end(), [](const StageState& s) {
    return s.spheres == SpheresAre::Same;
  });
  for (const MethodTable* t : order)
    if (together && equalsMethod(fit, *t)) {
      e.equals = t->id;
      e.equals_name = t->name;
      break;
    }
  const double h = fit.record.h;
  const bool dt_changed = fit.record.h_after != h;
  if (dt_changed)
    addCause(e, cause::kDeltatimeMutated, true,
             "deltaTime is " + sixDigits(fit.record.h_after) +
                 " s after integrate(), not h = " + sixDigits(h) + " s");
  if (e.course || !e.accepted.empty()) return e;

  // A step other than h: the first departing state equals the course's with h·s.
  const int m = fit.recorded, result = m + 1;
  const auto methodState = [&](int q) -> const MethodState& {
    return q <= int(course.evaluations.size()) ? course.evaluations[std::size_t(q - 1)]
                                               : course.result;
  };
  Departure later = e.departure;
  if (e.equals.empty() && e.departure.what != "calls" && e.departure.state >= 1 &&
      (e.departure.state <= int(course.evaluations.size()) || e.departure.state == result)) {
    std::vector<int> map;
    for (int k = 0; k <= m + 1; ++k) map.push_back(k);
    const int q = e.departure.state;
    const int body = e.departure.what == "spheres" ? kSpheres : kCloth;
    const double sx = stepFactor(fit, body, q, methodState(q), true, map);
    const double sv = stepFactor(fit, body, q, methodState(q), false, map);
    double s = e.departure.what == "velocity" ? sv : sx;
    if (body == kSpheres && !sameStep(sv, sx)) s = 0;
    if (s != 0 && !sameStep(s, 1)) {
      e.scale = s;
      later = departure(fit, course, s);
      const bool throughout = e.departure.state == 1 && later.state == 0;
      if (!dt_changed && throughout)
        addCause(e, cause::kDeltatimeMutated, false,
                 "every stage uses a step of " + sixDigits(s) + "·h");
    }
  }

  // The whole stub is a known method.
  const bool is_explicit = e.equals == "explicit" || e.equals == "symplectic";
  bool at_start = false;
  for (int q = 1; q <= m; ++q) at_start = at_start || fit.states[std::size_t(q - 1)].same_as == 0;
  const bool nothing_added = m > 0 && fit.result().same_as == m;
  if (e.equals == "heun")
    addCause(
        e, cause::kHeunMethod, true,
        "the result averages the slopes at the start and at the prediction: x0 + h/2·(v0 + v1)");
  // The predictor-corrector whose result (only) is the course's at h/2: the step advances h/2.
  if ((method == 1 || method == 2) && e.departure.state == result && e.scale != 1 &&
      sameStep(e.scale, 0.5) && !dt_changed)
    addCause(e, cause::kHalfStepCorrector, true,
             "the result is the course's with a step of h/2: x0 + h/2·v1, v0 + h/2·a1");
  if (method == 2 && e.equals.rfind("implicit", 0) == 0)
    addCause(e, cause::kMidpointFullStep, true, "the prediction takes the full step x0 + h·v0");
  if (method != 0 && is_explicit) {
    if (e.calls == 0) {
      addCause(e, cause::kNoReevaluation, true, "simulateOneStep() is never called");
    } else if (at_start) {
      const bool half = method == 2 && hints.integer_half;
      if (half)
        addCause(e, cause::kIntegerDivisionHalf, true,
                 "simulateOneStep() runs at the unchanged start state and the source has 1 / 2");
      addCause(e, cause::kNoReevaluation, !half,
               "simulateOneStep() runs at the unchanged start state");
    } else if (nothing_added) {
      addCause(e, cause::kBackupAlias, hints.alias_backup,
               "the result is the state of evaluation " + std::to_string(m) +
                   " unchanged: the corrector adds nothing (a difference from a backup that "
                   "follows the live state is zero)");
      addCause(e, cause::kNoReevaluation, !hints.alias_backup,
               "what simulateOneStep() computed is never used");
    } else if (method == 3) {
      addCause(e, cause::kRk4StagesDiscarded, true,
               "the stages are evaluated but the result uses only k1 (a0 and v0)");
    } else {
      addCause(e, cause::kNoReevaluation, true, "what simulateOneStep() computed is never used");
    }
  }

  // State by state: what each one computed instead of the course's.
  bool stage_on_previous = false, result_on_previous = false, mixed = false, wrong_stage = false,
       own_velocity = false;
  const int compared = std::min<int>(m, int(course.evaluations.size()));
  bool stages_explained = true;  // each stage the course's, at h·scale, or on the previous stage
  std::vector<int> identity;
  for (int k = 0; k <= m + 1; ++k) identity.push_back(k);
  for (int q = 1; q <= compared; ++q) {
    bool previous = false;
    const MethodState& want = course.evaluations[std::size_t(q - 1)];
    stateFindings(fit, q, want, method, previous, mixed, wrong_stage, own_velocity);
    stage_on_previous = stage_on_previous || previous;
    const auto at_scale = [&](bool position) {
      const double s = stepFactor(fit, kCloth, q, want, position, identity);
      return e.scale != 1 && sameStep(s, e.scale);
    };
    stages_explained = stages_explained && (previous || sameState(fit, q, want, identity) ||
                                            (at_scale(true) && at_scale(false)));
    if (fit.states[std::size_t(q - 1)].same_as == 0 && method != 0 && !is_explicit) {
      const bool half = method == 2 && hints.integer_half;
      if (half)
        addCause(e, cause::kIntegerDivisionHalf, true,
                 "evaluation at the unchanged start state and 1 / 2 in the source");
      addCause(e, cause::kNoReevaluation, !half,
               "simulateOneStep() runs at the unchanged start state");
    }
  }
  stateFindings(fit, result, course.result, method, result_on_previous, mixed, wrong_stage,
                own_velocity);
  if (method == 2 && m >= 1 && fit.states[0].x.fits) {
    std::vector<int> map = {0, 1};
    if (sameState(fit, 1, courseTable(1).evaluations[0], map))
      addCause(e, cause::kMidpointFullStep, true, "the prediction takes the full step x0 + h·v0");
  }
  if (result_on_previous)
    addCause(e,
             (method == 1 || method == 2) && copiesButNoView(hints)
                 ? cause::kCorrectorFromPrediction
                 : cause::kBackupAlias,
             true, "the result is built on the state of the last evaluation instead of the backup");
  if (stage_on_previous)
    addCause(
        e, method == 3 && !result_on_previous ? cause::kRk4StageNotFromBackup : cause::kBackupAlias,
        true, "a stage is built on the previous stage's state instead of the backup");
  if (stage_on_previous && result_on_previous && method == 3)
    addCause(e, cause::kRk4StageNotFromBackup, false, "the stages are built on the previous stage");
  if (mixed && method == 3)
    addCause(e, cause::kRk4MixedIncrements, true,
             "a position adds h·a (a velocity increment) or a velocity adds h·v");
  if (wrong_stage && method == 3)
    addCause(e, cause::kRk4MixedIncrements, true, "a stage uses the k of another evaluation");
  if (own_velocity && method == 3)
    addCause(e, cause::kRk4StageFromWrongIncrement, true,
             "a stage position uses that stage's new velocity instead of the previous k");

  // The result's own shape.
  const StageState& r = fit.result();
  const bool moved_x = !(r.x.fits && isStart(r.x.form, true));
  const bool moved_v = !(r.v.fits && isStart(r.v.form, false));
  Rational step(1);  // the consistent step factor as a small rational (weights compare at it)
  bool step_known = e.scale == 1;
  for (int d = 1; d <= kMaxDenominator && !step_known; ++d) {
    const double n = std::round(e.scale * d);
    if (n != 0 && sameStep(e.scale, n / d)) step = Rational(std::int64_t(n), d), step_known = true;
  }
  if (method == 3 && m >= 3 && !mixed && !result_on_previous && r.x.fits && r.v.fits &&
      !is_explicit && step_known && stages_explained) {
    // Weights of the result on the student's stages: x0 + sum w_k h v_k, v0 + sum u_k h a_k.
    bool wrong = false, zero_ends = !moved_x || !moved_v, restaged = true;
    std::string restaged_text;
    for (bool position : {true, false}) {
      Form want, scaled_want, have;
      const Form base{Term{position ? kGenX0 : kGenV0, 0, Rational(1)}};
      if (!toForm(fit, methodForm(course.result, position, identity, result), want) ||
          !toForm(fit, methodForm(course.result, position, identity, result, step), scaled_want) ||
          !increment(fit, result, position, 0, have))
        continue;
      // The course's weights at h, or at the step the stages were taken with.
      if (have == add(want, scaled(base, Rational(-1))) ||
          have == add(scaled_want, scaled(base, Rational(-1))))
        continue;
      wrong = true;
      const CourseForm& c = position ? r.x.course : r.v.course;
      bool first = false, last = false;
      for (const CourseTerm& t : c.terms)
        if (t.power == 1 && c.base_index == 0) {
          first = first || t.index == 0;
          last = last || t.index == 3;
        }
      zero_ends = zero_ends || (c.base_index == 0 && !first && !last);
      // The course's weights on k of other stages (a k read after a later stage overwrote it)?
      std::array<double, 4> w{};
      bool sum_of_k = c.base_index == 0 && step == Rational(1);
      for (const CourseTerm& t : c.terms)
        if (t.power == 1 && t.block == (position ? 'v' : 'a') && t.index >= 0 && t.index <= 3)
          w[std::size_t(t.index)] += t.coef.value();
        else
          sum_of_k = false;
      const auto from = sum_of_k ? courseWeightsOnOtherStages(w) : std::nullopt;
      restaged = restaged && from;
      if (from) restaged_text = otherStagesText(*from);
    }
    if (wrong && restaged) {
      addCause(e, cause::kRk4MixedIncrements, true,
               "the result has the course's weights on the wrong k: " + restaged_text);
    } else if (wrong) {
      const bool integer = zero_ends && hints.integer_sixth;
      if (integer)
        addCause(e, cause::kIntegerDivisionRk4, true,
                 "the weights are 0 where the course has 1/6, and the source has 1 / 6");
      addCause(e, cause::kRk4WrongWeights, !integer,
               "the result's weights are not (k1 + 2 k2 + 2 k3 + k4) / 6");
    }
  } else if (!is_explicit || method == 0) {
    if (!moved_v) addCause(e, cause::kVelocityNotIntegrated, true, "the result's velocity is v0");
    if (!moved_x) addCause(e, cause::kPositionNotIntegrated, true, "the result's position is x0");
  }
  if (method == 0 && r.x.fits && moved_x) {
    // x0 + h·v0 + c·h²·a0 with c not 0 (forward) or 1 (symplectic): the position uses a dt²/2.
    for (const Term& t : r.x.form)
      if (t.gen == genA(0) && t.power == 2 && t.coef != Rational(1) && !t.coef.zero())
        addCause(e, cause::kPositionUsesAcceleration, true,
                 "the position adds " + text(t.coef) + "·h²·a0");
  }
  if (e.calls < e.course_calls && e.causes.empty())
    addCause(e, cause::kNoReevaluation, true,
             "simulateOneStep() is called fewer times than the method needs");

  // A result velocity scaled down as a whole (v *= 0.999: damping added by hand).
  if (e.departure.state == result && e.departure.what == "velocity" && r.x.fits) {
    const double c = velocityFactor(fit, course.result);
    if (c > 0.5 && c < 1 && !sameStep(c, 1)) {
      e.damping = c;
      addCause(e, cause::kVelocityDamped, true,
               "the result's velocity is " + sixDigits(c) + " times the course's");
    }
  }
  // The bodies: all at one stage, and all integrated.
  bool split = false;
  for (int q = 1; q <= m; ++q) {
    const SpheresAre a = fit.states[std::size_t(q - 1)].spheres;
    split = split || a == SpheresAre::AtStart || a == SpheresAre::Own;
  }
  if (r.spheres == SpheresAre::AtStart)
    addCause(e, cause::kOnlyFirstBody, true, "the spheres (particles[1]) never move");
  else if (split)
    addCause(e, cause::kPerBodyLoop, true,
             "at an evaluation the spheres and the cloth are at different stages");
  return e;
}

}  // namespace clothref::grader::stages
