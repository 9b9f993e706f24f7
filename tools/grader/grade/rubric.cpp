#include "grader/grade/rubric.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "clothref/io/error.h"
#include "clothref/io/json_input.h"
#include "clothref/io/limits.h"

namespace clothref::grader {

Rubric defaultRubric(int edition) {
  Rubric rubric;
  for (const StubInfo& info : stubTable()) {
    const double points = edition == 2024 ? info.points_2024 : info.points_2022;
    if (points > 0) rubric.stub_points[info.name] = points;
  }
  for (const std::string& variant : acceptedVariantNames())
    rubric.accepted_variants[variant] = true;
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

}  // namespace

void applyRubric(const Rubric& rubric, GradeReport& report) {
  std::map<std::string, std::vector<std::size_t>> of_stub;  // stub -> its scored tests
  for (std::size_t k = 0; k < report.tests.size(); ++k) {
    TestResult& test = report.tests[k];
    test.max_score = test.score = 0;
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
    long earned = 0;
    for (std::size_t j = 0; j < parts.size(); ++j) {
      TestResult& test = report.tests[tests->second[j]];
      const long got = std::lround(double(parts[j]) * std::clamp(test.fraction, 0.0, 1.0));
      test.max_score = double(parts[j]) * unit;
      test.score = double(got) * unit;
      earned += got;
    }
    long total = 0;
    for (long part : parts) total += part;
    report.stub_max[stub] = double(total) * unit;
    report.stub_score[stub] = double(earned) * unit;
  }
  // Whole units of 1/8 sum exactly in any order; 1/1000 units are summed as integers first.
  for (const auto& [stub, max] : report.stub_max) report.max_score += max;
  for (const auto& [stub, score] : report.stub_score) report.score += score;
}

}  // namespace clothref::grader
