// The helpers the verify check families share (check_support.h).
#include "clothref/verify/check_support.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "clothref/core/world.h"
#include "clothref/scene/make_world.h"

namespace clothref::verify_support {

// Unit round-off u of a precision: 2^-24 for float, 2^-53 for double.
double unitRoundoff(Precision precision) {
  return precision == Precision::Float ? std::numeric_limits<float>::epsilon() / 2
                                       : std::numeric_limits<double>::epsilon() / 2;
}

namespace {

template <typename T>
Trajectory simulateParticle(const Scene& scene, Method method, double dt, int steps, int particle) {
  World<T> world = makeWorld<T>(scene, method, dt);
  Trajectory trajectory;
  trajectory.dt = double(world.physics.dt);
  const Particles<T>& p = world.cloth->particles;
  for (int k = 0;; ++k) {
    trajectory.position.push_back(xyz(p.position.col(particle)));
    trajectory.velocity.push_back(xyz(p.velocity.col(particle)));
    if (k == steps) break;
    step(world);
  }
  return trajectory;
}

}  // namespace

Trajectory simulateParticle(Precision precision, const Scene& scene, Method method, double dt,
                            int steps, int particle) {
  return precision == Precision::Float
             ? simulateParticle<float>(scene, method, dt, steps, particle)
             : simulateParticle<double>(scene, method, dt, steps, particle);
}

ExactMotion exactMotion(const Scene& scene) {
  ExactMotion motion;
  if (scene.cloth && !scene.cloth->springs.empty()) {
    const SpringProblem problem = springProblem(scene);
    motion.particle = problem.particle;
    motion.state = [problem](double t) { return springState(problem, t); };
    motion.derivative = [problem](double t, int k) {
      // m u'' = -c u' - k u, differentiated: u^(j) = -(c u^(j-1) + k u^(j-2)) / m
      const DampedOscillator& o = problem.oscillator;
      const Displacement u = oscillatorState(o, t);
      double older = u.position;
      double old = u.velocity;
      for (int j = 2; j <= k; ++j) {
        const double next = -(o.damping * old + o.stiffness * older) / o.mass;
        older = old;
        old = next;
      }
      return std::abs(old);
    };
    return motion;
  }
  const DragFall fall = dragFallProblem(scene);
  motion.state = [fall](double t) { return dragFallState(fall, t); };
  motion.derivative = [fall](double t, int k) {
    // x'' = g - v c / m, then x^(j) = -(c / m) x^(j-1)
    Eigen::Vector3d d = fall.gravity - dragFallState(fall, t).velocity * fall.drag / fall.mass;
    for (int j = 3; j <= k; ++j) d *= -fall.drag / fall.mass;
    return d.norm();
  };
  return motion;
}

// max over steps of |x_k - x_exact(k dt)|.
double maxError(const Trajectory& trajectory, const ExactMotion& exact) {
  double error = 0;
  for (std::size_t k = 0; k < trajectory.position.size(); ++k) {
    const PointState truth = exact.state(double(k) * trajectory.dt);
    error = std::max(error, (trajectory.position[k] - truth.position).norm());
  }
  return error;
}

namespace {
double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }
}  // namespace

// Leading global error of an order-p method over [0, T]: T h^p max|x^(p+1)| / (p+1)!, doubled
// for the next-order terms and the growth or decay of the error inside the horizon.
double truncationBound(const ExactMotion& exact, int order, double dt, int steps) {
  double largest = 0;
  for (int k = 0; k <= steps; ++k)
    largest = std::max(largest, exact.derivative(double(k) * dt, order + 1));
  return 2 * double(steps) * dt * std::pow(dt, order) * largest / factorial(order + 1);
}

// Round-off of `roundings` roundings of relative size u on quantities of size `scale`, modelled
// as a random walk, 8 sqrt(roundings) u scale. The worst case (linear, roundings * u * scale)
// is about sqrt(roundings) times larger and would hide real errors: with it, a 0.1 % stiffness
// error passes the float rows (docs/verification.md).
double roundoffEstimate(double roundings, Precision precision, double scale) {
  return 8 * std::sqrt(roundings) * unitRoundoff(precision) * scale;
}

// Round-off of a particle trajectory: each step rounds the position update (~u|x|) and the
// velocity update (~u|v|, which moves x by ~u|v|T by the end).
double roundoffBound(const ExactMotion& exact, Precision precision, double dt, int steps) {
  const double end_time = double(steps) * dt;
  double scale = 0;
  for (int k = 0; k <= steps; ++k) {
    const PointState s = exact.state(double(k) * dt);
    scale = std::max(scale, s.position.norm() + end_time * s.velocity.norm());
  }
  return roundoffEstimate(steps, precision, scale);
}

Scene impactBaseScene(const std::string& name) {
  Scene scene;
  scene.name = name;
  scene.dt = 1e-3;
  scene.gravity = {0, 0, 0};
  scene.viscous_coef = 0;
  return scene;
}

}  // namespace clothref::verify_support
