#include "clothref/verify/analytic.h"

#include <fmt/format.h>

#include <cmath>

#include "clothref/io/error.h"

namespace clothref {

namespace {

Eigen::Vector3d toEigen(const Vector3& v) { return Eigen::Vector3d(v[0], v[1], v[2]); }

[[noreturn]] void notFitting(const Scene& scene, const std::string& kind, const std::string& why) {
  throw InputError(fmt::format("scene '{}': not a {} problem: {}", scene.name, kind, why));
}

}  // namespace

double naturalFrequency(const DampedOscillator& oscillator) {
  return std::sqrt(oscillator.stiffness / oscillator.mass);
}

double dampingRatio(const DampedOscillator& oscillator) {
  return oscillator.damping / (2 * std::sqrt(oscillator.stiffness * oscillator.mass));
}

DampingRegime dampingRegime(const DampedOscillator& oscillator) {
  const double c2 = oscillator.damping * oscillator.damping;
  const double critical2 = 4 * oscillator.stiffness * oscillator.mass;
  if (std::abs(c2 - critical2) <= 1e-12 * critical2) return DampingRegime::Critical;
  return c2 < critical2 ? DampingRegime::Under : DampingRegime::Over;
}

Displacement oscillatorState(const DampedOscillator& oscillator, double t) {
  const double omega = naturalFrequency(oscillator);
  const double zeta = dampingRatio(oscillator);
  const double u0 = oscillator.displacement0;
  const double v0 = oscillator.velocity0;
  switch (dampingRegime(oscillator)) {
    case DampingRegime::Under: {
      // u = e^(-zeta w t) (A cos(wd t) + B sin(wd t)), A = u0, B = (v0 + zeta w u0) / wd
      const double decay = zeta * omega;
      const double wd = omega * std::sqrt(1 - zeta * zeta);
      const double a = u0;
      const double b = (v0 + decay * u0) / wd;
      const double envelope = std::exp(-decay * t);
      const double c = std::cos(wd * t);
      const double s = std::sin(wd * t);
      return {envelope * (a * c + b * s),
              envelope * ((b * wd - decay * a) * c - (a * wd + decay * b) * s)};
    }
    case DampingRegime::Critical: {
      // u = (A + B t) e^(-w t), A = u0, B = v0 + w u0
      const double a = u0;
      const double b = v0 + omega * u0;
      const double envelope = std::exp(-omega * t);
      return {(a + b * t) * envelope, (b - omega * (a + b * t)) * envelope};
    }
    case DampingRegime::Over: {
      // u = C1 e^(r1 t) + C2 e^(r2 t), r = -w (zeta -+ sqrt(zeta^2 - 1)), fitted to u0, v0
      const double root = std::sqrt(zeta * zeta - 1);
      const double r1 = -omega * (zeta - root);
      const double r2 = -omega * (zeta + root);
      const double c1 = (v0 - r2 * u0) / (r1 - r2);
      const double c2 = u0 - c1;
      const double e1 = std::exp(r1 * t);
      const double e2 = std::exp(r2 * t);
      return {c1 * e1 + c2 * e2, c1 * r1 * e1 + c2 * r2 * e2};
    }
  }
  return {};
}

SpringProblem springProblem(const Scene& scene) {
  const std::string kind = "spring";
  if (!scene.cloth || scene.cloth->grid)
    notFitting(scene, kind, "needs an explicit-particle cloth");
  if (scene.spheres) notFitting(scene, kind, "has spheres");
  const ClothSpec& cloth = *scene.cloth;
  if (cloth.particles.size() != 2 || cloth.springs.size() != 1)
    notFitting(scene, kind, "needs exactly two particles and one spring");
  if (toEigen(scene.gravity) != Eigen::Vector3d::Zero())
    notFitting(scene, kind, "gravity is not 0");

  // the fixed particle is the anchor: mass 0 in the list or named in `fixed`
  auto is_fixed = [&cloth](int i) {
    if (cloth.particles[i].mass == 0) return true;
    for (int f : cloth.fixed)
      if (f == i) return true;
    return false;
  };
  if (is_fixed(0) == is_fixed(1)) notFitting(scene, kind, "needs one fixed and one free particle");
  const int particle = is_fixed(0) ? 1 : 0;
  const ParticleSpec& anchor = cloth.particles[1 - particle];
  const ParticleSpec& free = cloth.particles[particle];
  if (toEigen(anchor.velocity) != Eigen::Vector3d::Zero())
    notFitting(scene, kind, "the fixed particle moves");

  SpringProblem problem;
  problem.particle = particle;
  problem.anchor = toEigen(anchor.position);
  const Eigen::Vector3d offset = toEigen(free.position) - problem.anchor;
  const double length = offset.norm();
  if (!(length > 0)) notFitting(scene, kind, "the particles coincide");
  problem.axis = offset / length;
  // any velocity across the axis would swing the spring: no longer one-dimensional
  const Eigen::Vector3d velocity = toEigen(free.velocity);
  const double axial = velocity.dot(problem.axis);
  if ((velocity - axial * problem.axis).norm() > 1e-12 * (1 + velocity.norm()))
    notFitting(scene, kind, "the free particle's velocity is not along the spring");
  problem.rest_length = cloth.springs[0].rest_length;
  problem.oscillator.stiffness = cloth.spring_coef;
  problem.oscillator.damping = cloth.damper_coef + scene.viscous_coef;
  problem.oscillator.mass = free.mass;
  problem.oscillator.displacement0 = length - problem.rest_length;
  problem.oscillator.velocity0 = axial;
  if (!(problem.oscillator.stiffness > 0)) notFitting(scene, kind, "spring_coef must be > 0");
  return problem;
}

bool isSpringScene(const Scene& scene) {
  try {
    springProblem(scene);
    return true;
  } catch (const InputError&) {
    return false;
  }
}

PointState springState(const SpringProblem& problem, double t) {
  const Displacement u = oscillatorState(problem.oscillator, t);
  return {problem.anchor + (problem.rest_length + u.position) * problem.axis,
          u.velocity * problem.axis};
}

DragFall dragFallProblem(const Scene& scene) {
  const std::string kind = "free-fall";
  if (!scene.cloth || scene.cloth->grid)
    notFitting(scene, kind, "needs an explicit-particle cloth");
  if (scene.spheres) notFitting(scene, kind, "has spheres");
  const ClothSpec& cloth = *scene.cloth;
  if (cloth.particles.size() != 1 || !cloth.springs.empty() || !cloth.fixed.empty())
    notFitting(scene, kind, "needs exactly one free particle and no springs");
  if (!(cloth.particles[0].mass > 0)) notFitting(scene, kind, "the particle has no mass");
  DragFall fall;
  fall.position0 = toEigen(cloth.particles[0].position);
  fall.velocity0 = toEigen(cloth.particles[0].velocity);
  fall.gravity = toEigen(scene.gravity);
  fall.drag = scene.viscous_coef;
  fall.mass = cloth.particles[0].mass;
  return fall;
}

PointState dragFallState(const DragFall& fall, double t) {
  // with w = t c / m: v = v0 e^-w + g t phi1(w), x = x0 + v0 t phi1(w) + g t^2 phi2(w),
  // phi1 = (1 - e^-w) / w, phi2 = (e^-w - 1 + w) / w^2; both are 1 and 1/2 at w = 0 (no drag),
  // and written without the cancellation of v_inf = g m / c against x0 at small drag
  const double w = t * fall.drag / fall.mass;
  double phi1 = 1;
  double phi2 = 0.5;
  if (w > 1e-2) {
    phi1 = -std::expm1(-w) / w;
    phi2 = (std::expm1(-w) + w) / (w * w);
  } else if (w > 0) {
    // Taylor series; the first omitted terms, w^5 / 720 and w^5 / 5040, are <= 1.4e-13 here
    phi1 = 1 - w / 2 + w * w / 6 - w * w * w / 24 + w * w * w * w / 120;
    phi2 = 0.5 - w / 6 + w * w / 24 - w * w * w / 120 + w * w * w * w / 720;
  }
  return {fall.position0 + fall.velocity0 * (t * phi1) + fall.gravity * (t * t * phi2),
          fall.velocity0 * std::exp(-w) + fall.gravity * (t * phi1)};
}

ImpactVelocities impactVelocities(double mass_a, const Eigen::Vector3d& velocity_a, double mass_b,
                                  const Eigen::Vector3d& velocity_b, const Eigen::Vector3d& normal,
                                  double restitution) {
  ImpactVelocities result{velocity_a, velocity_b};
  const double ua = velocity_a.dot(normal);
  const double ub = velocity_b.dot(normal);
  const bool approaching = ua - ub < 0;
  const bool a_immovable = mass_a == 0;
  const bool b_immovable = mass_b == 0;
  if (!approaching || (a_immovable && b_immovable)) return result;
  double ua_after = ua;
  double ub_after = ub;
  if (a_immovable) {
    // the limit m_a -> infinity: b bounces off a wall moving with a
    ub_after = ua + restitution * (ua - ub);
  } else if (b_immovable) {
    ua_after = ub + restitution * (ub - ua);
  } else {
    const double total = mass_a + mass_b;
    ua_after = (mass_a * ua + mass_b * ub + mass_b * restitution * (ub - ua)) / total;
    ub_after = (mass_a * ua + mass_b * ub + mass_a * restitution * (ua - ub)) / total;
  }
  result.a += (ua_after - ua) * normal;
  result.b += (ub_after - ub) * normal;
  return result;
}

ContactOutcome contactOutcome(double mass_a, const Eigen::Vector3d& position_a,
                              const Eigen::Vector3d& velocity_a, double mass_b,
                              const Eigen::Vector3d& position_b, const Eigen::Vector3d& velocity_b,
                              double contact_distance, double restitution, double correction) {
  ContactOutcome outcome{false,      0,         Eigen::Vector3d::Zero(), position_a, velocity_a,
                         position_b, velocity_b};
  const Eigen::Vector3d d = position_a - position_b;
  outcome.penetration = contact_distance - d.norm();
  outcome.normal = d / d.norm();
  outcome.contact = outcome.penetration >= 0;
  if (!outcome.contact) return outcome;
  const ImpactVelocities after =
      impactVelocities(mass_a, velocity_a, mass_b, velocity_b, outcome.normal, restitution);
  outcome.velocity_a = after.a;
  outcome.velocity_b = after.b;
  const Eigen::Vector3d shift = correction * outcome.penetration * outcome.normal;
  outcome.position_a += shift;
  outcome.position_b -= shift;
  return outcome;
}

}  // namespace clothref
