// verify's conservation family: a free cloth keeps its momentum under every method.
#include "clothref/verify/verify.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <complex>
#include <functional>
#include <limits>
#include <random>

#include "clothref/core/world.h"
#include "clothref/scene/make_world.h"
#include "clothref/solver/backward_euler.h"
#include "clothref/verify/analytic.h"
#include "clothref/verify/check_support.h"

namespace clothref {

using namespace verify_support;

namespace {

constexpr int kFreeClothSteps = 500;

// A uniform double in [lo, hi) from the top 53 bits of one draw: portable, unlike
// std::uniform_real_distribution.
double uniform(std::mt19937_64& random, double lo, double hi) {
  return lo + (hi - lo) * double(random() >> 11) * 0x1.0p-53;
}

// Free 9 x 9 course cloth, no fixed particles, gravity or drag; velocities uniform in [-1, 1].
template <typename T>
World<T> freeClothWorld(Method method) {
  Scene scene = impactBaseScene("free-cloth");
  scene.dt = 1e-4;
  ClothSpec cloth;
  cloth.grid = GridSpec{9, 1, 0, 1};
  cloth.spring_coef = 25000;
  cloth.damper_coef = 750;
  scene.cloth = cloth;
  World<T> world = makeWorld<T>(scene, method);
  std::mt19937_64 random(20240521);
  Mat4X<T>& v = world.cloth->particles.velocity;
  for (int i = 0; i < v.cols(); ++i)
    for (int k = 0; k < 3; ++k) v(k, i) = T(uniform(random, -1, 1));
  return world;
}

// Relative momentum drift over kFreeClothSteps, and its round-off estimate: per step, per
// derivative evaluation and per particle the velocity rounds by ~u |v|, and its acceleration
// (a sum of at most 12 spring forces) by ~12 u |a|, moving v by 12 u |a| dt; relative to
// sum m |v| at the start (unit masses).
template <typename T>
CheckRow freeClothRow(Method method, Precision precision) {
  World<T> world = freeClothWorld<T>(method);
  const Particles<T>& p = world.cloth->particles;
  const std::array<double, 3> start = momentum(world);
  double scale = 0;
  for (int i = 0; i < p.size(); ++i) scale += double(p.mass[i]) * xyz(p.velocity.col(i)).norm();
  double drift = 0;
  double v_max = 0;
  double a_max = 0;
  // backward Euler's CG stops at |r| <= tol |b|; the internal forces cancel in sum(b), so each
  // solve moves the momentum by sum(r) per axis, at most sqrt(N) tol |b|
  double solver_drift = 0;
  for (int k = 0; k < kFreeClothSteps; ++k) {
    step(world);
    if (const BackwardEulerSolver<T>* solver = backwardEulerSolver(world))
      solver_drift += std::sqrt(double(p.size())) * cgTolerance<T>(solver->settings) *
                      double(solver->rhs.norm());
    const std::array<double, 3> now = momentum(world);
    drift = std::max(
        drift, Eigen::Vector3d(now[0] - start[0], now[1] - start[1], now[2] - start[2]).norm());
    v_max = std::max(v_max, double(p.velocity.cwiseAbs().maxCoeff()));
    a_max = std::max(a_max, double(p.acceleration.cwiseAbs().maxCoeff()));
  }
  const double roundings = double(kFreeClothSteps) * methodInfo(method).evaluations * p.size();
  const double bound =
      (roundoffEstimate(roundings, precision, v_max + 12 * a_max * double(world.physics.dt)) +
       solver_drift) /
      scale;
  return makeRow(fmt::format("free 9x9 cloth: momentum drift / sum m|v|, {} steps of {:g} s{}",
                             kFreeClothSteps, double(world.physics.dt),
                             isFinite(world) ? "" : " (NOT FINITE)"),
                 std::string(methodName(method)), precision, 0,
                 isFinite(world) ? drift / scale : std::numeric_limits<double>::quiet_NaN(), bound);
}

}  // namespace

std::vector<CheckRow> freeClothMomentumChecks() {
  std::vector<CheckRow> rows;
  for (Precision precision : kPrecisions)
    for (Method method : kAllMethods)
      rows.push_back(withPrecision(
          precision, [&]<typename T>() { return freeClothRow<T>(method, precision); }));
  return rows;
}

}  // namespace clothref
