// Analytic checks: the simulation (the eight stubs, run through World::step) measured against
// closed forms (analytic.h) and conservation laws, in float and double. `clothref verify` runs
// them all; docs/verification.md states every bound and why.
//
// Each check returns rows {check, method, precision, expected, observed, tolerance, pass}:
//   Within  passes when |observed - expected| <= tolerance
//   AtMost  passes when observed <= expected + tolerance (one-sided, e.g. "no energy gain")
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "clothref/base/precision.h"
#include "clothref/core/integrator.h"

namespace clothref {

enum class CheckRule { Within, AtMost };

struct CheckRow {
  std::string check;   // what is measured, with its case and units
  std::string method;  // integrator name, or "-" when the check does not depend on one
  Precision precision = Precision::Double;
  double expected = 0;
  double observed = 0;
  double tolerance = 0;
  CheckRule rule = CheckRule::Within;
  bool pass = false;
};

// Builds a row and decides `pass` by its rule (a NaN observation fails).
CheckRow makeRow(std::string check, std::string method, Precision precision, double expected,
                 double observed, double tolerance, CheckRule rule = CheckRule::Within);

// Least-squares slope of log(error) against log(dt): the observed convergence order.
// dts and errors have the same length >= 2, all > 0.
double fitOrder(std::span<const double> dts, std::span<const double> errors);

// One convergence study on the `spring` scene to a fixed end time: the error of one method at a
// ladder of dt halvings. For float, `roundoff` holds |x_float - x_double| at the same dt (the
// float floor); a point enters the fit only when its error is >= 10x its round-off.
struct ConvergenceStudy {
  Method method = Method::Explicit;
  Precision precision = Precision::Double;
  int expected_order = 1;
  double end_time = 0;           // seconds
  std::vector<double> dts;       // seconds, coarse to fine
  std::vector<double> errors;    // max over steps of |x - x_exact| (m)
  std::vector<double> roundoff;  // float only: max over steps of |x_float - x_double| (m)
  std::vector<bool> fitted;      // the points used in the fit
  std::optional<double> order;   // null when fewer than 3 points lie above the float floor
};

// Every method in double and float.
std::vector<ConvergenceStudy> convergenceStudies();

// Rows for the studies: |order - expected| <= 0.2 (double, and float where measurable), and the
// float floor (largest round-off error seen in the float ladder).
std::vector<CheckRow> convergenceChecks(const std::vector<ConvergenceStudy>& studies);

// Error against the closed form at the scenes' dt (1e-3 s) over 1 s, every method, on spring,
// spring-undamped and free-fall, float and double.
std::vector<CheckRow> closedFormChecks();

// Oblique two-sphere impacts through World::step (explicit Euler), e in {0, .25, .5, .8, 1} and
// mass ratios {1, 10, 100}: momentum, restitution, tangential velocity, energy, closed form.
std::vector<CheckRow> sphereSphereChecks();

// The same for a sphere and one free cloth particle, plus a fixed particle (mass 0) that must
// act as immovable in the impulse.
std::vector<CheckRow> sphereClothChecks();

// Where one evaluation's contacts put the bodies (simulateOneStep on a world of two bodies): a
// cloth particle pressed into a sphere (the fast kernel and the course-form stub) and an
// overlapping sphere pair, approaching and separating, restitution 0 and not, and a fixed
// particle, against the course's equations in double (analytic.h contactOutcome): positions
// after the correction, velocities after the impulse, and a separating pair's velocities exactly
// unchanged.
std::vector<CheckRow> contactChecks();

// A free 9x9 cloth (no fixed particles, gravity or drag, random velocities) keeps its total
// momentum under every method: the spring forces sum to zero.
std::vector<CheckRow> freeClothMomentumChecks();

// Energy on spring-undamped at dt = 0.02 s (omega dt = 0.2), every method, float and double:
// explicit, implicit, midpoint and RK4 multiply the energy by exactly |R(i omega dt)|^2 per step
// (R the method's amplification factor: explicit grows, implicit decays, midpoint grows slowly,
// RK4 decays slowly), checked after 50 steps; symplectic Euler stays within its bound
// |E/E0 - 1| <= (omega dt / 2) / (1 - omega dt / 2) over 1000 steps.
std::vector<CheckRow> energyChecks();

// The course scenes against the course's facts (2022 and 2024 defaults): every parameter, and the
// float worlds they build (625 particles, fixed corners, 1200 / 1152 / 1150 springs with the
// course's rest-length bits, sphere mass 1000 r^3), the spheres' force after one evaluation (2022
// gravity and drag, 2024 none) and fixed corners that do not move. Exact rows (tolerance 0).
std::vector<CheckRow> courseFactChecks();

// The fast kernels (clothref/fast) against the course-form loops, the course's stubs as written
// (setExecution with use_fast = false): course2022 (springs) and course2024 (the cloth on the
// sphere from the first step: contacts) with every method, kCourseFormSteps steps in float.
// Exact rows: the largest |difference| of any position or velocity must be 0. This is what makes
// verify see a bug in the course-form stubs, which the fast paths otherwise shadow.
inline constexpr int kCourseFormSteps = 300;
std::vector<CheckRow> courseFormChecks();

// The library's explicit, RK4 and symplectic Euler against Boost.Odeint's euler, runge_kutta4 and
// symplectic_euler stepping the same world from the library's evaluation (odeint_peer.h), step by
// step over kPeerSteps steps: the course cloth without spheres (double and float; the peer in
// double) and the course cloth on a fixed sphere (euler and rk4, double). Rows: the largest
// position difference over every step and particle, against a round-off estimate.
inline constexpr int kPeerSteps = 1000;
std::vector<CheckRow> peerChecks();

struct VerifyReport {
  std::vector<ConvergenceStudy> studies;
  std::vector<CheckRow> checks;

  bool passed() const;
};

// Runs everything above.
VerifyReport runVerification();

// {"orders": {"<method>": {"double": p, "float": p or null}}, "float_floor": {...},
//  "studies": [...], "checks": [...], "passed": bool}
nlohmann::ordered_json reportToJson(const VerifyReport& report);

// The checks as a fixed-width text table, one row per check, then a summary line.
std::string reportTable(const VerifyReport& report);

}  // namespace clothref
