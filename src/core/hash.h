// The one hash of lodline: a 64-bit FNV-1a variant over 8-byte words, used for the
// progressive-mesh cache (content hash of the input, file checksum) and for short stable
// names (sweep runs); and a mixer of 64-bit keys for deterministic noise (the stroke
// styles' jitter and the generated brushes). Not cryptographic; stable across runs, builds
// and machines of the same endianness.
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

/// hashBytes() of a byte stream given in pieces: update() with each piece in order, then
/// finish() equals hashBytes(all the pieces concatenated, their total size, seed) — so a file
/// can be checked while it is read straight into its arrays.
class StreamingHash {
 public:
  explicit StreamingHash(uint64_t seed = kHashSeed) : h_(seed) {}
  void update(const void* data, size_t size);
  uint64_t finish() const;

 private:
  uint64_t h_;
  size_t total_ = 0;
  unsigned char pending_[8] = {};
  size_t npending_ = 0;  // bytes of an unfinished word, < 8
};

/// hashBytes() of the characters of `text`.
inline uint64_t hashText(std::string_view text, uint64_t seed = kHashSeed) {
  return hashBytes(text.data(), text.size(), seed);
}

/// splitmix64's finaliser of `key` (+ the golden-ratio increment): well-spread bits.
inline uint64_t mixBits(uint64_t key) {
  uint64_t z = key + 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

/// mixBits() of `key` as a float in [0, 1) (24 bits).
inline float unitNoise(uint64_t key) { return static_cast<float>(mixBits(key) >> 40) / static_cast<float>(1u << 24); }

}  // namespace lodline
