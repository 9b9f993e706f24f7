// The integrator probe's systems (grader/grade/probes/integrate/systems.h): its simulateOneStep,
// a copy of the course's order with switches, is the library's simulateOneStep bit for bit; the
// integrators are the library's method-table rows; the stability limit is the theory's.
#include "grader/grade/probes/integrate/systems.h"

#include <gtest/gtest.h>

#include <complex>
#include <cstring>

#include "clothref/core/world.h"
#include "grader/grade/results.h"

namespace clothref::grader::integrators {
namespace {

bool bitEqual(const Mat4X<float>& a, const Mat4X<float>& b) {
  return a.cols() == b.cols() &&
         std::memcmp(a.data(), b.data(), sizeof(float) * std::size_t(a.size())) == 0;
}

void expectBitEqual(const Particles<float>& a, const Particles<float>& b, const char* what) {
  EXPECT_TRUE(bitEqual(a.position, b.position)) << what << " position";
  EXPECT_TRUE(bitEqual(a.velocity, b.velocity)) << what << " velocity";
  EXPECT_TRUE(bitEqual(a.acceleration, b.acceleration)) << what << " acceleration";
}

// The library's world of the same bodies and parameters (sphere-cloth contact always on).
World<float> worldOf(const System& s) {
  World<float> w;
  w.cloth = s.cloth;
  w.spheres = s.spheres;
  w.physics.dt = s.dt;
  w.physics.gravity = s.gravity;
  w.physics.viscous_coef = s.viscous;
  w.physics.sphere_external_force = s.sphere_gravity;
  w.physics.restitution_cloth = 0.0f;
  w.physics.correction = 0.15f;
  return w;
}

TEST(IntegrateSystems, SimulateIsTheLibrarysSimulateOneStep) {
  std::vector<System> systems;
  for (std::uint64_t seed : {20221u, 20228u, 7u}) {
    systems.push_back(randomSystem(seed));
    System no_sphere_gravity = randomSystem(seed);
    no_sphere_gravity.sphere_gravity = false;
    systems.push_back(no_sphere_gravity);
  }
  for (int edition : {2022, 2024}) {
    System course = courseSystem(20221, edition);
    course.contact = true;  // the 2024 sphere touches the cloth: contacts happen
    systems.push_back(course);
  }
  for (const System& system : systems) {
    for (bool fast : {true, false}) {
      System ours = system;
      World<float> library = worldOf(system);
      setExecution(library, fast, fast::defaultSimdPath(), 1);
      for (int step = 0; step < 3; ++step) {  // moved states too
        simulate(ours);
        simulateOneStep(library);
        expectBitEqual(ours.cloth.particles, library.cloth->particles, "cloth");
        expectBitEqual(ours.spheres.particles, library.spheres->particles, "spheres");
        ours.cloth.particles.position += ours.cloth.particles.velocity * 0.01f;
        library.cloth->particles.position += library.cloth->particles.velocity * 0.01f;
      }
    }
  }
  // The test can fail: drag on the spheres switched off in one of them only.
  System ours = randomSystem(3);
  World<float> library = worldOf(ours);
  library.physics.sphere_external_force = false;
  simulate(ours);
  simulateOneStep(library);
  EXPECT_FALSE(
      bitEqual(ours.spheres.particles.acceleration, library.spheres->particles.acceleration));
}

TEST(IntegrateSystems, IntegratorsAreTheLibrarysCourseRows) {
  const Method expected[] = {Method::Explicit, Method::Implicit, Method::Midpoint, Method::Rk4};
  for (int index = 0; index < 4; ++index) {
    const Method method = integratorMethod(index);
    EXPECT_EQ(method, expected[index]);
    const MethodInfo& info = methodInfo(method);
    EXPECT_EQ(info.origin, MethodOrigin::Course);
    EXPECT_EQ(std::string(info.course_name) + "::integrate", stubName(integratorStub(index)));
  }
}

// The limit is where one step's amplification on the spring's eigenvalue reaches 1.
TEST(IntegrateSystems, StabilityLimitIsWhereTheAmplificationReachesOne) {
  const std::complex<double> lambda(-1.0, std::sqrt(99.0));  // k = 100, c = 2, m = 1
  for (int index = 0; index < 4; ++index) {
    const Method method = integratorMethod(index);
    const double limit = stabilityLimit(method);
    const auto radius = [&](double h) {
      return std::abs(amplification(methodInfo(method).amplification, lambda * h));
    };
    EXPECT_LE(radius(limit), 1 + 1e-12) << methodName(method);
    EXPECT_GT(radius(limit * (1 + 1e-9)), 1) << methodName(method);
  }
  EXPECT_NEAR(stabilityLimit(Method::Explicit), 0.02, 1e-12);  // |1 + h lambda| = 1
}

}  // namespace
}  // namespace clothref::grader::integrators
