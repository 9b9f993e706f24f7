// What the verify check families share: the precisions they run, round-off sizes, and a particle's
// simulated trajectory beside the closed form it is checked against (closed forms and orders).
// Internal to lib/clothref/verify.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "clothref/base/precision.h"
#include "clothref/core/method.h"
#include "clothref/scene/scene.h"
#include "clothref/verify/analytic.h"

namespace clothref::verify_support {

inline constexpr Precision kPrecisions[] = {Precision::Double, Precision::Float};

inline constexpr double kHorizon = 1.0;  // seconds, for the closed-form and convergence checks

// Unit round-off u of a precision: 2^-24 for float, 2^-53 for double.
double unitRoundoff(Precision precision);

template <typename Column>
Eigen::Vector3d xyz(const Column& column) {
  return Eigen::Vector3d(double(column[0]), double(column[1]), double(column[2]));
}

// Position and velocity of one cloth particle at steps 0..n.
struct Trajectory {
  double dt = 0;  // the step the world actually took, in its precision
  std::vector<Eigen::Vector3d> position;
  std::vector<Eigen::Vector3d> velocity;
};

// The trajectory of cloth particle `particle` over `steps` steps of `dt` in `precision`.
Trajectory simulateParticle(Precision precision, const Scene& scene, Method method, double dt,
                            int steps, int particle);

// The exact motion of the one moving particle of a spring or free-fall scene.
//   state(t)         closed form
//   derivative(t, k) |x^(k)(t)| (k >= 2), by the ODE's recursion applied to the exact state
struct ExactMotion {
  int particle = 0;
  std::function<PointState(double)> state;
  std::function<double(double, int)> derivative;
};

ExactMotion exactMotion(const Scene& scene);

// max over steps of |x_k - x_exact(k dt)|.
double maxError(const Trajectory& trajectory, const ExactMotion& exact);

// Leading global error of an order-p method over [0, T]: T h^p max|x^(p+1)| / (p+1)!, doubled
// for the next-order terms and the growth or decay of the error inside the horizon.
double truncationBound(const ExactMotion& exact, int order, double dt, int steps);

// Round-off of `roundings` roundings of relative size u on quantities of size `scale`, modelled
// as a random walk, 8 sqrt(roundings) u scale (docs/verification.md).
double roundoffEstimate(double roundings, Precision precision, double scale);

// Round-off of a particle trajectory: each step rounds the position update (~u|x|) and the
// velocity update (~u|v|, which moves x by ~u|v|T by the end).
double roundoffBound(const ExactMotion& exact, Precision precision, double dt, int steps);

// A scene named `name` with dt 1e-3 s and no gravity or drag: the base of the impact and
// free-cloth scenes.
Scene impactBaseScene(const std::string& name);

}  // namespace clothref::verify_support
