// computeExternalForce, the course's Shape::computeExternalForce, bit for bit: every free
// particle's acceleration is SET to gravity - (velocity * viscousCoef) * inverseMass, evaluated per
// component in that order (the course's `gravity - velocity * viscousCoef * inverseMass(i)`); a
// fixed particle's (mass 0) is set to zero. Masses and drag coefficients that are not powers of
// two, so that the association order shows in the last bit. Also the world's use of it.
#include <gtest/gtest.h>

#include <vector>

#include "clothref/core/particles.h"
#include "clothref/core/world.h"
#include "clothref/scene/make_world.h"
#include "test_util.h"

namespace clothref {
namespace {

template <typename T>
class ExternalForce : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(ExternalForce, Scalars);

// Seven particles: masses not powers of two (one fixed), velocities in every component, and an
// acceleration left over from a previous evaluation that the call must overwrite.
template <typename T>
Particles<T> sampleParticles() {
  const std::vector<T> masses = {T(3), T(0.7), T(0), T(1.3), T(125), T(64) * T(0.4), T(11)};
  Particles<T> p = makeParticles<T>(int(masses.size()), T(1));
  for (int i = 0; i < p.size(); ++i) {
    setMass(p, i, masses[std::size_t(i)]);
    p.velocity.col(i) =
        Vec4<T>(T(0.37) * T(i + 1), T(-1.9) + T(0.61) * T(i), T(2.3) / T(i + 3), T(0));
    p.acceleration.col(i) = Vec4<T>(T(100), T(-200), T(300), T(0));  // stale
  }
  return p;
}

TYPED_TEST(ExternalForce, BitsAreTheCoursesExpressionOrder) {
  using T = TypeParam;
  const Vec4<T> gravity(T(0.1), T(-9.8), T(0.3), T(0));
  int association_differs = 0;  // components where v * (c * invM) rounds differently
  for (const T drag : {T(3.4e-4), T(0.37), T(1.7)}) {
    Particles<T> p = sampleParticles<T>();
    computeExternalForce(p, gravity, drag);
    for (int i = 0; i < p.size(); ++i) {
      for (int k = 0; k < 4; ++k) {
        const T v = p.velocity(k, i);
        const T inverse_mass = p.mass[i] == T(0) ? T(0) : T(1) / p.mass[i];
        const T expected = p.mass[i] == T(0) ? T(0) : gravity[k] - (v * drag) * inverse_mass;
        EXPECT_EQ(test::bits(p.acceleration(k, i)), test::bits(expected))
            << "particle " << i << " component " << k << " drag " << drag << ": "
            << p.acceleration(k, i) << " expected " << expected;
        association_differs +=
            p.mass[i] != T(0) && gravity[k] - v * (drag * inverse_mass) != expected;
      }
    }
  }
  // the inputs are chosen so that the other association order would be seen
  EXPECT_GT(association_differs, 0);
}

TYPED_TEST(ExternalForce, DragOpposesTheVelocityAndFixedParticlesGetNothing) {
  using T = TypeParam;
  Particles<T> p = sampleParticles<T>();
  computeExternalForce(p, Vec4<T>(T(0), T(-9.8), T(0), T(0)), T(0.5));
  for (int i = 0; i < p.size(); ++i) {
    if (p.mass[i] == T(0)) {
      EXPECT_EQ(p.acceleration.col(i), Vec4<T>::Zero()) << "fixed particle " << i;
      continue;
    }
    const Vec4<T> drag = p.acceleration.col(i) - Vec4<T>(T(0), T(-9.8), T(0), T(0));
    EXPECT_LT(drag.dot(p.velocity.col(i)), T(0)) << "particle " << i;
  }
}

// One free particle on a spring to a fixed anchor, under gravity and drag: after simulateOneStep
// its acceleration is gravity + drag + spring force (the external force first, then the springs
// accumulate); the anchor's is zero.
TEST(ExternalForceInTheStep, SpringForceAddsToGravityAndDrag) {
  Scene scene = *findBuiltinScene("spring");
  scene.gravity = {0, -9.8, 0};
  scene.viscous_coef = 0.3;
  scene.cloth->particles[1].velocity = {0.4, 0.2, 0};
  World<double> world = makeWorld<double>(scene, Method::Explicit);
  simulateOneStep(world);
  const Particles<double>& p = world.cloth->particles;
  const double stretch = 1.2 - 1.0, k = 100, c = 2, m = 1;
  // the damper acts on the relative velocity along the spring (x), the drag on all of it
  const double spring_x = -(k * stretch + c * 0.4) / m;
  EXPECT_NEAR(p.acceleration(0, 1), spring_x - 0.4 * 0.3 / m, 1e-12);
  EXPECT_NEAR(p.acceleration(1, 1), -9.8 - 0.2 * 0.3 / m, 1e-12);
  EXPECT_EQ(p.acceleration.col(0), Vec4<double>::Zero());
}

// Spheres get gravity and drag only when the scene says so (2022 yes, 2024 no).
TEST(ExternalForceInTheStep, SpheresOnlyWhenTheSceneEnablesIt) {
  for (const bool enabled : {true, false}) {
    Scene scene = *findBuiltinScene("two-spheres");
    scene.gravity = {0, -9.8, 0};
    scene.viscous_coef = 0.25;
    scene.spheres->external_force = enabled;
    scene.spheres->items[0].center = {-5, 0, 0};  // apart: no contact
    World<float> world = makeWorld<float>(scene, Method::Explicit);
    simulateOneStep(world);
    const Particles<float>& p = world.spheres->particles;
    for (int i = 0; i < p.size(); ++i) {
      Vec4<float> expected = Vec4<float>::Zero();
      if (enabled) {
        expected = Vec4<float>(0, -9.8f, 0, 0);
        expected -= p.velocity.col(i) * 0.25f * p.inverse_mass[i];
      }
      EXPECT_EQ(p.acceleration.col(i), expected) << "sphere " << i << " enabled " << enabled;
    }
  }
}

}  // namespace
}  // namespace clothref
