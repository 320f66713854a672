// Progressive mesh cache file (see pm_file.h for the layout). Hoppe 1998, "Efficient
// implementation of progressive meshes", §3 motivates the compact flat-array encoding.
#include "pm/pm_file.h"

#include <cstdio>
#include <cstring>
#include <fstream>
#include <system_error>

#include "io/atomic_file.h"

namespace lodline {

namespace {

constexpr char kMagic[8] = {'L', 'O', 'D', 'L', 'P', 'M', '\0', '\x1a'};

struct FileHeader {
  char magic[8];
  uint32_t version;
  uint32_t vertex_count;
  uint32_t face_count;
  uint32_t split_count;
  uint32_t base_face_count;
  uint32_t reserved;
  uint64_t content_hash;
  uint64_t params_hash;
  uint64_t payload_size;
  uint64_t checksum;
};
static_assert(sizeof(FileHeader) == 64, "header layout");
static_assert(sizeof(VertexSplit) == 32, "split layout");

uint64_t payloadSize(uint64_t n, uint64_t nf, uint64_t ns, uint64_t nb) {
  return n * 12 + nf * 12 + ((n + 3) / 4) * 4 + ns * 32 + nb * 4 + nb * 12 + nb * 12;
}

uint64_t checksumOf(FileHeader h, const char* payload, size_t size) {
  h.checksum = 0;
  return hashBytes(payload, size, hashBytes(&h, sizeof(h)));
}

template <class T>
void append(std::string& buf, const std::vector<T>& v) {
  buf.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

template <class T>
void take(const char*& p, std::vector<T>& v, size_t count) {
  v.resize(count);
  std::memcpy(v.data(), p, count * sizeof(T));
  p += count * sizeof(T);
}

}  // namespace

Status savePm(const std::filesystem::path& path, const ProgressiveMesh& pm) {
  FileHeader h{};
  std::memcpy(h.magic, kMagic, 8);
  h.version = kPmFileVersion;
  h.vertex_count = pm.vertexCount();
  h.face_count = pm.faceCount();
  h.split_count = static_cast<uint32_t>(pm.splits.size());
  h.base_face_count = static_cast<uint32_t>(pm.base_faces.size());
  h.content_hash = pm.content_hash;
  h.params_hash = pm.params_hash;
  h.payload_size = payloadSize(h.vertex_count, h.face_count, h.split_count, h.base_face_count);
  std::string payload;
  payload.reserve(h.payload_size);
  append(payload, pm.positions);
  append(payload, pm.faces);
  append(payload, pm.vertex_flags);
  payload.append(((pm.vertex_flags.size() + 3) / 4) * 4 - pm.vertex_flags.size(), '\0');
  append(payload, pm.splits);
  append(payload, pm.base_faces);
  append(payload, pm.base_corners);
  append(payload, pm.base_neighbors);
  if (payload.size() != h.payload_size)
    return Error::runtime(path.string() + ": internal error: inconsistent progressive mesh");
  h.checksum = checksumOf(h, payload.data(), payload.size());
  return writeFileAtomically(path, [&](std::ostream& os) -> Status {
    os.write(reinterpret_cast<const char*>(&h), sizeof(h));
    os.write(payload.data(), static_cast<std::streamsize>(payload.size()));
    return Status::success();
  });
}

Result<ProgressiveMesh> loadPm(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::error_code ec;
  const auto file_size = std::filesystem::file_size(path, ec);
  if (ec) return Error::runtime(name + ": cannot read progressive mesh file: " + ec.message());
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error::runtime(name + ": cannot open progressive mesh file");
  if (file_size < sizeof(FileHeader))
    return Error::runtime(name + ": truncated progressive mesh file (" +
                          std::to_string(file_size) + " bytes, header needs 64)");
  FileHeader h;
  in.read(reinterpret_cast<char*>(&h), sizeof(h));
  if (!in) return Error::runtime(name + ": cannot read header");
  if (std::memcmp(h.magic, kMagic, 8) != 0)
    return Error::runtime(name + ": not a lodline progressive mesh file (bad magic)");
  if (h.version != kPmFileVersion)
    return Error::runtime(name + ": progressive mesh file version " + std::to_string(h.version) +
                          " is not supported (expected " + std::to_string(kPmFileVersion) + ")");
  const uint64_t expect =
      payloadSize(h.vertex_count, h.face_count, h.split_count, h.base_face_count);
  if (h.payload_size != expect)
    return Error::runtime(name + ": corrupt header (payload size does not match the counts)");
  if (file_size - sizeof(FileHeader) < expect)
    return Error::runtime(name + ": truncated progressive mesh file (" +
                          std::to_string(file_size) + " bytes, expected " +
                          std::to_string(expect + sizeof(FileHeader)) + ")");
  if (file_size - sizeof(FileHeader) > expect)
    return Error::runtime(name + ": trailing bytes after the progressive mesh data");
  std::string payload(expect, '\0');
  in.read(payload.data(), static_cast<std::streamsize>(expect));
  if (!in) return Error::runtime(name + ": read error");
  if (checksumOf(h, payload.data(), payload.size()) != h.checksum)
    return Error::runtime(name + ": checksum mismatch (file corrupt)");
  ProgressiveMesh pm;
  const char* p = payload.data();
  take(p, pm.positions, h.vertex_count);
  take(p, pm.faces, h.face_count);
  take(p, pm.vertex_flags, h.vertex_count);
  p += ((h.vertex_count + 3) / 4) * 4 - h.vertex_count;
  take(p, pm.splits, h.split_count);
  take(p, pm.base_faces, h.base_face_count);
  take(p, pm.base_corners, h.base_face_count);
  take(p, pm.base_neighbors, h.base_face_count);
  pm.content_hash = h.content_hash;
  pm.params_hash = h.params_hash;
  Status st = pm.finalize(name);
  if (!st.ok()) return st.error();
  return pm;
}

std::filesystem::path pmCachePath(const std::filesystem::path& cache_dir, uint64_t content_hash) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%016llx.lpm", static_cast<unsigned long long>(content_hash));
  return cache_dir / buf;
}

Result<ProgressiveMesh> loadOrBuildPm(const TriMesh& mesh, uint64_t content_hash,
                                      const std::filesystem::path& cache_dir,
                                      const PmBuildParams& params, const PmProgress& progress,
                                      std::string* note) {
  const std::filesystem::path path = pmCachePath(cache_dir, content_hash);
  const uint64_t params_hash = buildParamsHash(params);
  std::string why = "no cache";
  std::error_code ec;
  if (std::filesystem::exists(path, ec)) {
    Result<ProgressiveMesh> cached = loadPm(path);
    if (cached.ok()) {
      const ProgressiveMesh& pm = cached.value();
      if (pm.content_hash == content_hash && pm.params_hash == params_hash &&
          pm.vertexCount() == mesh.vertexCount() && pm.faceCount() == mesh.faceCount()) {
        if (note) *note = "loaded progressive mesh cache " + path.string();
        return cached;
      }
      why = "cache stale (different model or build parameters)";
    } else {
      why = "cache unreadable (" + cached.error().message + ")";
    }
  }
  Result<ProgressiveMesh> built = buildProgressiveMesh(mesh, params, progress);
  if (!built.ok()) return built;
  built.value().content_hash = content_hash;
  std::filesystem::create_directories(cache_dir, ec);
  Status saved = ec ? Status(Error::runtime(cache_dir.string() + ": " + ec.message()))
                    : savePm(path, built.value());
  if (note) {
    *note = why + ", rebuilt progressive mesh";
    if (saved.ok()) *note += " and wrote " + path.string();
    else *note += "; could not write the cache: " + saved.error().message;
  }
  return built;
}

}  // namespace lodline
