// findIntersectionSegmentsCached(): the search, or its result read from the cache file
// (io/intersection_cache.h) of the same meshes.
#include <cstdio>

#include "cgal/intersections.h"
#include "core/hash.h"
#include "io/intersection_cache.h"
#include "pm/progressive_mesh.h"

namespace lodline {

std::vector<std::vector<glm::vec3>> findIntersectionSegmentsCached(std::span<const TriMesh* const> meshes,
                                                                  const std::filesystem::path& cache_dir,
                                                                  std::string* note) {
  // The key: the meshes' content and the search's version (a better search: other lines).
  constexpr uint32_t kSearchVersion = 2;
  uint64_t key = hashBytes(&kSearchVersion, sizeof(kSearchVersion));
  for (const TriMesh* m : meshes) {
    const uint64_t c = meshContentHash(*m);
    key = hashBytes(&c, sizeof(c), key);
  }
  char name[32];
  std::snprintf(name, sizeof(name), "%016llx.lix", static_cast<unsigned long long>(key));
  const std::filesystem::path path = cache_dir / name;
  std::error_code ec;
  if (std::filesystem::exists(path, ec)) {
    auto cached = loadIntersectionCache(path, key, meshes.size());
    if (cached) {
      if (note) *note = "loaded intersection lines " + path.string();
      return std::move(cached.value());
    }
  }
  auto out = findIntersectionSegments(meshes);
  std::filesystem::create_directories(cache_dir, ec);
  const Status s = saveIntersectionCache(path, key, out);
  if (note)
    *note = s ? "found intersection lines, wrote " + path.string()
              : "found intersection lines (cache not written: " + s.error().message + ")";
  return out;
}

}  // namespace lodline
