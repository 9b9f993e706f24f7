// A step allocates nothing: this test binary replaces malloc, calloc, realloc and operator new
// (Eigen allocates with malloc, so counting operator new alone would miss it) and counts the calls
// made during 1000 steps of every method, after one warm-up step that sizes the scratch buffers.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "clothref/core/world.h"
#include "clothref/scene/make_world.h"

#if defined(__SANITIZE_ADDRESS__)
#define CLOTHREF_COUNT_ALLOCATIONS 0  // the sanitizer owns malloc
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

void count() {
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
  count();
  return __libc_malloc(size);
}
void* calloc(std::size_t n, std::size_t size) {
  count();
  return __libc_calloc(n, size);
}
void* realloc(void* pointer, std::size_t size) {
  count();
  return __libc_realloc(pointer, size);
}
void free(void* pointer) { __libc_free(pointer); }
}

void* operator new(std::size_t size) {
  count();
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
long allocationsOverSteps(World<T>& world, int steps) {
  step(world);  // sizes the integrator scratch
  allocations.store(0);
  counting.store(true);
  for (int k = 0; k < steps; ++k) step(world);
  counting.store(false);
  return allocations.load();
}

TEST(StepAllocation, CountingWorks) {
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

TEST(StepAllocation, NoneInAThousandStepsOfEveryMethod) {
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

TEST(StepAllocation, NoneWithThreads) {
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
