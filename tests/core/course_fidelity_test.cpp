// Bit-for-bit fidelity to the course's code shape. The course stores particles in
// Eigen::Matrix4Xf and hands out Eigen::Ref<Eigen::Vector4f> columns; its norm() and dot() are
// Eigen's 4-wide reductions over those. The oracle below writes the instructor's spring force and
// sphere-cloth contact (course-api.md §A.16) in that idiom; the library must give the same bits.
#include <random>

#include <gtest/gtest.h>

#include "clothref/core/world.h"
#include "test_util.h"

namespace clothref {
namespace {

// The course's Particles accessors, as they are declared (course-api.md §A.5).
struct CourseParticles {
  Eigen::Matrix4Xf& x;
  Eigen::Matrix4Xf& v;
  Eigen::Matrix4Xf& a;
  const VecX<float>& inverse_mass;
  Eigen::Ref<Eigen::Vector4f> position(int i) { return x.col(i); }
  Eigen::Ref<Eigen::Vector4f> velocity(int i) { return v.col(i); }
  Eigen::Ref<Eigen::Vector4f> acceleration(int i) { return a.col(i); }
  float inverseMass(int i) { return inverse_mass[i]; }
};

void courseSpringForce(CourseParticles p, const std::vector<Spring<float>>& springs, float springCoef,
                       float damperCoef) {
  for (const auto& spring : springs) {
    const int s = spring.start, e = spring.end;
    Eigen::Vector4f d = p.position(s) - p.position(e);
    const float length = d.norm();
    d.normalize();
    const Eigen::Vector4f force =
        d * (damperCoef * (p.velocity(s) - p.velocity(e)).dot(d) + springCoef * (length - spring.rest_length));
    p.acceleration(s) -= force * p.inverseMass(s);
    p.acceleration(e) += force * p.inverseMass(e);
  }
}

void courseCollide(CourseParticles sphere, float radius, CourseParticles cloth, int count) {
  constexpr float coefRestitution = 0.0f;
  for (int j = 0; j < count; ++j) {
    Eigen::Vector4f normal = sphere.position(0) - cloth.position(j);
    const float penetration = radius - normal.norm();
    if (penetration < 0) continue;
    normal.normalize();
    const Eigen::Vector4f relative = sphere.velocity(0) - cloth.velocity(j);
    const float approach = relative.dot(normal);
    if (approach < 0) {
      const Eigen::Vector4f impulse = -(1 + coefRestitution) * normal * approach /
                                      (cloth.inverseMass(j) + sphere.inverseMass(0));
      sphere.velocity(0) += impulse * sphere.inverseMass(0);
      cloth.velocity(j) -= impulse * cloth.inverseMass(j);
    }
    const Eigen::Vector4f correction = penetration * normal * 0.15f;
    sphere.position(0) += correction;
    cloth.position(j) -= correction;
  }
}

// A small course cloth after 3000 explicit steps, with velocities scrambled so that every spring
// has a stretch and a relative velocity in all three components, and the sphere pushed into it.
World<float> scrambledCourseWorld() {
  World<float> world = makeWorld<float>(*findBuiltinScene("small-cloth"), Method::Explicit);
  for (int i = 0; i < 3000; ++i) step(world);
  std::mt19937_64 random(20261121);
  for (int i = 0; i < world.cloth->particles.size(); ++i)
    for (int k = 0; k < 3; ++k)
      world.cloth->particles.velocity(k, i) += float(random() % 2001) / 1000.0f - 1.0f;
  const int centre = 40;
  world.spheres->particles.position.col(0) =
      world.cloth->particles.position.col(centre) + Vec4<float>(0.01f, 0.3f, -0.02f, 0);
  world.spheres->particles.velocity.col(0) = Vec4<float>(0.1f, -1.0f, 0.2f, 0);
  return world;
}

TEST(CourseFidelity, SpringForceHasTheCoursesBits) {
  World<float> world = scrambledCourseWorld();
  Particles<float>& p = world.cloth->particles;
  p.acceleration.setZero();
  Eigen::Matrix4Xf course_a = p.acceleration;
  computeSpringForce(*world.cloth);
  courseSpringForce({p.position, p.velocity, course_a, p.inverse_mass}, world.cloth->springs,
                    world.cloth->spring_coef, world.cloth->damper_coef);
  for (int i = 0; i < p.size(); ++i)
    for (int k = 0; k < 4; ++k)
      ASSERT_EQ(test::bits(p.acceleration(k, i)), test::bits(course_a(k, i))) << i << "," << k;
}

TEST(CourseFidelity, SphereClothContactHasTheCoursesBits) {
  World<float> world = scrambledCourseWorld();
  Particles<float> cloth_copy = world.cloth->particles;
  Particles<float> sphere_copy = world.spheres->particles;
  int contacts = 0;
  for (int j = 0; j < cloth_copy.size(); ++j)
    contacts += (sphere_copy.position.col(0) - cloth_copy.position.col(j)).norm() <= world.spheres->radius[0];
  ASSERT_GT(contacts, 3) << "the sphere should overlap the cloth";
  collide(*world.spheres, *world.cloth, 0.0f, 0.15f);
  courseCollide({sphere_copy.position, sphere_copy.velocity, sphere_copy.acceleration, sphere_copy.inverse_mass},
                world.spheres->radius[0],
                {cloth_copy.position, cloth_copy.velocity, cloth_copy.acceleration, cloth_copy.inverse_mass},
                cloth_copy.size());
  EXPECT_EQ(world.cloth->particles.position, cloth_copy.position);
  EXPECT_EQ(world.cloth->particles.velocity, cloth_copy.velocity);
  EXPECT_EQ(world.spheres->particles.position, sphere_copy.position);
  EXPECT_EQ(world.spheres->particles.velocity, sphere_copy.velocity);
}

}  // namespace
}  // namespace clothref
