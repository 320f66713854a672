// Mesh order for memory locality (docs/performance.md, "Vertex order"): the stages that run
// over a full-detail mesh — adjacency, curvature and its derivatives, the per-view line
// passes — read each face's three corners and each vertex's ring. In the order many files
// store them (a refined mesh appends the new vertices at the end), a face's corners lie
// about half the mesh apart, and every corner read is a cache miss. Numbering the vertices
// along a Morton (Z-order) curve through the bounding box and sorting the faces by their
// lowest corner puts neighbours near each other in every array.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "core/mesh.h"

namespace lodline {

/// Renumbers `mesh`'s vertices along a Morton curve over its bounding box (10 bits an axis;
/// ties keep the stored order) and sorts its faces by their lowest new vertex index (ties
/// keep the stored order), when the stored order is not local already: only if the median
/// corner spread (below) is above 256 and falls, so a mesh stored in a good order (a
/// generated tube, ring by ring) keeps it. Each face keeps its corners' cyclic order, so its orientation; marked
/// edges and face materials follow their vertices and faces. The surface is the same: only
/// the indices change. A mesh with a non-finite position or an index out of range is left
/// as it is (validateMesh reports it). Returns whether the mesh was reordered; then
/// `stored_to_drawn`, if given, receives the new index of each vertex as stored (else it is
/// emptied). Linear in the size plus sorts.
bool orderForLocality(TriMesh& mesh, std::vector<uint32_t>* stored_to_drawn = nullptr);

/// The 30-bit Morton code of a point of the unit cube `t` (10 bits an axis; each coordinate
/// clamped to [0, 1], NaN to 0).
uint32_t mortonCode(const glm::vec3& t);

/// Sorts `items` stably by `code[item]` (codes below 2^30): a least-significant-digit radix
/// sort, 10 bits a pass. `tmp` is scratch.
void sortByCode(std::span<const uint32_t> code, std::vector<uint32_t>& items, std::vector<uint32_t>& tmp);

/// `order` receives the indices of `faces` sorted stably by their lowest corner (a counting
/// sort over `vertex_count` vertices; every corner must be below it). `start` is scratch.
void orderByLowestCorner(std::span<const std::array<uint32_t, 3>> faces, uint32_t vertex_count,
                         std::vector<uint32_t>& order, std::vector<uint32_t>& start);

/// The median, over faces, of the largest minus the smallest corner index: how far apart in
/// the vertex arrays a face's corners lie (0 for an empty mesh).
uint32_t medianCornerSpread(const TriMesh& mesh);

}  // namespace lodline
