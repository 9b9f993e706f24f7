// Every parameter of every built-in scene, against the course's facts (the 2022 and 2024 defaults,
// restated in docs/verification.md "Mutation testing") or, for the small scenes, against what
// their descriptions promise; then the worlds they build in float: masses, fixed particles, spring
// counts per type and the rest lengths' bits.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <string>

#include "clothref/core/world.h"
#include "clothref/scene/make_world.h"
#include "clothref/scene/scene.h"
#include "test_util.h"

namespace clothref {
namespace {

// Takes the name as a C string: a `const std::string&` would make each call's argument a
// temporary, and GCC 13+ then warns (-Wdangling-reference) at every `const Scene& s = scene(...)`,
// although the scene returned is a built-in that lives as long as the program.
const Scene& scene(const char* name) {
  const Scene* found = findBuiltinScene(name);
  if (!found) throw std::runtime_error(std::string("no built-in scene ") + name);
  return *found;
}

void expectCourseGrid(const ClothSpec& cloth, double y, double spring_coef) {
  ASSERT_TRUE(cloth.grid.has_value());
  EXPECT_EQ(cloth.grid->particles_per_edge, 25);                // particlesPerEdge
  EXPECT_EQ(cloth.grid->half_extent, 2.0);                      // clothWidth = clothHeight = 2
  EXPECT_EQ(cloth.grid->y, y);                                  // 0 in 2022, 1 in 2024
  EXPECT_EQ(cloth.grid->particle_mass, 1.0);                    // particleMass
  EXPECT_EQ(cloth.fixed, (std::vector<int>{0, 24, 600, 624}));  // the four corners
  EXPECT_TRUE(cloth.particles.empty());
  EXPECT_TRUE(cloth.springs.empty());
  EXPECT_EQ(cloth.spring_coef, spring_coef);  // springCoef
  EXPECT_EQ(cloth.damper_coef, 750.0);        // damperCoef
}

TEST(BuiltinSceneValues, Course2022IsTheCourseDefault) {
  const Scene& s = scene("course2022");
  EXPECT_EQ(builtinScenes().front().name, "course2022");
  EXPECT_EQ(s.dt, 1e-4);                        // deltaTime
  EXPECT_EQ(s.gravity, (Vector3{0, -9.8, 0}));  // Shape::computeExternalForce
  EXPECT_EQ(s.viscous_coef, 3.4e-4);            // viscousCoef
  ASSERT_TRUE(s.cloth && s.spheres);
  expectCourseGrid(*s.cloth, 0, 25000);
  const SpheresSpec& spheres = *s.spheres;
  ASSERT_EQ(spheres.items.size(), 4u);
  const Vector3 centres[4] = {
      {-0.75, 1, -0.75}, {0.75, 1, -0.75}, {-0.75, 1, 0.75}, {0.75, 1, 0.75}};
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(spheres.items[i].center, centres[i]) << "sphere " << i;
    EXPECT_EQ(spheres.items[i].radius, 0.5) << "sphere " << i;
    EXPECT_EQ(spheres.items[i].velocity, (Vector3{0, 0, 0})) << "sphere " << i;
    EXPECT_FALSE(spheres.items[i].mass.has_value()) << "mass from the course's density * r^3";
  }
  EXPECT_EQ(spheres.density, 1000.0);            // sphereDensity
  EXPECT_TRUE(spheres.external_force);           // 2022 calls spheres.computeExternalForce()
  EXPECT_TRUE(spheres.sphere_sphere_collision);  // 2022 calls spheres.collide()
  EXPECT_EQ(spheres.restitution_cloth, 0.0);     // coefRestitution in collide(Cloth*)
  EXPECT_EQ(spheres.restitution_sphere, 0.8);    // coefRestitution in collide()
  EXPECT_EQ(spheres.correction, 0.15);           // the TODO hint's penetration * normal * 0.15
  EXPECT_FALSE(s.frame_loop.has_value());        // 2022's loop has no per-frame work
}

TEST(BuiltinSceneValues, Course2024DiffersOnlyWhereTheCourseDoes) {
  const Scene& s = scene("course2024");
  EXPECT_EQ(s.dt, 1e-4);
  EXPECT_EQ(s.gravity, (Vector3{0, -9.8, 0}));
  EXPECT_EQ(s.viscous_coef, 3.4e-4);
  ASSERT_TRUE(s.cloth && s.spheres);
  expectCourseGrid(*s.cloth, 1, 20000);  // 2024: cloth at y = 1, springCoef 20000
  const SpheresSpec& spheres = *s.spheres;
  ASSERT_EQ(spheres.items.size(), 1u);  // one sphere r = 1 at the origin
  EXPECT_EQ(spheres.items[0].center, (Vector3{0, 0, 0}));
  EXPECT_EQ(spheres.items[0].radius, 1.0);
  EXPECT_EQ(spheres.items[0].velocity, (Vector3{0, 0, 0}));
  EXPECT_FALSE(spheres.items[0].mass.has_value());
  EXPECT_EQ(spheres.density, 1000.0);
  EXPECT_FALSE(spheres.external_force);           // 2024's loop gives the sphere no force
  EXPECT_FALSE(spheres.sphere_sphere_collision);  // and has no Spheres::collide()
  EXPECT_EQ(spheres.restitution_cloth, 0.0);
  EXPECT_EQ(spheres.correction, 0.15);
  // every frame (simulationPerFrame 10 x speedMultiplier 4 on a 60 Hz monitor = 40 steps) the
  // corners are re-pinned and the sphere's velocity set to the held arrow-key value, 0 at rest
  ASSERT_TRUE(s.frame_loop.has_value());
  EXPECT_EQ(s.frame_loop->steps_per_frame, 40);
  EXPECT_EQ(s.frame_loop->sphere_velocity, (Vector3{0, 0, 0}));
}

TEST(BuiltinSceneValues, SmallScenesAreWhatTheirDescriptionsSay) {
  for (const char* name : {"spring", "spring-undamped"}) {
    const Scene& s = scene(name);
    SCOPED_TRACE(name);
    EXPECT_EQ(s.dt, 1e-3);
    EXPECT_EQ(s.gravity, (Vector3{0, 0, 0}));
    EXPECT_EQ(s.viscous_coef, 0.0);
    EXPECT_FALSE(s.spheres.has_value());
    ASSERT_TRUE(s.cloth.has_value());
    ASSERT_EQ(s.cloth->particles.size(), 2u);
    EXPECT_EQ(s.cloth->particles[0].mass, 0.0);  // the anchor
    EXPECT_EQ(s.cloth->particles[0].position, (Vector3{0, 0, 0}));
    EXPECT_EQ(s.cloth->particles[1].mass, 1.0);
    EXPECT_EQ(s.cloth->particles[1].position, (Vector3{1.2, 0, 0}));
    EXPECT_EQ(s.cloth->particles[1].velocity, (Vector3{0, 0, 0}));
    ASSERT_EQ(s.cloth->springs.size(), 1u);
    EXPECT_EQ(s.cloth->springs[0].rest_length, 1.0);
    EXPECT_EQ(s.cloth->spring_coef, 100.0);
  }
  EXPECT_EQ(scene("spring").cloth->damper_coef, 2.0);  // zeta = c / (2 sqrt(k m)) = 0.1
  EXPECT_EQ(scene("spring-undamped").cloth->damper_coef, 0.0);

  const Scene& fall = scene("free-fall");
  EXPECT_EQ(fall.gravity, (Vector3{0, -9.8, 0}));
  EXPECT_EQ(fall.viscous_coef, 0.5);
  ASSERT_EQ(fall.cloth->particles.size(), 1u);
  EXPECT_EQ(fall.cloth->particles[0].position, (Vector3{0, 10, 0}));
  EXPECT_EQ(fall.cloth->particles[0].velocity, (Vector3{2, 5, 0}));
  EXPECT_EQ(fall.cloth->particles[0].mass, 1.0);

  const Scene& two = scene("two-spheres");
  EXPECT_EQ(two.gravity, (Vector3{0, 0, 0}));
  EXPECT_EQ(two.viscous_coef, 0.0);
  EXPECT_FALSE(two.cloth.has_value());
  ASSERT_EQ(two.spheres->items.size(), 2u);
  EXPECT_EQ(two.spheres->items[0].velocity, (Vector3{2, 0, 0}));
  EXPECT_EQ(two.spheres->items[1].velocity, (Vector3{-2, 0, 0}));
  EXPECT_EQ(two.spheres->restitution_sphere, 0.8);
  EXPECT_TRUE(two.spheres->sphere_sphere_collision);

  const Scene& small = scene("small-cloth");
  ASSERT_TRUE(small.cloth->grid.has_value());
  EXPECT_EQ(small.cloth->grid->particles_per_edge, 9);
  EXPECT_EQ(small.cloth->grid->half_extent, 1.0);
  EXPECT_EQ(small.cloth->fixed, (std::vector<int>{0, 8, 72, 80}));
  EXPECT_EQ(small.cloth->spring_coef, 25000.0);
  EXPECT_EQ(small.cloth->damper_coef, 750.0);
  EXPECT_EQ(small.spheres->items.size(), 1u);
}

// The off-axis impact: e != 0, spheres of different masses, and a contact normal with three
// non-zero components (checked where it happens, in tests/core/oblique_impact_test.cpp).
TEST(BuiltinSceneValues, ObliqueImpactScene) {
  const Scene& s = scene("two-spheres-oblique");
  EXPECT_EQ(s.gravity, (Vector3{0, 0, 0}));
  EXPECT_EQ(s.viscous_coef, 0.0);
  EXPECT_FALSE(s.cloth.has_value());
  ASSERT_EQ(s.spheres->items.size(), 2u);
  EXPECT_NE(s.spheres->items[0].radius, s.spheres->items[1].radius);
  EXPECT_EQ(s.spheres->restitution_sphere, 0.8);
  EXPECT_TRUE(s.spheres->sphere_sphere_collision);
  EXPECT_FALSE(s.spheres->external_force);
}

// The worlds the course scenes build, in float: the course's numbers (course facts: masses, the
// 3502 springs by type, and the rest lengths' bits measured from the float grid).
TEST(BuiltinSceneValues, CourseWorldsInFloat) {
  for (const char* name : {"course2022", "course2024"}) {
    SCOPED_TRACE(name);
    const World<float> world = makeWorld<float>(scene(name), Method::Explicit);
    const Particles<float>& cloth = world.cloth->particles;
    ASSERT_EQ(cloth.size(), 625);
    for (int i = 0; i < cloth.size(); ++i) {
      const bool corner = i == 0 || i == 24 || i == 600 || i == 624;
      EXPECT_EQ(cloth.mass[i], corner ? 0.0f : 1.0f) << i;
      EXPECT_EQ(cloth.position(1, i), name == std::string("course2022") ? 0.0f : 1.0f) << i;
    }
    // wStep = 2.0f * 2 / 24, one rounding: 1/6 correctly rounded
    EXPECT_EQ(test::bits(cloth.position(0, 1) - cloth.position(0, 0)), 0x3e2aaaa8u);
    EXPECT_EQ(cloth.position(0, 0), -2.0f);
    EXPECT_EQ(cloth.position(2, 624), 2.0f);

    std::map<SpringType, int> count;
    std::map<SpringType, std::set<std::uint32_t>> rest_bits;
    for (const Spring<float>& spring : world.cloth->springs) {
      ++count[spring.type];
      rest_bits[spring.type].insert(test::bits(spring.rest_length));
    }
    EXPECT_EQ(world.cloth->springs.size(), 3502u);
    EXPECT_EQ(count[SpringType::Structural], 1200);
    EXPECT_EQ(count[SpringType::Shear], 1152);
    EXPECT_EQ(count[SpringType::Bend], 1150);
    EXPECT_EQ(rest_bits[SpringType::Structural], (std::set<std::uint32_t>{0x3e2aaaa8u}));
    EXPECT_EQ(rest_bits[SpringType::Shear], (std::set<std::uint32_t>{0x3e715bebu}));
    EXPECT_EQ(rest_bits[SpringType::Bend], (std::set<std::uint32_t>{0x3eaaaaacu}));
  }
  const World<float> w2022 = makeWorld<float>(scene("course2022"), Method::Explicit);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(w2022.spheres->particles.mass[i], 125.0f);  // 1000 * 0.5^3
  EXPECT_EQ(w2022.physics.dt, 1e-4f);
  EXPECT_EQ(w2022.physics.viscous_coef, 3.4e-4f);
  EXPECT_EQ(w2022.physics.gravity, Vec4<float>(0, -9.8f, 0, 0));
  EXPECT_EQ(w2022.physics.restitution_sphere, 0.8f);
  EXPECT_EQ(w2022.physics.correction, 0.15f);
  EXPECT_EQ(w2022.cloth->spring_coef, 25000.0f);
  EXPECT_EQ(w2022.cloth->damper_coef, 750.0f);
  const World<float> w2024 = makeWorld<float>(scene("course2024"), Method::Explicit);
  EXPECT_EQ(w2024.spheres->particles.mass[0], 1000.0f);  // 1000 * 1^3
  EXPECT_EQ(w2024.cloth->spring_coef, 20000.0f);
  EXPECT_FALSE(w2024.physics.sphere_external_force);
  EXPECT_FALSE(w2024.physics.sphere_sphere_collision);
}

}  // namespace
}  // namespace clothref
