#include "grader/grade/rubric.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "clothref/io/error.h"
#include "clothref/io/json_input.h"
#include "clothref/io/limits.h"
#include "grader/grade/cause_ids.h"
#include "grader/grade/text.h"

namespace clothref::grader {

// The catalogue's kinds and default deductions (tools/grader/diagnoses.json, generated into
// cause_ids.h; docs/grading.md, "Points follow mistakes"): a slip costs little, a missing piece of
// physics more, a wrong method half the stub; the kind "never" (a crash, a timeout, a symptom or a
// guess) has no deduction.
const std::vector<CauseDeduction>& causeDeductions() {
  static const std::vector<CauseDeduction> table = [] {
    std::vector<CauseDeduction> rows;
    for (const cause::Entry& entry : cause::entries())
      rows.push_back({entry.id, entry.kind, entry.deduction});
    return rows;
  }();
  return table;
}

Rubric defaultRubric(int edition) {
  Rubric rubric;
  for (const StubInfo& info : stubTable()) {
    const double points = edition == 2024 ? info.points_2024 : info.points_2022;
    if (points > 0) rubric.stub_points[info.name] = points;
  }
  for (const std::string& variant : acceptedVariantNames())
    rubric.accepted_variants[variant] = true;
  for (const CauseDeduction& cause : causeDeductions())
    if (cause.deduction >= 0) rubric.deductions[cause.id] = cause.deduction;
  return rubric;
}

namespace {

[[noreturn]] void rubricError(const std::string& source, const std::string& pointer,
                              const std::string& problem) {
  throw InputError(source + ": " + pointer + ": " + problem);
}

// "/" + the key, cut short: a key is user text and may be megabytes long
std::string child(const std::string& pointer, const std::string& key) {
  return pointer + "/" + excerpt(key);
}

void requireObject(const nlohmann::json& value, const std::string& source,
                   const std::string& pointer) {
  if (!value.is_object())
    rubricError(source, pointer, "expected an object, got " + excerpt(value.dump()));
}

double nonNegative(const nlohmann::json& value, const std::string& source,
                   const std::string& pointer) {
  if (!value.is_number() || !(value.get<double>() >= 0))
    rubricError(source, pointer, "expected a number >= 0, got " + excerpt(value.dump()));
  return value.get<double>();
}

}  // namespace

Rubric loadRubric(const std::string& path, Rubric base) {
  return rubricFromJson(readJsonFile(path, "rubric"), path, std::move(base));
}

Rubric rubricFromJson(const nlohmann::json& document, const std::string& source, Rubric rubric) {
  requireObject(document, source, "/");
  for (const auto& [key, value] : document.items()) {
    const std::string pointer = child("", key);
    if (key == "stubs") {
      requireObject(value, source, pointer);
      for (const auto& [stub, points] : value.items()) {
        bool known = false;
        for (const auto& name : stubNames()) known = known || name == stub;
        if (!known) rubricError(source, child(pointer, stub), "unknown stub");
        rubric.stub_points[stub] = nonNegative(points, source, child(pointer, stub));
      }
    } else if (key == "tests") {
      requireObject(value, source, pointer);
      for (const auto& [test, weight] : value.items())
        rubric.test_weights[test] = nonNegative(weight, source, child(pointer, test));
    } else if (key == "tolerances") {
      requireObject(value, source, pointer);
      for (const auto& [name, tolerance] : value.items()) {
        const double t = nonNegative(tolerance, source, child(pointer, name));
        if (name == "force_rel")
          rubric.tolerances.force_rel = t;
        else if (name == "collide_rel")
          rubric.tolerances.collide_rel = t;
        else if (name == "integrate_rel")
          rubric.tolerances.integrate_rel = t;
        else if (name == "rest_length_rel")
          rubric.tolerances.rest_length_rel = t;
        else if (name == "order")
          rubric.tolerances.order = t;
        else
          rubricError(source, child(pointer, name), "unknown tolerance");
      }
    } else if (key == "accepted_variants") {
      requireObject(value, source, pointer);
      for (const auto& [name, on] : value.items()) {
        const auto& names = acceptedVariantNames();
        if (std::find(names.begin(), names.end(), name) == names.end())
          rubricError(source, child(pointer, name), "unknown variant");
        if (!on.is_boolean())
          rubricError(source, child(pointer, name),
                      "expected true or false, got " + excerpt(on.dump()));
        rubric.accepted_variants[name] = on.get<bool>();
      }
    } else if (key == "visibility") {
      requireObject(value, source, pointer);
      for (const auto& [name, shown] : value.items()) {
        // a stub's name, or a test's "<stub>: <check>"
        const std::string stub = name.substr(0, name.find(": "));
        const auto& stubs = stubNames();
        if (std::find(stubs.begin(), stubs.end(), stub) == stubs.end())
          rubricError(source, child(pointer, name), "unknown stub (a stub or \"<stub>: <check>\")");
        const auto& names = visibilityNames();
        if (!shown.is_string() ||
            std::find(names.begin(), names.end(), shown.get<std::string>()) == names.end())
          rubricError(source, child(pointer, name),
                      "expected visible, hidden, after_due_date or after_published, got " +
                          excerpt(shown.dump()));
        rubric.visibility[name] = shown.get<std::string>();
      }
    } else if (key == "scoring") {
      if (value == scoringName(Scoring::PerMistake))
        rubric.scoring = Scoring::PerMistake;
      else if (value == scoringName(Scoring::PerCheck))
        rubric.scoring = Scoring::PerCheck;
      else
        rubricError(source, pointer,
                    "expected \"per-mistake\" or \"per-check\", got " + excerpt(value.dump()));
    } else if (key == "deductions") {
      requireObject(value, source, pointer);
      for (const auto& [id, share] : value.items()) {
        const auto& table = causeDeductions();
        const auto cause = std::find_if(table.begin(), table.end(),
                                        [&](const CauseDeduction& c) { return id == c.id; });
        if (cause == table.end())
          rubricError(source, child(pointer, id), "unknown cause (not in diagnoses.json)");
        if (share.is_null()) {  // this cause is scored per check
          rubric.deductions.erase(id);
          continue;
        }
        if (cause->deduction < 0)
          rubricError(source, child(pointer, id),
                      "never scored per mistake (a crash, a timeout, a symptom or a guess): "
                      "only null is accepted, got " +
                          excerpt(share.dump()));
        if (!share.is_number() || !(share.get<double>() >= 0 && share.get<double>() <= 1))
          rubricError(source, child(pointer, id),
                      "expected a share of the stub's points from 0 to 1 (or null), got " +
                          excerpt(share.dump()));
        rubric.deductions[id] = share.get<double>();
      }
    } else {
      rubricError(source, pointer, "unknown field");
    }
  }
  return rubric;
}

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

// The one likely cause every failed check of a stub names, when the stub has a failed check, no
// failed check names another likely cause or none, and the rubric has a deduction for it; else
// "". Guesses are not counted, nor `non-finite` beside another likely cause: it is that cause's
// symptom (a division by a zero speed makes NaN), not a second mistake.
std::string oneMistake(const Rubric& rubric, const std::vector<const TestResult*>& tests) {
  std::string mistake;
  for (const TestResult* test : tests) {
    if (test->passed()) continue;
    std::vector<std::string> likely;
    for (const Cause& cause : test->causes)
      if (cause.likely && std::find(likely.begin(), likely.end(), cause.id) == likely.end())
        likely.push_back(cause.id);
    if (likely.size() > 1)
      likely.erase(std::remove(likely.begin(), likely.end(), cause::kNonFinite), likely.end());
    if (likely.size() > 1) return "";  // two likely causes
    const std::string named = likely.empty() ? "" : likely.front();
    if (named.empty() || (!mistake.empty() && named != mistake)) return "";
    mistake = named;
  }
  return rubric.deductions.count(mistake) ? mistake : "";
}

// Points as the outputs show them: rounded to 0.001, no trailing zeros (report/outputs.h points).
std::string shown(double value) {
  std::ostringstream out;
  out << std::round(value * 1000) / 1000;
  return out.str();
}

// Per-mistake scoring of one stub: `got` (units each test earned per check) raised so the stub
// earns round(total x (1 - deduction)) units when that is more; the units given back go to the
// failed checks in proportion to the units each lost, so no check earns less than per check.
// Returns the units the stub earns.
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
  const std::string mistake = oneMistake(rubric, of_stub);
  if (mistake.empty()) return earned;
  const double deduction = rubric.deductions.at(mistake);
  const long target = std::lround(double(total) * (1 - deduction));
  if (target <= earned) return earned;  // per check costs no more: nothing to say
  std::vector<double> lost;
  for (std::size_t j = 0; j < parts.size(); ++j) lost.push_back(double(parts[j] - got[j]));
  const std::vector<long> back = apportion(target - earned, lost);
  for (std::size_t j = 0; j < parts.size(); ++j) got[j] += back[j];
  for (std::size_t j = 0; j < parts.size(); ++j) {
    TestResult& test = report.tests[tests[j]];
    if (test.passed()) continue;
    test.rubric_note = "One mistake (" + codeSpan(mistake) +
                       ") explains every failed check of this stub: it loses " +
                       shown(deduction * 100) +
                       " % of its points once (rubric: per-mistake; per-check scoring would give " +
                       shown(double(earned) * unit) + " / " + shown(double(total) * unit) + ").";
    break;
  }
  return target;
}

}  // namespace

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
