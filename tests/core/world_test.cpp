#include "clothref/core/world.h"
#include "clothref/scene/make_world.h"

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>

#include <gtest/gtest.h>

#include "clothref/record/world_views.h"

// A step allocates nothing. This test binary (and only it) replaces malloc, calloc, realloc and
// operator new to count the calls made while `counting` is set: Eigen allocates with malloc, std
// containers through operator new, so counting operator new alone would miss some. Sanitizers
// bring their own malloc: the counting tests skip there.
#if defined(__SANITIZE_ADDRESS__)
#define CLOTHREF_COUNT_ALLOCATIONS 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define CLOTHREF_COUNT_ALLOCATIONS 0
#endif
#endif
#ifndef CLOTHREF_COUNT_ALLOCATIONS
#define CLOTHREF_COUNT_ALLOCATIONS 1
#endif

namespace {

std::atomic<bool> counting{false};
std::atomic<long> allocations{0};

void countAllocation() {
  if (counting.load(std::memory_order_relaxed)) allocations.fetch_add(1, std::memory_order_relaxed);
}

}  // namespace

#if CLOTHREF_COUNT_ALLOCATIONS
// glibc's own entry points, so the replacements can forward to them.
extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* pointer, std::size_t size);
void __libc_free(void* pointer);

void* malloc(std::size_t size) {
  countAllocation();
  return __libc_malloc(size);
}
void* calloc(std::size_t n, std::size_t size) {
  countAllocation();
  return __libc_calloc(n, size);
}
void* realloc(void* pointer, std::size_t size) {
  countAllocation();
  return __libc_realloc(pointer, size);
}
void free(void* pointer) { __libc_free(pointer); }
}

void* operator new(std::size_t size) {
  countAllocation();
  if (void* p = __libc_malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void operator delete(void* pointer) noexcept { __libc_free(pointer); }
void operator delete[](void* pointer) noexcept { __libc_free(pointer); }
void operator delete(void* pointer, std::size_t) noexcept { __libc_free(pointer); }
void operator delete[](void* pointer, std::size_t) noexcept { __libc_free(pointer); }
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

template <typename T>
long allocationsOverSteps(World<T>& world, int steps) {
  step(world);  // sizes the integrator scratch
  allocations.store(0);
  counting.store(true);
  for (int k = 0; k < steps; ++k) step(world);
  counting.store(false);
  return allocations.load();
}

TEST(WorldAllocation, CountingWorks) {
  if (!CLOTHREF_COUNT_ALLOCATIONS) GTEST_SKIP() << "sanitizer build: malloc is not ours";
  allocations.store(0);
  counting.store(true);
  void* volatile p = std::malloc(64);
  int* volatile q = new int(3);
  counting.store(false);
  std::free(p);
  delete q;
  EXPECT_EQ(allocations.load(), 2);
}

TEST(WorldAllocation, NoneInAThousandStepsOfEveryMethod) {
  if (!CLOTHREF_COUNT_ALLOCATIONS) GTEST_SKIP() << "sanitizer build: malloc is not ours";
  for (const Scene& scene : builtinScenes())
    for (Method method : kAllMethods) {
      World<float> single = makeWorld<float>(scene, method);
      EXPECT_EQ(allocationsOverSteps(single, 1000), 0) << scene.name << ' ' << methodName(method);
      World<double> precise = makeWorld<double>(scene, method);
      EXPECT_EQ(allocationsOverSteps(precise, 1000), 0)
          << scene.name << ' ' << methodName(method) << " double";
    }
}

TEST(WorldAllocation, NoneWithThreads) {
  if (!CLOTHREF_COUNT_ALLOCATIONS) GTEST_SKIP() << "sanitizer build: malloc is not ours";
  Scene scene = *findBuiltinScene("course2022");
  scene.cloth->grid->particles_per_edge = 100;
  scene.cloth->fixed = {0, 99, 9900, 9999};
  for (Method method : kAllMethods) {
    World<float> world = makeWorld<float>(scene, method);
    setExecution(world, true, world.execution.simd, 2);
    ASSERT_NE(world.execution.pool, nullptr);
    EXPECT_EQ(allocationsOverSteps(world, 20), 0) << methodName(method);
  }
}

}  // namespace
}  // namespace clothref
