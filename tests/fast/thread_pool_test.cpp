// ThreadPool: every index runs exactly once per run, on its own thread (index 0 on the caller),
// and run() returns only when all have finished, over many runs (the kernels call it several
// times per step) and with pools made and destroyed in a loop.
#include "clothref/fast/thread_pool.h"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>
#include <vector>

namespace clothref::fast {
namespace {

struct Record {
  std::vector<std::atomic<int>> runs;
  std::vector<std::thread::id> thread;
  explicit Record(int n) : runs(n), thread(n) {}
};

void mark(void* context, int index) {
  auto& record = *static_cast<Record*>(context);
  record.thread[index] = std::this_thread::get_id();
  record.runs[index].fetch_add(1, std::memory_order_relaxed);
}

TEST(ThreadPool, EachIndexRunsOnceOnItsOwnThread) {
  for (int threads : {1, 2, 3, 4}) {
    ThreadPool pool(threads);
    ASSERT_EQ(pool.size(), threads);
    Record record(threads);
    pool.run(mark, &record);
    EXPECT_EQ(record.thread[0], std::this_thread::get_id()) << threads;
    for (int i = 0; i < threads; ++i) {
      EXPECT_EQ(record.runs[i].load(), 1) << threads << " threads, index " << i;
      for (int j = 0; j < i; ++j) EXPECT_NE(record.thread[i], record.thread[j]) << i << ' ' << j;
    }
  }
}

// A run's results are complete when run() returns: each task writes its own slot, the caller
// reads every slot straight after, run after run.
TEST(ThreadPool, RunReturnsAfterEveryTaskOfThatRun) {
  ThreadPool pool(3);
  struct Sums {
    std::vector<long> slot = std::vector<long>(3, 0);
    long round = 0;
  } sums;
  auto task = [](void* context, int index) {
    auto& s = *static_cast<Sums*>(context);
    s.slot[index] += s.round * (index + 1);
  };
  long expected = 0;
  for (long round = 1; round <= 2000; ++round) {
    sums.round = round;
    pool.run(task, &sums);
    expected += round;
    ASSERT_EQ(sums.slot[0], expected) << "round " << round;
    ASSERT_EQ(sums.slot[1], 2 * expected) << "round " << round;
    ASSERT_EQ(sums.slot[2], 3 * expected) << "round " << round;
  }
}

TEST(ThreadPool, PoolsAreMadeAndDestroyedCleanly) {
  for (int k = 0; k < 50; ++k) {
    ThreadPool idle(2);  // destroyed without a run: its worker must still stop
    ThreadPool used(2);
    Record record(2);
    used.run(mark, &record);
    EXPECT_EQ(record.runs[1].load(), 1);
  }
}

}  // namespace
}  // namespace clothref::fast
