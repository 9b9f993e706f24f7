// The grader's mistake variants (grader/grade/mistakes/formula_variants.h): with no mistake they
// are the library's stubs bit for bit (so a variant that matches a student's numbers differs from
// the course only by its mistake), and each mistake changes something on a state where it can.
#include "grader/grade/mistakes/formula_variants.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>

namespace clothref::grader {
namespace {

bool sameBits(const Mat4X<float>& a, const Mat4X<float>& b) {
  return a.cols() == b.cols() && std::memcmp(a.data(), b.data(), sizeof(float) * a.size()) == 0;
}

// A 6 x 6 course cloth, perturbed and moving, one corner fixed, some heavy particles.
Cloth<float> randomCloth(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  Cloth<float> cloth;
  cloth.particles = initializeVertex<float>(6, 2.0f, 0.0f, 1.0f);
  initializeSpring(cloth, 6);
  cloth.spring_coef = 25000.0f;
  cloth.damper_coef = 750.0f;
  for (int i = 0; i < cloth.particles.size(); ++i) {
    for (int r = 0; r < 3; ++r) {
      cloth.particles.position(r, i) += 0.05f * u(rng);
      cloth.particles.velocity(r, i) = u(rng);
      cloth.particles.acceleration(r, i) = 3 * u(rng);
    }
    if (i % 7 == 3) setMass(cloth.particles, i, 2.5f);
  }
  setMass(cloth.particles, 0, 0.0f);
  return cloth;
}

TEST(FormulaVariants, NoMistakeSpringForceIsTheLibrarysStub) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 50; ++trial) {
    Cloth<float> cloth = randomCloth(rng);
    const Mat4X<float> acc0 = cloth.particles.acceleration;
    const Mat4X<float> variant = springAccelerations(cloth, acc0, ForceMistake::None);
    computeSpringForce(cloth);
    ASSERT_TRUE(sameBits(variant, cloth.particles.acceleration)) << "trial " << trial;
  }
}

TEST(FormulaVariants, EverySpringMistakeChangesARandomState) {
  std::mt19937 rng(8);
  const Cloth<float> cloth = randomCloth(rng);
  const Mat4X<float>& acc0 = cloth.particles.acceleration;
  const Mat4X<float> course = springAccelerations(cloth, acc0, ForceMistake::None);
  for (ForceMistake m :
       {ForceMistake::Assign, ForceMistake::SpringSign, ForceMistake::DamperSign,
        ForceMistake::NoDamper, ForceMistake::DamperUnnormalised, ForceMistake::OneEnd,
        ForceMistake::MassNotInverse, ForceMistake::DivideByMass, ForceMistake::OtherEndOnly,
        ForceMistake::AssignTotal, ForceMistake::AssignTotalGravity})
    EXPECT_FALSE(sameBits(springAccelerations(cloth, acc0, m), course)) << int(m);
}

// Three spheres and a 5 x 5 cloth close together: many contacts, approaching and separating,
// touching, a fixed particle.
void randomScene(std::mt19937& rng, Spheres<float>& spheres, Cloth<float>& cloth) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  cloth = Cloth<float>{};
  cloth.particles = initializeVertex<float>(5, 1.0f, 0.0f, 1.0f);
  setMass(cloth.particles, 0, 0.0f);
  spheres = Spheres<float>{};
  const float radii[] = {0.3f, 0.3f, 0.5f};
  for (float r : radii)
    addSphere(spheres, Vec4<float>(0.5f * u(rng), 0.2f * u(rng), 0.5f * u(rng), 1), r, 1000.0f);
  for (int i = 0; i < cloth.particles.size(); ++i)
    for (int r = 0; r < 3; ++r) cloth.particles.velocity(r, i) = u(rng);
  for (int i = 0; i < spheres.size(); ++i)
    for (int r = 0; r < 3; ++r) spheres.particles.velocity(r, i) = u(rng);
}

TEST(FormulaVariants, NoMistakeContactIsTheLibrarysStub) {
  std::mt19937 rng(9);
  int contacts = 0;
  for (int trial = 0; trial < 50; ++trial)
    for (const bool sphere_sphere : {false, true})
      for (const float e : {0.0f, 0.8f}) {
        Spheres<float> spheres, course_spheres;
        Cloth<float> cloth, course_cloth;
        randomScene(rng, spheres, cloth);
        course_spheres = spheres;
        course_cloth = cloth;
        collideWithMistake(spheres, cloth, sphere_sphere, e, 0.15f, ContactMistake::None);
        if (sphere_sphere)
          collide(course_spheres, e, 0.15f);
        else
          collide(course_spheres, course_cloth, e, 0.15f);
        ASSERT_TRUE(sameBits(spheres.particles.position, course_spheres.particles.position));
        ASSERT_TRUE(sameBits(spheres.particles.velocity, course_spheres.particles.velocity));
        ASSERT_TRUE(sameBits(cloth.particles.position, course_cloth.particles.position));
        ASSERT_TRUE(sameBits(cloth.particles.velocity, course_cloth.particles.velocity));
        if (!sameBits(cloth.particles.position,
                      initializeVertex<float>(5, 1.0f, 0.0f, 1.0f).position))
          ++contacts;
      }
  EXPECT_GT(contacts, 20);  // the scenes did have contacts
}

TEST(FormulaVariants, EveryContactMistakeChangesSomething) {
  std::mt19937 rng(10);
  for (int m = 1; m <= int(ContactMistake::ImpulseNotDivided); ++m) {
    const auto mistake = ContactMistake(m);
    const bool sphere_sphere = mistake == ContactMistake::PairTwice;
    bool changed = false;
    for (int trial = 0; trial < 200 && !changed; ++trial) {
      Spheres<float> spheres, course_spheres;
      Cloth<float> cloth, course_cloth;
      randomScene(rng, spheres, cloth);
      if (mistake == ContactMistake::TouchingSkipped) {  // exactly touching: |x_a - x_b| = r
        spheres.particles.position.col(0) = cloth.particles.position.col(12);
        spheres.particles.position(1, 0) += 0.25f;
        spheres.radius[0] = 0.25f;
        spheres.particles.velocity.col(0) = Vec4<float>(0, -1, 0, 0);
      }
      course_spheres = spheres;
      course_cloth = cloth;
      const float e = mistake == ContactMistake::RestitutionZero ? 0.8f : 0.0f;
      collideWithMistake(spheres, cloth, sphere_sphere, e, 0.15f, mistake);
      collideWithMistake(course_spheres, course_cloth, sphere_sphere, e, 0.15f,
                         ContactMistake::None);
      changed = !sameBits(spheres.particles.velocity, course_spheres.particles.velocity) ||
                !sameBits(spheres.particles.position, course_spheres.particles.position) ||
                !sameBits(cloth.particles.velocity, course_cloth.particles.velocity) ||
                !sameBits(cloth.particles.position, course_cloth.particles.position);
    }
    EXPECT_TRUE(changed) << "mistake " << m;
  }
}

}  // namespace
}  // namespace clothref::grader
