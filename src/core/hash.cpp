#include "core/hash.h"

#include <algorithm>
#include <cstring>

namespace lodline {

namespace {
constexpr uint64_t kPrime = 0x100000001b3ull;  // FNV-1a's 64-bit prime

inline uint64_t word(uint64_t h, const unsigned char* p) {
  uint64_t w;
  std::memcpy(&w, p, 8);
  h = (h ^ w) * kPrime;
  return h ^ (h >> 29);
}

inline uint64_t finishHash(uint64_t h, const unsigned char* tail, size_t tail_size, size_t size) {
  for (size_t i = 0; i < tail_size; ++i) h = (h ^ tail[i]) * kPrime;
  h ^= size;
  h *= kPrime;
  h ^= h >> 32;
  return h;
}
}  // namespace

void StreamingHash::update(const void* data, size_t size) {
  const auto* p = static_cast<const unsigned char*>(data);
  total_ += size;
  size_t i = 0;
  if (npending_ > 0) {  // complete the unfinished word first
    const size_t take = std::min<size_t>(8 - npending_, size);
    std::memcpy(pending_ + npending_, p, take);
    npending_ += take;
    i = take;
    if (npending_ < 8) return;
    h_ = word(h_, pending_);
    npending_ = 0;
  }
  for (; i + 8 <= size; i += 8) h_ = word(h_, p + i);
  npending_ = size - i;
  if (npending_ > 0) std::memcpy(pending_, p + i, npending_);
}

uint64_t StreamingHash::finish() const { return finishHash(h_, pending_, npending_, total_); }

uint64_t hashBytes(const void* data, size_t size, uint64_t seed) {
  const auto* p = static_cast<const unsigned char*>(data);
  uint64_t h = seed;
  size_t i = 0;
  for (; i + 8 <= size; i += 8) h = word(h, p + i);
  return finishHash(h, p + i, size - i, size);
}

}  // namespace lodline
