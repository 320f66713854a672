// A few worker threads for data-parallel loops over flat arrays (the shape stage's per-face
// and per-vertex kernels). Owned by the stage that uses it — there is no global pool — and
// idle workers sleep on a condition variable instead of spinning, so they take no CPU from
// the GL driver's own threads between frames (llvmpipe renders on every core).
//
//   WorkerPool pool(0);                         // 0: one thread per core (caller included)
//   pool.forRange(n, 1024, [&](size_t begin, size_t end) {
//     for (size_t i = begin; i < end; ++i) out[i] = f(in[i]);   // disjoint writes only
//   });
//
// Results do not depend on the thread count as long as every index writes only its own
// outputs, which is how all callers use it.
#pragma once

#include <algorithm>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <thread>
#include <type_traits>
#include <vector>

namespace lodline {

class WorkerPool {
 public:
  /// `threads` counts the calling thread too: 1 runs everything inline; 0 uses
  /// std::thread::hardware_concurrency() (at most 16).
  explicit WorkerPool(unsigned threads = 0);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  /// Threads that run a loop, the caller included.
  unsigned threadCount() const { return static_cast<unsigned>(workers_.size()) + 1; }

  /// Calls fn(begin, end) on contiguous, disjoint chunks that cover [0, n), one per thread,
  /// and returns when all are done. Loops shorter than 2·min_chunk run inline. `fn` must not
  /// throw. Calls from several threads at once are serialised.
  template <class Fn>
  void forRange(size_t n, size_t min_chunk, Fn&& fn) {
    const size_t by_size = min_chunk > 0 ? n / min_chunk : n;
    const unsigned parts = static_cast<unsigned>(std::min<size_t>(threadCount(), by_size));
    if (parts <= 1) {
      if (n > 0) fn(size_t{0}, n);
      return;
    }
    run(n, parts, [](void* ctx, size_t b, size_t e) { (*static_cast<std::remove_reference_t<Fn>*>(ctx))(b, e); },
        const_cast<void*>(static_cast<const void*>(&fn)));
  }

 private:
  using Call = void (*)(void*, size_t, size_t);
  void run(size_t n, unsigned parts, Call call, void* ctx);
  void workerLoop(unsigned index);

  std::vector<std::thread> workers_;
  std::mutex run_mutex_;  // one loop at a time
  std::mutex mutex_;
  std::condition_variable start_cv_, done_cv_;
  uint64_t generation_ = 0;
  unsigned parts_ = 0, unfinished_ = 0;
  size_t n_ = 0;
  Call call_ = nullptr;
  void* ctx_ = nullptr;
  bool stop_ = false;
};

}  // namespace lodline
