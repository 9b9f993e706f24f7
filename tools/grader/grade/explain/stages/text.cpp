// stageText and the forms as text (stages.h): the course's names x0, v0, a0 for the start, x1, v1,
// a1 for evaluation 1 (the first simulateOneStep() inside integrate), v_new for the result's
// velocity, and h for deltaTime.
#include <cctype>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "grader/grade/explain/stages/methods.h"

namespace clothref::grader::stages {
namespace {

std::string name(char block, int index, int recorded) {
  if (index > recorded) return std::string(1, block) + "_new";
  return std::string(1, block) + std::to_string(index);
}

// |coef| h^power as a factor: "h/2", "3h/8", "2h", "h²/2", "1/2" (power 0), "" (1).
std::string factor(Rational c, int power) {
  const std::int64_t n = c.num < 0 ? -c.num : c.num;
  std::string h = power == 0   ? ""
                  : power == 1 ? "h"
                  : power == 2 ? "h²"
                               : "h^" + std::to_string(power);
  std::string out = n == 1 && !h.empty() ? h : std::to_string(n) + h;
  if (n == 1 && h.empty() && c.den == 1) out = "";
  if (c.den != 1) out += "/" + std::to_string(c.den);
  return out;
}

std::string joined(const std::vector<std::pair<Rational, std::string>>& parts, bool leading) {
  std::string out;
  for (const auto& [c, what] : parts) {
    const bool negative = c.num < 0;
    if (out.empty() && !leading)
      out += negative ? "−" : "";
    else
      out += negative ? " − " : " + ";
    out += what;
  }
  return out;
}

}  // namespace

std::string text(const CourseForm& form, int recorded) {
  std::string out = name(form.base, form.base_index, recorded);
  // Terms of one block kind and power, three or more: one factor, e.g. h/6·(v0 + 2·v1 + ...).
  std::vector<bool> grouped(form.terms.size(), false);
  std::vector<std::pair<Rational, std::string>> parts;
  for (std::size_t i = 0; i < form.terms.size(); ++i) {
    if (grouped[i]) continue;
    std::vector<std::size_t> group;
    for (std::size_t j = i; j < form.terms.size(); ++j)
      if (form.terms[j].block == form.terms[i].block &&
          form.terms[j].power == form.terms[i].power && form.terms[j].power > 0)
        group.push_back(j);
    if (group.size() >= 3) {
      std::int64_t den = 1, g = 0;
      for (std::size_t j : group) den = std::lcm(den, form.terms[j].coef.den);
      for (std::size_t j : group)
        g = std::gcd(g, std::abs(form.terms[j].coef.num * (den / form.terms[j].coef.den)));
      const Rational common(g, den);
      std::vector<std::pair<Rational, std::string>> inner;
      for (std::size_t j : group) {
        const Rational k = form.terms[j].coef / common;
        const std::string f = factor(k, 0);
        inner.push_back({k, (f.empty() ? "" : f + "·") +
                                name(form.terms[j].block, form.terms[j].index, recorded)});
        grouped[j] = true;
      }
      parts.push_back(
          {common, factor(common, form.terms[i].power) + "·(" + joined(inner, false) + ")"});
      continue;
    }
    const CourseTerm& t = form.terms[i];
    const std::string f = factor(t.coef, t.power);
    parts.push_back({t.coef, (f.empty() ? "" : f + "·") + name(t.block, t.index, recorded)});
  }
  return out + joined(parts, true);
}

std::string stateName(int state, int recorded) {
  if (state <= 0) return "the start";
  if (state > recorded) return "the result";
  return "evaluation " + std::to_string(state);
}

std::string stageText(const StageFit& fit, const StageExplanation& e) {
  const MethodTable& course = courseTable(e.method);
  const int m = fit.recorded;
  std::string out = "Your integrate() called simulateOneStep() " + std::to_string(e.calls) +
                    " time" + (e.calls == 1 ? "" : "s") + "; " + course.name + " calls it " +
                    std::to_string(e.course_calls) + " time" + (e.course_calls == 1 ? "" : "s") +
                    ". On a contact-free state (x0, v0, a0 at the start; x_k, v_k, a_k at your "
                    "k-th call; h = deltaTime):\n\n";
  out += "| state | position | velocity |\n|---|---|---|\n";
  for (int q = 1; q <= int(fit.states.size()); ++q) {
    const StageState& s = fit.states[std::size_t(q - 1)];
    const auto cell = [&](const Fitted& f) {
      return f.fits
                 ? text(f.course, m)
                 : "no combination (off by " + sixDigits(f.residual * kUlps) + " float roundings)";
    };
    std::string row = "| " + stateName(q, m) + " | " + cell(s.x) + " | " + cell(s.v) + " |\n";
    if (s.spheres == SpheresAre::AtStart)
      row += "| " + stateName(q, m) + ", spheres | at their start | at their start |\n";
    else if (s.spheres == SpheresAre::Own)
      row += "| " + stateName(q, m) + ", spheres | " + text(s.sphere_x.course, m) + " | " +
             text(s.sphere_v.course, m) + " |\n";
    else if (s.spheres == SpheresAre::NoFit)
      row += "| " + stateName(q, m) + ", spheres | no combination | no combination |\n";
    out += row;
  }
  if (fit.record.calls > m)
    out += "\n(Only the first " + std::to_string(m) + " calls were recorded.)\n";
  out += "\n";
  if (e.course) {
    out += "Every evaluation and the result are " + course.name + ", stage by stage.\n";
    return out;
  }
  if (!e.accepted.empty()) {
    for (const MethodTable& t : methodTables())
      if (t.accepted == e.accepted && t.stub == e.method)
        out += "This is " + t.name + ", an accepted variant (`" + t.accepted + "`).\n";
    return out;
  }
  if (e.departure.state != 0) {
    std::string where = stateName(e.departure.state, m);
    where[0] = char(std::toupper(static_cast<unsigned char>(where[0])));
    if (e.departure.what == "calls")
      out +=
          where + ": yours " + e.departure.yours + "; the course's " + e.departure.course + ".\n";
    else if (e.departure.what == "spheres")
      out += where + ": " + e.departure.yours + "; the course has " + e.departure.course + ".\n";
    else
      out += where + " " + e.departure.what + ": yours " + e.departure.yours + ", the course's " +
             e.departure.course + ".\n";
  }
  const int same = fit.result().same_as;
  if (same > 0)
    out += "The result is the state handed to simulateOneStep() at evaluation " +
           std::to_string(same) + ", unchanged: what that call computed is never used.\n";
  if (e.scale != 1) {
    const std::string subject = e.departure.what == "spheres" ? "There the spheres are"
                                : e.departure.state == 1      ? "From there on your stages are"
                                                              : "That state is";
    out += subject + " the course's with a step of " + sixDigits(e.scale) + "·h (" +
           sixDigits(e.scale * fit.record.h) + " s) instead of h = " + sixDigits(fit.record.h) +
           " s.\n";
  }
  if (e.damping != 1) {
    std::vector<int> map;
    for (int k = 0; k <= m + 1; ++k) map.push_back(k);
    out += "The result velocity is " + sixDigits(e.damping) + "·(" +
           text(methodForm(course.result, false, map, m + 1), m) +
           "): the course's velocity scaled down, damping the course does not have.\n";
  }
  if (!e.equals.empty()) {
    int n = 0;
    for (const MethodTable& t : methodTables())
      if (t.id == e.equals) n = int(t.evaluations.size());
    bool at_start = e.calls > 0;
    for (int q = 1; q <= m; ++q) at_start = at_start && fit.states[std::size_t(q - 1)].same_as == 0;
    const std::string times = e.calls == 1 ? "once" : std::to_string(e.calls) + " times";
    std::string how;
    if (e.calls == 0 && e.course_calls > 0)
      how = "simulateOneStep() is never called";
    else if (at_start)
      how = "simulateOneStep() " + times + ", at the start state";
    else if (e.calls > n)
      how = "simulateOneStep() " + times + ", and what " +
            (n == 0 ? std::string(e.calls == 1 ? "it computes" : "they compute")
                    : std::string("the calls the method does not make compute")) +
            " is never used";
    out += "This is " + e.equals_name + (how.empty() ? "" : ": " + how) + ".\n";
  }
  return out;
}

std::string sixDigits(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

}  // namespace clothref::grader::stages
