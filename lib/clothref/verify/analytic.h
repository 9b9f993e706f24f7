// Closed-form solutions the checks compare the simulation against (docs/verification.md).
//
//   damped oscillator  m u'' + c u' + k u = 0, u = spring length - rest length (metres), in the
//                      under-, critically and over-damped regimes; fits the `spring` scenes
//   linear-drag fall   x'' = g - x' c / m per component (the course's drag); fits `free-fall`
//   impact             post-impact velocities of two bodies meeting along a unit normal with
//                      restitution e; the textbook mass-weighted formula (docs/course.md §1),
//                      with mass 0 meaning immovable (a fixed cloth particle, §3.3)
//   contact            where one contact of the course puts two overlapping bodies: the impact
//                      above while they approach, and always the position correction (§3.3)
//
// Everything here is double: the closed forms are the reference a float or double run is
// measured against.
#pragma once

#include <Eigen/Core>

#include "clothref/scene/scene.h"

namespace clothref {

// A 1-D damped harmonic oscillator.
//   stiffness k (N/m) > 0, damping c (N s/m) >= 0, mass m (kg) > 0
//   displacement0 u(0) (m), velocity0 u'(0) (m/s)
struct DampedOscillator {
  double stiffness = 1;
  double damping = 0;
  double mass = 1;
  double displacement0 = 0;
  double velocity0 = 0;
};

enum class DampingRegime { Under, Critical, Over };

// Critical when c^2 and 4 k m agree to 1e-12 relative (a scene written with c = 2 sqrt(k m)
// lands there despite rounding), under below, over above.
DampingRegime dampingRegime(const DampedOscillator& oscillator);

// Natural angular frequency sqrt(k / m) (rad/s) and damping ratio c / (2 sqrt(k m)).
double naturalFrequency(const DampedOscillator& oscillator);
double dampingRatio(const DampedOscillator& oscillator);

// u(t) (m) and u'(t) (m/s).
struct Displacement {
  double position = 0;
  double velocity = 0;
};

// The exact motion at time t >= 0 (seconds).
Displacement oscillatorState(const DampedOscillator& oscillator, double t);

// Position (m, 3-vector) and velocity (m/s) of one particle.
struct PointState {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
};

// A spring scene read as an oscillator: a fixed anchor, one free particle on one spring, moving
// along the spring's axis (the course's damper and drag then act along that axis only).
//   particle  index of the free particle in the scene's cloth
//   anchor    position of the fixed particle (m); axis: unit vector from anchor to particle
//   oscillator.damping = damper_coef + viscous_coef (both are linear in the axial velocity)
struct SpringProblem {
  DampedOscillator oscillator;
  double rest_length = 1;
  Eigen::Vector3d anchor = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();
  int particle = 1;
};

// Reads a spring problem from a scene: two explicit particles (one with mass 0), one spring,
// no spheres, zero gravity, initial velocity along the axis. Throws InputError naming the
// scene and what does not fit otherwise.
SpringProblem springProblem(const Scene& scene);

// Whether springProblem accepts the scene (the analyses take another path for any other scene).
bool isSpringScene(const Scene& scene);

// The free particle's exact state at time t.
PointState springState(const SpringProblem& problem, double t);

// One particle under gravity g (m/s^2) and linear drag c (kg/s): x'' = g - x' c / m.
struct DragFall {
  Eigen::Vector3d position0 = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity0 = Eigen::Vector3d::Zero();
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();
  double drag = 0;
  double mass = 1;
};

// Reads a fall problem from a scene: one explicit free particle, no springs, no spheres.
// Throws InputError otherwise.
DragFall dragFallProblem(const Scene& scene);

// The exact state at time t: v = v_inf + (v0 - v_inf) e^(-t/tau), tau = m / c, v_inf = g tau,
// and its integral; for c = 0 the ballistic parabola (one formula covers both, see the .cpp).
PointState dragFallState(const DragFall& fall, double t);

// The velocities of bodies a and b right after an impact along the unit `normal` (pointing
// from b to a), restitution e in [0, 1]. Masses in kg, 0 = immovable. Only the normal
// components change: with u = normal components, u_a' = (m_a u_a + m_b u_b + m_b e (u_b - u_a))
// / (m_a + m_b) and symmetrically for b. Bodies already separating ((v_a - v_b) . n >= 0), or
// two immovable ones, keep their velocities.
struct ImpactVelocities {
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
};

ImpactVelocities impactVelocities(double mass_a, const Eigen::Vector3d& velocity_a, double mass_b,
                                  const Eigen::Vector3d& velocity_b, const Eigen::Vector3d& normal,
                                  double restitution);

// One contact of the course between body a (a sphere) and body b (a cloth particle or another
// sphere), written from the course's equations (docs/course.md §3.3), not from the library's
// formula: with d = x_a - x_b, penetration p = contact_distance - |d| and n = d / |d|, when
// p >= 0 the velocities become impactVelocities(m_a, v_a, m_b, v_b, n, e) (unchanged when the
// bodies separate) and the positions x_a + correction p n, x_b - correction p n (both bodies,
// whatever their masses). Masses in kg, 0 = immovable; |d| > 0.
struct ContactOutcome {
  bool contact = false;  // p >= 0
  double penetration = 0;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  Eigen::Vector3d position_a, velocity_a, position_b, velocity_b;
};

ContactOutcome contactOutcome(double mass_a, const Eigen::Vector3d& position_a,
                              const Eigen::Vector3d& velocity_a, double mass_b,
                              const Eigen::Vector3d& position_b, const Eigen::Vector3d& velocity_b,
                              double contact_distance, double restitution, double correction);

}  // namespace clothref
