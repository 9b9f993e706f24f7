// The rubric: points per stub (the course's weights by default), optional per-test weights,
// tolerances and which accepted variants get full marks. A JSON file overrides any of it:
//
//   {"stubs": {"Cloth::computeSpringForce": 25, ...},          points per stub
//    "tests": {"RungeKuttaFourth::integrate: convergence order": 2, ...},  relative weights
//    "tolerances": {"force_rel": 1e-4, "collide_rel": 1e-5, "integrate_rel": 2e-5,
//                   "rest_length_rel": 1e-5, "order": 0.35},
//    "accepted_variants": {"explicit-as-symplectic": true, "implicit-corrector-v-new": true,
//                          "symplectic-predictor": true},
//    "visibility": {"RungeKuttaFourth::integrate": "after_due_date",    Gradescope's visibility
//                   "Cloth::computeSpringForce: moving state (damper)": "hidden"}}  of a stub's
//                                                                     tests, or of one test
#pragma once
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "grader/grade/results.h"

namespace clothref::grader {

struct Tolerances {
  double force_rel = 1e-4;        // of the sum of |spring force| / m acting on the particle
  double collide_rel = 1e-5;      // of the largest |value| in the compared state
  double integrate_rel = 2e-5;    // of |x0| + |v0 dt| + |a0 dt^2| per component
  double rest_length_rel = 1e-5;  // of the reference rest length
  double order = 0.35;            // |observed - expected| convergence order
};

// The accepted variants a rubric can switch (docs/grading.md lists each with its formula):
//   explicit-as-symplectic    ExplicitEuler: v += a dt, then x += v dt
//   implicit-corrector-v-new  ImplicitEuler's corrector: v = v0 + a dt, then x = x0 + v dt
//   symplectic-predictor      Implicit and Midpoint: the predictor v += a h dt, then x += v h dt
inline const std::vector<std::string>& acceptedVariantNames() {
  static const std::vector<std::string> names = {
      "explicit-as-symplectic", "implicit-corrector-v-new", "symplectic-predictor"};
  return names;
}

// Gradescope's visibilities of a test (results.json "visibility"); "visible" is the default.
inline const std::vector<std::string>& visibilityNames() {
  static const std::vector<std::string> names = {"visible", "hidden", "after_due_date",
                                                 "after_published"};
  return names;
}

struct Rubric {
  std::map<std::string, double> stub_points;   // course stub name -> points
  std::map<std::string, double> test_weights;  // full test name -> relative weight
  Tolerances tolerances;
  std::map<std::string, bool> accepted_variants;
  // stub name or full test name -> one of visibilityNames(); a test's own entry wins
  std::map<std::string, std::string> visibility;
  bool accepts(const std::string& variant) const {
    auto it = accepted_variants.find(variant);
    return it != accepted_variants.end() && it->second;
  }
  // The visibility of the test `test_name` of `stub`: its own, else its stub's, else "visible".
  const std::string& visibilityOf(const std::string& test_name, const std::string& stub) const {
    static const std::string visible = "visible";
    for (const std::string* key : {&test_name, &stub}) {
      auto it = visibility.find(*key);
      if (it != visibility.end()) return it->second;
    }
    return visible;
  }
};

// The course's weights for `edition` (2022: springs 15, forces 20, collisions 10 + 10,
// Explicit 5, Implicit + Midpoint 5, RK4 15; 2024: springs 10, forces 25, collision 20, same
// integrators), every accepted variant on.
Rubric defaultRubric(int edition);

// `base` with the overrides of the JSON file at `path`, read by the library's one JSON reader
// (io/json_input.h). Throws InputError "<path>: <JSON pointer>: <problem>" for a malformed file
// (with line and column for a syntax error), a value of the wrong type or an unknown stub,
// tolerance, variant or field.
Rubric loadRubric(const std::string& path, Rubric base);

// The same from a parsed document; `source` names it in messages.
Rubric rubricFromJson(const nlohmann::json& document, const std::string& source, Rubric base);

// Splits each stub's points over its scored tests by weight and fills score / max_score; fills
// the report's totals.
void applyRubric(const Rubric& rubric, GradeReport& report);

}  // namespace clothref::grader
