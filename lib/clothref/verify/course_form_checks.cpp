// verify's course-form family: the course scenes against the course's facts, and the fast kernels
// against the course-form stubs, bit for bit.
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

}  // namespace clothref
