// The methods a stage fit is compared with, as data (docs/grading-reference.md, "The four
// integrators" and "Accepted variants"), and the comparisons: stage by stage, and whole stub (known
// method).
#pragma once
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "grader/grade/explain/stages/stages.h"

namespace clothref::grader::stages {

// One term of a method's stage: num/den · h · (v or a) of state `index` of that method (0 = the
// start, k = its evaluation k), or of the stage's own velocity (kOwn: v_new in a result).
inline constexpr int kOwn = -1;
struct MethodTerm {
  int num, den;
  char block;  // 'v' (in a position) or 'a' (in a velocity)
  int index;
};
// A state of a method: x = x0 + sum of x terms, v = v0 + sum of v terms.
struct MethodState {
  std::vector<MethodTerm> x, v;
};
struct MethodTable {
  std::string id;
  std::string name;      // "forward Euler (the course's explicit Euler)"
  int stub = -1;         // the course stub (0..3) whose method or accepted variant it is; -1 none
  bool course = false;   // the course's own method of `stub`
  std::string accepted;  // the rubric switch of an accepted variant of `stub`, or ""
  std::vector<MethodState> evaluations;
  MethodState result;
};
// Every table: the four course methods, their accepted variants, then other known methods.
const std::vector<MethodTable>& methodTables();
const MethodTable& courseTable(int method);

// A method's state in the course's terms, with its indices mapped to the student's states
// (`map[k]` = the student's state of the method's state k) and its coefficients times `scale`.
CourseForm methodForm(const MethodState& state, bool position, const std::vector<int>& map, int own,
                      Rational scale = Rational(1));

// Whether the student's state `q` (1.. evaluations, recorded + 1 the result) equals the method's
// state in position and velocity (exactly, on the cloth).
bool sameState(const StageFit& fit, int q, const MethodState& state, const std::vector<int>& map,
               Rational scale = Rational(1));

// Two step factors agree within this relative difference: a factor fitted from float stages is
// good to about 1e-5 (rounding of positions ~1 over increments ~h·v ~ 1e-2).
inline constexpr double kStepAgreement = 1e-4;
inline bool sameStep(double a, double b) { return std::abs(a - b) <= kStepAgreement * std::abs(b); }

// The factor s for which the student's position (or velocity) of state q of `body` equals the
// method's state with h replaced by s·h, to rounding; 0 when there is none.
double stepFactor(const StageFit& fit, int body, int q, const MethodState& state, bool position,
                  const std::vector<int>& map);

// The first state where the student leaves `table` stage by stage (identity map), where a
// position or velocity may also match at h·`factor` (0: only at h). state 0: none.
Departure departure(const StageFit& fit, const MethodTable& table, double factor = 0);

// Whether the whole stub equals `table`: its evaluations are met, in order, among the student's
// (others unused), and the result equals the method's result.
bool equalsMethod(const StageFit& fit, const MethodTable& table);

// The course's RK4 result weights on k1..k4 (units of h), and whether `w` is they, each within
// `tolerance`.
inline constexpr std::array<double, 4> kRk4Weights = {1.0 / 6, 1.0 / 3, 1.0 / 3, 1.0 / 6};
bool areRk4Weights(const std::array<double, 4>& w, double tolerance = 1e-9);

// RK4 result weights w on k1..k4 (units of h) that are the course's (1/6, 1/3, 1/3, 1/6) with
// some k read from another stage: from[i] is the stage whose k stands where k(i+1) belongs, e.g.
// (0, 1/3, 1/3, 1/3) is k1 read after stage 4 overwrote the state (from = 3, 1, 2, 3). The map
// with the most k in place; none when w is the course's itself or no map gives it (each weight
// within `tolerance`: exact for the stage fit's rationals, 1e-3 for a least-squares fit).
std::optional<std::array<int, 4>> courseWeightsOnOtherStages(const std::array<double, 4>& w,
                                                             double tolerance = 1e-9);
// "k4 where k1 belongs" for such a map.
std::string otherStagesText(const std::array<int, 4>& from);

}  // namespace clothref::grader::stages
