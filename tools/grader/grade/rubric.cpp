#include "rubric.h"

#include <fstream>
#include <nlohmann/json.hpp>

#include "clothref/io/error.h"
#include "clothref/io/json_input.h"

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

Rubric loadRubric(const std::string& path, Rubric rubric) {
  const nlohmann::json document = readJsonFile(path, "rubric");
  const auto number = [&](const nlohmann::json& value, const std::string& field) {
    if (!value.is_number() || value.get<double>() < 0)
      throw InputError(path + ": " + field + " must be a number >= 0");
    return value.get<double>();
  };
  if (!document.is_object()) throw InputError(path + ": the rubric must be a JSON object");
  for (const auto& [key, value] : document.items()) {
    if (key == "stubs") {
      if (!value.is_object()) throw InputError(path + ": /stubs must be an object");
      for (const auto& [stub, points] : value.items()) {
        bool known = false;
        for (const auto& name : stubNames()) known = known || name == stub;
        if (!known) throw InputError(path + ": /stubs/" + stub + ": unknown stub");
        rubric.stub_points[stub] = number(points, "/stubs/" + stub);
      }
    } else if (key == "tests") {
      if (!value.is_object()) throw InputError(path + ": /tests must be an object");
      for (const auto& [test, weight] : value.items())
        rubric.test_weights[test] = number(weight, "/tests/" + test);
    } else if (key == "tolerances") {
      if (!value.is_object()) throw InputError(path + ": /tolerances must be an object");
      for (const auto& [name, tolerance] : value.items()) {
        const double t = number(tolerance, "/tolerances/" + name);
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
          throw InputError(path + ": /tolerances/" + name + ": unknown tolerance");
      }
    } else if (key == "accepted_variants") {
      if (!value.is_object()) throw InputError(path + ": /accepted_variants must be an object");
      for (const auto& [name, on] : value.items()) {
        if (name != "explicit-as-symplectic" && name != "implicit-corrector-v-new")
          throw InputError(path + ": /accepted_variants/" + name + ": unknown variant");
        if (!on.is_boolean())
          throw InputError(path + ": /accepted_variants/" + name + " must be true or false");
        rubric.accepted_variants[name] = on.get<bool>();
      }
    } else {
      throw InputError(path + ": /" + key + ": unknown field");
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
