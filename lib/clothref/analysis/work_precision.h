// Work-precision sweeps: for each method, precision and dt, the position error against a
// reference, the wall time per simulated second, and the derivative evaluations
// (docs/methods.md states the schema and how to read the charts).
//
// Reference and norms. Positions are compared at sample times t_m = m * sample_interval
// (m = 1 .. horizon / sample_interval), every dt in the ladder dividing the interval exactly.
//   error_final  max over particles of |x_i(T) - x_ref_i(T)| at the horizon T (m)
//   error_rms    sqrt(mean over t_m of (max over particles of |x_i(t_m) - x_ref_i(t_m)|)^2) (m)
//   reference    the closed form (verify/analytic.h) for the spring scenes; for any other scene
//                a double RK4 run at dt = sample_interval / reference_substeps.
// Timing. Each point runs `repeats` times; the first run also measures the error. Time per
// simulated second, median, min and max over the runs, both as wall time (steady_clock) and as
// the thread's CPU time (CLOCK_THREAD_CPUTIME_ID), which time slices lost to other processes
// on a shared machine do not inflate.
// The peer. A point can also be stepped by Boost.Odeint's euler or runge_kutta4 from the library's
// evaluation (verify/odeint_peer.h): the same scene, reference and norms, `method` named
// "odeint-euler" or "odeint-rk4", its evaluations counted as the counterpart method's.
// Stability. A run that turns non-finite or exceeds 100 m or 100 m/s stops there: the point is
// unstable, timed once over the part simulated, and its errors are null. On the spring scenes a
// point is also unstable when clothref stability's criterion fires at its dt (the amplitude can
// grow a hundredfold without leaving the bounds); it keeps its errors.
#pragma once

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
#include "clothref/verify/odeint_peer.h"

namespace clothref {

struct SweepSettings {
  double horizon = 1;                        // T, s
  double sample_interval = 0.1;              // s
  std::vector<int> substeps;                 // dt = sample_interval / substeps[k], coarse to fine
  std::vector<int> backward_euler_substeps;  // the same for backward Euler (empty: substeps)
  int repeats = 5;
  int reference_substeps = 1000;  // non-spring scenes: the reference's dt divides the interval
};

// The settings the sweep uses for a scene: spring scenes T = 1 s, interval 0.1 s,
// dt = 0.1 .. ~1e-5 s; other scenes T = 1 s, interval 0.01 s, dt = 1e-2 .. 4e-5 s, backward
// Euler (stable everywhere, and the dearest step) 1e-2 .. 1e-4 s.
SweepSettings defaultSweepSettings(const Scene& scene);

struct SweepPoint {
  std::string scene;
  std::string method;
  Precision precision = Precision::Double;
  double dt = 0;                 // s
  std::int64_t steps = 0;        // steps to the horizon
  std::int64_t evaluations = 0;  // derivative evaluations to the horizon
  bool stable = true;
  std::optional<double> error_final;  // m
  std::optional<double> error_rms;    // m
  double seconds_median = 0;          // wall seconds per simulated second
  double seconds_min = 0;
  double seconds_max = 0;
  double cpu_seconds_median = 0;  // the thread's CPU seconds per simulated second
  double cpu_seconds_min = 0;
  double cpu_seconds_max = 0;
  int runs = 0;
  std::optional<double> cg_iterations;  // backward Euler: mean CG iterations per step
};

// Positions of every particle (cloth, then spheres) at the sample times: samples x 3N.
struct SweepReference {
  std::vector<Eigen::VectorXd> positions;
  std::string description;
};

// The reference of `scene` under `settings`.
SweepReference sweepReference(const Scene& scene, const SweepSettings& settings);

// One point.
SweepPoint sweepPoint(const Scene& scene, Method method, Precision precision, int substeps,
                      const SweepSettings& settings, const SweepReference& reference);

// One point stepped by the odeint peer (on spring scenes judged unstable by the stability
// criterion of its counterpart method, which makes the same step).
SweepPoint sweepPeerPoint(const Scene& scene, PeerStepper stepper, Precision precision,
                          int substeps, const SweepSettings& settings,
                          const SweepReference& reference);

struct SweepResult {
  std::vector<SweepPoint> points;
  std::vector<std::string> references;  // one description per scene
};

// Every scene x method x precision x dt, then every peer stepper likewise (on the ladder of its
// counterpart method); `progress` (may be empty) gets one line per point.
SweepResult sweep(const std::vector<Scene>& scenes, const std::vector<Method>& methods,
                  const std::vector<Precision>& precisions,
                  const std::function<SweepSettings(const Scene&)>& settings_for,
                  const std::function<void(const std::string&)>& progress,
                  const std::vector<PeerStepper>& peers = {});

// CSV, one header line then one line per point (columns as SweepPoint; empty for null).
std::string sweepToCsv(const SweepResult& result);

// {"format": "clothref-sweep", "version": 1, "machine", "compiler", "build_type", "norms",
//  "references", "points": [...]} (docs/methods.md).
nlohmann::ordered_json sweepToJson(const SweepResult& result);

}  // namespace clothref
