#include "clothref/core/integrator.h"
#include "clothref/scene/make_world.h"

#include <cmath>

#include <gtest/gtest.h>

#include "clothref/core/world.h"
#include "test_util.h"

namespace clothref {
namespace {

// One particle on an undamped spring to a fixed anchor, along x, in double: displacement x0 from
// rest, velocity v0, omega^2 = k / m. The one-step maps of every method are known in closed form.
struct Oscillator {
  double omega2 = 100.0;  // k = 100, m = 1
  double x0 = 0.2, v0 = 0.5, h = 0.01;

  World<double> world(Method method) const {
    Scene scene = *findBuiltinScene("spring-undamped");
    scene.cloth->particles[1].position = {1 + x0, 0, 0};
    scene.cloth->particles[1].velocity = {v0, 0, 0};
    return makeWorld<double>(scene, method, h);
  }
};

// The exact one-step map of each method on x' = v, v' = -omega^2 x.
std::array<double, 2> expectedStep(Method method, const Oscillator& o) {
  const double w2 = o.omega2, h = o.h, x = o.x0, v = o.v0;
  auto a = [w2](double position) { return -w2 * position; };
  switch (method) {
    case Method::Explicit:
      return {x + h * v, v + h * a(x)};
    case Method::Symplectic: {
      const double v1 = v + h * a(x);
      return {x + h * v1, v1};
    }
    case Method::Implicit:  // derivatives read at the forward-Euler prediction
      return {x + h * (v + h * a(x)), v + h * a(x + h * v)};
    case Method::Midpoint:  // derivatives read at the half-step prediction
      return {x + h * (v + 0.5 * h * a(x)), v + h * a(x + 0.5 * h * v)};
    case Method::Rk4: {
      const double k1x = h * v, k1v = h * a(x);
      const double k2x = h * (v + k1v / 2), k2v = h * a(x + k1x / 2);
      const double k3x = h * (v + k2v / 2), k3v = h * a(x + k2x / 2);
      const double k4x = h * (v + k3v), k4v = h * a(x + k3x);
      return {x + (k1x + 2 * k2x + 2 * k3x + k4x) / 6, v + (k1v + 2 * k2v + 2 * k3v + k4v) / 6};
    }
    case Method::BackwardEuler: {  // v1 = v + h a(x + h v1), solved: the problem is linear
      const double v1 = (v + h * a(x)) / (1 + h * h * w2);
      return {x + h * v1, v1};
    }
  }
  return {0, 0};
}

class EveryMethod : public ::testing::TestWithParam<Method> {};

TEST_P(EveryMethod, OneStepMatchesTheMethodsClosedFormMap) {
  const Oscillator oscillator;
  World<double> world = oscillator.world(GetParam());
  step(world);
  const auto expected = expectedStep(GetParam(), oscillator);
  EXPECT_NEAR(world.cloth->particles.position(0, 1) - 1.0, expected[0], 1e-12);
  EXPECT_NEAR(world.cloth->particles.velocity(0, 1), expected[1], 1e-12);
  // the anchor (mass 0) stays put and the motion stays on the x axis
  EXPECT_EQ(world.cloth->particles.position.col(0), Vec4<double>(0, 0, 0, 1));
  EXPECT_EQ(world.cloth->particles.position(1, 1), 0.0);
  EXPECT_EQ(world.cloth->particles.position(3, 1), 1.0);
}

// A cloth at exact rest (grid spacing 1 m, so every spring length is exact) with gravity off has
// zero force everywhere: no method may move it by a single bit.
TEST_P(EveryMethod, ClothAtRestWithoutGravityStaysBitIdentical) {
  Scene scene = *findBuiltinScene("small-cloth");
  scene.spheres.reset();
  scene.gravity = {0, 0, 0};
  scene.cloth->grid = GridSpec{5, 2, 0, 1};
  scene.cloth->fixed = {0, 4, 20, 24};
  World<float> world = makeWorld<float>(scene, GetParam());
  const Particles<float> initial = world.cloth->particles;
  for (int i = 0; i < 1000; ++i) step(world);
  EXPECT_EQ(world.cloth->particles.position, initial.position);
  EXPECT_EQ(world.cloth->particles.velocity, initial.velocity);
}

// Under gravity the fixed corners of the course cloth never move (no sphere reaches them).
TEST_P(EveryMethod, FixedParticlesNeverMoveUnderGravity) {
  World<float> world = makeWorld<float>(*findBuiltinScene("course2022"), GetParam());
  const Particles<float> initial = world.cloth->particles;
  for (int i = 0; i < 1000; ++i) {
    step(world);
    for (int corner : {0, 24, 600, 624}) {
      ASSERT_EQ(world.cloth->particles.position.col(corner), initial.position.col(corner))
          << "corner " << corner << " step " << i;
      ASSERT_EQ(world.cloth->particles.velocity.col(corner), Vec4<float>::Zero());
    }
  }
  // and the free particles did fall
  EXPECT_LT(world.cloth->particles.position(1, 312), -1e-3f);
}

INSTANTIATE_TEST_SUITE_P(Integrators, EveryMethod, ::testing::ValuesIn(kAllMethods),
                         [](const auto& info) { return test::methodTestName(info.param); });

TEST(Method, NamesRoundTrip) {
  for (Method method : kAllMethods) {
    EXPECT_EQ(parseMethod(methodName(method)), method);
  }
  EXPECT_FALSE(parseMethod("euler").has_value());
}

}  // namespace
}  // namespace clothref
