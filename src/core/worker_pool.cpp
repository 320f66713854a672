#include "core/worker_pool.h"

#include <algorithm>

namespace lodline {

WorkerPool::WorkerPool(unsigned threads) {
  if (threads == 0) threads = std::clamp(std::thread::hardware_concurrency(), 1u, 8u);
  threads = std::min(threads, 256u);  // the helper count of a loop travels in 8 bits
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

WorkerPool::Awake::Awake(WorkerPool* pool) : pool_(pool) {
  if (pool_ && pool_->quiet_.load(std::memory_order_relaxed)) pool_ = nullptr;  // a no-op scope
  if (!pool_ || pool_->workers_.empty()) return;
  if (pool_->awake_.fetch_add(1, std::memory_order_relaxed) == 0) {
    std::lock_guard lock(pool_->mutex_);  // sleeping workers re-check and start polling
  }
  pool_->start_cv_.notify_all();
}

WorkerPool::Awake::~Awake() {
  if (pool_ && !pool_->workers_.empty()) pool_->awake_.fetch_sub(1, std::memory_order_relaxed);
}

void WorkerPool::drain(unsigned slot) {
  const size_t chunks = (n_ + chunk_ - 1) / chunk_;
  for (size_t c = next_.fetch_add(1, std::memory_order_relaxed); c < chunks;
       c = next_.fetch_add(1, std::memory_order_relaxed))
    call_(ctx_, c * chunk_, std::min(n_, (c + 1) * chunk_), slot);
}

void WorkerPool::run(size_t n, size_t chunk, Call call, void* ctx) {
  std::lock_guard run_lock(run_mutex_);
  const size_t chunks = (n + chunk - 1) / chunk;
  n_ = n;
  chunk_ = chunk;
  call_ = call;
  ctx_ = ctx;
  next_.store(0, std::memory_order_relaxed);
  const unsigned helpers = static_cast<unsigned>(std::min<size_t>(workers_.size(), chunks - 1));
  unfinished_.store(helpers, std::memory_order_relaxed);
  {
    // Under the mutex, so a worker about to sleep either sees the new loop or is woken.
    std::lock_guard lock(mutex_);
    const uint64_t next_loop = (generation_.load(std::memory_order_relaxed) >> 8) + 1;
    generation_.store((next_loop << 8) | helpers, std::memory_order_release);
  }
  start_cv_.notify_all();
  drain(0);  // the caller works too
  if (waitBriefly([this] { return unfinished_.load(std::memory_order_acquire) == 0; })) return;
  std::unique_lock lock(mutex_);
  done_cv_.wait(lock, [this] { return unfinished_.load(std::memory_order_acquire) == 0; });
}

void WorkerPool::workerLoop(unsigned index) {
  uint64_t seen = 0;
  for (;;) {
    if (!waitBriefly([&] { return generation_.load(std::memory_order_acquire) != seen; })) {
      std::unique_lock lock(mutex_);
      start_cv_.wait(lock, [&] {
        return stop_ || generation_.load(std::memory_order_acquire) != seen ||
               awake_.load(std::memory_order_relaxed) > 0;
      });
      if (stop_) return;
      if (generation_.load(std::memory_order_acquire) == seen) continue;  // woken to poll
    }
    seen = generation_.load(std::memory_order_acquire);
    if (index > (seen & 0xff)) continue;  // this loop needs fewer threads
    drain(index);
    if (unfinished_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
      std::lock_guard lock(mutex_);  // pairs with the caller's predicate check
      done_cv_.notify_one();
    }
  }
}

}  // namespace lodline
