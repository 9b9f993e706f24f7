// makeWorld: a scene's parameters land in the world converted once to T, the grid is the course's
// (vertices, fixed particles, springs), listed particles and springs keep their values with the
// smaller index as the start, spheres get their velocity and mass override, the frame loop its
// pinned particles, a dt override wins, backward Euler gets its stepper, and an invalid scene
// throws SceneError before anything is built.
#include "clothref/scene/make_world.h"

#include <gtest/gtest.h>

namespace clothref {
namespace {

Scene listedScene() {
  Scene scene;
  scene.name = "listed";
  scene.dt = 2e-3;
  scene.gravity = {0, -1.5, 0.25};
  scene.viscous_coef = 0.125;
  ClothSpec cloth;
  cloth.particles = {{{0, 1, 0}, {0.5, 0, 0}, 2}, {{1, 1, 0}, {0, 0, 0}, 3}, {{2, 1, 0}, {}, 1}};
  cloth.springs = {{1, 0, 1.25}, {1, 2, 0.75}};  // the first one written end-first
  cloth.fixed = {2};
  cloth.spring_coef = 100;
  cloth.damper_coef = 0.5;
  scene.cloth = cloth;
  SpheresSpec spheres;
  spheres.items = {{{0, 3, 0}, 0.5, {1, 0, 0}, std::nullopt}, {{0, 5, 0}, 0.25, {}, 7.0}};
  spheres.density = 8;
  spheres.external_force = false;
  spheres.sphere_sphere_collision = false;
  spheres.restitution_cloth = 0.25;
  spheres.restitution_sphere = 0.5;
  spheres.correction = 0.125;
  scene.spheres = spheres;
  return scene;
}

TEST(MakeWorld, ListedClothAndSpheresKeepTheirValues) {
  const World<double> world = makeWorld<double>(listedScene(), Method::Midpoint);
  EXPECT_EQ(world.method, Method::Midpoint);
  EXPECT_EQ(world.physics.dt, 2e-3);
  EXPECT_EQ(world.physics.gravity, Vec4<double>(0, -1.5, 0.25, 0));
  EXPECT_EQ(world.physics.viscous_coef, 0.125);
  ASSERT_TRUE(world.cloth.has_value());
  const Cloth<double>& cloth = *world.cloth;
  ASSERT_EQ(cloth.particles.size(), 3);
  EXPECT_EQ(cloth.particles.position.col(0), Vec4<double>(0, 1, 0, 1));    // points: w = 1
  EXPECT_EQ(cloth.particles.velocity.col(0), Vec4<double>(0.5, 0, 0, 0));  // directions: w = 0
  EXPECT_EQ(cloth.particles.mass[1], 3);
  EXPECT_EQ(cloth.particles.inverse_mass[1], 1.0 / 3);
  EXPECT_EQ(cloth.particles.mass[2], 0);  // fixed
  EXPECT_EQ(cloth.particles.inverse_mass[2], 0);
  ASSERT_EQ(cloth.springs.size(), 2u);
  EXPECT_EQ(cloth.springs[0].start, 0u);
  EXPECT_EQ(cloth.springs[0].end, 1u);
  EXPECT_EQ(cloth.springs[0].rest_length, 1.25);
  EXPECT_EQ(cloth.springs[1].start, 1u);
  EXPECT_EQ(cloth.springs[1].end, 2u);
  EXPECT_EQ(cloth.spring_coef, 100);
  EXPECT_EQ(cloth.damper_coef, 0.5);

  ASSERT_TRUE(world.spheres.has_value());
  const Spheres<double>& spheres = *world.spheres;
  ASSERT_EQ(spheres.size(), 2);
  EXPECT_EQ(spheres.particles.position.col(1), Vec4<double>(0, 5, 0, 1));
  EXPECT_EQ(spheres.particles.velocity.col(0), Vec4<double>(1, 0, 0, 0));
  EXPECT_EQ(spheres.radius[1], 0.25);
  EXPECT_EQ(spheres.particles.mass[0], 8 * 0.5 * 0.5 * 0.5);  // the course's density * r^3
  EXPECT_EQ(spheres.particles.mass[1], 7);                    // the override
  EXPECT_FALSE(world.physics.sphere_external_force);
  EXPECT_FALSE(world.physics.sphere_sphere_collision);
  EXPECT_EQ(world.physics.restitution_cloth, 0.25);
  EXPECT_EQ(world.physics.restitution_sphere, 0.5);
  EXPECT_EQ(world.physics.correction, 0.125);
  EXPECT_EQ(world.stepper, nullptr);
  EXPECT_EQ(world.step, 0);
}

TEST(MakeWorld, ParametersAreConvertedOnceToTheWorldsPrecision) {
  Scene scene = listedScene();
  scene.viscous_coef = 3.4e-4;
  const World<float> world = makeWorld<float>(scene, Method::Explicit, 1e-4);
  EXPECT_EQ(world.physics.dt, 1e-4f);  // the override, not the scene's 2e-3
  EXPECT_EQ(world.physics.viscous_coef, float(3.4e-4));
  EXPECT_EQ(world.cloth->particles.velocity(0, 0), 0.5f);
}

TEST(MakeWorld, TheCourseGridWithFixedCornersAndFrameLoop) {
  const Scene& scene = *findBuiltinScene("course2024");
  ASSERT_TRUE(scene.cloth && scene.cloth->grid && scene.frame_loop);
  const World<float> world = makeWorld<float>(scene, Method::Rk4);
  const int n = scene.cloth->grid->particles_per_edge;
  ASSERT_EQ(world.cloth->particles.size(), n * n);
  for (int i : scene.cloth->fixed) EXPECT_EQ(world.cloth->particles.inverse_mass[i], 0.0f) << i;
  // the course's grid: 2 n (n - 1) structural, 2 (n - 1)^2 shear, 2 n (n - 2) bend springs
  EXPECT_EQ(world.cloth->springs.size(),
            std::size_t(2 * n * (n - 1) + 2 * (n - 1) * (n - 1) + 2 * n * (n - 2)));
  EXPECT_EQ(world.frame_loop.pinned, scene.cloth->fixed);
  EXPECT_EQ(world.frame_loop.steps_per_frame, scene.frame_loop->steps_per_frame);
}

TEST(MakeWorld, BackwardEulerGetsItsStepper) {
  World<double> world = makeWorld<double>(*findBuiltinScene("spring"), Method::BackwardEuler);
  ASSERT_NE(world.stepper, nullptr);
  const Vec4<double> before = world.cloth->particles.position.col(1);
  step(world);
  EXPECT_EQ(world.step, 1);
  EXPECT_NE(world.cloth->particles.position.col(1), before);
}

TEST(MakeWorld, AnInvalidSceneThrowsBeforeBuilding) {
  Scene scene = listedScene();
  scene.cloth->springs.push_back({0, 3, 1});  // particle 3 does not exist
  EXPECT_THROW(makeWorld<float>(scene, Method::Explicit), SceneError);
  scene = listedScene();
  scene.cloth->fixed = {-1};
  EXPECT_THROW(makeWorld<double>(scene, Method::Explicit), SceneError);
}

}  // namespace
}  // namespace clothref
