#include "rubric.h"

#include <utility>

#include "clothref/io/error.h"
#include "clothref/io/json_input.h"
#include "clothref/io/limits.h"

namespace clothref::grader {

Rubric defaultRubric(int edition) {
  Rubric rubric;
  const bool y2024 = edition == 2024;
  rubric.stub_points = {{"Cloth::initializeSpring", y2024 ? 10 : 15},
                        {"Cloth::computeSpringForce", y2024 ? 25 : 20},
                        {"Spheres::collide(Cloth*)", y2024 ? 20 : 10},
                        {"ExplicitEuler::integrate", 5},
                        {"ImplicitEuler::integrate", 2.5},
                        {"MidpointEuler::integrate", 2.5},
                        {"RungeKuttaFourth::integrate", 15}};
  if (!y2024) rubric.stub_points["Spheres::collide()"] = 10;
  rubric.accepted_variants = {{"explicit-as-symplectic", true}, {"implicit-corrector-v-new", true}};
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
        if (name != "explicit-as-symplectic" && name != "implicit-corrector-v-new")
          rubricError(source, child(pointer, name), "unknown variant");
        if (!on.is_boolean())
          rubricError(source, child(pointer, name),
                      "expected true or false, got " + excerpt(on.dump()));
        rubric.accepted_variants[name] = on.get<bool>();
      }
    } else {
      rubricError(source, pointer, "unknown field");
    }
  }
  return rubric;
}

void applyRubric(const Rubric& rubric, GradeReport& report) {
  std::map<std::string, double> weight_sum;
  for (TestResult& test : report.tests) {
    if (test.informational) continue;
    auto it = rubric.test_weights.find(test.name());
    if (it != rubric.test_weights.end()) test.weight = it->second;
    weight_sum[test.stub] += test.weight;
  }
  report.score = report.max_score = 0;
  report.stub_score.clear();
  report.stub_max.clear();
  for (TestResult& test : report.tests) {
    if (test.informational) {
      test.max_score = test.score = 0;
      continue;
    }
    auto points = rubric.stub_points.find(test.stub);
    const double stub_points = points == rubric.stub_points.end() ? 0 : points->second;
    const double sum = weight_sum[test.stub];
    test.max_score = sum > 0 ? stub_points * test.weight / sum : 0;
    test.score = test.max_score * std::clamp(test.fraction, 0.0, 1.0);
    report.stub_score[test.stub] += test.score;
    report.stub_max[test.stub] += test.max_score;
    report.score += test.score;
    report.max_score += test.max_score;
  }
}

}  // namespace clothref::grader
