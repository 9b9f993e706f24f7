// An integrator explained by its stages (docs/grading-reference.md, "Integrators explained by their
// stages"). On a contact-free system the probe driver records every state a student's integrate()
// hands to simulateOneStep() and the state it returns; here each of them is written as an exact
// combination of the course's building blocks (x0, v0, the accelerations a_k of the evaluations so
// far, the velocities v_k of the evaluations, the step h), compared with the course's method
// (written as data, one table per method), and named in the course's terms and catalogue ids.
//
// Pure functions on plain data (no child process, no clothref types):
//   record.cpp   the record from the probe's answer (and the request's case)
//   fit.cpp      fitStages: the exact forms (least squares, then small rationals)
//   forms.cpp    rationals, forms, and forms in the course's terms
//   methods.cpp  the course's methods as tables, and the comparisons with them
//   causes.cpp   explainStages: the departure and the causes
//   text.cpp     stageText: the explanation as text
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "grader/grade/submission/source_patterns.h"

namespace probe {
struct ProbeMessage;
}

namespace clothref::grader::stages {

// ---- The record

// One body's state, 4 x n column-major (x, y, z, w per particle) as the course's matrices.
struct BodyState {
  std::vector<double> x, v;  // positions (m), velocities (m/s)
  std::vector<double> a;     // accelerations our simulateOneStep() produced there (m/s^2)
};
inline constexpr int kCloth = 0, kSpheres = 1;  // the bodies, in the course's particles vector
inline constexpr int kMaxRecordedCalls = 16;    // evaluations recorded per step
// The recorded step (s): one step of every method is well inside its stability on the probe's
// cloth (k_s = 500, |lambda| h < 1), the stages lie apart by h·a ~ 0.3 m/s, and h is no round
// number, so that B + S·h (a mix-up plus a natural term) never equals another such pair exactly.
inline constexpr float kStageStep = 0.0113f;

struct StageRecord {
  double h = 0;        // deltaTime during the step (s), the float the student read
  double h_after = 0;  // deltaTime after integrate() (s)
  int calls = 0;       // simulateOneStep() calls integrate() made (only the first 16 are recorded)
  std::array<BodyState, 2> start;                     // x0, v0, and a0 from the simulate() before
  std::vector<std::array<BodyState, 2>> evaluations;  // call k (1-based = index + 1): state and a
  std::array<BodyState, 2> result;                    // x, v after integrate() (a unused)
};

// The record of case k of an integrator probe's answer (stage keys, bridge/probe_keys.h), for a
// step of h; false when the answer has none or its sizes disagree.
bool stageRecordFrom(const probe::ProbeMessage& answer, int k, double h, StageRecord& record);

// ---- Exact forms

struct Rational {
  std::int64_t num = 0, den = 1;  // den > 0, lowest terms
  Rational() = default;
  Rational(std::int64_t n, std::int64_t d = 1);
  double value() const { return double(num) / double(den); }
  bool zero() const { return num == 0; }
};
Rational operator+(Rational a, Rational b);
Rational operator-(Rational a, Rational b);
Rational operator*(Rational a, Rational b);
Rational operator/(Rational a, Rational b);
bool operator==(Rational a, Rational b);
inline bool operator!=(Rational a, Rational b) { return !(a == b); }
std::string text(Rational r);  // "1/6", "-2", "0"

// A generator of every recorded quantity: x0, v0, or the acceleration a_k of evaluation k (a_0 =
// the start's a0). Evaluations at a state met before share its generator (same state, same a).
inline constexpr int kGenX0 = 0, kGenV0 = 1;
inline int genA(int k) { return 2 + k; }

// coef * h^power * generator
struct Term {
  int gen = 0;
  int power = 0;
  Rational coef;
};
// A sum of terms, sorted by (gen, power), no zero coefficient: equal forms are equal vectors.
using Form = std::vector<Term>;
Form add(const Form& a, const Form& b);
Form scaled(const Form& a, Rational c, int extra_power = 0);
bool operator==(const Term& a, const Term& b);
// The acceleration a velocity form introduces: its highest generator, with that generator's
// coefficient d at power 1 (v = ... + d·h·a_k); false when it has none.
bool introduces(const Form& velocity, int& gen, Rational& d);

// The same quantity in the course's terms: a base (x0 or v0, or the state of an earlier
// evaluation) plus coef * h^power * block, block the velocity 'v' or acceleration 'a' of state
// `index` (0 = start, k = evaluation k, recorded + 1 = the result: v_new); 'x' only for x0.
struct CourseTerm {
  Rational coef;
  int power = 1;
  char block = 'v';
  int index = 0;
};
struct CourseForm {
  char base = 'x';     // 'x' (a position) or 'v' (a velocity)
  int base_index = 0;  // 0: x0 / v0; k: the state of evaluation k
  std::vector<CourseTerm> terms;
};

// ---- The fit

// One fitted quantity (a position or a velocity of one body at one state).
struct Fitted {
  bool fits = false;    // an exact combination of the building blocks, to rounding
  Form form;            // the combination (empty when it does not fit)
  CourseForm course;    // in the course's terms (the simpler of base x0/v0 and the previous state)
  double residual = 0;  // worst |recorded - combination| / tolerance (fits: <= 1)
  double least_squares = 0;  // the same for the unrounded least-squares coefficients
};

enum class SpheresAre {
  Same,     // at the cloth's stage (the cloth's form, applied to the spheres' own blocks)
  AtStart,  // at their start state while the cloth is not
  Own,      // at a stage of their own (sphere_x, sphere_v)
  NoFit     // no combination of their building blocks
};

// One evaluation (the state handed to a simulateOneStep() call) or the result.
struct StageState {
  Fitted x, v;       // the cloth
  int same_as = -1;  // the cloth's state is, bit for bit, that of evaluation same_as (0 = start)
  SpheresAre spheres = SpheresAre::Same;
  Fitted sphere_x, sphere_v;  // the spheres' own fit (spheres == Own)
};

struct StageFit {
  StageRecord record;
  int recorded = 0;                // evaluations recorded (<= calls)
  std::vector<StageState> states;  // evaluation 1 .. recorded, then the result (last)
  std::vector<int> canonical;      // a_k's generator: canonical[k] (k = 0 .. recorded)
  const StageState& result() const { return states.back(); }
};

// The tolerance of "exact to rounding": a recorded value is the combination to within
// kUlps * 2^-24 * (|value| + sum of |each term|) (float arithmetic of a few operations per
// component, in any order; docs/grading-reference.md).
inline constexpr double kUlps = 32;
inline constexpr double kUnit = 1.0 / 16777216.0;  // 2^-24, float's unit roundoff
inline constexpr int kMaxDenominator = 12;         // rationals of the course's terms: 1/2, 1/6, ...

StageFit fitStages(const StageRecord& record);

// A number in a stage text: six significant digits (%.6g).
std::string sixDigits(double value);

// The recorded state `index` of `body` (0 = start, k = evaluation k, recorded + 1 = result).
const BodyState& recordedState(const StageRecord& record, int index, int body);

// Numbers of the fit, for the methods' comparison: the recorded column of (body, generator).
const std::vector<double>& column(const StageFit& fit, int body, int gen);
// A form applied to `body`'s own blocks, and its worst residual against `recorded` / tolerance.
double formResidual(const StageFit& fit, int body, const Form& form,
                    const std::vector<double>& recorded);

// A course-terms form as an exact form, with the student's own fitted velocities for v_k. False
// when a block it names has no exact form (a velocity that does not fit, an evaluation not made).
bool toForm(const StageFit& fit, const CourseForm& course, Form& out);
// An exact form of state `state_index` in the course's terms: on base x0/v0, or on the state of
// evaluation `base_index` (> 0) when that needs fewer terms; a position may use its own velocity.
CourseForm toCourse(const StageFit& fit, const Form& form, char base, int base_index,
                    int state_index);
// The same for `body` (the spheres' velocities are theirs).
CourseForm toCourseOf(const StageFit& fit, const Form& form, char base, int base_index,
                      int state_index, int body);

// ---- The explanation

struct StageCause {
  std::string id;       // catalogue id (tools/grader/diagnoses.json)
  bool likely = false;  // the fit confirms it; otherwise a possible cause
  std::string why;      // in the course's terms
};

// Where the stub first leaves the course's method.
struct Departure {
  int state = 0;     // 1.. evaluation, calls + 1 the result; 0: none
  std::string what;  // "position", "velocity", "spheres", "calls"
  std::string yours, course;
};

struct StageExplanation {
  int method = 0;  // 0 explicit, 1 implicit, 2 midpoint, 3 RK4 (the stub)
  int calls = 0, course_calls = 0;
  bool fits = false;     // every cloth state is an exact combination
  bool course = false;   // the course's method, stage by stage
  std::string accepted;  // the accepted variant's rubric switch it equals, or ""
  std::string equals;    // the known method the whole stub equals (table id), or ""
  std::string equals_name;
  double scale = 1;    // a consistent factor on h (deltaTime changed), 1 = none
  double damping = 1;  // the result's velocity times this factor (v *= c), 1 = none
  Departure departure;
  std::vector<StageCause> causes;
};

StageExplanation explainStages(const StageFit& fit, int method, const SourceHints& hints);

// ---- Text

std::string text(const CourseForm& form, int calls);  // "x0 + h/2·v1"
std::string stateName(int state, int calls);          // "evaluation 2", "the result"
std::string stageText(const StageFit& fit, const StageExplanation& explanation);
// The fit and the explanation as JSON (states in the course's terms, departure, causes, text).
std::string stageJson(const StageFit& fit, const StageExplanation& explanation);

}  // namespace clothref::grader::stages
