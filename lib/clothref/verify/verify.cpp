#include "clothref/verify/verify.h"
#include "clothref/scene/make_world.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <functional>
#include <limits>
#include <random>

#include "clothref/core/world.h"
#include "clothref/solver/backward_euler.h"
#include "clothref/verify/analytic.h"

namespace clothref {

CheckRow makeRow(std::string check, std::string method, Precision precision, double expected,
                 double observed, double tolerance, CheckRule rule) {
  CheckRow row;
  row.check = std::move(check);
  row.method = std::move(method);
  row.precision = precision;
  row.expected = expected;
  row.observed = observed;
  row.tolerance = tolerance;
  row.rule = rule;
  // written so that a NaN observation fails
  row.pass = rule == CheckRule::Within ? std::abs(observed - expected) <= tolerance
                                       : observed <= expected + tolerance;
  return row;
}

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

bool VerifyReport::passed() const {
  return std::all_of(checks.begin(), checks.end(), [](const CheckRow& row) { return row.pass; });
}

namespace {

constexpr Precision kPrecisions[] = {Precision::Double, Precision::Float};

// Unit round-off u of a precision: 2^-24 for float, 2^-53 for double.
double unitRoundoff(Precision precision) {
  return precision == Precision::Float ? std::numeric_limits<float>::epsilon() / 2
                                       : std::numeric_limits<double>::epsilon() / 2;
}

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

Trajectory simulateParticle(Precision precision, const Scene& scene, Method method, double dt,
                            int steps, int particle) {
  return precision == Precision::Float
             ? simulateParticle<float>(scene, method, dt, steps, particle)
             : simulateParticle<double>(scene, method, dt, steps, particle);
}

// The exact motion of the one moving particle of a spring or free-fall scene.
//   state(t)         closed form
//   derivative(t, k) |x^(k)(t)| (k >= 2), by the ODE's recursion applied to the exact state
struct ExactMotion {
  int particle = 0;
  std::function<PointState(double)> state;
  std::function<double(double, int)> derivative;
};

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

double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

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

constexpr double kHorizon = 1.0;  // seconds, for the closed-form and convergence checks

}  // namespace

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

namespace {

// One body of an impact: particle `index` of `particles`.
template <typename T>
struct BodyRef {
  Particles<T>* particles;
  int index;

  Eigen::Vector3d position() const { return xyz(particles->position.col(index)); }
  Eigen::Vector3d velocity() const { return xyz(particles->velocity.col(index)); }
  double mass() const { return double(particles->mass[index]); }
};

// What one impact did. Speeds and drifts are relative (see measureImpact).
struct ImpactMeasure {
  bool contact = false;
  double restitution = std::numeric_limits<double>::quiet_NaN();
  double tangential_change = std::numeric_limits<double>::quiet_NaN();
  double closed_form_error = std::numeric_limits<double>::quiet_NaN();
  double momentum_drift = std::numeric_limits<double>::quiet_NaN();
  double energy_change = std::numeric_limits<double>::quiet_NaN();
  double velocity_b_change = std::numeric_limits<double>::quiet_NaN();  // |v_b' - v_b| (m/s)
};

constexpr int kMaxApproachSteps = 2000;
constexpr int kStepsAfterContact = 200;

// Steps `world` until the step whose contact changes a velocity (a is body i of the stub, b body
// j: the normal runs from b to a), and measures that step:
//   restitution        -((v_a' - v_b') . n) / ((v_a - v_b) . n)
//   tangential_change  max over a, b of |v_t' - v_t| / |v_a - v_b|
//   closed_form_error  max over a, b of |v' - v_closed_form| / |v_a - v_b| (impactVelocities)
// then runs kStepsAfterContact more steps (later contacts included) and measures
//   momentum_drift     |P_end - P_start| / sum m |v| at the start
//   energy_change      (K_end - K_start) / K_start
template <typename T>
ImpactMeasure measureImpact(World<T>& world, BodyRef<T> a, BodyRef<T> b) {
  ImpactMeasure measure;
  const std::array<double, 3> p_start = momentum(world);
  const double k_start = kineticEnergy(world);
  const double momentum_scale = a.mass() * a.velocity().norm() + b.mass() * b.velocity().norm();
  for (int k = 0; k < kMaxApproachSteps && !measure.contact; ++k) {
    const Eigen::Vector3d xa = a.position(), xb = b.position();
    const Eigen::Vector3d va = a.velocity(), vb = b.velocity();
    step(world);
    if (a.velocity() == va && b.velocity() == vb) continue;
    measure.contact = true;
    const Eigen::Vector3d n = (xa - xb).normalized();
    const Eigen::Vector3d relative = va - vb;
    measure.restitution = -(a.velocity() - b.velocity()).dot(n) / relative.dot(n);
    auto tangential = [&n](const Eigen::Vector3d& v) { return v - v.dot(n) * n; };
    measure.tangential_change = std::max((tangential(a.velocity()) - tangential(va)).norm(),
                                         (tangential(b.velocity()) - tangential(vb)).norm()) /
                                relative.norm();
    const double e = double(world.spheres && b.particles == &world.spheres->particles
                                ? world.physics.restitution_sphere
                                : world.physics.restitution_cloth);
    const ImpactVelocities closed = impactVelocities(a.mass(), va, b.mass(), vb, n, e);
    measure.closed_form_error =
        std::max((a.velocity() - closed.a).norm(), (b.velocity() - closed.b).norm()) /
        relative.norm();
    measure.velocity_b_change = (b.velocity() - vb).norm();
  }
  for (int k = 0; k < kStepsAfterContact; ++k) step(world);
  const std::array<double, 3> p_end = momentum(world);
  measure.momentum_drift =
      Eigen::Vector3d(p_end[0] - p_start[0], p_end[1] - p_start[1], p_end[2] - p_start[2]).norm() /
      momentum_scale;
  measure.energy_change = (kineticEnergy(world) - k_start) / k_start;
  return measure;
}

constexpr double kRestitutions[] = {0, 0.25, 0.5, 0.8, 1};
constexpr double kMassRatios[] = {1, 10, 100};

Scene impactBaseScene(const std::string& name) {
  Scene scene;
  scene.name = name;
  scene.dt = 1e-3;
  scene.gravity = {0, 0, 0};
  scene.viscous_coef = 0;
  return scene;
}

// Sphere 0 (125 kg) overtakes sphere 1 (125 * ratio kg) off-centre: the contact normal is
// oblique to both velocities, so each has a tangential part.
Scene sphereSphereScene(double restitution, double mass_ratio) {
  Scene scene = impactBaseScene("impact-sphere-sphere");
  SpheresSpec spheres;
  spheres.items = {SphereSpec{{-0.9, 0.3, 0.1}, 0.5, {2, 0, 0.25}, 125.0},
                   SphereSpec{{0.4, 0, 0}, 0.5, {-1, 0.5, 0}, 125.0 * mass_ratio}};
  spheres.external_force = false;
  spheres.sphere_sphere_collision = true;
  spheres.restitution_sphere = restitution;
  scene.spheres = spheres;
  return scene;
}

// A sphere (mass_ratio kg) and one cloth particle (1 kg, or fixed when `fixed`) meeting
// obliquely.
Scene sphereClothScene(double restitution, double mass_ratio, bool fixed) {
  Scene scene = impactBaseScene("impact-sphere-cloth");
  ClothSpec cloth;
  cloth.particles = {fixed ? ParticleSpec{{0.3, -0.9, 0.1}, {0, 0, 0}, 0}
                           : ParticleSpec{{0.3, -0.9, 0.1}, {0.4, 1.5, 0}, 1}};
  cloth.spring_coef = 0;
  cloth.damper_coef = 0;
  scene.cloth = cloth;
  SpheresSpec spheres;
  spheres.items = {SphereSpec{{0, 0, 0}, 0.5, {0.2, -1, 0.3}, mass_ratio}};
  spheres.external_force = false;
  spheres.sphere_sphere_collision = false;
  spheres.restitution_cloth = restitution;
  scene.spheres = spheres;
  return scene;
}

template <typename T>
ImpactMeasure sphereSphereImpact(double restitution, double mass_ratio) {
  World<T> world = makeWorld<T>(sphereSphereScene(restitution, mass_ratio), Method::Explicit);
  return measureImpact(world, BodyRef<T>{&world.spheres->particles, 0},
                       BodyRef<T>{&world.spheres->particles, 1});
}

template <typename T>
ImpactMeasure sphereClothImpact(double restitution, double mass_ratio, bool fixed) {
  World<T> world = makeWorld<T>(sphereClothScene(restitution, mass_ratio, fixed), Method::Explicit);
  return measureImpact(world, BodyRef<T>{&world.spheres->particles, 0},
                       BodyRef<T>{&world.cloth->particles, 0});
}

// Conservation tolerances: a few roundings of size u per impulse, relative. Float 1e-6 and
// double 1e-12 (docs/verification.md); restitution 1e-5 in float, 1e-12 in double.
double conservationTolerance(Precision precision) {
  return precision == Precision::Float ? 1e-6 : 1e-12;
}
double restitutionTolerance(Precision precision) {
  return precision == Precision::Float ? 1e-5 : 1e-12;
}

// Worst case of a sweep: the measured value farthest from its target, with its label.
struct Worst {
  double value = 0;
  double distance = -1;
  std::string label;

  void offer(double candidate, double target, const std::string& where) {
    const double d = std::isnan(candidate) ? std::numeric_limits<double>::infinity()
                                           : std::abs(candidate - target);
    if (d > distance) {
      distance = d;
      value = candidate;
      label = where;
    }
  }
};

// Rows shared by both impact kinds: per e the worst restitution over the mass ratios, then the
// worst momentum drift, tangential change, closed-form error and energy change over the sweep.
template <typename Measure>
void impactRows(const std::string& kind, Precision precision, Measure&& measure,
                std::vector<CheckRow>& rows) {
  Worst momentum, tangential, closed, energy_elastic, energy_gain;
  for (double e : kRestitutions) {
    Worst restitution;
    for (double ratio : kMassRatios) {
      const ImpactMeasure m = measure(e, ratio);
      const std::string where = fmt::format("e {:g}, ratio {:g}", e, ratio);
      restitution.offer(m.restitution, e, fmt::format("ratio {:g}", ratio));
      momentum.offer(m.momentum_drift, 0, where);
      tangential.offer(m.tangential_change, 0, where);
      closed.offer(m.closed_form_error, 0, where);
      if (e == 1) energy_elastic.offer(m.energy_change, 0, where);
      // the signed change: the worst is the largest gain (or smallest loss)
      else
        energy_gain.offer(m.energy_change, -1, where);
    }
    rows.push_back(makeRow(fmt::format("{}: restitution e {:g} (worst of ratios 1, 10, 100: {})",
                                       kind, e, restitution.label),
                           "explicit", precision, e, restitution.value,
                           restitutionTolerance(precision)));
  }
  const double tol = conservationTolerance(precision);
  const std::string sweep = "worst of 15";
  rows.push_back(
      makeRow(fmt::format("{}: momentum drift / sum m|v| ({}: {})", kind, sweep, momentum.label),
              "explicit", precision, 0, momentum.value, tol));
  rows.push_back(makeRow(
      fmt::format("{}: tangential |dv_t| / |v_rel| ({}: {})", kind, sweep, tangential.label),
      "explicit", precision, 0, tangential.value, tol));
  rows.push_back(
      makeRow(fmt::format("{}: |v - v_closed_form| / |v_rel| ({}: {})", kind, sweep, closed.label),
              "explicit", precision, 0, closed.value, restitutionTolerance(precision)));
  rows.push_back(makeRow(
      fmt::format("{}: energy change / K at e = 1 (worst of 3: {})", kind, energy_elastic.label),
      "explicit", precision, 0, energy_elastic.value, tol));
  rows.push_back(makeRow(
      fmt::format("{}: energy change / K at e < 1 (largest of 12: {})", kind, energy_gain.label),
      "explicit", precision, 0, energy_gain.value, tol, CheckRule::AtMost));
}

}  // namespace

std::vector<CheckRow> sphereSphereChecks() {
  std::vector<CheckRow> rows;
  for (Precision precision : kPrecisions) {
    impactRows(
        "sphere-sphere", precision,
        [precision](double e, double ratio) {
          return withPrecision(precision,
                               [&]<typename T>() { return sphereSphereImpact<T>(e, ratio); });
        },
        rows);
  }
  return rows;
}

std::vector<CheckRow> sphereClothChecks() {
  std::vector<CheckRow> rows;
  for (Precision precision : kPrecisions) {
    auto measure = [precision](double e, double ratio, bool fixed) {
      return withPrecision(precision,
                           [&]<typename T>() { return sphereClothImpact<T>(e, ratio, fixed); });
    };
    impactRows(
        "sphere-cloth", precision,
        [&measure](double e, double ratio) { return measure(e, ratio, false); }, rows);
    // a fixed particle is immovable in the impulse: it keeps its (zero) velocity, and the sphere
    // bounces off it as off a wall
    Worst restitution, closed, particle, energy_gain;
    for (double e : kRestitutions) {
      const ImpactMeasure m = measure(e, 125, true);
      const std::string where = fmt::format("e {:g}", e);
      restitution.offer(m.restitution - e, 0, where);
      closed.offer(m.closed_form_error, 0, where);
      particle.offer(m.velocity_b_change, 0, where);
      energy_gain.offer(m.energy_change, -1, where);
    }
    const std::string kind = "sphere-fixed particle";
    rows.push_back(
        makeRow(fmt::format("{}: restitution - e (worst of 5: {})", kind, restitution.label),
                "explicit", precision, 0, restitution.value, restitutionTolerance(precision)));
    rows.push_back(
        makeRow(fmt::format("{}: particle |dv| (m/s) (worst of 5: {})", kind, particle.label),
                "explicit", precision, 0, particle.value, 0));
    rows.push_back(makeRow(
        fmt::format("{}: |v - v_closed_form| / |v_rel| (worst of 5: {})", kind, closed.label),
        "explicit", precision, 0, closed.value, restitutionTolerance(precision)));
    rows.push_back(
        makeRow(fmt::format("{}: energy change / K (largest of 5: {})", kind, energy_gain.label),
                "explicit", precision, 0, energy_gain.value, conservationTolerance(precision),
                CheckRule::AtMost));
  }
  return rows;
}

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

namespace {

// Energy on `spring-undamped` (k = 100 N/m, m = 1 kg, omega = 10 rad/s) at dt = 0.02 s, so
// theta = omega dt = 0.2. The particle stays on the +x side of the anchor, so the motion is the
// linear oscillator u'' = -omega^2 u (u = length - rest) and in (u, v / omega) every course
// method's step is a rotation scaled by |R(i theta)|, R its amplification factor: the energy
// E = 1/2 m v^2 + 1/2 k u^2 is multiplied by exactly |R(i theta)|^2 per step.
constexpr double kEnergyDt = 0.02;  // seconds
constexpr int kEnergySteps = 50;    // 1 s: explicit Euler's amplitude stays below the rest length
constexpr int kSymplecticSteps = 1000;  // 20 s, ~32 periods: bounded, not just slow to grow

// |R(i theta)|^2 of each method's amplification factor on y' = lambda y, at lambda dt = i theta.
double amplificationSquared(Method method, double theta) {
  const double t2 = theta * theta;
  switch (method) {
    case Method::Explicit:  // R = 1 + z
      return 1 + t2;
    case Method::Implicit:  // the course's one predictor-corrector pass: R = 1 + z + z^2
      return (1 - t2) * (1 - t2) + t2;
    case Method::Midpoint:  // R = 1 + z + z^2 / 2
      return (1 - t2 / 2) * (1 - t2 / 2) + t2;
    case Method::Rk4: {  // R = 1 + z + z^2 / 2 + z^3 / 6 + z^4 / 24
      const double re = 1 - t2 / 2 + t2 * t2 / 24;
      const double im = theta - theta * t2 / 6;
      return re * re + im * im;
    }
    case Method::Symplectic:  // not a scaled rotation: see energyChecks
      return 1;
    case Method::BackwardEuler:  // R = 1 / (1 - z): the spring is linear, so the linearised
      return 1 / (1 + t2);       // step is backward Euler itself
  }
  return 1;
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
      if (method == Method::Symplectic) {
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

namespace {

// The course facts a built-in course scene must reproduce (course2022 and course2024 defaults).
struct CourseFacts {
  const char* scene;
  double cloth_y;      // metres: 0 in 2022, 1 in 2024
  double spring_coef;  // N/m: 25000 in 2022, 20000 in 2024
  std::vector<Vector3> sphere_centres;
  double sphere_radius;  // metres
  bool sphere_force;     // 2022's loop gives the spheres gravity and drag, 2024's does not
};

// An exact fact: observed must equal expected (tolerance 0).
CheckRow factRow(const std::string& scene, const std::string& what, Precision precision,
                 double expected, double observed) {
  return makeRow(fmt::format("{} fact: {}", scene, what), "-", precision, expected, observed, 0);
}

// Largest |a - b| over the x, y, z of two lists of points (NaN when their sizes differ).
double largestDistance(const std::vector<Vector3>& a, const std::vector<Vector3>& b) {
  if (a.size() != b.size()) return std::numeric_limits<double>::quiet_NaN();
  double worst = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(a[i][k] - b[i][k]));
  return worst;
}

std::vector<CheckRow> courseFactRows(const CourseFacts& facts) {
  std::vector<CheckRow> rows;
  const Scene& scene = *findBuiltinScene(facts.scene);
  const std::string name = facts.scene;
  const Precision d = Precision::Double, f = Precision::Float;
  rows.push_back(factRow(name, "dt (s)", d, 1e-4, scene.dt));
  rows.push_back(factRow(name, "|gravity - (0, -9.8, 0)| (m/s^2)", d, 0,
                         largestDistance({scene.gravity}, {Vector3{0, -9.8, 0}})));
  rows.push_back(factRow(name, "viscous drag (kg/s)", d, 3.4e-4, scene.viscous_coef));
  rows.push_back(factRow(name, "spring coefficient (N/m)", d, facts.spring_coef,
                         scene.cloth ? scene.cloth->spring_coef : -1));
  rows.push_back(factRow(name, "damper coefficient (N s/m)", d, 750,
                         scene.cloth ? scene.cloth->damper_coef : -1));
  const SpheresSpec spheres = scene.spheres.value_or(SpheresSpec{});
  std::vector<Vector3> centres;
  double radius_error = 0;
  for (const SphereSpec& sphere : spheres.items) {
    centres.push_back(sphere.center);
    radius_error = std::max(radius_error, std::abs(sphere.radius - facts.sphere_radius));
  }
  rows.push_back(factRow(name, "sphere centres, largest |c - c_course| (m)", d, 0,
                         largestDistance(centres, facts.sphere_centres)));
  rows.push_back(factRow(name, "sphere radii, largest |r - r_course| (m)", d, 0, radius_error));
  rows.push_back(factRow(name, "restitution sphere-cloth", d, 0, spheres.restitution_cloth));
  rows.push_back(factRow(name, "position correction (fraction of the penetration)", d, 0.15,
                         spheres.correction));
  if (facts.sphere_force)
    rows.push_back(factRow(name, "restitution sphere-sphere", d, 0.8, spheres.restitution_sphere));

  // The float world the scene builds: the course's grid, masses and springs.
  World<float> world = makeWorld<float>(scene, Method::Explicit);
  const Particles<float>& cloth = world.cloth->particles;
  int mass_errors = 0;
  double y_error = 0;
  for (int i = 0; i < cloth.size(); ++i) {
    const bool corner = i == 0 || i == 24 || i == 600 || i == 624;
    mass_errors += cloth.mass[i] != (corner ? 0.0f : 1.0f);
    y_error = std::max(y_error, std::abs(double(cloth.position(1, i)) - facts.cloth_y));
  }
  rows.push_back(factRow(name, "cloth particles (25 x 25)", f, 625, cloth.size()));
  rows.push_back(factRow(name, "cloth masses != 1 kg (0 at the four corners)", f, 0, mass_errors));
  rows.push_back(factRow(name, "cloth height, largest |y - y_course| (m)", f, 0, y_error));
  // Counts per type from the course's six passes, and the rest lengths measured on the float
  // grid: |p0 - p1| = 0x3e2aaaa8, |p0 - p26| = 0x3e715beb, |p0 - p2| = 0x3eaaaaac.
  const SpringType types[3] = {SpringType::Structural, SpringType::Shear, SpringType::Bend};
  const int counts[3] = {1200, 1152, 1150};
  const float rest[3] = {std::bit_cast<float>(0x3e2aaaa8u), std::bit_cast<float>(0x3e715bebu),
                         std::bit_cast<float>(0x3eaaaaacu)};
  for (int t = 0; t < 3; ++t) {
    int count = 0;
    double rest_error = 0;
    for (const Spring<float>& spring : world.cloth->springs) {
      if (spring.type != types[t]) continue;
      ++count;
      rest_error = std::max(rest_error, std::abs(double(spring.rest_length) - double(rest[t])));
    }
    const std::string type(enumName(kSpringTypeNames, types[t]));
    rows.push_back(factRow(name, type + " springs", f, counts[t], count));
    rows.push_back(
        factRow(name, type + " rest length, largest |L - L_course| (m)", f, 0, rest_error));
  }
  double mass_error = 0;
  const Particles<float>& balls = world.spheres->particles;
  const double course_mass = 1000 * facts.sphere_radius * facts.sphere_radius * facts.sphere_radius;
  for (int i = 0; i < balls.size(); ++i)
    mass_error = std::max(mass_error, std::abs(double(balls.mass[i]) - course_mass));
  rows.push_back(factRow(name, "sphere masses, largest |m - 1000 r^3| (kg)", f, 0, mass_error));

  // One evaluation and ten steps: the spheres' force as the edition's loop has it, and fixed
  // corners that never move (no sphere reaches them).
  World<float> stepped = makeWorld<float>(scene, Method::Explicit);
  simulateOneStep(stepped);
  double sphere_acceleration = 0;
  for (int i = 0; i < stepped.spheres->size(); ++i)
    sphere_acceleration =
        std::max(sphere_acceleration, xyz(stepped.spheres->particles.acceleration.col(i)).norm());
  if (facts.sphere_force)
    rows.push_back(makeRow(name + " fact: sphere |a| after one evaluation = |g| (m/s^2)", "-", f,
                           9.8, sphere_acceleration, 1e-5));
  else
    rows.push_back(factRow(name, "sphere |a| after one evaluation (no force on it) (m/s^2)", f, 0,
                           sphere_acceleration));
  double corner_motion = 0;
  for (int s = 0; s < 10; ++s) step(stepped);
  for (int corner : {0, 24, 600, 624})
    corner_motion = std::max(corner_motion, (xyz(stepped.cloth->particles.position.col(corner)) -
                                             xyz(cloth.position.col(corner)))
                                                .norm());
  rows.push_back(
      factRow(name, "fixed corners' largest displacement after 10 steps (m)", f, 0, corner_motion));
  return rows;
}

}  // namespace

std::vector<CheckRow> courseFactChecks() {
  std::vector<CheckRow> rows;
  const CourseFacts editions[] = {
      {"course2022",
       0,
       25000,
       {{-0.75, 1, -0.75}, {0.75, 1, -0.75}, {-0.75, 1, 0.75}, {0.75, 1, 0.75}},
       0.5,
       true},
      {"course2024", 1, 20000, {{0, 0, 0}}, 1, false},
  };
  for (const CourseFacts& facts : editions) {
    const std::vector<CheckRow> edition = courseFactRows(facts);
    rows.insert(rows.end(), edition.begin(), edition.end());
  }
  return rows;
}

namespace {

// Largest |a - b| over positions and velocities (x, y, z); NaN when any difference is NaN.
template <typename T>
double largestDifference(const Particles<T>& a, const Particles<T>& b) {
  double worst = 0;
  for (int i = 0; i < a.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      for (const double d : {std::abs(double(a.position(k, i)) - double(b.position(k, i))),
                             std::abs(double(a.velocity(k, i)) - double(b.velocity(k, i)))})
        if (!(d <= worst)) worst = d;  // a NaN difference sticks
    }
  }
  return worst;
}

}  // namespace

std::vector<CheckRow> courseFormChecks() {
  std::vector<CheckRow> rows;
  for (const char* name : {"course2022", "course2024"}) {
    const Scene& scene = *findBuiltinScene(name);
    for (Method method : kAllMethods) {
      World<float> fast = makeWorld<float>(scene, method);
      World<float> course = makeWorld<float>(scene, method);
      setExecution(course, false, course.execution.simd, 1);
      for (int s = 0; s < kCourseFormSteps; ++s) {
        step(fast);
        step(course);
      }
      double worst = largestDifference(fast.cloth->particles, course.cloth->particles);
      if (fast.spheres) {
        const double spheres =
            largestDifference(fast.spheres->particles, course.spheres->particles);
        if (!(spheres <= worst)) worst = spheres;
      }
      rows.push_back(makeRow(
          fmt::format("{}: fast kernels vs the course-form stubs, max |dx|, |dv| after {} steps",
                      name, kCourseFormSteps),
          std::string(methodName(method)), Precision::Float, 0, worst, 0));
    }
  }
  return rows;
}

VerifyReport runVerification() {
  VerifyReport report;
  report.studies = convergenceStudies();
  auto append = [&report](std::vector<CheckRow> rows) {
    report.checks.insert(report.checks.end(), rows.begin(), rows.end());
  };
  append(closedFormChecks());
  append(convergenceChecks(report.studies));
  append(sphereSphereChecks());
  append(sphereClothChecks());
  append(freeClothMomentumChecks());
  append(energyChecks());
  append(courseFactChecks());
  append(courseFormChecks());
  return report;
}

nlohmann::ordered_json reportToJson(const VerifyReport& report) {
  using ordered_json = nlohmann::ordered_json;
  ordered_json orders = ordered_json::object();
  ordered_json floors = ordered_json::object();
  for (const ConvergenceStudy& study : report.studies) {
    const std::string method(methodName(study.method));
    const std::string precision(precisionName(study.precision));
    orders[method][precision] = study.order ? ordered_json(*study.order) : ordered_json(nullptr);
    if (study.precision == Precision::Float)
      floors[method] = *std::max_element(study.roundoff.begin(), study.roundoff.end());
  }
  ordered_json studies = ordered_json::array();
  for (const ConvergenceStudy& study : report.studies) {
    studies.push_back(
        {{"scene", "spring"},
         {"method", methodName(study.method)},
         {"precision", precisionName(study.precision)},
         {"expected_order", study.expected_order},
         {"end_time", study.end_time},
         {"fit", "least squares of log error on log dt over the fitted points"},
         {"dts", study.dts},
         {"errors", study.errors},
         {"roundoff", study.roundoff},
         {"fitted", study.fitted},
         {"order", study.order ? ordered_json(*study.order) : ordered_json(nullptr)}});
  }
  ordered_json checks = ordered_json::array();
  for (const CheckRow& row : report.checks) {
    checks.push_back({{"check", row.check},
                      {"method", row.method},
                      {"precision", precisionName(row.precision)},
                      {"expected", row.expected},
                      {"observed", row.observed},
                      {"tolerance", row.tolerance},
                      {"rule", row.rule == CheckRule::Within ? "within" : "at_most"},
                      {"pass", row.pass}});
  }
  return {{"orders", orders},
          {"float_floor", floors},
          {"studies", studies},
          {"checks", checks},
          {"passed", report.passed()}};
}

std::string reportTable(const VerifyReport& report) {
  // every column as wide as its longest entry (a method name like backward-euler, "<= 1e-05")
  const auto expectedText = [](const CheckRow& row) {
    return row.rule == CheckRule::AtMost ? fmt::format("<= {:.6g}", row.expected)
                                         : fmt::format("{:.6g}", row.expected);
  };
  std::size_t width = 5, method_width = 6, expected_width = 8;
  for (Method method : kAllMethods)
    method_width = std::max(method_width, std::string(methodName(method)).size());
  for (const CheckRow& row : report.checks) {
    width = std::max(width, row.check.size());
    method_width = std::max(method_width, row.method.size());
    expected_width = std::max(expected_width, expectedText(row).size());
  }
  std::string table = fmt::format("{:<{}}  {:<{}}  {:<6}  {:>{}}  {:>12}  {:>10}  {}\n", "check",
                                  width, "method", method_width, "prec", "expected", expected_width,
                                  "observed", "tolerance", "pass");
  int failed = 0;
  for (const CheckRow& row : report.checks) {
    table +=
        fmt::format("{:<{}}  {:<{}}  {:<6}  {:>{}}  {:>12.4e}  {:>10.3e}  {}\n", row.check, width,
                    row.method, method_width, precisionName(row.precision), expectedText(row),
                    expected_width, row.observed, row.tolerance, row.pass ? "yes" : "NO");
    failed += row.pass ? 0 : 1;
  }
  // one line per method: the orders side by side, and where the float floor lies
  table +=
      "\norders on spring (least squares of log error on log dt, pass |p - expected| <= 0.2);\n"
      "float floor = largest |x_float - x_double| in the ladder; null = < 3 dt above 10x floor:\n";
  for (Method method : kAllMethods) {
    std::string line = fmt::format("  {:<{}}  expected {}", methodName(method), method_width,
                                   methodInfo(method).order);
    for (const ConvergenceStudy& study : report.studies) {
      if (study.method != method) continue;
      line += fmt::format("  {} {}", precisionName(study.precision),
                          study.order ? fmt::format("{:.3f}", *study.order) : "null");
      if (study.precision == Precision::Float)
        line += fmt::format("  float floor {:.2e} m",
                            *std::max_element(study.roundoff.begin(), study.roundoff.end()));
    }
    table += line + "\n";
  }
  table += fmt::format("\n{} checks, {} failed\n", report.checks.size(), failed);
  return table;
}

}  // namespace clothref
