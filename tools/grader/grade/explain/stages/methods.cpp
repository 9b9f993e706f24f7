// The course's methods as data and the comparisons of a stage fit with them (stages/methods.h).
#include "grader/grade/explain/stages/methods.h"

#include <cmath>

namespace clothref::grader::stages {
namespace {

// x = x0 + sum (num/den) h v_k, v = v0 + sum (num/den) h a_k
MethodState state(std::vector<MethodTerm> x, std::vector<MethodTerm> v) { return {x, v}; }
MethodTerm hv(int num, int den, int k) { return {num, den, 'v', k}; }
MethodTerm ha(int num, int den, int k) { return {num, den, 'a', k}; }

}  // namespace

const std::vector<MethodTable>& methodTables() {
  static const std::vector<MethodTable> tables = [] {
    std::vector<MethodTable> t;
    const MethodState implicit_result = state({hv(1, 1, 1)}, {ha(1, 1, 1)});
    t.push_back({"explicit",
                 "forward Euler (the course's explicit Euler)",
                 0,
                 true,
                 "",
                 {},
                 state({hv(1, 1, 0)}, {ha(1, 1, 0)})});
    t.push_back({"symplectic",
                 "symplectic Euler (v first, then x with the new v)",
                 0,
                 false,
                 "explicit-as-symplectic",
                 {},
                 state({hv(1, 1, kOwn)}, {ha(1, 1, 0)})});
    t.push_back({"implicit",
                 "the course's implicit Euler (a full-step prediction, one re-evaluation)",
                 1,
                 true,
                 "",
                 {state({hv(1, 1, 0)}, {ha(1, 1, 0)})},
                 implicit_result});
    t.push_back({"implicit-v-new",
                 "implicit Euler whose corrector uses the new v",
                 1,
                 false,
                 "implicit-corrector-v-new",
                 {state({hv(1, 1, 0)}, {ha(1, 1, 0)})},
                 state({hv(1, 1, kOwn)}, {ha(1, 1, 1)})});
    t.push_back({"implicit-symplectic-predictor",
                 "implicit Euler with a symplectic predictor (v first, then x)",
                 1,
                 false,
                 "symplectic-predictor",
                 {state({hv(1, 1, kOwn)}, {ha(1, 1, 0)})},
                 implicit_result});
    t.push_back({"midpoint",
                 "the course's midpoint (a half-step prediction, one re-evaluation)",
                 2,
                 true,
                 "",
                 {state({hv(1, 2, 0)}, {ha(1, 2, 0)})},
                 implicit_result});
    t.push_back({"midpoint-symplectic-predictor",
                 "midpoint with a symplectic predictor (v first, then x)",
                 2,
                 false,
                 "symplectic-predictor",
                 {state({hv(1, 2, kOwn)}, {ha(1, 2, 0)})},
                 implicit_result});
    t.push_back({"rk4",
                 "the course's RK4",
                 3,
                 true,
                 "",
                 {state({hv(1, 2, 0)}, {ha(1, 2, 0)}), state({hv(1, 2, 1)}, {ha(1, 2, 1)}),
                  state({hv(1, 1, 2)}, {ha(1, 1, 2)})},
                 state({hv(1, 6, 0), hv(1, 3, 1), hv(1, 3, 2), hv(1, 6, 3)},
                       {ha(1, 6, 0), ha(1, 3, 1), ha(1, 3, 2), ha(1, 6, 3)})});
    // Known methods that are none of the course's: named when a whole stub equals one.
    t.push_back({"heun",
                 "Heun's method (the trapezoidal corrector)",
                 -1,
                 false,
                 "",
                 {state({hv(1, 1, 0)}, {ha(1, 1, 0)})},
                 state({hv(1, 2, 0), hv(1, 2, 1)}, {ha(1, 2, 0), ha(1, 2, 1)})});
    t.push_back({"rk4-three-eighths",
                 "the 3/8-rule Runge-Kutta method",
                 -1,
                 false,
                 "",
                 {state({hv(1, 3, 0)}, {ha(1, 3, 0)}),
                  state({hv(-1, 3, 0), hv(1, 1, 1)}, {ha(-1, 3, 0), ha(1, 1, 1)}),
                  state({hv(1, 1, 0), hv(-1, 1, 1), hv(1, 1, 2)},
                        {ha(1, 1, 0), ha(-1, 1, 1), ha(1, 1, 2)})},
                 state({hv(1, 8, 0), hv(3, 8, 1), hv(3, 8, 2), hv(1, 8, 3)},
                       {ha(1, 8, 0), ha(3, 8, 1), ha(3, 8, 2), ha(1, 8, 3)})});
    return t;
  }();
  return tables;
}

const MethodTable& courseTable(int method) {
  for (const MethodTable& t : methodTables())
    if (t.course && t.stub == method) return t;
  return methodTables().front();
}

CourseForm methodForm(const MethodState& state, bool position, const std::vector<int>& map, int own,
                      Rational scale) {
  CourseForm form;
  form.base = position ? 'x' : 'v';
  for (const MethodTerm& t : position ? state.x : state.v) {
    const int index = t.index == kOwn             ? own
                      : t.index < int(map.size()) ? map[std::size_t(t.index)]
                                                  : -1;
    form.terms.push_back({Rational(t.num, t.den) * scale, 1, t.block, index});
  }
  return form;
}

bool sameState(const StageFit& fit, int q, const MethodState& state, const std::vector<int>& map,
               Rational scale) {
  if (q < 1 || q > int(fit.states.size())) return false;
  const StageState& s = fit.states[std::size_t(q - 1)];
  Form x, v;
  return s.x.fits && s.v.fits && toForm(fit, methodForm(state, true, map, q, scale), x) &&
         toForm(fit, methodForm(state, false, map, q, scale), v) && x == s.x.form && v == s.v.form;
}

double stepFactor(const StageFit& fit, int body, int q, const MethodState& state, bool position,
                  const std::vector<int>& map) {
  const StageRecord& r = fit.record;
  const BodyState& at = recordedState(r, q, body);
  const std::vector<double>& recorded = position ? at.x : at.v;
  const std::vector<double>& base =
      position ? r.start[std::size_t(body)].x : r.start[std::size_t(body)].v;
  std::vector<double> increment(recorded.size(), 0.0);
  for (const MethodTerm& t : position ? state.x : state.v) {
    const int index = t.index == kOwn             ? q
                      : t.index < int(map.size()) ? map[std::size_t(t.index)]
                                                  : -1;
    if (index < 0 || index > int(fit.states.size()) || (t.block == 'a' && index == q)) return 0;
    const BodyState& block = recordedState(r, index, body);
    const std::vector<double>& col = t.block == 'v' ? block.v : block.a;
    if (col.size() != recorded.size()) return 0;
    for (std::size_t i = 0; i < col.size(); ++i)
      increment[i] += double(t.num) / double(t.den) * r.h * col[i];
  }
  if (base.size() != recorded.size()) return 0;
  double along = 0, norm = 0;
  for (std::size_t i = 0; i < recorded.size(); ++i) {
    along += (recorded[i] - base[i]) * increment[i];
    norm += increment[i] * increment[i];
  }
  if (!(norm > 0)) return 0;
  const double s = along / norm;
  for (std::size_t i = 0; i < recorded.size(); ++i) {
    const double error = std::abs(recorded[i] - base[i] - s * increment[i]);
    const double scale = std::abs(recorded[i]) + std::abs(base[i]) + std::abs(s * increment[i]);
    if (!(error <= kUlps * kUnit * scale)) return 0;
  }
  return s;
}

Departure departure(const StageFit& fit, const MethodTable& table, double factor) {
  const int n = int(table.evaluations.size()), m = fit.recorded;
  std::vector<int> map;
  for (int k = 0; k <= std::max(n, m) + 1; ++k) map.push_back(k);
  const auto at = [&](int q, const MethodState& method) -> Departure {
    const StageState& s = fit.states[std::size_t(q - 1)];
    for (bool position : {true, false}) {
      const Fitted& f = position ? s.x : s.v;
      const CourseForm want = methodForm(method, position, map, q);
      Form form;
      if (f.fits && toForm(fit, want, form) && form == f.form) continue;
      const double step = factor != 0 ? stepFactor(fit, kCloth, q, method, position, map) : 0;
      if (step != 0 && sameStep(step, factor)) continue;
      return {
          q, position ? "position" : "velocity",
          f.fits ? text(f.course, fit.recorded) : "no combination of the course's building blocks",
          text(want, fit.recorded)};
    }
    if (s.spheres != SpheresAre::Same) {
      bool scaled = factor != 0;
      for (bool position : {true, false}) {
        const double step = factor != 0 ? stepFactor(fit, kSpheres, q, method, position, map) : 0;
        scaled = scaled && step != 0 && sameStep(step, factor);
      }
      if (!scaled) {
        std::string yours = s.spheres == SpheresAre::AtStart ? "still at their start state"
                            : s.spheres == SpheresAre::Own
                                ? "at x = " + text(s.sphere_x.course, fit.recorded) +
                                      ", v = " + text(s.sphere_v.course, fit.recorded)
                                : "at no combination of their building blocks";
        return {q, "spheres", "the spheres " + yours,
                "every body at the same stage: the spheres at x = " +
                    text(methodForm(method, true, map, q), fit.recorded) +
                    ", v = " + text(methodForm(method, false, map, q), fit.recorded)};
      }
    }
    return {};
  };
  for (int j = 1; j <= std::max(n, m); ++j) {
    if (j > m)
      return {
          j, "calls",
          "no evaluation " + std::to_string(j) + " (simulateOneStep() called " +
              std::to_string(fit.record.calls) + " time" + (fit.record.calls == 1 ? "" : "s") + ")",
          "an evaluation at x = " +
              text(methodForm(table.evaluations[std::size_t(j - 1)], true, map, j), m) +
              ", v = " + text(methodForm(table.evaluations[std::size_t(j - 1)], false, map, j), m)};
    const StageState& s = fit.states[std::size_t(j - 1)];
    if (j > n)
      return {j, "calls",
              "an extra evaluation at x = " + (s.x.fits ? text(s.x.course, m) : "?") +
                  ", v = " + (s.v.fits ? text(s.v.course, m) : "?"),
              "no evaluation " + std::to_string(j) +
                  ": the course's method calls "
                  "simulateOneStep() " +
                  std::to_string(n) + " time" + (n == 1 ? "" : "s")};
    const Departure d = at(j, table.evaluations[std::size_t(j - 1)]);
    if (d.state != 0) return d;
  }
  return at(m + 1, table.result);
}

bool equalsMethod(const StageFit& fit, const MethodTable& table) {
  std::vector<int> map = {0};
  int next = 1;
  for (const MethodState& evaluation : table.evaluations) {
    bool found = false;
    for (int j = next; j <= fit.recorded && !found; ++j)
      if (sameState(fit, j, evaluation, map)) {
        map.push_back(j);
        next = j + 1;
        found = true;
      }
    if (!found) return false;
  }
  return sameState(fit, fit.recorded + 1, table.result, map);
}

bool areRk4Weights(const std::array<double, 4>& w, double tolerance) {
  for (std::size_t j = 0; j < 4; ++j)
    if (!(std::abs(kRk4Weights[j] - w[j]) <= tolerance)) return false;
  return true;
}

std::optional<std::array<int, 4>> courseWeightsOnOtherStages(const std::array<double, 4>& w,
                                                             double tolerance) {
  // the course's weights themselves are no such reading (k1 and k4 swapped give them too)
  if (areRk4Weights(w, tolerance)) return std::nullopt;
  const std::array<double, 4>& course = kRk4Weights;
  std::optional<std::array<int, 4>> best;
  int best_in_place = -1;
  for (int code = 0; code < 256; ++code) {  // every map of the 4 k onto 4 stages
    std::array<int, 4> from{};
    std::array<double, 4> sum{};
    int in_place = 0;
    for (int i = 0; i < 4; ++i) {
      from[std::size_t(i)] = (code >> (2 * i)) & 3;
      sum[std::size_t(from[std::size_t(i)])] += course[std::size_t(i)];
      in_place += from[std::size_t(i)] == i;
    }
    bool same = in_place < 4;
    for (int j = 0; j < 4 && same; ++j)
      same = std::abs(sum[std::size_t(j)] - w[std::size_t(j)]) <= tolerance;
    if (same && in_place > best_in_place) best = from, best_in_place = in_place;
  }
  return best;
}

std::string otherStagesText(const std::array<int, 4>& from) {
  std::string out;
  for (int i = 0; i < 4; ++i)
    if (from[std::size_t(i)] != i)
      out += (out.empty() ? "" : ", ") + std::string("k") +
             std::to_string(from[std::size_t(i)] + 1) + " where k" + std::to_string(i + 1) +
             " belongs";
  return out;
}

}  // namespace clothref::grader::stages
