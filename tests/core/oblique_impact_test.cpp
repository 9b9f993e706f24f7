// The built-in off-axis impact (`two-spheres-oblique`: restitution 0.8, 125 kg against 27 kg, a
// contact normal oblique to both velocities) stepped in float through World::step, against the
// instructor's sphere-sphere contact written in the course's idiom and evaluation order: normal
// velocity u = n (v_rel . n) first, then J = (-(1 + e) u) / (invM_b + invM_a), then the position
// correction (p n) 0.15. With e != 0 and n not along an axis, the other association orders of the
// impulse round differently; the test checks that they would, so it can see them.
#include <gtest/gtest.h>

#include <optional>

#include "clothref/core/world.h"
#include "clothref/scene/make_world.h"
#include "test_util.h"

namespace clothref {
namespace {

struct Contact {
  Eigen::Vector4f normal;
  Eigen::Matrix4Xf position, velocity;  // both spheres after the contact
  bool other_order_differs = false;     // (-(1 + e) n) s would give other bits
};

// The course's Spheres::collide() body for the pair (0, 1), on copies.
std::optional<Contact> courseContact(const Particles<float>& p, float r0, float r1, float e,
                                     float correction) {
  Contact c{Eigen::Vector4f::Zero(), p.position, p.velocity, false};
  Eigen::Vector4f normal = c.position.col(0) - c.position.col(1);
  const float penetration = (r0 + r1) - normal.norm();
  if (penetration < 0) return std::nullopt;
  normal.normalize();
  c.normal = normal;
  const Eigen::Vector4f relative = c.velocity.col(0) - c.velocity.col(1);
  const float approach = relative.dot(normal);
  if (approach < 0) {
    const Eigen::Vector4f normal_velocity = normal * approach;
    const Eigen::Vector4f impulse =
        (-(1 + e) * normal_velocity) / (p.inverse_mass[1] + p.inverse_mass[0]);
    const Eigen::Vector4f other =
        (-(1 + e) * normal) * approach / (p.inverse_mass[1] + p.inverse_mass[0]);
    for (int k = 0; k < 4; ++k)
      c.other_order_differs |= test::bits(impulse[k]) != test::bits(other[k]);
    c.velocity.col(0) += impulse * p.inverse_mass[0];
    c.velocity.col(1) -= impulse * p.inverse_mass[1];
  }
  const Eigen::Vector4f shift = penetration * normal * correction;
  c.position.col(0) += shift;
  c.position.col(1) -= shift;
  return c;
}

TEST(ObliqueImpact, FirstContactHasTheCoursesBits) {
  const Scene& scene = *findBuiltinScene("two-spheres-oblique");
  World<float> world = makeWorld<float>(scene, Method::Explicit);
  const float e = world.physics.restitution_sphere, dt = world.physics.dt;
  ASSERT_NE(e, 0.0f);
  for (int s = 0; s < 1000; ++s) {
    const Particles<float> before = world.spheres->particles;
    const std::optional<Contact> contact = courseContact(
        before, world.spheres->radius[0], world.spheres->radius[1], e, world.physics.correction);
    step(world);
    if (!contact) {
      ASSERT_EQ(world.spheres->particles.velocity, before.velocity) << "no contact, no force";
      continue;
    }
    // the contact happened in this step's simulateOneStep; explicit Euler then moved x by v dt
    // (no gravity, no drag: a = 0, so v is as the contact left it)
    const Eigen::Matrix4Xf expected_x = contact->position + contact->velocity * dt;
    const Particles<float>& after = world.spheres->particles;
    for (int i = 0; i < 2; ++i)
      for (int k = 0; k < 4; ++k) {
        EXPECT_EQ(test::bits(after.velocity(k, i)), test::bits(contact->velocity(k, i)))
            << "sphere " << i << " v[" << k << "] at step " << s;
        EXPECT_EQ(test::bits(after.position(k, i)), test::bits(expected_x(k, i)))
            << "sphere " << i << " x[" << k << "] at step " << s;
      }
    // an impact that can tell the evaluation orders apart: off-axis, e != 0
    for (int k = 0; k < 3; ++k) EXPECT_GT(std::abs(contact->normal[k]), 0.05f) << "normal " << k;
    EXPECT_TRUE(contact->other_order_differs);
    EXPECT_NE(after.velocity.col(0), before.velocity.col(0)) << "an impulse, not only a correction";
    return;
  }
  FAIL() << "the spheres never touched";
}

}  // namespace
}  // namespace clothref
