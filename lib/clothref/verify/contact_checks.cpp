// verify's contact family: where one evaluation's contacts put the bodies. One cloth particle
// pressed into a sphere and one overlapping sphere pair, approaching and separating, restitution 0
// and not: the world's evaluation (simulateOneStep) against the course's equations in double
// (analytic.h contactOutcome, which never calls the library's contact formula).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "clothref/core/world.h"
#include "clothref/scene/make_world.h"
#include "clothref/verify/analytic.h"
#include "clothref/verify/check_support.h"
#include "clothref/verify/verify.h"

namespace clothref {

using namespace verify_support;

namespace {

// The course's position correction: 0.15 of the penetration, on each body (docs/course.md §3.3).
constexpr double kCourseCorrection = 0.15;

// Tolerance of a position or velocity after one contact: 16 roundings of relative size u of the
// largest quantity involved (docs/verification.md): the normal and the penetration take about
// ten (a difference, a dot product, a square root, a division), the impulse and the correction a
// few more, each on a value no larger than the largest position plus the contact distance (or
// the largest speed).
constexpr double kContactRoundings = 16;

// One overlapping pair: body a (a sphere) and body b (a cloth particle or a second sphere).
struct ContactCase {
  std::string name;
  bool sphere_pair = false;  // b is a sphere (sphere-sphere contact), else a cloth particle
  double restitution = 0;
  double radius_a = 0.5, radius_b = 0;  // metres; radius_b only for a sphere
  double mass_a = 3, mass_b = 1;        // kg, 0 = fixed
  Vector3 position_a{}, velocity_a{}, position_b{}, velocity_b{};
};

// a at the origin, b inside it along an oblique normal; "approaching" moves them together along
// it (with tangential parts), "separating" is the same pair with both velocities reversed.
std::vector<ContactCase> contactCases() {
  std::vector<ContactCase> cases;
  for (bool approaching : {true, false}) {
    const double sign = approaching ? 1 : -1;
    const std::string way = approaching ? "approaching" : "separating";
    for (double e : {0.0, 0.6}) {
      ContactCase c;
      c.name = fmt::format("particle in sphere, {}, e {:g}", way, e);
      c.restitution = e;
      c.position_a = {0, 0, 0};
      c.position_b = {0.12, -0.38, 0.2};  // 0.446 m from the centre: penetration 0.054 m
      c.velocity_a = {sign * 0.1, sign * -0.4, sign * 0.3};
      c.velocity_b = {sign * -0.2, sign * 1.5, sign * 0.1};
      cases.push_back(c);
    }
    for (double e : {0.0, 0.8}) {
      ContactCase c;
      c.name = fmt::format("sphere pair, {}, e {:g}", way, e);
      c.sphere_pair = true;
      c.restitution = e;
      c.radius_a = 0.5;
      c.radius_b = 0.4;
      c.mass_a = 8;
      c.mass_b = 3;
      c.position_a = {0.1, 0.2, -0.05};
      c.position_b = {0.8, 0.5, 0.1};  // 0.776 m apart: penetration 0.124 m
      c.velocity_a = {sign * 1, sign * 0.2, 0};
      c.velocity_b = {sign * -0.5, sign * 0.3, sign * 0.4};
      cases.push_back(c);
    }
  }
  // a fixed particle (mass 0) is immovable in the impulse, yet the correction moves it
  ContactCase fixed = cases[1];
  fixed.name = "fixed particle in sphere, approaching, e 0.6";
  fixed.mass_b = 0;
  fixed.velocity_b = {0, 0, 0};
  cases.push_back(fixed);
  return cases;
}

Scene contactScene(const ContactCase& c) {
  Scene scene = impactBaseScene("contact");
  SpheresSpec spheres;
  spheres.items = {SphereSpec{c.position_a, c.radius_a, c.velocity_a, c.mass_a}};
  spheres.external_force = false;
  spheres.correction = kCourseCorrection;
  if (c.sphere_pair) {
    spheres.items.push_back(SphereSpec{c.position_b, c.radius_b, c.velocity_b, c.mass_b});
    spheres.sphere_sphere_collision = true;
    spheres.restitution_sphere = c.restitution;
  } else {
    ClothSpec cloth;
    cloth.particles = {ParticleSpec{c.position_b, c.velocity_b, c.mass_b}};
    cloth.spring_coef = 0;
    cloth.damper_coef = 0;
    scene.cloth = cloth;
    spheres.sphere_sphere_collision = false;
    spheres.restitution_cloth = c.restitution;
  }
  scene.spheres = spheres;
  return scene;
}

// What one evaluation did against the closed form, worst of both bodies (and, for a particle,
// of both execution paths: the fast contact kernel and the course-form stub).
struct ContactMeasure {
  double position = 0;        // max |x - x_closed| (m)
  double velocity = 0;        // max |v - v_closed| (m/s)
  double velocity_moved = 0;  // max |v - v_before| (m/s): 0 for a separating pair
  double position_scale = 0;  // max |x| + contact distance (m)
  double velocity_scale = 0;  // max |v| (m/s)
  bool approaching = false;
  bool contact = false;
};

template <typename T>
void measureContact(const ContactCase& c, bool use_fast, ContactMeasure& measure) {
  World<T> world = makeWorld<T>(contactScene(c), Method::Explicit);
  setExecution(world, use_fast, fast::defaultSimdPath(), 1);
  Particles<T>& a = world.spheres->particles;
  Particles<T>& b = c.sphere_pair ? world.spheres->particles : world.cloth->particles;
  const int j = c.sphere_pair ? 1 : 0;
  // the world's own numbers (float inputs are rounded): the closed form sees what the run sees
  const Eigen::Vector3d xa = xyz(a.position.col(0)), va = xyz(a.velocity.col(0));
  const Eigen::Vector3d xb = xyz(b.position.col(j)), vb = xyz(b.velocity.col(j));
  const double distance =
      double(world.spheres->radius[0]) + (c.sphere_pair ? double(world.spheres->radius[1]) : 0);
  const double restitution =
      double(c.sphere_pair ? world.physics.restitution_sphere : world.physics.restitution_cloth);
  const ContactOutcome closed = contactOutcome(double(a.mass[0]), xa, va, double(b.mass[j]), xb, vb,
                                               distance, restitution, kCourseCorrection);
  simulateOneStep(world);
  const Eigen::Vector3d xa1 = xyz(a.position.col(0)), va1 = xyz(a.velocity.col(0));
  const Eigen::Vector3d xb1 = xyz(b.position.col(j)), vb1 = xyz(b.velocity.col(j));
  measure.position = std::max(
      {measure.position, (xa1 - closed.position_a).norm(), (xb1 - closed.position_b).norm()});
  measure.velocity = std::max(
      {measure.velocity, (va1 - closed.velocity_a).norm(), (vb1 - closed.velocity_b).norm()});
  measure.velocity_moved = std::max({measure.velocity_moved, (va1 - va).norm(), (vb1 - vb).norm()});
  measure.position_scale =
      std::max(measure.position_scale, std::max(xa.norm(), xb.norm()) + distance);
  measure.velocity_scale = std::max({measure.velocity_scale, va.norm(), vb.norm()});
  measure.approaching = (va - vb).dot(closed.normal) < 0;
  measure.contact = closed.contact;
}

}  // namespace

std::vector<CheckRow> contactChecks() {
  std::vector<CheckRow> rows;
  for (Precision precision : kPrecisions) {
    for (const ContactCase& c : contactCases()) {
      ContactMeasure m;
      withPrecision(precision, [&]<typename T>() {
        measureContact<T>(c, true, m);
        if (!c.sphere_pair) measureContact<T>(c, false, m);  // the sphere-cloth stub as well
      });
      const std::string paths = c.sphere_pair ? "" : ", fast and course-form";
      const double u = unitRoundoff(precision);
      rows.push_back(makeRow(fmt::format("contact: {}: max |x - x_closed| (m){}", c.name, paths),
                             "-", precision, 0,
                             m.contact ? m.position : std::numeric_limits<double>::quiet_NaN(),
                             kContactRoundings * u * m.position_scale));
      if (m.approaching)
        rows.push_back(
            makeRow(fmt::format("contact: {}: max |v - v_closed| (m/s){}", c.name, paths), "-",
                    precision, 0, m.velocity, kContactRoundings * u * m.velocity_scale));
      else  // a separating pair's velocities are not touched at all
        rows.push_back(
            makeRow(fmt::format("contact: {}: max |v - v_before| (m/s){}", c.name, paths), "-",
                    precision, 0, m.velocity_moved, 0));
    }
  }
  return rows;
}

}  // namespace clothref
