// ThreadPool: a fixed set of worker threads that run one indexed task per thread and return, with
// no allocation per run (the fast kernels call it several times per step). Workers spin briefly,
// then sleep on an atomic, between runs.
#pragma once

#include <atomic>
#include <thread>
#include <vector>

namespace clothref::fast {

class ThreadPool {
 public:
  // `threads` >= 1 in total, the calling thread included (so threads - 1 workers are started).
  explicit ThreadPool(int threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int size() const { return static_cast<int>(workers_.size()) + 1; }

  // Runs task(context, i) for every i in [0, size()); i = 0 runs on the calling thread. Returns
  // when every task has finished. Not reentrant: one run at a time.
  void run(void (*task)(void* context, int index), void* context);

 private:
  void work(int index);

  std::vector<std::thread> workers_;
  void (*task_)(void*, int) = nullptr;
  void* context_ = nullptr;
  std::atomic<unsigned> generation_{0};
  std::atomic<int> pending_{0};
  std::atomic<bool> stop_{false};
};

}  // namespace clothref::fast
