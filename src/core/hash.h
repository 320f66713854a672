// The one hash of lodline: a 64-bit FNV-1a variant over 8-byte words, used for the
// progressive-mesh cache (content hash of the input, file checksum) and for short stable
// names (sweep runs). Not cryptographic; stable across runs, builds and machines of the
// same endianness.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace lodline {

/// FNV-1a's 64-bit offset basis, the default seed.
inline constexpr uint64_t kHashSeed = 0xcbf29ce484222325ull;

/// Hash of `size` bytes at `data`, continuing from `seed` (chain calls to hash several
/// buffers as one).
uint64_t hashBytes(const void* data, size_t size, uint64_t seed = kHashSeed);

/// hashBytes() of the characters of `text`.
inline uint64_t hashText(std::string_view text, uint64_t seed = kHashSeed) {
  return hashBytes(text.data(), text.size(), seed);
}

}  // namespace lodline
