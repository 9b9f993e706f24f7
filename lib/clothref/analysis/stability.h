// Stability limits: the largest stable dt of each method on a scene, predicted from the
// amplification of one step on the scene's linearised modes, and measured by bisection.
//
// Theory. A linear mode  u'' + delta u' + kappa u = 0  (kappa = omega^2 in 1/s^2, delta in 1/s)
// has the eigenvalues lambda = (-delta +- sqrt(delta^2 - 4 kappa)) / 2. A one-step method maps
// each to R(h lambda): explicit 1 + mu, the course's implicit (one predictor-corrector pass)
// 1 + mu + mu^2, midpoint 1 + mu + mu^2 / 2, RK4 the degree-4 Taylor polynomial, backward Euler
// 1 / (1 - mu). Symplectic Euler is not a function of mu alone: its 2x2 step matrix
// [[1 - h^2 kappa, h (1 - h delta)], [-h kappa, 1 - h delta]] is used. The mode's limit is the
// first h where the spectral radius exceeds 1; the scene's is the smallest over its modes.
//   spring scenes  one mode, kappa = k / m, delta = c / m (verify/analytic.h's SpringProblem)
//   cloth scenes   the modes of the cloth linearised at rest: the eigenvalues kappa_i of the
//                  mass-scaled stiffness M^-1/2 K M^-1/2 (free particles, Eigen's
//                  SelfAdjointEigenSolver); every spring has the same k_d / k_s, so the damping
//                  is proportional and delta_i = (k_d / k_s) kappa_i + c / m exactly (equal
//                  masses; the course's are). omega_max = sqrt(max kappa_i).
//
// Measurement. A run at dt is unstable when its criterion fires (stabilityCriterion below); the
// limit is found by bisection on log(dt) inside [dt_low, dt_high] until hi / lo - 1 <= resolution;
// the reported limit is the largest dt found stable.
#pragma once

#include <complex>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "clothref/base/precision.h"
#include "clothref/core/types.h"
#include "clothref/scene/make_world.h"
#include "clothref/scene/scene.h"
#include "clothref/solver/backward_euler.h"

namespace clothref {

// One linear mode: kappa (1/s^2), delta (1/s).
struct Mode {
  double kappa = 0;
  double delta = 0;
};

// Spectral radius of one step of `method` at step h (s) on `mode`.
double stepSpectralRadius(Method method, const Mode& mode, double h);

// Why a theoretical limit is what it is.
enum class TheoryKind {
  Limit,         // a finite limit
  NeverStable,   // the radius exceeds 1 at every h > 0 (e.g. explicit Euler, undamped)
  AlwaysStable,  // never exceeds 1 (backward Euler)
};

struct TheoryLimit {
  TheoryKind kind = TheoryKind::Limit;
  double dt = 0;  // seconds, for Limit
};

// The largest h (s) for which the radius stays <= 1 on every mode (relative accuracy 1e-10).
TheoryLimit theoryLimit(Method method, const std::vector<Mode>& modes);

// The linear modes of a scene: the spring scenes' one mode, or the cloth's modes at rest.
// Throws InputError for a scene that is neither.
std::vector<Mode> sceneModes(const Scene& scene);

// The criterion a measured run is judged by, stated in words in `text`.
struct StabilityCriterion {
  enum class Kind { Oscillator, Cloth } kind = Kind::Cloth;
  int steps = 0;               // Oscillator: steps per run
  double growth = 0;           // Oscillator: allowed growth of the amplitude (relative)
  double initial_scale = 1;    // Oscillator: factor on the initial displacement and velocity
  double amplitude_bound = 0;  // Oscillator: largest amplitude allowed, in initial amplitudes
  double horizon = 0;          // Cloth: simulated seconds per run
  int min_steps = 0;           // Cloth: at least this many steps per run
  double speed_bound = 0;      // Cloth: m/s
  double position_bound = 0;   // Cloth: m
  std::string text;
};

// The criterion used for a scene: Oscillator for the spring scenes, Cloth otherwise.
StabilityCriterion stabilityCriterion(const Scene& scene);

// True when a run of `scene` with `method` at `dt` stays stable by `criterion`.
// With `cg`, a backward-Euler run's CG statistics are written there.
bool runIsStable(const Scene& scene, Method method, Precision precision, double dt,
                 const StabilityCriterion& criterion, CgStats* cg = nullptr);

struct SearchRange {
  double low = 0;         // s
  double high = 0;        // s
  double resolution = 0;  // relative
};

// The range searched on a scene: [1e-2, 1] s at 1e-3 for the spring scenes, [3e-5, 2e-2] s at
// 1e-2 for the others.
SearchRange searchRange(const Scene& scene);

enum class MeasuredKind {
  Limit,          // the bisection's result
  UnstableAtLow,  // unstable already at range.low
  StableAtHigh,   // stable at range.high: the limit is above the range
};

struct MeasuredLimit {
  MeasuredKind kind = MeasuredKind::Limit;
  double dt = 0;  // s: the largest dt found stable (Limit), or range.high (StableAtHigh)
  int runs = 0;
  std::optional<double> cg_iterations;  // backward Euler: mean CG iterations per step at dt
  int cg_max_iterations = 0;
};

MeasuredLimit measureLimit(const Scene& scene, Method method, Precision precision,
                           const StabilityCriterion& criterion, const SearchRange& range);

struct StabilityResult {
  std::string scene;
  std::string method;
  Precision precision = Precision::Double;
  MeasuredLimit measured;
  TheoryLimit theory;
  std::optional<double> omega_max;  // rad/s, cloth scenes
  std::string criterion;
  SearchRange range;
  double seconds = 0;  // wall time of the measurement
};

// Every (scene, method, precision) asked for. `progress` (may be empty) gets one line per result.
// `high`, when given, replaces the search range's upper end (s) for every scene.
std::vector<StabilityResult> stabilityStudy(const std::vector<Scene>& scenes,
                                            const std::vector<Method>& methods,
                                            const std::vector<Precision>& precisions,
                                            const std::function<void(const std::string&)>& progress,
                                            std::optional<double> high = std::nullopt);

// {"results": [{"scene", "method", "precision", "dt_max_measured", "dt_max_theory",
//   "criterion", "ratio", "measured_note", "theory_note", "omega_max", "resolution",
//   "search_low", "search_high", "runs", "seconds"}, ...]}; limits are null where there is none.
nlohmann::ordered_json stabilityToJson(const std::vector<StabilityResult>& results);

// The same as a fixed-width table.
std::string stabilityTable(const std::vector<StabilityResult>& results);

}  // namespace clothref
