// verify's stability family: energy on spring-undamped grows or decays by exactly |R(i theta)|^2
// per step, R the method table's amplification factor; symplectic Euler stays bounded.
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

// Energy on `spring-undamped` (k = 100 N/m, m = 1 kg, omega = 10 rad/s) at dt = 0.02 s, so
// theta = omega dt = 0.2. The particle stays on the +x side of the anchor, so the motion is the
// linear oscillator u'' = -omega^2 u (u = length - rest) and in (u, v / omega) every course
// method's step is a rotation scaled by |R(i theta)|, R its amplification factor: the energy
// E = 1/2 m v^2 + 1/2 k u^2 is multiplied by exactly |R(i theta)|^2 per step.
constexpr double kEnergyDt = 0.02;  // seconds
constexpr int kEnergySteps = 50;    // 1 s: explicit Euler's amplitude stays below the rest length
constexpr int kSymplecticSteps = 1000;  // 20 s, ~32 periods: bounded, not just slow to grow

// |R(i theta)|^2 of the method's amplification factor on y' = lambda y (the method table's
// R = P / Q), at lambda dt = i theta, as |P|^2 / |Q|^2 (no complex division, so backward Euler's
// 1 / (1 + theta^2) is exact). On a linear spring backward Euler's linearised step is backward
// Euler itself, so its table R applies too. Symplectic Euler is not a scaled rotation: see
// energyChecks.
double amplificationSquared(Method method, double theta) {
  const Amplification& r = methodInfo(method).amplification;
  const std::complex<double> z(0, theta);
  return std::norm(evaluatePolynomial(r.p, z)) / std::norm(evaluatePolynomial(r.q, z));
}

// E_k / E_0 for k = 0..steps on spring-undamped.
template <typename T>
std::vector<double> energyRatios(Method method, int steps) {
  const Scene& scene = *findBuiltinScene("spring-undamped");
  World<T> world = makeWorld<T>(scene, method, kEnergyDt);
  const double k = scene.cloth->spring_coef;
  const double rest = scene.cloth->springs[0].rest_length;
  const Particles<T>& p = world.cloth->particles;
  auto energy = [&] {
    const double stretch = (xyz(p.position.col(1)) - xyz(p.position.col(0))).norm() - rest;
    return 0.5 * double(p.mass[1]) * xyz(p.velocity.col(1)).squaredNorm() +
           0.5 * k * stretch * stretch;
  };
  const double start = energy();
  std::vector<double> ratios{1.0};
  for (int s = 0; s < steps; ++s) {
    step(world);
    ratios.push_back(energy() / start);
  }
  return ratios;
}

// Relative tolerance of an energy ratio: the stretch u ~ 0.2 m is the difference of positions
// ~1.2 m, so each step rounds u by ~6 unit round-offs relative and u^2 by twice that; over 50 to
// 1000 steps as a random walk (7 to 32 x) that is 1e-6 to 5e-6 in float. Measured: at most 4e-6 in
// float and 1e-14 in double; the tolerances keep a margin of 10 and 100: 4e-5 and 1e-12.
double energyTolerance(Precision precision) { return precision == Precision::Float ? 4e-5 : 1e-12; }

}  // namespace

std::vector<CheckRow> energyChecks() {
  std::vector<CheckRow> rows;
  const double theta = 10 * kEnergyDt;
  for (Precision precision : kPrecisions) {
    for (Method method : kAllMethods) {
      if (methodInfo(method).amplification.kind == AmplificationKind::SymplecticEuler) {
        // Symplectic Euler keeps H = u^2 + w^2 - theta u w exactly (w = v / omega); from rest
        // that bounds |E / E0 - 1| by (theta / 2) / (1 - theta / 2) at every step, forever.
        const std::vector<double> ratios = precision == Precision::Float
                                               ? energyRatios<float>(method, kSymplecticSteps)
                                               : energyRatios<double>(method, kSymplecticSteps);
        double worst = 0;
        for (double ratio : ratios) worst = std::max(worst, std::abs(ratio - 1));
        rows.push_back(makeRow(
            fmt::format("spring-undamped energy: max |E/E0 - 1| over {} steps of {:g} s (bounded)",
                        kSymplecticSteps, kEnergyDt),
            std::string(methodName(method)), precision, (theta / 2) / (1 - theta / 2), worst,
            energyTolerance(precision), CheckRule::AtMost));
        continue;
      }
      const std::vector<double> ratios = precision == Precision::Float
                                             ? energyRatios<float>(method, kEnergySteps)
                                             : energyRatios<double>(method, kEnergySteps);
      const double expected = std::pow(amplificationSquared(method, theta), kEnergySteps);
      rows.push_back(makeRow(
          fmt::format("spring-undamped energy: E/E0 after {} steps of {:g} s = |R(i {:g})|^{}",
                      kEnergySteps, kEnergyDt, theta, 2 * kEnergySteps),
          std::string(methodName(method)), precision, expected, ratios.back(),
          energyTolerance(precision) * expected));
    }
  }
  return rows;
}

}  // namespace clothref
