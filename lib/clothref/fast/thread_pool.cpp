#include "clothref/fast/thread_pool.h"

namespace clothref::fast {

namespace {

// Spins before sleeping: a step's runs are microseconds apart, a futex round trip is not cheaper.
constexpr int kSpins = 20000;

}  // namespace

ThreadPool::ThreadPool(int threads) {
  for (int i = 1; i < threads; ++i) workers_.emplace_back([this, i] { work(i); });
}

ThreadPool::~ThreadPool() {
  stop_.store(true, std::memory_order_relaxed);
  generation_.fetch_add(1, std::memory_order_release);
  generation_.notify_all();
  for (std::thread& worker : workers_) worker.join();
}

void ThreadPool::run(void (*task)(void*, int), void* context) {
  if (workers_.empty()) {
    task(context, 0);
    return;
  }
  task_ = task;
  context_ = context;
  pending_.store(static_cast<int>(workers_.size()), std::memory_order_relaxed);
  generation_.fetch_add(1, std::memory_order_release);
  generation_.notify_all();
  task(context, 0);
  for (int spin = 0;; ++spin) {
    const int left = pending_.load(std::memory_order_acquire);
    if (left == 0) return;
    if (spin > kSpins) pending_.wait(left, std::memory_order_acquire);
  }
}

void ThreadPool::work(int index) {
  unsigned seen = 0;
  for (;;) {
    unsigned current = generation_.load(std::memory_order_acquire);
    for (int spin = 0; current == seen; ++spin) {
      if (spin > kSpins) generation_.wait(seen, std::memory_order_acquire);
      current = generation_.load(std::memory_order_acquire);
    }
    seen = current;
    if (stop_.load(std::memory_order_relaxed)) return;
    task_(context_, index);
    if (pending_.fetch_sub(1, std::memory_order_acq_rel) == 1) pending_.notify_one();
  }
}

}  // namespace clothref::fast
