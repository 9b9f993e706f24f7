// A stub's points from its checks and its proven mistakes (declared in rubric.h): per-check or
// per-mistake scoring, in whole point units so every sum prints exactly.
#include "grader/grade/rubric.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "grader/grade/cause_ids.h"
#include "grader/grade/text.h"

namespace clothref::grader {

namespace {

// A stub's points in whole units: 1/8 point when the points are a multiple of it (the course's
// weights are), else 1/1000. Both print exactly with three decimals (results.json rounds to
// three), and 1/8 is a power of two, so every sum of test points is exact in binary too.
double pointUnit(double points) {
  return std::abs(points * 8 - std::round(points * 8)) < 1e-9 ? 0.125 : 0.001;
}

// Splits `units` over `weights` by the largest remainder: the parts add up to `units` exactly.
std::vector<long> apportion(long units, const std::vector<double>& weights) {
  double sum = 0;
  for (double w : weights) sum += w;
  std::vector<long> parts(weights.size(), 0);
  if (!(sum > 0)) return parts;
  std::vector<std::pair<double, std::size_t>> remainders;
  long given = 0;
  for (std::size_t k = 0; k < weights.size(); ++k) {
    const double share = double(units) * weights[k] / sum;
    parts[k] = static_cast<long>(std::floor(share));
    given += parts[k];
    remainders.push_back({share - double(parts[k]), k});
  }
  // Ties go to the earlier test, so the split does not depend on the sort's stability.
  std::stable_sort(remainders.begin(), remainders.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  for (std::size_t k = 0; given < units && k < remainders.size(); ++k, ++given)
    ++parts[remainders[k].second];
  return parts;
}

// The proven mistakes that explain a stub's failures (docs/grading-reference.md, "Likely means
// proven" and "Points follow mistakes"): every failed check names at least one cause that is proven
// on this submission (Cause::proven: likely, with its replay or repair) and has a deduction in the
// rubric; the mistakes are those causes, each once, in the order the checks name them. Empty when
// the stub has no failed check, or a failed check names no such cause (a guess, a crash, NaN,
// `unknown`, a likely cause without its proof): per-check scoring then.
std::vector<std::string> provenMistakes(const Rubric& rubric,
                                        const std::vector<const TestResult*>& tests) {
  std::vector<std::string> mistakes;
  for (const TestResult* test : tests) {
    if (test->passed()) continue;
    bool covered = false;
    for (const Cause& cause : test->causes) {
      if (!cause.proven() || !rubric.deductions.count(cause.id)) continue;
      covered = true;
      if (std::find(mistakes.begin(), mistakes.end(), cause.id) == mistakes.end())
        mistakes.push_back(cause.id);
    }
    if (!covered) return {};
  }
  return mistakes;
}

// Points as the outputs show them: rounded to 0.001, no trailing zeros (report/outputs.h points).
std::string shown(double value) {
  std::ostringstream out;
  out << std::round(value * 1000) / 1000;
  return out.str();
}

// Per-mistake scoring of one stub: `got` (units each test earned per check) raised so the stub
// earns round(total x (1 - the proven mistakes' deductions, at most 1)) units when that is more;
// the units given back go to the failed checks in proportion to the units each lost, so no check
// earns less than per check. Returns the units the stub earns.
long perMistake(const Rubric& rubric, GradeReport& report, const std::vector<std::size_t>& tests,
                const std::vector<long>& parts, std::vector<long>& got, double unit) {
  long total = 0, earned = 0;
  std::vector<const TestResult*> of_stub;
  for (std::size_t j = 0; j < parts.size(); ++j) {
    total += parts[j];
    earned += got[j];
    of_stub.push_back(&report.tests[tests[j]]);
  }
  if (rubric.scoring != Scoring::PerMistake || total == 0) return earned;
  const std::vector<std::string> mistakes = provenMistakes(rubric, of_stub);
  if (mistakes.empty()) return earned;
  double deduction = 0;
  std::string ids, shares;
  for (const std::string& id : mistakes) {
    deduction += rubric.deductions.at(id);
    ids += (ids.empty() ? "" : ", ") + codeSpan(id);
    shares += (shares.empty() ? "" : " + ") + shown(rubric.deductions.at(id) * 100);
  }
  deduction = std::min(deduction, 1.0);
  const long target = std::lround(double(total) * (1 - deduction));
  if (target <= earned) return earned;  // per check costs no more: nothing to say
  std::vector<double> lost;
  for (std::size_t j = 0; j < parts.size(); ++j) lost.push_back(double(parts[j] - got[j]));
  const std::vector<long> back = apportion(target - earned, lost);
  for (std::size_t j = 0; j < parts.size(); ++j) got[j] += back[j];
  const std::string per_check = " (rubric: per-mistake; per-check scoring would give " +
                                shown(double(earned) * unit) + " / " + shown(double(total) * unit) +
                                ").";
  for (std::size_t j = 0; j < parts.size(); ++j) {
    TestResult& test = report.tests[tests[j]];
    if (test.passed()) continue;
    test.rubric_note =
        mistakes.size() == 1
            ? "One mistake (" + ids + ") explains every failed check of this stub: it loses " +
                  shares + " % of its points once" + per_check
            : std::to_string(mistakes.size()) + " proven mistakes (" + ids +
                  ") explain every failed check of this stub: together they lose " + shares +
                  (mistakes.size() > 1 ? " = " + shown(deduction * 100) : "") +
                  " % of its points once" + per_check;
    break;
  }
  return target;
}

}  // namespace

void markNonFinite(const std::set<std::string>& non_finite_stubs,
                   const std::set<std::string>& can_be_non_finite, std::vector<TestResult>& tests) {
  std::set<std::string> said_per_check;  // stubs whose probe named non-finite on its checks
  for (const TestResult& t : tests)
    if (!t.passed() && t.names(cause::kNonFinite)) said_per_check.insert(t.stub);
  for (TestResult& test : tests) {
    const bool by_stub = non_finite_stubs.count(test.stub) && !said_per_check.count(test.stub);
    if (test.passed() || test.informational || !(by_stub || test.names(cause::kNonFinite)))
      continue;
    bool explained = false;  // by a likely cause that can make non-finite numbers: NaN a guess
    for (Cause& c : test.causes) {
      // A proven cause stays: its replay gave these non-finite numbers, or its repair mended them.
      c.likely =
          c.likely && (c.id == cause::kNonFinite || can_be_non_finite.count(c.id) || c.proven());
      explained = explained || (c.likely && c.id != cause::kNonFinite);
    }
    if (!test.names(cause::kNonFinite)) test.addCause(cause::kNonFinite, !explained);
    std::ranges::stable_partition(test.causes, [](const Cause& c) { return c.likely; });
  }
}

void applyRubric(const Rubric& rubric, GradeReport& report) {
  std::map<std::string, std::vector<std::size_t>> of_stub;  // stub -> its scored tests
  for (std::size_t k = 0; k < report.tests.size(); ++k) {
    TestResult& test = report.tests[k];
    test.max_score = test.score = 0;
    test.rubric_note.clear();
    if (test.informational) continue;
    auto it = rubric.test_weights.find(test.name());
    if (it != rubric.test_weights.end()) test.weight = it->second;
    of_stub[test.stub].push_back(k);
  }
  report.score = report.max_score = 0;
  report.stub_score.clear();
  report.stub_max.clear();
  // Points are whole units (pointUnit), so test points add up to the stub's points exactly and
  // the stubs to the total, in every output and in whatever order a reader sums them.
  for (const std::string& stub : stubNames()) {
    auto tests = of_stub.find(stub);
    if (tests == of_stub.end()) continue;
    auto points = rubric.stub_points.find(stub);
    const double stub_points = points == rubric.stub_points.end() ? 0 : points->second;
    const double unit = pointUnit(stub_points);
    std::vector<double> weights;
    for (std::size_t k : tests->second) weights.push_back(report.tests[k].weight);
    const std::vector<long> parts = apportion(std::lround(stub_points / unit), weights);
    std::vector<long> got;
    for (std::size_t j = 0; j < parts.size(); ++j) {
      const double fraction = std::clamp(report.tests[tests->second[j]].fraction, 0.0, 1.0);
      got.push_back(std::lround(double(parts[j]) * fraction));
    }
    const long earned = perMistake(rubric, report, tests->second, parts, got, unit);
    long total = 0;
    for (std::size_t j = 0; j < parts.size(); ++j) {
      TestResult& test = report.tests[tests->second[j]];
      test.max_score = double(parts[j]) * unit;
      test.score = double(got[j]) * unit;
      total += parts[j];
    }
    report.stub_max[stub] = double(total) * unit;
    report.stub_score[stub] = double(earned) * unit;
  }
  // Whole units of 1/8 sum exactly in any order; 1/1000 units are summed as integers first.
  for (const auto& [stub, max] : report.stub_max) report.max_score += max;
  for (const auto& [stub, score] : report.stub_score) report.score += score;
}

}  // namespace clothref::grader
