// verify's closed-form family: every method's error against the exact motion of the spring,
// spring-undamped and free-fall scenes at their dt, float and double.
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

std::vector<CheckRow> closedFormChecks() {
  std::vector<CheckRow> rows;
  for (const char* name : {"spring", "spring-undamped", "free-fall"}) {
    const Scene& scene = *findBuiltinScene(name);
    const ExactMotion exact = exactMotion(scene);
    const int steps = int(std::lround(kHorizon / scene.dt));
    for (Precision precision : kPrecisions) {
      for (Method method : kAllMethods) {
        const Trajectory trajectory =
            simulateParticle(precision, scene, method, scene.dt, steps, exact.particle);
        const double tolerance =
            truncationBound(exact, methodInfo(method).order, trajectory.dt, steps) +
            roundoffBound(exact, precision, trajectory.dt, steps);
        rows.push_back(makeRow(
            fmt::format("{}: max |x - x_exact| (m), dt {:g} s, {:g} s", name, scene.dt, kHorizon),
            std::string(methodName(method)), precision, 0, maxError(trajectory, exact), tolerance));
      }
    }
  }
  return rows;
}

}  // namespace clothref
