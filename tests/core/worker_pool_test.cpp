#include "core/worker_pool.h"

#include <atomic>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace lodline {
namespace {

// Every index of [0, n) is visited exactly once, whatever the thread and item counts.
TEST(WorkerPool, ChunksCoverTheRangeExactlyOnce) {
  for (unsigned threads : {1u, 2u, 3u, 7u}) {
    WorkerPool pool(threads);
    EXPECT_EQ(pool.threadCount(), threads);
    for (size_t n : {size_t{0}, size_t{1}, size_t{5}, size_t{6}, size_t{1000}, size_t{100003}}) {
      std::vector<std::atomic<int>> hits(n);
      std::atomic<int> calls{0}, short_chunks{0};
      pool.forRange(n, 7, [&](size_t begin, size_t end) {
        ASSERT_LT(begin, end);
        ASSERT_LE(end, n);
        ++calls;
        if (end - begin < 7 && end != n) ++short_chunks;  // only the last may be short
        for (size_t i = begin; i < end; ++i) ++hits[i];
      });
      for (size_t i = 0; i < n; ++i) ASSERT_EQ(hits[i].load(), 1) << threads << " threads, n=" << n << ", i=" << i;
      EXPECT_EQ(short_chunks.load(), 0) << n;
      if (threads == 1 || n < 14) {
        EXPECT_LE(calls.load(), 1) << n;  // inline, one call
      }
    }
  }
}

// Short loops (under two minimum chunks) run inline, as one call on the caller's thread.
TEST(WorkerPool, ShortLoopsRunInline) {
  WorkerPool pool(4);
  const auto caller = std::this_thread::get_id();
  int calls = 0;
  pool.forRange(100, 64, [&](size_t begin, size_t end) {
    ++calls;
    EXPECT_EQ(begin, 0u);
    EXPECT_EQ(end, 100u);
    EXPECT_EQ(std::this_thread::get_id(), caller);
  });
  EXPECT_EQ(calls, 1);
}

// A quiet pool (the stages beside a drawn frame) runs every loop inline, as one call on the
// caller's thread with slot 0, Awake scopes or not; once no longer quiet it spreads loops
// over its threads again.
TEST(WorkerPool, AQuietPoolRunsLoopsOnTheCallersThread) {
  WorkerPool pool(4);
  const auto caller = std::this_thread::get_id();
  pool.setQuiet(true);
  {
    const WorkerPool::Awake awake(&pool);
    int calls = 0;
    pool.forRangeWithSlot(100000, 64, [&](size_t begin, size_t end, unsigned slot) {
      ++calls;
      EXPECT_EQ(begin, 0u);
      EXPECT_EQ(end, 100000u);
      EXPECT_EQ(slot, 0u);
      EXPECT_EQ(std::this_thread::get_id(), caller);
    });
    EXPECT_EQ(calls, 1);
  }
  pool.setQuiet(false);
  std::atomic<int> calls{0};
  pool.forRange(100000, 64, [&](size_t, size_t) { ++calls; });
  EXPECT_GT(calls.load(), 1);
}

// Many loops in a row, as a frame loop issues them: each sees all of its range and none of
// the previous loop's work leaks into it.
TEST(WorkerPool, RepeatedLoopsStayConsistent) {
  WorkerPool pool(3);
  std::vector<uint32_t> data(4096, 0);
  for (uint32_t round = 1; round <= 2000; ++round) {
    pool.forRange(data.size(), 16, [&](size_t begin, size_t end) {
      for (size_t i = begin; i < end; ++i) data[i] += 1;
    });
  }
  for (uint32_t x : data) ASSERT_EQ(x, 2000u);
}

}  // namespace
}  // namespace lodline
