#include "core/worker_pool.h"

#include <algorithm>

namespace lodline {

WorkerPool::WorkerPool(unsigned threads) {
  if (threads == 0) threads = std::clamp(std::thread::hardware_concurrency(), 1u, 16u);
  workers_.reserve(threads - 1);
  for (unsigned i = 1; i < threads; ++i) workers_.emplace_back([this, i] { workerLoop(i); });
}

WorkerPool::~WorkerPool() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  start_cv_.notify_all();
  for (std::thread& t : workers_) t.join();
}

void WorkerPool::run(size_t n, unsigned parts, Call call, void* ctx) {
  std::lock_guard run_lock(run_mutex_);
  {
    std::lock_guard lock(mutex_);
    n_ = n;
    parts_ = parts;
    call_ = call;
    ctx_ = ctx;
    unfinished_ = parts - 1;  // the caller does part 0 itself
    ++generation_;
  }
  start_cv_.notify_all();
  call(ctx, 0, n / parts);
  std::unique_lock lock(mutex_);
  done_cv_.wait(lock, [this] { return unfinished_ == 0; });
}

void WorkerPool::workerLoop(unsigned index) {
  uint64_t seen = 0;
  for (;;) {
    size_t begin = 0, end = 0;
    Call call = nullptr;
    void* ctx = nullptr;
    {
      std::unique_lock lock(mutex_);
      start_cv_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
      if (index >= parts_) continue;  // this loop has fewer chunks than threads
      begin = n_ * index / parts_;
      end = n_ * (index + 1) / parts_;
      call = call_;
      ctx = ctx_;
    }
    call(ctx, begin, end);
    bool last = false;
    {
      std::lock_guard lock(mutex_);
      last = --unfinished_ == 0;
    }
    if (last) done_cv_.notify_one();
  }
}

}  // namespace lodline
