#include "core/hash.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace lodline {
namespace {

// A stream hashed in pieces of any sizes (empty, shorter than a word, straddling words)
// gives hashBytes() of the whole: the progressive-mesh loader checks its file this way.
TEST(StreamingHash, PiecesEqualTheWhole) {
  std::mt19937 rng(3);
  std::vector<unsigned char> data(1000);
  for (auto& b : data) b = static_cast<unsigned char>(rng());
  for (size_t total : {size_t{0}, size_t{5}, size_t{8}, size_t{13}, size_t{64}, size_t{1000}}) {
    const uint64_t whole = hashBytes(data.data(), total, 42);
    for (int trial = 0; trial < 20; ++trial) {
      StreamingHash s(42);
      size_t at = 0;
      while (at < total) {
        const size_t piece = std::min<size_t>(total - at, rng() % 12);
        s.update(data.data() + at, piece);
        at += piece;
      }
      EXPECT_EQ(s.finish(), whole) << "total " << total << ", trial " << trial;
    }
  }
  // A different byte changes it.
  StreamingHash s(42);
  std::vector<unsigned char> other(data.begin(), data.begin() + 64);
  other[17] ^= 1;
  s.update(other.data(), 64);
  EXPECT_NE(s.finish(), hashBytes(data.data(), 64, 42));
}

}  // namespace
}  // namespace lodline
