// Closed forms (analytic.h) checked against properties that hold independently of the formulas:
// the differential equation itself (finite-difference residual), the initial conditions, known
// limits, and conservation laws of the impact.
#include "clothref/verify/analytic.h"

#include <gtest/gtest.h>

#include <cmath>

#include "clothref/io/error.h"

namespace clothref {
namespace {

// Three oscillators with k = 100, m = 1 (omega = 10): zeta = 0.1, 1 and 3.
DampedOscillator oscillator(double zeta, double u0 = 0.2, double v0 = -1.5) {
  DampedOscillator o;
  o.stiffness = 100;
  o.mass = 1;
  o.damping = zeta * 2 * std::sqrt(o.stiffness * o.mass);
  o.displacement0 = u0;
  o.velocity0 = v0;
  return o;
}

TEST(Oscillator, RegimeFollowsDampingRatio) {
  EXPECT_EQ(dampingRegime(oscillator(0.1)), DampingRegime::Under);
  EXPECT_EQ(dampingRegime(oscillator(1.0)), DampingRegime::Critical);
  EXPECT_EQ(dampingRegime(oscillator(3.0)), DampingRegime::Over);
  EXPECT_DOUBLE_EQ(naturalFrequency(oscillator(0.1)), 10);
  EXPECT_DOUBLE_EQ(dampingRatio(oscillator(0.1)), 0.1);
}

TEST(Oscillator, MeetsInitialConditionsInEveryRegime) {
  for (double zeta : {0.0, 0.1, 1.0, 3.0}) {
    const Displacement u = oscillatorState(oscillator(zeta), 0);
    EXPECT_NEAR(u.position, 0.2, 1e-15) << "zeta " << zeta;
    EXPECT_NEAR(u.velocity, -1.5, 1e-14) << "zeta " << zeta;
  }
}

// m u'' + c u' + k u = 0, with u'' by central differences of the returned velocity, and the
// returned velocity equal to the central difference of the returned position.
TEST(Oscillator, SatisfiesTheOdeInEveryRegime) {
  const double h = 1e-5;
  for (double zeta : {0.0, 0.1, 0.999, 1.0, 1.001, 3.0}) {
    const DampedOscillator o = oscillator(zeta);
    for (double t : {0.05, 0.3, 0.77, 1.4}) {
      const Displacement u = oscillatorState(o, t);
      const Displacement before = oscillatorState(o, t - h);
      const Displacement after = oscillatorState(o, t + h);
      const double acceleration = (after.velocity - before.velocity) / (2 * h);
      const double residual =
          o.mass * acceleration + o.damping * u.velocity + o.stiffness * u.position;
      // scale: the spring force at the initial displacement, 20 N
      EXPECT_NEAR(residual, 0, 1e-6 * 20) << "zeta " << zeta << " t " << t;
      EXPECT_NEAR(u.velocity, (after.position - before.position) / (2 * h), 1e-7)
          << "zeta " << zeta << " t " << t;
    }
  }
}

TEST(Oscillator, UndampedLimitIsCosineAndSine) {
  for (double zeta : {0.0, 1e-12}) {
    const DampedOscillator o = oscillator(zeta);
    for (double t : {0.1, 1.0, 5.0}) {
      EXPECT_NEAR(oscillatorState(o, t).position, 0.2 * std::cos(10 * t) - 0.15 * std::sin(10 * t),
                  1e-10);
    }
  }
}

// The three formulas meet at zeta = 1: the solution depends continuously on the damping.
TEST(Oscillator, RegimesAgreeNearCriticalDamping) {
  for (double t : {0.05, 0.2, 0.6}) {
    const double critical = oscillatorState(oscillator(1.0), t).position;
    EXPECT_NEAR(oscillatorState(oscillator(1 - 1e-7), t).position, critical, 1e-6);
    EXPECT_NEAR(oscillatorState(oscillator(1 + 1e-7), t).position, critical, 1e-6);
  }
}

TEST(Oscillator, DampedMotionDecays) {
  for (double zeta : {0.1, 1.0, 3.0}) {
    const Displacement late = oscillatorState(oscillator(zeta), 20);
    EXPECT_LT(std::abs(late.position), 1e-6) << "zeta " << zeta;
  }
}

TEST(SpringProblem, ReadsTheSpringScene) {
  const SpringProblem problem = springProblem(*findBuiltinScene("spring"));
  EXPECT_EQ(problem.particle, 1);
  EXPECT_DOUBLE_EQ(naturalFrequency(problem.oscillator), 10);
  EXPECT_DOUBLE_EQ(dampingRatio(problem.oscillator), 0.1);
  EXPECT_NEAR(problem.oscillator.displacement0, 0.2, 1e-15);
  const PointState start = springState(problem, 0);
  EXPECT_NEAR((start.position - Eigen::Vector3d(1.2, 0, 0)).norm(), 0, 1e-15);
  EXPECT_EQ(start.velocity, Eigen::Vector3d::Zero());
  // half a period later the undamped particle is at the other turning point, 0.8 m
  const SpringProblem undamped = springProblem(*findBuiltinScene("spring-undamped"));
  EXPECT_NEAR(springState(undamped, M_PI / 10).position.x(), 0.8, 1e-12);
}

TEST(SpringProblem, RejectsScenesThatAreNotOneSpring) {
  EXPECT_THROW(springProblem(*findBuiltinScene("free-fall")), InputError);
  EXPECT_THROW(springProblem(*findBuiltinScene("course2022")), InputError);
  Scene sideways = *findBuiltinScene("spring");
  sideways.cloth->particles[1].velocity = {0, 1, 0};
  EXPECT_THROW(springProblem(sideways), InputError);
}

DragFall fall(double drag) {
  Scene scene = *findBuiltinScene("free-fall");
  scene.viscous_coef = drag;
  return dragFallProblem(scene);
}

TEST(DragFall, MeetsInitialConditionsAndTheOde) {
  const DragFall f = fall(0.5);
  const PointState start = dragFallState(f, 0);
  EXPECT_NEAR((start.position - Eigen::Vector3d(0, 10, 0)).norm(), 0, 1e-15);
  EXPECT_NEAR((start.velocity - Eigen::Vector3d(2, 5, 0)).norm(), 0, 1e-15);
  const double h = 1e-5;
  for (double t : {0.1, 0.9, 3.0}) {
    const PointState now = dragFallState(f, t);
    const Eigen::Vector3d acceleration =
        (dragFallState(f, t + h).velocity - dragFallState(f, t - h).velocity) / (2 * h);
    const Eigen::Vector3d residual = acceleration - (f.gravity - now.velocity * f.drag / f.mass);
    EXPECT_LT(residual.norm(), 1e-7) << "t " << t;
    const Eigen::Vector3d slope =
        (dragFallState(f, t + h).position - dragFallState(f, t - h).position) / (2 * h);
    EXPECT_LT((slope - now.velocity).norm(), 1e-8) << "t " << t;
  }
}

// w = t c / m = 1e-2 switches from the series to the closed form: both must agree there.
TEST(DragFall, SeriesAndClosedFormMeet) {
  const DragFall f = fall(0.5);
  const double t = 1e-2 / 0.5;
  const PointState below = dragFallState(f, std::nextafter(t, 0.0));
  const PointState above = dragFallState(f, std::nextafter(t, 1.0));
  EXPECT_LT((below.position - above.position).norm(), 1e-13);
  EXPECT_LT((below.velocity - above.velocity).norm(), 1e-13);
}

TEST(DragFall, NoDragIsTheParabolaAndLongTimesReachTerminalVelocity) {
  const double t = 1.3;
  const Eigen::Vector3d parabola(2 * t, 10 + 5 * t - 4.9 * t * t, 0);
  EXPECT_LT((dragFallState(fall(0), t).position - parabola).norm(), 1e-12);
  EXPECT_LT((dragFallState(fall(1e-9), t).position - parabola).norm(), 1e-8);
  // terminal velocity g m / c = (0, -19.6, 0)
  EXPECT_LT((dragFallState(fall(0.5), 60).velocity - Eigen::Vector3d(0, -19.6, 0)).norm(), 1e-9);
}

// An oblique impact: normal not along either velocity, so there is a tangential part.
struct Impact {
  double ma, mb;
  Eigen::Vector3d va, vb, normal;
};

Impact obliqueImpact(double ma, double mb) {
  return {ma, mb, Eigen::Vector3d(-2, 0.5, 0.3), Eigen::Vector3d(1, -0.4, 0.2),
          Eigen::Vector3d(1, 0.3, -0.2).normalized()};
}

TEST(ImpactVelocities, ConservesMomentumAndRestoresNormalSpeedByE) {
  for (double ratio : {1.0, 10.0, 100.0}) {
    for (double e : {0.0, 0.25, 0.5, 0.8, 1.0}) {
      const Impact c = obliqueImpact(125, 125 * ratio);
      const ImpactVelocities out = impactVelocities(c.ma, c.va, c.mb, c.vb, c.normal, e);
      const Eigen::Vector3d before = c.ma * c.va + c.mb * c.vb;
      const Eigen::Vector3d after = c.ma * out.a + c.mb * out.b;
      EXPECT_LT((after - before).norm(), 1e-12 * (c.ma * c.va.norm() + c.mb * c.vb.norm()));
      const double approach = (c.va - c.vb).dot(c.normal);
      ASSERT_LT(approach, 0);
      EXPECT_NEAR((out.a - out.b).dot(c.normal), -e * approach, 1e-12);
      // tangential parts untouched
      auto tangential = [&c](const Eigen::Vector3d& v) { return v - v.dot(c.normal) * c.normal; };
      EXPECT_LT((tangential(out.a) - tangential(c.va)).norm(), 1e-12);
      EXPECT_LT((tangential(out.b) - tangential(c.vb)).norm(), 1e-12);
      // energy falls by (1 - e^2) mu (v_rel . n)^2 / 2 (reduced mass μ; docs/verification.md)
      auto energy = [&c](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
        return 0.5 * c.ma * a.squaredNorm() + 0.5 * c.mb * b.squaredNorm();
      };
      const double mu = c.ma * c.mb / (c.ma + c.mb);
      EXPECT_NEAR(energy(c.va, c.vb) - energy(out.a, out.b),
                  (1 - e * e) * 0.5 * mu * approach * approach, 1e-9 * energy(c.va, c.vb));
    }
  }
}

TEST(ImpactVelocities, ImmovableBodyIsTheHeavyLimit) {
  const Impact c = obliqueImpact(1, 0);
  for (double e : {0.0, 0.5, 1.0}) {
    const ImpactVelocities wall = impactVelocities(c.ma, c.va, 0, c.vb, c.normal, e);
    const ImpactVelocities heavy = impactVelocities(c.ma, c.va, 1e13, c.vb, c.normal, e);
    EXPECT_EQ(wall.b, c.vb);
    EXPECT_LT((wall.a - heavy.a).norm(), 1e-9);
    // and the same with the roles swapped
    const ImpactVelocities swapped = impactVelocities(0, c.vb, c.ma, c.va, -c.normal, e);
    EXPECT_EQ(swapped.a, c.vb);
    EXPECT_LT((swapped.b - wall.a).norm(), 1e-15);
  }
}

TEST(ImpactVelocities, SeparatingBodiesKeepTheirVelocities) {
  const Impact c = obliqueImpact(1, 2);
  const ImpactVelocities out = impactVelocities(c.ma, c.va, c.mb, c.vb, -c.normal, 0.5);
  EXPECT_EQ(out.a, c.va);
  EXPECT_EQ(out.b, c.vb);
}

// The contact's closed form: the positions move apart along the normal by 2 * 0.15 * p in total,
// each body by 0.15 p whatever its mass (a fixed particle too); the velocities are the impact's.
TEST(ContactOutcome, CorrectsBothBodiesAndAppliesTheImpactOnlyWhenApproaching) {
  const Eigen::Vector3d xa(0.1, 0.2, -0.05), xb(0.8, 0.5, 0.1);
  const double distance = 0.9;
  const double gap = (xa - xb).norm();
  const Eigen::Vector3d n = (xa - xb) / gap;
  const Eigen::Vector3d va(1, 0.2, 0), vb(-0.5, 0.3, 0.4);
  ASSERT_LT((va - vb).dot(n), 0);  // approaching
  for (double mb : {3.0, 0.0}) {
    for (double e : {0.0, 0.8}) {
      const ContactOutcome out = contactOutcome(8, xa, va, mb, xb, vb, distance, e, 0.15);
      ASSERT_TRUE(out.contact);
      EXPECT_NEAR(out.penetration, distance - gap, 1e-15);
      EXPECT_LT((out.normal - n).norm(), 1e-15);
      // separation grows by 0.3 p along n; each body moved by 0.15 p, the unweighted midpoint stays
      EXPECT_NEAR((out.position_a - out.position_b).dot(n), gap + 0.3 * (distance - gap), 1e-15);
      EXPECT_NEAR((out.position_a - xa).norm(), 0.15 * (distance - gap), 1e-15);
      EXPECT_NEAR((out.position_b - xb).norm(), 0.15 * (distance - gap), 1e-15);
      EXPECT_LT((out.position_a + out.position_b - xa - xb).norm(), 1e-15);
      const ImpactVelocities impact = impactVelocities(8, va, mb, vb, n, e);
      EXPECT_LT((out.velocity_a - impact.a).norm(), 1e-15);
      EXPECT_LT((out.velocity_b - impact.b).norm(), 1e-15);
      EXPECT_NEAR((out.velocity_a - out.velocity_b).dot(n), -e * (va - vb).dot(n), 1e-12);
      if (mb == 0) {
        EXPECT_EQ(out.velocity_b, vb);  // immovable in the impulse, not in position
      }
    }
  }
  // separating: velocities untouched, positions corrected all the same
  const ContactOutcome apart = contactOutcome(8, xa, -va, 3, xb, -vb, distance, 0.8, 0.15);
  ASSERT_TRUE(apart.contact);
  EXPECT_EQ(apart.velocity_a, -va);
  EXPECT_EQ(apart.velocity_b, -vb);
  EXPECT_NEAR((apart.position_a - xa).norm(), 0.15 * (distance - gap), 1e-15);
  // out of reach: nothing moves; touching (p = 0) counts as a contact
  const ContactOutcome far = contactOutcome(8, xa, va, 3, xb, vb, 0.5, 0.8, 0.15);
  EXPECT_FALSE(far.contact);
  EXPECT_EQ(far.position_a, xa);
  EXPECT_EQ(far.velocity_b, vb);
  EXPECT_TRUE(
      contactOutcome(1, Eigen::Vector3d(1, 0, 0), va, 1, Eigen::Vector3d(0, 0, 0), vb, 1, 0, 0.15)
          .contact);
}

}  // namespace
}  // namespace clothref
