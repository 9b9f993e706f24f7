// One step of every method on particles under a constant acceleration, where each method's result
// is known exactly: forward Euler x0 + v0 h; symplectic Euler x0 + (v0 + a h) h; the course's
// implicit (one predictor-corrector pass) x0 + (v0 + a h) h; midpoint and RK4 the exact parabola
// x0 + v0 h + a h^2 / 2; every method v0 + a h. Two bodies (a cloth particle and a sphere), so a
// method that integrates only the first body fails.
//   float:  bit for bit against the course's expressions in the course's evaluation order
//   double: against the exact real-number result, within a few roundings
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "clothref/core/world.h"
#include "clothref/scene/make_world.h"
#include "test_util.h"

namespace clothref {
namespace {

constexpr double kDt = 0.01;                  // s
constexpr Vector3 kGravity{0.5, -9.8, 0.25};  // m/s^2, not axis-aligned
constexpr Vector3 kClothX{0.1, 2.0, -0.3};    // m
constexpr Vector3 kClothV{1.25, 2.5, -0.75};  // m/s
constexpr Vector3 kSphereX{5.0, 7.0, 3.0};    // far from the particle: no contact
constexpr Vector3 kSphereV{-0.3, 0.7, 1.1};   // m/s

// One free cloth particle (1.5 kg) and one sphere, both under gravity, no drag, no springs.
Scene constantAccelerationScene() {
  Scene scene;
  scene.name = "constant-acceleration";
  scene.dt = kDt;
  scene.gravity = kGravity;
  scene.viscous_coef = 0;  // a = g exactly: gravity - v * 0 * invM
  ClothSpec cloth;
  cloth.particles = {ParticleSpec{kClothX, kClothV, 1.5}};
  cloth.spring_coef = 0;
  cloth.damper_coef = 0;
  scene.cloth = cloth;
  SpheresSpec spheres;
  spheres.items = {SphereSpec{kSphereX, 0.5, kSphereV, std::nullopt}};
  spheres.external_force = true;
  spheres.sphere_sphere_collision = false;
  scene.spheres = spheres;
  return scene;
}

struct PointState {
  std::array<double, 3> x, v;
};

// The course's one step, component by component, in T and in the course's evaluation order (the
// integrator stubs of course-api: backups, `p += v * dt`, the midpoint half step `(v * dt) * 0.5`,
// RK4's `x0 + (k1 + 2 k2 + 2 k3 + k4) / 6`). With a constant acceleration every evaluation
// returns the same a, so the stages need no simulation.
template <typename T>
std::array<T, 2> courseStep(Method method, T x0, T v0, T a, T h) {
  switch (method) {
    case Method::Explicit:
      return {x0 + v0 * h, v0 + a * h};
    case Method::Symplectic: {
      const T v1 = v0 + a * h;
      return {x0 + v1 * h, v1};
    }
    case Method::Implicit: {
      const T v_pred = v0 + a * h;
      return {x0 + v_pred * h, v0 + a * h};
    }
    case Method::Midpoint: {
      const T v_mid = v0 + a * h * T(0.5);
      return {x0 + v_mid * h, v0 + a * h};
    }
    case Method::Rk4: {
      const T k1x = v0 * h, k1v = a * h;
      const T v2 = v0 + k1v * T(0.5);
      const T k2x = v2 * h, k2v = a * h;
      const T v3 = v0 + k2v * T(0.5);
      const T k3x = v3 * h, k3v = a * h;
      const T v4 = v0 + k3v;
      const T k4x = v4 * h, k4v = a * h;
      return {x0 + (k1x + T(2) * k2x + T(2) * k3x + k4x) / T(6),
              v0 + (k1v + T(2) * k2v + T(2) * k3v + k4v) / T(6)};
    }
    case Method::BackwardEuler:  // not an integrator stub: its CG is checked in tests/solver
      break;
  }
  return {T(0), T(0)};
}

// The exact real-number result of each method (long double), from the formulas in the header.
std::array<long double, 2> exactStep(Method method, long double x0, long double v0, long double a,
                                     long double h) {
  const long double v1 = v0 + a * h;
  switch (method) {
    case Method::Explicit:
      return {x0 + v0 * h, v1};
    case Method::Symplectic:
    case Method::Implicit:
      return {x0 + (v0 + a * h) * h, v1};
    case Method::Midpoint:
    case Method::Rk4:
      return {x0 + v0 * h + a * h * h / 2, v1};
    case Method::BackwardEuler:
      break;
  }
  return {0, 0};
}

class OneStep : public ::testing::TestWithParam<Method> {};

TEST_P(OneStep, FloatHasTheCoursesBitsOnBothBodies) {
  const Method method = GetParam();
  World<float> world = makeWorld<float>(constantAccelerationScene(), method);
  step(world);
  const float h = float(kDt);
  auto check = [&](const char* body, const Particles<float>& p, const Vector3& x0,
                   const Vector3& v0) {
    for (int k = 0; k < 3; ++k) {
      const auto [x, v] =
          courseStep<float>(method, float(x0[k]), float(v0[k]), float(kGravity[k]), h);
      EXPECT_EQ(test::bits(p.position(k, 0)), test::bits(x))
          << body << " x[" << k << "]: " << p.position(k, 0) << " expected " << x;
      EXPECT_EQ(test::bits(p.velocity(k, 0)), test::bits(v))
          << body << " v[" << k << "]: " << p.velocity(k, 0) << " expected " << v;
    }
    EXPECT_EQ(p.position(3, 0), 1.0f) << body << ": w of a point stays 1";
    EXPECT_EQ(p.velocity(3, 0), 0.0f) << body << ": w of a velocity stays 0";
  };
  check("cloth", world.cloth->particles, kClothX, kClothV);
  check("sphere", world.spheres->particles, kSphereX, kSphereV);
}

TEST_P(OneStep, DoubleMatchesTheExactResultOnBothBodies) {
  const Method method = GetParam();
  World<double> world = makeWorld<double>(constantAccelerationScene(), method);
  step(world);
  auto check = [&](const char* body, const Particles<double>& p, const Vector3& x0,
                   const Vector3& v0) {
    for (int k = 0; k < 3; ++k) {
      const auto [x, v] = exactStep(method, x0[k], v0[k], kGravity[k], kDt);
      // a handful of roundings of values below 10: 1e-14 is ~50 ulps
      EXPECT_NEAR(p.position(k, 0), double(x), 1e-14) << body << " x[" << k << "]";
      EXPECT_NEAR(p.velocity(k, 0), double(v), 1e-14) << body << " v[" << k << "]";
    }
  };
  check("cloth", world.cloth->particles, kClothX, kClothV);
  check("sphere", world.spheres->particles, kSphereX, kSphereV);
}

// The methods differ by a h^2 / 2 (4.9e-4 m in y here), far above the tolerance above: the test
// can tell each method from the others. Guard that the chosen numbers keep it so.
TEST(OneStepSetUp, TheMethodsAreDistinguishable) {
  const auto explicit_x = exactStep(Method::Explicit, 2.0L, 2.5L, -9.8L, kDt)[0];
  const auto symplectic_x = exactStep(Method::Symplectic, 2.0L, 2.5L, -9.8L, kDt)[0];
  const auto exact_x = exactStep(Method::Rk4, 2.0L, 2.5L, -9.8L, kDt)[0];
  EXPECT_GT(std::fabs(double(explicit_x - exact_x)), 1e-4);
  EXPECT_GT(std::fabs(double(symplectic_x - exact_x)), 1e-4);
}

// the integrator stubs' arithmetic; backward Euler's CG is checked in tests/solver
INSTANTIATE_TEST_SUITE_P(EveryMethod, OneStep, ::testing::ValuesIn(kIntegratorMethods),
                         [](const auto& info) { return test::methodTestName(info.param); });

}  // namespace
}  // namespace clothref
