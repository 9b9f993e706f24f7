#include "clothref/base/function_ref.h"

#include <gtest/gtest.h>

namespace clothref {
namespace {

int twice(int x) { return 2 * x; }

int apply(FunctionRef<int(int)> f, int x) { return f(x); }

TEST(FunctionRef, CallsLambdasFunctionsAndFunctionPointers) {
  int calls = 0;
  EXPECT_EQ(apply([&calls](int x) { return x + ++calls; }, 10), 11);
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(apply(twice, 21), 42);
  EXPECT_EQ(apply(&twice, 4), 8);
}

TEST(FunctionRef, RefersToTheCallableItDoesNotCopyIt) {
  struct Counter {
    int count = 0;
    void operator()() { ++count; }
  } counter;
  FunctionRef<void()> ref(counter);
  ref();
  ref();
  EXPECT_EQ(counter.count, 2);
}

}  // namespace
}  // namespace clothref
