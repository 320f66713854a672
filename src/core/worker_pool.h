// A few worker threads for data-parallel loops over flat arrays: lodline's one parallel-for
// (the shape stage's kernels, level of detail, the lines stage, the software rasteriser's
// binning, tiles and shading). Owned by the stage that uses it — there is no global pool.
//
// Waking a sleeping thread costs 0.05–0.5 ms on these VMs, as much as a whole loop of a
// frame. So a frame's CPU stages run inside a WorkerPool::Awake scope, during which idle
// workers poll for the next loop instead of sleeping; outside it they poll for kSpinMicros
// after a loop, then sleep on a condition variable, leaving the cores to the GL driver's
// threads (llvmpipe renders on every core).
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
#include <atomic>
#include <chrono>
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
  /// std::thread::hardware_concurrency() (at most 8: these loops gain little beyond).
  explicit WorkerPool(unsigned threads = 0);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  /// Threads that run a loop, the caller included.
  unsigned threadCount() const { return static_cast<unsigned>(workers_.size()) + 1; }

  /// While one exists, idle workers wait for the next loop by polling (wakes them now if
  /// they sleep). Scopes nest. None made while the pool is quiet (setQuiet()) has an effect.
  class Awake {
   public:
    explicit Awake(WorkerPool* pool);
    ~Awake();
    Awake(const Awake&) = delete;
    Awake& operator=(const Awake&) = delete;

   private:
    WorkerPool* pool_;
  };

  /// Quiet: loops run on the calling thread alone and Awake scopes made from now on do
  /// nothing, so the workers sleep. For loops that run beside other work on the same cores
  /// (the next frame's stages while a frame is drawn: docs/performance.md, "Frames in a
  /// pipeline"), where waking and polling workers take cycles the other work needs. Results
  /// are the same (they never depend on the thread count). Scopes alive when it changes keep
  /// what they did.
  void setQuiet(bool quiet) { quiet_.store(quiet, std::memory_order_relaxed); }

  /// Calls fn(begin, end) on contiguous, disjoint chunks that cover [0, n) and returns when
  /// all are done. Chunks hold at least min_chunk items (the last may hold fewer) and are
  /// handed out as threads become free, so uneven work balances. Loops shorter than
  /// 2·min_chunk, and every loop while the pool is quiet, run inline as one call. `fn` must
  /// not throw. Calls from several threads at once are serialised (inline ones need not be).
  template <class Fn>
  void forRange(size_t n, size_t min_chunk, Fn&& fn) {
    min_chunk = std::max<size_t>(min_chunk, 1);
    if (threadCount() <= 1 || n < 2 * min_chunk || quiet_.load(std::memory_order_relaxed)) {
      if (n > 0) fn(size_t{0}, n);
      return;
    }
    // About 4 chunks per thread: enough to even out, few enough to keep the hand-out cheap.
    const size_t chunk = std::max(min_chunk, (n + 4 * threadCount() - 1) / (4 * threadCount()));
    run(n, chunk, [](void* ctx, size_t b, size_t e, unsigned) { (*static_cast<std::remove_reference_t<Fn>*>(ctx))(b, e); },
        const_cast<void*>(static_cast<const void*>(&fn)));
  }

  /// As forRange(), and fn(begin, end, slot) also gets the index of the thread that runs the
  /// chunk, in [0, threadCount()) (0: the caller), for per-thread scratch memory. Slots
  /// differ between threads running at once; which chunk a slot gets is not fixed.
  template <class Fn>
  void forRangeWithSlot(size_t n, size_t min_chunk, Fn&& fn) {
    min_chunk = std::max<size_t>(min_chunk, 1);
    if (threadCount() <= 1 || n < 2 * min_chunk || quiet_.load(std::memory_order_relaxed)) {
      if (n > 0) fn(size_t{0}, n, 0u);
      return;
    }
    const size_t chunk = std::max(min_chunk, (n + 4 * threadCount() - 1) / (4 * threadCount()));
    run(n, chunk,
        [](void* ctx, size_t b, size_t e, unsigned slot) { (*static_cast<std::remove_reference_t<Fn>*>(ctx))(b, e, slot); },
        const_cast<void*>(static_cast<const void*>(&fn)));
  }

 private:
  using Call = void (*)(void*, size_t, size_t, unsigned);
  void run(size_t n, size_t chunk, Call call, void* ctx);
  void workerLoop(unsigned index);
  void drain(unsigned slot);  // takes chunks until none are left
  // Polls `ready` while an Awake scope exists, else for up to kSpinMicros; true as soon as
  // it holds.
  template <class Ready>
  bool waitBriefly(Ready&& ready) const {
    auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(kSpinMicros);
    for (unsigned i = 1;; ++i) {
      if (ready()) return true;
#if defined(__x86_64__) || defined(__i386__)
      __builtin_ia32_pause();  // be gentle with a hyper-threaded sibling
#endif
      if ((i & 63) != 0) continue;
      const auto now = std::chrono::steady_clock::now();
      if (awake_.load(std::memory_order_relaxed) > 0) {
        until = now + std::chrono::microseconds(kSpinMicros);
      } else if (now > until) {
        return false;
      }
    }
  }
  static constexpr int kSpinMicros = 100;
  std::atomic<int> awake_{0};  // Awake scopes alive
  std::atomic<bool> quiet_{false};  // setQuiet()

  std::vector<std::thread> workers_;
  std::mutex run_mutex_;  // one loop at a time
  std::mutex mutex_;
  std::condition_variable start_cv_, done_cv_;
  // One value per loop, which workers watch: (loop counter << 8) | workers taking part. The
  // helper count travels in the same word, so a worker never pairs one loop's count with
  // another's; the loop's other fields are read only by those helpers, which the caller
  // waits for before the next loop can begin.
  std::atomic<uint64_t> generation_{0};
  std::atomic<unsigned> unfinished_{0};    // of those, still working
  size_t n_ = 0, chunk_ = 0;
  std::atomic<size_t> next_{0};  // index of the next chunk to hand out
  Call call_ = nullptr;
  void* ctx_ = nullptr;
  bool stop_ = false;
};

}  // namespace lodline
