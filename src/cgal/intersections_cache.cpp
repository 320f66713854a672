// The cache of findIntersectionSegmentsCached(). Layout (little-endian): magic "LODLIX\0\x1a",
// u32 version, u32 mesh count, u64 key (the hash of every mesh's positions and faces), then
// per mesh a u64 count of points and 3 f32 per point, then a u64 checksum (hashBytes) of all
// that precedes it.
#include <cstring>
#include <fstream>
#include <sstream>

#include "cgal/intersections.h"
#include "core/hash.h"
#include "io/atomic_file.h"
#include "pm/progressive_mesh.h"

namespace lodline {
namespace {

constexpr char kMagic[8] = {'L', 'O', 'D', 'L', 'I', 'X', '\0', '\x1a'};
constexpr uint32_t kVersion = 1;
// Far more points than any scene's crossings have: a count above it is damage.
constexpr uint64_t kMaxPoints = uint64_t{1} << 28;

uint64_t keyOf(std::span<const TriMesh* const> meshes) {
  uint64_t h = hashBytes(&kVersion, sizeof(kVersion));
  for (const TriMesh* m : meshes) {
    const uint64_t c = meshContentHash(*m);
    h = hashBytes(&c, sizeof(c), h);
  }
  return h;
}

template <class T>
void put(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof(T));
}

template <class T>
bool get(const std::string& in, size_t& at, T& v) {
  if (at + sizeof(T) > in.size()) return false;
  std::memcpy(&v, in.data() + at, sizeof(T));
  at += sizeof(T);
  return true;
}

// The segments stored in `bytes` for `key` and `count` meshes, or false.
bool parse(const std::string& bytes, uint64_t key, size_t count, std::vector<std::vector<glm::vec3>>& out) {
  if (bytes.size() < sizeof(kMagic) + 8 + 8 + 8 || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0) return false;
  uint64_t checksum = 0;
  std::memcpy(&checksum, bytes.data() + bytes.size() - 8, 8);
  if (hashBytes(bytes.data(), bytes.size() - 8) != checksum) return false;
  size_t at = sizeof(kMagic);
  uint32_t version = 0, meshes = 0;
  uint64_t stored_key = 0;
  if (!get(bytes, at, version) || !get(bytes, at, meshes) || !get(bytes, at, stored_key)) return false;
  if (version != kVersion || meshes != count || stored_key != key) return false;
  out.assign(count, {});
  for (size_t m = 0; m < count; ++m) {
    uint64_t n = 0;
    if (!get(bytes, at, n) || n > kMaxPoints || n % 2 != 0 || at + n * 12 > bytes.size() - 8) return false;
    out[m].resize(n);
    std::memcpy(out[m].data(), bytes.data() + at, n * 12);
    at += n * 12;
  }
  return at == bytes.size() - 8;
}

}  // namespace

std::vector<std::vector<glm::vec3>> findIntersectionSegmentsCached(std::span<const TriMesh* const> meshes,
                                                                  const std::filesystem::path& cache_dir,
                                                                  std::string* note) {
  const uint64_t key = keyOf(meshes);
  char name[32];
  std::snprintf(name, sizeof(name), "%016llx.lix", static_cast<unsigned long long>(key));
  const std::filesystem::path path = cache_dir / name;
  std::error_code ec;
  if (std::filesystem::is_regular_file(path, ec)) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream buffer;
    buffer << in.rdbuf();
    std::vector<std::vector<glm::vec3>> out;
    if (in && parse(buffer.str(), key, meshes.size(), out)) {
      if (note) *note = "loaded intersection lines " + path.string();
      return out;
    }
  }
  auto out = findIntersectionSegments(meshes);
  std::string bytes(kMagic, sizeof(kMagic));
  put(bytes, kVersion);
  put(bytes, static_cast<uint32_t>(meshes.size()));
  put(bytes, key);
  for (const auto& segments : out) {
    put(bytes, static_cast<uint64_t>(segments.size()));
    bytes.append(reinterpret_cast<const char*>(segments.data()), segments.size() * sizeof(glm::vec3));
  }
  put(bytes, hashBytes(bytes.data(), bytes.size()));
  std::filesystem::create_directories(cache_dir, ec);
  const Status s = writeFileAtomically(path, [&](std::ostream& os) -> Status {
    os.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return {};
  });
  if (note) *note = s ? "found intersection lines, wrote " + path.string() : "found intersection lines (cache not written: " + s.error().message + ")";
  return out;
}

}  // namespace lodline
