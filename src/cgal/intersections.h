// Intersection lines: where the surfaces of two objects of a scene, or two parts of one
// object, cross (Line Art's and Freestyle's "intersection" edges). Computed once, in world
// space, on the full-detail meshes (objects are rigid): candidate triangle pairs from
// CGAL's box intersection (box_self_intersection_d over every triangle's bounding box),
// the exact intersection test (CGAL::do_intersect over the Epick kernel), then the segment
// from each triangle's piece on the other's plane, cut where the exact orientation of the
// corners changes. Triangles with a common corner (neighbours, or parts touching there) and
// coplanar overlaps are not crossings.
// The CGAL code lives in cgal_algorithms.cpp, the one CGAL translation unit.
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "core/mesh.h"

namespace lodline {

/// Segments where surfaces cross, for each mesh of `meshes`: out[i] holds segment endpoints
/// in pairs (world units), the crossings of mesh i with a mesh j > i and with itself.
/// Coplanar overlaps (no curve) are left out; degenerate triangles are skipped.
std::vector<std::vector<glm::vec3>> findIntersectionSegments(std::span<const TriMesh* const> meshes);

/// findIntersectionSegments(), cached in `cache_dir` under the hash of the meshes (one
/// checksummed file per set of meshes, "<16 hex digits>.lix", written atomically): a scene
/// or model drawn again does not search again. A cache that cannot be read or written is
/// not an error: the search runs (and `note`, optional, says what happened).
std::vector<std::vector<glm::vec3>> findIntersectionSegmentsCached(std::span<const TriMesh* const> meshes,
                                                                  const std::filesystem::path& cache_dir,
                                                                  std::string* note = nullptr);

}  // namespace lodline
