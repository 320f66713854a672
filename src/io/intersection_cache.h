// The cache file of intersection lines (cgal/intersections.h): the segments found for a set
// of meshes, so a scene drawn again does not search again. Compact, versioned, checksummed
// binary (little-endian):
//   magic "LODLIX\0\x1a", u32 version, u32 mesh count, u64 key (the caller's hash of the
//   meshes), then per mesh a u64 count of points (even: endpoint pairs) and 3 f32 per point,
//   then a u64 checksum (hashBytes) of everything before it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include <glm/vec3.hpp>

#include "core/result.h"

namespace lodline {

/// Segments (endpoint pairs) per mesh.
using IntersectionSegments = std::vector<std::vector<glm::vec3>>;

/// Writes `segments` for `key` to `path` atomically. Errors name the path.
Status saveIntersectionCache(const std::filesystem::path& path, uint64_t key, const IntersectionSegments& segments);

/// Reads a file written by saveIntersectionCache() for `key` and `mesh_count` meshes.
/// Errors name the path and the problem: not a regular file, wrong magic or version,
/// another key or mesh count, truncation, checksum mismatch, impossible counts. Never
/// crashes on hostile input.
Result<IntersectionSegments> loadIntersectionCache(const std::filesystem::path& path, uint64_t key,
                                                   size_t mesh_count);

}  // namespace lodline
