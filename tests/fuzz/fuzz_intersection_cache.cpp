// Fuzz target: the intersection-line cache reader (loadIntersectionCache).
//
// Random bytes almost never pass the magic and checksum checks, so the harness repairs what
// a hostile writer could forge: the first input byte picks the mode, the rest is the file.
//   mode bit 0 = 0: only the checksum (the last 8 bytes) is recomputed;
//   mode bit 0 = 1: also the magic, the version, the mesh count (1..4, from the mode byte)
//                   and the key, so the fuzzer reaches the point counts and the payload.
#include <cstring>
#include <string>

#include "core/hash.h"
#include "harness.h"
#include "io/intersection_cache.h"

namespace {

constexpr uint64_t kKey = 0x1234567890abcdefull;

std::string repair(const uint8_t* data, size_t size, size_t& meshes) {
  meshes = 1;
  if (size == 0) return {};
  const bool consistent = data[0] & 1;
  meshes = 1 + ((data[0] >> 1) & 3);
  std::string b(reinterpret_cast<const char*>(data + 1), size - 1);
  if (consistent && b.size() >= 24) {
    const char magic[8] = {'L', 'O', 'D', 'L', 'I', 'X', '\0', '\x1a'};
    std::memcpy(b.data(), magic, 8);
    const uint32_t version = 1, count = static_cast<uint32_t>(meshes);
    std::memcpy(b.data() + 8, &version, 4);
    std::memcpy(b.data() + 12, &count, 4);
    std::memcpy(b.data() + 16, &kKey, 8);
  }
  if (b.size() >= 8) {
    const uint64_t sum = lodline::hashBytes(b.data(), b.size() - 8);
    std::memcpy(b.data() + b.size() - 8, &sum, 8);
  }
  return b;
}

}  // namespace

LODLINE_FUZZ_TARGET(intersection_cache) {
  using namespace lodline;
  size_t meshes = 1;
  const std::string bytes = repair(data, size, meshes);
  const fuzz::InputFile input(".lix", bytes, nullptr, 0);
  auto cache = loadIntersectionCache(input.path(), kKey, meshes);
  if (!cache) {
    fuzz::expectCleanError(cache.error(), input.path());
    return;
  }
  if (cache->size() != meshes) fuzz::fail("intersection cache: wrong mesh count accepted");
  for (const auto& segments : *cache)
    if (segments.size() % 2 != 0) fuzz::fail("intersection cache: an odd point count accepted");
}
