#include "io/intersection_cache.h"

#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "core/hash.h"
#include "io/atomic_file.h"
#include "io/input_check.h"

namespace lodline {
namespace {

constexpr char kMagic[8] = {'L', 'O', 'D', 'L', 'I', 'X', '\0', '\x1a'};
constexpr uint32_t kVersion = 1;
// Far more points than any scene's crossings have: a count above it is damage.
constexpr uint64_t kMaxPoints = uint64_t{1} << 28;
// Larger files are not caches lodline wrote.
constexpr uint64_t kMaxFileBytes = uint64_t{1} << 32;

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

}  // namespace

Status saveIntersectionCache(const std::filesystem::path& path, uint64_t key, const IntersectionSegments& segments) {
  std::string bytes(kMagic, sizeof(kMagic));
  put(bytes, kVersion);
  put(bytes, static_cast<uint32_t>(segments.size()));
  put(bytes, key);
  for (const auto& s : segments) {
    put(bytes, static_cast<uint64_t>(s.size()));
    if (!s.empty()) bytes.append(reinterpret_cast<const char*>(s.data()), s.size() * sizeof(glm::vec3));
  }
  put(bytes, hashBytes(bytes.data(), bytes.size()));
  return writeFileAtomically(path, [&](std::ostream& os) -> Status {
    os.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return {};
  });
}

Result<IntersectionSegments> loadIntersectionCache(const std::filesystem::path& path, uint64_t key,
                                                   size_t mesh_count) {
  const std::string name = path.string();
  if (Status s = checkInputFile(path, "intersection-line cache"); !s) return s.error();
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec || size > kMaxFileBytes) return Error::runtime(name + ": not an intersection-line cache (size)");
  std::ifstream in(path, std::ios::binary);
  std::string bytes(static_cast<size_t>(size), '\0');
  if (!in.read(bytes.data(), static_cast<std::streamsize>(bytes.size())))
    return Error::runtime(name + ": cannot read");
  if (bytes.size() < sizeof(kMagic) + 4 + 4 + 8 + 8 || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0)
    return Error::runtime(name + ": not an intersection-line cache (magic)");
  uint64_t checksum = 0;
  std::memcpy(&checksum, bytes.data() + bytes.size() - 8, 8);
  if (hashBytes(bytes.data(), bytes.size() - 8) != checksum) return Error::runtime(name + ": checksum mismatch");
  size_t at = sizeof(kMagic);
  uint32_t version = 0, meshes = 0;
  uint64_t stored_key = 0;
  if (!get(bytes, at, version) || !get(bytes, at, meshes) || !get(bytes, at, stored_key))
    return Error::runtime(name + ": truncated header");
  if (version != kVersion) return Error::runtime(name + ": unsupported version " + std::to_string(version));
  if (meshes != mesh_count || stored_key != key) return Error::runtime(name + ": written for other meshes");
  IntersectionSegments out(mesh_count);
  const size_t end = bytes.size() - 8;
  for (size_t m = 0; m < mesh_count; ++m) {
    uint64_t n = 0;
    if (at + 8 > end || !get(bytes, at, n)) return Error::runtime(name + ": truncated");
    if (n > kMaxPoints || n % 2 != 0 || n * 12 > end - at)
      return Error::runtime(name + ": impossible point count " + std::to_string(n));
    out[m].resize(static_cast<size_t>(n));
    if (n > 0) std::memcpy(out[m].data(), bytes.data() + at, static_cast<size_t>(n) * 12);
    at += static_cast<size_t>(n) * 12;
  }
  if (at != end) return Error::runtime(name + ": trailing bytes");
  return out;
}

}  // namespace lodline
