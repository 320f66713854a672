#include "core/hash.h"

#include <cstring>

namespace lodline {

uint64_t hashBytes(const void* data, size_t size, uint64_t seed) {
  const auto* p = static_cast<const unsigned char*>(data);
  uint64_t h = seed;
  constexpr uint64_t kPrime = 0x100000001b3ull;  // FNV-1a's 64-bit prime
  size_t i = 0;
  for (; i + 8 <= size; i += 8) {
    uint64_t w;
    std::memcpy(&w, p + i, 8);
    h = (h ^ w) * kPrime;
    h ^= h >> 29;
  }
  for (; i < size; ++i) h = (h ^ p[i]) * kPrime;
  h ^= size;
  h *= kPrime;
  h ^= h >> 32;
  return h;
}

}  // namespace lodline
