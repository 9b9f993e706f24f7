// verify's collision family: oblique sphere-sphere and sphere-cloth impacts through World::step,
// against the closed-form impulse (restitution, momentum, tangential velocity, energy).
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

}  // namespace clothref
