// verify's convergence orders: dt ladders on `spring`, the fitted order of every method against
// its table order, and the float floor.
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

double fitOrder(std::span<const double> dts, std::span<const double> errors) {
  const std::size_t n = dts.size();
  double mean_x = 0;
  double mean_y = 0;
  for (std::size_t i = 0; i < n; ++i) {
    mean_x += std::log(dts[i]);
    mean_y += std::log(errors[i]);
  }
  mean_x /= double(n);
  mean_y /= double(n);
  double sxy = 0;
  double sxx = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double dx = std::log(dts[i]) - mean_x;
    sxy += dx * (std::log(errors[i]) - mean_y);
    sxx += dx * dx;
  }
  return sxy / sxx;
}

namespace {

// Coarsest dt of a method's ladder on `spring` (omega = 10 rad/s): omega dt = 0.1, inside every
// method's asymptotic range (explicit Euler is only stable below dt = 2 zeta / omega = 0.02 s);
// RK4 starts at omega dt = 0.4 so its finest error stays far above double round-off.
double ladderStart(Method method) { return method == Method::Rk4 ? 4e-2 : 1e-2; }

constexpr int kHalvings = 5;
constexpr double kFloorFactor = 10;  // a float point is fitted when error >= 10 x round-off

}  // namespace

std::vector<ConvergenceStudy> convergenceStudies() {
  const Scene& scene = *findBuiltinScene("spring");
  const ExactMotion exact = exactMotion(scene);
  std::vector<ConvergenceStudy> studies;
  for (Precision precision : kPrecisions) {
    for (Method method : kAllMethods) {
      ConvergenceStudy study;
      study.method = method;
      study.precision = precision;
      study.expected_order = methodInfo(method).order;
      study.end_time = kHorizon;
      for (int k = 0; k <= kHalvings; ++k) {
        const double dt = ladderStart(method) / double(1 << k);
        const int steps = int(std::lround(kHorizon / dt));
        const Trajectory run =
            simulateParticle(precision, scene, method, dt, steps, exact.particle);
        study.dts.push_back(run.dt);
        study.errors.push_back(maxError(run, exact));
        bool above_floor = true;
        if (precision == Precision::Float) {
          // the same run in double at the float run's exact dt isolates the round-off
          const Trajectory reference =
              simulateParticle(Precision::Double, scene, method, run.dt, steps, exact.particle);
          double roundoff = 0;
          for (std::size_t i = 0; i < run.position.size(); ++i)
            roundoff = std::max(roundoff, (run.position[i] - reference.position[i]).norm());
          study.roundoff.push_back(roundoff);
          above_floor = study.errors.back() >= kFloorFactor * roundoff;
        }
        study.fitted.push_back(above_floor);
      }
      std::vector<double> dts;
      std::vector<double> errors;
      for (std::size_t i = 0; i < study.dts.size(); ++i) {
        if (!study.fitted[i]) continue;
        dts.push_back(study.dts[i]);
        errors.push_back(study.errors[i]);
      }
      if (dts.size() >= 3) study.order = fitOrder(dts, errors);
      studies.push_back(std::move(study));
    }
  }
  return studies;
}

std::vector<CheckRow> convergenceChecks(const std::vector<ConvergenceStudy>& studies) {
  std::vector<CheckRow> rows;
  const Scene& scene = *findBuiltinScene("spring");
  const ExactMotion exact = exactMotion(scene);
  for (const ConvergenceStudy& study : studies) {
    const std::string method(methodName(study.method));
    const int fitted = int(std::count(study.fitted.begin(), study.fitted.end(), true));
    if (study.order) {
      rows.push_back(
          makeRow(fmt::format("spring: order, least squares over {} dt {:g}..{:g} s, {:g} s",
                              fitted, study.dts.front(), study.dts.back(), study.end_time),
                  method, study.precision, study.expected_order, *study.order, 0.2));
    }
    if (study.precision != Precision::Float) continue;
    // the float floor: round-off error at the finest dt against its worst-case bound
    const int steps = int(std::lround(study.end_time / study.dts.back()));
    rows.push_back(
        makeRow(fmt::format("spring: float floor |x_float - x_double| (m), dt {:g} s{}",
                            study.dts.back(), study.order ? "" : " (order: < 3 dt above floor)"),
                method, study.precision, 0, study.roundoff.back(),
                roundoffBound(exact, study.precision, study.dts.back(), steps)));
  }
  return rows;
}

}  // namespace clothref
