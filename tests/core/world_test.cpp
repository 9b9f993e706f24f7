#include "clothref/core/world.h"
#include "clothref/scene/make_world.h"

#include <cmath>
#include <cstdlib>

#include <gtest/gtest.h>

#include "clothref/record/world_views.h"

// Count heap allocations in this test binary by interposing malloc (glibc's __libc_malloc does the
// work). Eigen's dynamic matrices allocate with malloc, std containers through operator new, which
// calls malloc, so both are seen. Sanitizers bring their own malloc: the count is skipped there.
#if defined(__SANITIZE_ADDRESS__)
#define CLOTHREF_COUNT_MALLOC 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define CLOTHREF_COUNT_MALLOC 0
#endif
#endif
#ifndef CLOTHREF_COUNT_MALLOC
#define CLOTHREF_COUNT_MALLOC 1
#endif

#if CLOTHREF_COUNT_MALLOC
namespace {
long g_malloc_calls = 0;
}
extern "C" void* __libc_malloc(std::size_t size);
extern "C" void* malloc(std::size_t size) {
  ++g_malloc_calls;
  return __libc_malloc(size);
}
#endif

namespace clothref {
namespace {

template <typename T>
std::vector<std::uint64_t> hashes(const Scene& scene, Method method, int steps) {
  World<T> world = makeWorld<T>(scene, method);
  std::vector<std::uint64_t> result{stateHash(world)};
  for (int i = 0; i < steps; ++i) {
    step(world);
    result.push_back(stateHash(world));
  }
  return result;
}

TEST(World, TwoRunsGiveTheSameHashesAtEveryStep) {
  for (Method method : kAllMethods) {
    const Scene& scene = *findBuiltinScene("course2022");
    EXPECT_EQ(hashes<float>(scene, method, 200), hashes<float>(scene, method, 200))
        << methodName(method);
  }
}

TEST(World, TwoWorldsInOneProcessAreIndependent) {
  const Scene& scene = *findBuiltinScene("small-cloth");
  const auto alone = hashes<float>(scene, Method::Rk4, 300);
  World<float> a = makeWorld<float>(scene, Method::Rk4);
  World<float> b = makeWorld<float>(*findBuiltinScene("course2024"), Method::Explicit);
  for (int i = 0; i < 300; ++i) {
    step(a);
    step(b);
    ASSERT_EQ(stateHash(a), alone[i + 1]) << "step " << i + 1;
  }
}

TEST(World, FloatAndDoubleSpringRunsAgreeToFloatPrecision) {
  for (Method method : kAllMethods) {
    const Scene& scene = *findBuiltinScene("spring");
    World<float> f = makeWorld<float>(scene, method);
    World<double> d = makeWorld<double>(scene, method);
    for (int i = 0; i < 2000; ++i) {
      step(f);
      step(d);
    }
    // amplitude 0.2 m; float round-off accumulated over 2000 steps stays a few ULP of 1 m
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(f.cloth->particles.position(k, 1), d.cloth->particles.position(k, 1), 2e-6)
          << methodName(method);
      EXPECT_NEAR(f.cloth->particles.velocity(k, 1), d.cloth->particles.velocity(k, 1), 2e-5)
          << methodName(method);
    }
  }
}

TEST(World, OnlyThePartsTheSceneHas) {
  World<float> spheres_only = makeWorld<float>(*findBuiltinScene("two-spheres"), Method::Rk4);
  EXPECT_FALSE(spheres_only.cloth.has_value());
  ASSERT_TRUE(spheres_only.spheres.has_value());
  std::array<Particles<float>*, 2> storage{};
  EXPECT_EQ(bodies(spheres_only, storage).size(), 1u);
  for (int i = 0; i < 500; ++i) step(spheres_only);
  // the head-on impact reversed both spheres
  EXPECT_LT(spheres_only.spheres->particles.velocity(0, 0), 0.0f);
  EXPECT_GT(spheres_only.spheres->particles.velocity(0, 1), 0.0f);

  World<float> falling = makeWorld<float>(*findBuiltinScene("free-fall"), Method::Explicit);
  EXPECT_FALSE(falling.spheres.has_value());
  EXPECT_TRUE(falling.cloth->springs.empty());
}

TEST(World, CourseBodiesAndMasses) {
  World<float> world = makeWorld<float>(*findBuiltinScene("course2022"), Method::Explicit);
  ASSERT_EQ(world.cloth->particles.size(), 625);
  ASSERT_EQ(world.spheres->size(), 4);
  EXPECT_EQ(world.cloth->springs.size(), 3502u);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(world.spheres->particles.mass[i], 125.0f);
  int fixed = 0;
  for (int i = 0; i < 625; ++i) fixed += world.cloth->particles.inverse_mass[i] == 0.0f;
  EXPECT_EQ(fixed, 4);
  EXPECT_EQ(world.physics.dt, 1e-4f);
  EXPECT_EQ(world.physics.viscous_coef, 3.4e-4f);
  EXPECT_EQ(world.physics.gravity, Vec4<float>(0, -9.8f, 0, 0));
  EXPECT_EQ(world.cloth->spring_coef, 25000.0f);
  EXPECT_EQ(world.physics.restitution_sphere, 0.8f);
  EXPECT_EQ(world.physics.correction, 0.15f);
}

// The 2024 frame loop: at the first step of every frame (and only then) the pinned corners are
// re-pinned and sphere 0 gets the held velocity; in between, the sphere moves freely.
TEST(World, FrameLoopActsAtTheStartOfEachFrameOnly) {
  Scene scene = *findBuiltinScene("course2024");
  scene.spheres->items[0].center = {0, -5, 0};  // clear of the cloth: only the loop moves it
  scene.frame_loop->steps_per_frame = 5;
  scene.frame_loop->sphere_velocity = {0.5, 0, -0.25};
  World<double> world = makeWorld<double>(scene, Method::Explicit);
  ASSERT_EQ(world.frame_loop.pinned, (std::vector<int>{0, 24, 600, 624}));
  const Vec4<double> held(0.5, 0, -0.25, 0);
  const Vec4<double> knocked(0, 2, 0, 0);
  for (int i = 0; i < 23; ++i) {
    // a corner and the sphere knocked between frames are reset when the next frame starts
    if (i == 7) {
      setMass(world.cloth->particles, 24, 1.0);
      world.cloth->particles.velocity.col(24) = Vec4<double>(0, 1, 0, 0);
      world.spheres->particles.velocity.col(0) = knocked;
    }
    const bool frame_start = world.step % 5 == 0;
    const Vec4<double> sphere_x = world.spheres->particles.position.col(0);
    const Vec4<double> sphere_v = world.spheres->particles.velocity.col(0);
    step(world);
    // explicit Euler moves the sphere by the velocity it had when the step began
    const Vec4<double> moved_with = frame_start ? held : sphere_v;
    EXPECT_EQ(world.spheres->particles.position.col(0), sphere_x + moved_with * 1e-4)
        << "step " << i;
    if (i >= 7 && i < 10) {
      EXPECT_EQ(sphere_v, knocked) << "step " << i;
    }
    if (frame_start) {
      EXPECT_EQ(world.cloth->particles.mass[24], 0.0) << "step " << i;
    }
  }
  EXPECT_EQ(world.cloth->particles.velocity.col(24), Vec4<double>::Zero());
  // without the frame loop the same knock stays
  scene.frame_loop.reset();
  World<double> free_world = makeWorld<double>(scene, Method::Explicit);
  setMass(free_world.cloth->particles, 24, 1.0);
  free_world.spheres->particles.velocity.col(0) = knocked;
  for (int i = 0; i < 10; ++i) step(free_world);
  EXPECT_EQ(free_world.cloth->particles.mass[24], 1.0);
  EXPECT_EQ(free_world.spheres->particles.velocity.col(0), knocked);
}

TEST(World, AStepAllocatesNothing) {
#if CLOTHREF_COUNT_MALLOC
  for (Method method : kAllMethods) {
    World<float> world = makeWorld<float>(*findBuiltinScene("course2022"), method);
    step(world);  // the first step sizes the integrator scratch
    const long before = g_malloc_calls;
    for (int i = 0; i < 20; ++i) step(world);
    EXPECT_EQ(g_malloc_calls - before, 0) << methodName(method);
  }
  // the counter does see allocations
  const long before = g_malloc_calls;
  World<float> world = makeWorld<float>(*findBuiltinScene("small-cloth"), Method::Explicit);
  EXPECT_GT(g_malloc_calls - before, 0);
#else
  GTEST_SKIP() << "malloc is the sanitizer's in this build";
#endif
}

}  // namespace
}  // namespace clothref
