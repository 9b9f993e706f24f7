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
//                   "Cloth::computeSpringForce: moving state (damper)": "hidden"},  of a stub's
//                                                                     tests, or of one test
//    "scoring": "per-mistake",                 or "per-check" (docs/grading-reference.md,
//    "deductions": {"correction-factor": 0.25}}  "Points follow mistakes"): a cause's cost, of its
//                                                stub's points
#pragma once
#include <map>
#include <set>
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

// The accepted variants a rubric can switch (docs/grading-reference.md lists each with its
// formula):
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

// How a stub's failed checks cost points. PerCheck: each check loses its own points. PerMistake
// (the default): a stub whose failed checks proven mistakes explain loses their deductions once,
// never more than per check would take.
enum class Scoring { PerMistake, PerCheck };

inline const char* scoringName(Scoring scoring) {
  return scoring == Scoring::PerCheck ? "per-check" : "per-mistake";
}

// A catalogue cause as per-mistake scoring sees it: the share of its stub's points it costs once,
// by the kind of mistake it is; `deduction` < 0 for a cause that never explains a stub's failures
// on its own (a crash, a timeout, a guess, a symptom such as a wrong convergence order).
struct CauseDeduction {
  const char* id;
  const char* kind;  // "a wrong constant", ... (docs/grading-reference.md's table says it)
  double deduction;  // 0..1 of the stub's points, or < 0: never
};

// The one table of default deductions: an entry for every catalogue id
// (tools/grader/diagnoses.json), grouped by stub as the catalogue is.
const std::vector<CauseDeduction>& causeDeductions();

struct Rubric {
  std::map<std::string, double> stub_points;   // course stub name -> points
  std::map<std::string, double> test_weights;  // full test name -> relative weight
  Tolerances tolerances;
  std::map<std::string, bool> accepted_variants;
  // stub name or full test name -> one of visibilityNames(); a test's own entry wins
  std::map<std::string, std::string> visibility;
  Scoring scoring = Scoring::PerMistake;
  // cause id -> share of its stub's points the mistake costs once (per-mistake scoring); a cause
  // without an entry is scored per check
  std::map<std::string, double> deductions;
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
// integrators), every accepted variant on, per-mistake scoring with causeDeductions().
Rubric defaultRubric(int edition);

// `base` with the overrides of the JSON file at `path`, read by the library's one JSON reader
// (io/json_input.h). Throws InputError "<path>: <JSON pointer>: <problem>" for a malformed file
// (with line and column for a syntax error), a value of the wrong type or an unknown stub,
// tolerance, variant, scoring, cause or field, and for a deduction outside 0..1.
Rubric loadRubric(const std::string& path, Rubric base);

// The same from a parsed document; `source` names it in messages.
Rubric rubricFromJson(const nlohmann::json& document, const std::string& source, Rubric base);

// NaN and garbage never earn a mistake's points (docs/grading-reference.md, "Points follow
// mistakes"): the post-pass over a grade's results before applyRubric. A check's answers are
// non-finite when it names `non-finite` itself, or when its stub's probe answered with NaN or
// infinity (a stub of `non_finite_stubs`) and no failed check of that stub names `non-finite` (the
// probe does not say which checks: each failed one is taken as non-finite). On each such failed
// check `non-finite` is named (likely) and a likely cause whose model cannot make non-finite
// numbers from the probe's finite inputs (not in `can_be_non_finite`, the catalogue's "non_finite"
// entries) becomes a guess: it does not explain those numbers, so it earns no mistake's points.
void markNonFinite(const std::set<std::string>& non_finite_stubs,
                   const std::set<std::string>& can_be_non_finite, std::vector<TestResult>& tests);

// Splits each stub's points over its scored tests by weight and fills score / max_score; fills
// the report's totals. Per-mistake scoring: a stub each of whose failed checks names a proven
// mistake with a deduction (Cause::proven) totals max(per-check score, its points x (1 - the sum
// of those mistakes' deductions, at most 1)); the points given back go to its failed checks in
// proportion to what each lost, and the first failed check's rubric_note says so.
void applyRubric(const Rubric& rubric, GradeReport& report);

}  // namespace clothref::grader
