// The grader's mistake variants (grader/grade/mistakes/formula_variants.h): with no mistake they
// are the library's stubs bit for bit (so a variant that matches a student's numbers differs from
// the course only by its mistake), and each mistake changes something on a state where it can.
#include "grader/grade/mistakes/formula_variants.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>

#include "grader/grade/cause_ids.h"

namespace clothref::grader {
namespace {

const Vec4<float> kGravity(0, -9.8f, 0, 0);  // m/s^2, what an assigned sum adds back

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
    const Mat4X<float> variant = springAccelerations(cloth, acc0, ForceRow{}, kGravity);
    computeSpringForce(cloth);
    ASSERT_TRUE(sameBits(variant, cloth.particles.acceleration)) << "trial " << trial;
  }
}

TEST(FormulaVariants, EverySpringMistakeChangesARandomState) {
  std::mt19937 rng(8);
  const Cloth<float> cloth = randomCloth(rng);
  const Mat4X<float>& acc0 = cloth.particles.acceleration;
  const Mat4X<float> course = springAccelerations(cloth, acc0, ForceRow{}, kGravity);
  // every row, those the probe simulates and those it only replays
  for (const ForceRow& row : forceRows())
    EXPECT_FALSE(sameBits(springAccelerations(cloth, acc0, row, kGravity), course))
        << row.cause << " (row " << row.row << ")";
  EXPECT_GT(forceRows().size(), 10u);
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
        collideWithMistake(spheres, cloth, sphere_sphere, e, 0.15f, ContactRow{});
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

// Every row of both collision probes (contactRows()) changes the outcome of some random scene;
// every other scene also drops sphere 0 onto the fixed particle 0.
TEST(FormulaVariants, EveryContactMistakeChangesSomething) {
  std::mt19937 rng(10);
  int rows = 0;
  for (const bool sphere_sphere : {false, true})
    for (const ContactRow& row : contactRows(sphere_sphere)) {
      ++rows;
      const bool touching = row.cause == std::string(cause::kTouchingSkipped);
      bool changed = false;
      for (int trial = 0; trial < 200 && !changed; ++trial) {
        Spheres<float> spheres, course_spheres;
        Cloth<float> cloth, course_cloth;
        randomScene(rng, spheres, cloth);
        if (trial % 2 == 1) {  // onto the fixed particle 0
          spheres.particles.position.col(0) = cloth.particles.position.col(0);
          spheres.particles.position(1, 0) += 0.2f;
          spheres.particles.velocity.col(0) = Vec4<float>(0, -1, 0, 0);
        }
        if (touching && sphere_sphere) {  // |x_0 - x_1| = r_0 + r_1
          spheres.particles.position.col(0) = Vec4<float>(0, 0, 0, 1);
          spheres.particles.position.col(1) =
              Vec4<float>(0, spheres.radius[0] + spheres.radius[1], 0, 1);
          spheres.particles.position.col(2) = Vec4<float>(10, 10, 10, 1);
          spheres.particles.velocity.col(1) = Vec4<float>(0, -1, 0, 0);
        } else if (touching) {  // |x_a - x_b| = r
          spheres.particles.position.col(0) = cloth.particles.position.col(12);
          spheres.particles.position(1, 0) += 0.25f;
          spheres.radius[0] = 0.25f;
          spheres.particles.velocity.col(0) = Vec4<float>(0, -1, 0, 0);
        }
        course_spheres = spheres;
        course_cloth = cloth;
        // a restitution overwritten (with 0 or 1) against the course's 0.8
        const float e = row.cause == std::string(cause::kRestitutionIgnored) ? 0.8f : 0.0f;
        collideWithMistake(spheres, cloth, sphere_sphere, e, 0.15f, row);
        collideWithMistake(course_spheres, course_cloth, sphere_sphere, e, 0.15f, ContactRow{});
        changed = !sameBits(spheres.particles.velocity, course_spheres.particles.velocity) ||
                  !sameBits(spheres.particles.position, course_spheres.particles.position) ||
                  !sameBits(cloth.particles.velocity, course_cloth.particles.velocity) ||
                  !sameBits(cloth.particles.position, course_cloth.particles.position);
      }
      EXPECT_TRUE(changed) << row.cause << " (row " << row.row << ": " << row.text << ")";
    }
  EXPECT_GT(rows, 20);
}

// A fixed particle read as massless (the textbook exchange of normal velocities, the grader's own
// formula, no longer the library's): the course's contact test and correction are untouched (the
// positions are the course's bit for bit); a free pair's velocities are the course's impulse to
// rounding (the exchange is the impulse rearranged); a fixed particle, massless, gets the normal
// velocity u_s + e (u_s - u_p) from the sphere's u_s and its own u_p.
TEST(FormulaVariants, TheMasslessExchangeKeepsTheCoursesGeometry) {
  std::mt19937 rng(13);
  int fixed_contacts = 0;
  for (int trial = 0; trial < 50; ++trial)
    for (const float e : {0.0f, 0.8f})
      for (const int below : {0, 12}) {  // onto the fixed particle 0, or free particle 12
        Spheres<float> spheres, course_spheres;
        Cloth<float> cloth, course_cloth;
        randomScene(rng, spheres, cloth);
        spheres = Spheres<float>{};  // one sphere, falling onto `below` and its neighbours
        Vec4<float> above = cloth.particles.position.col(below);
        above(1) += 0.2f;
        addSphere(spheres, above, 0.6f, 1000.0f);
        spheres.particles.velocity.col(0) = Vec4<float>(0, -1, 0, 0);
        course_spheres = spheres;
        course_cloth = cloth;
        const Vec4<float> fixed_before = cloth.particles.velocity.col(0);
        collideWithMistake(spheres, cloth, false, e, 0.15f,
                           contactRow(cause::kFixedParticleMassless));
        collideWithMistake(course_spheres, course_cloth, false, e, 0.15f, ContactRow{});
        ASSERT_TRUE(sameBits(spheres.particles.position, course_spheres.particles.position));
        ASSERT_TRUE(sameBits(cloth.particles.position, course_cloth.particles.position));
        if (below != 0) {  // free bodies only: the course's impulse, rearranged
          for (int i = 0; i < cloth.particles.size(); ++i)
            EXPECT_LE(
                (cloth.particles.velocity.col(i) - course_cloth.particles.velocity.col(i)).norm(),
                1e-5f * (1 + course_cloth.particles.velocity.col(i).norm()))
                << "particle " << i;
          EXPECT_LE(
              (spheres.particles.velocity.col(0) - course_spheres.particles.velocity.col(0)).norm(),
              1e-5f);
          continue;
        }
        // the sphere meets the fixed particle first, at its starting velocity, along n = +y
        const float u_s = -1, u_p = fixed_before(1);
        if (u_s - u_p < 0) {
          ++fixed_contacts;
          EXPECT_NEAR(cloth.particles.velocity(1, 0), u_s + e * (u_s - u_p), 1e-5f);
          EXPECT_TRUE(sameBits(course_cloth.particles.velocity.col(0), fixed_before));
        }
      }
  EXPECT_GT(fixed_contacts, 20);
}

// `d.normalized();` discarded: the force along the unnormalised d = x_s - x_e, both terms (k_s
// (|d| - rest) d, k_d ((v_s - v_e) . d) d), written here for one spring as the student's code is.
TEST(FormulaVariants, DirectionUnnormalisedIsTheForceAlongD) {
  std::mt19937 rng(11);
  const Cloth<float> cloth = randomCloth(rng);
  const Mat4X<float>& acc0 = cloth.particles.acceleration;
  const Mat4X<float> model =
      springAccelerations(cloth, acc0, forceRow(cause::kDirectionNotNormalised), kGravity);
  Mat4X<float> by_hand = acc0;
  const auto& p = cloth.particles;
  for (const auto& s : cloth.springs) {
    const Vec4<float> d = p.position.col(int(s.start)) - p.position.col(int(s.end));
    const Vec4<float> dv = p.velocity.col(int(s.start)) - p.velocity.col(int(s.end));
    const Vec4<float> f =
        d * (cloth.damper_coef * dv.dot(d) + cloth.spring_coef * (d.norm() - s.rest_length));
    by_hand.col(int(s.start)) -= f * p.inverse_mass[int(s.start)];
    by_hand.col(int(s.end)) += f * p.inverse_mass[int(s.end)];
  }
  for (int i = 0; i < model.cols(); ++i)
    EXPECT_LE((model.col(i) - by_hand.col(i)).norm(), 1e-4f * (1 + by_hand.col(i).norm())) << i;
}

// The contact models: switches and constants combine; a contact distance is a larger reach; a
// normal speed formed as |v| cos gives NaN only to a pair that approaches with a body at rest.
TEST(FormulaVariants, ContactModelsCombineSwitchesAndConstants) {
  std::mt19937 rng(12);
  const ContactModel course = courseContact(0.0f, 0.15f);
  for (int trial = 0; trial < 20; ++trial) {
    Spheres<float> spheres;
    Cloth<float> cloth;
    randomScene(rng, spheres, cloth);
    // two mistakes at once: for sphere 0 only, with restitution 1
    const ContactModel both =
        combined(withMistake(course, contactRow(cause::kFirstSphereOnly)),
                 withMistake(course, contactRow(cause::kRestitutionIgnored, 1)), course);
    EXPECT_EQ(contactModelText(both),
              "the course's collide for sphere 0 only and with restitution 1");
    Spheres<float> a = spheres;
    Cloth<float> ca = cloth, cb = cloth;
    collideModel(a, ca, false, both);
    Spheres<float> one_sphere;  // sphere 0 alone
    addSphere(one_sphere, Vec4<float>(spheres.particles.position.col(0)), spheres.radius[0],
              1000.0f);
    one_sphere.particles.velocity.col(0) = spheres.particles.velocity.col(0);
    collide(one_sphere, cb, 1.0f, 0.15f);
    EXPECT_TRUE(sameBits(ca.particles.position, cb.particles.position)) << trial;
    EXPECT_TRUE(sameBits(ca.particles.velocity, cb.particles.velocity)) << trial;
    // a contact distance of r + 0.1 is the course's contact with radii 0.1 larger
    ContactModel reach = course;
    reach.reach_offset = 0.1f;
    Spheres<float> c = spheres, d = spheres;
    Cloth<float> cc = cloth, cd = cloth;
    collideModel(c, cc, false, reach);
    for (float& r : d.radius) r += 0.1f;
    collide(d, cd, 0.0f, 0.15f);
    EXPECT_TRUE(sameBits(cc.particles.position, cd.particles.position)) << trial;
    EXPECT_TRUE(sameBits(cc.particles.velocity, cd.particles.velocity)) << trial;
  }
  // A sphere falling onto a particle at rest: NaN for both; moving bodies: the course's numbers.
  Spheres<float> spheres;
  addSphere(spheres, Vec4<float>(0, 0.4f, 0, 1), 0.5f, 125.0f);
  Cloth<float> cloth;
  cloth.particles = makeParticles<float>(1, 1.0f);
  spheres.particles.velocity.col(0) = Vec4<float>(0, -1, 0, 0);
  ContactModel speed = course;
  speed.divides_by_speed = true;
  Spheres<float> s1 = spheres;
  Cloth<float> c1 = cloth;
  collideModel(s1, c1, false, speed);
  EXPECT_TRUE(std::isnan(s1.particles.velocity(1, 0)));
  EXPECT_TRUE(std::isnan(c1.particles.velocity(1, 0)));
  cloth.particles.velocity.col(0) = Vec4<float>(0.1f, 0, 0, 0);
  Spheres<float> s2 = spheres, s3 = spheres;
  Cloth<float> c2 = cloth, c3 = cloth;
  collideModel(s2, c2, false, speed);
  collideModel(s3, c3, false, course);
  EXPECT_TRUE(sameBits(s2.particles.velocity, s3.particles.velocity));
  EXPECT_TRUE(sameBits(c2.particles.velocity, c3.particles.velocity));
}

}  // namespace
}  // namespace clothref::grader
