// Mesh adjacency over flat arrays (STYLE.md §2): vertex→face and vertex→vertex rings in
// compressed (offsets/data) form, an undirected edge list with its adjacent faces, and the
// three edges of every face. Built once per connectivity; the per-frame stages (shape,
// lines) only read it.
//
// Robustness: faces with a repeated or out-of-range vertex index are "invalid": they are
// listed in no ring and own no edge. Edges shared by more than two faces (non-manifold)
// are kept, with their face count; boundary edges have exactly one face.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/mesh.h"

namespace lodline {

/// Marks "no face / no edge" in the index arrays below.
inline constexpr uint32_t kNoIndex = std::numeric_limits<uint32_t>::max();

struct MeshAdjacency {
  uint32_t vertex_count = 0;
  uint32_t face_count = 0;

  /// Faces around each vertex: faces of vertex v are
  /// vertex_faces[vertex_face_offsets[v] .. vertex_face_offsets[v+1]), in increasing face
  /// order. vertex_face_offsets has vertex_count + 1 entries.
  std::vector<uint32_t> vertex_face_offsets;
  std::vector<uint32_t> vertex_faces;
  /// Which corner (0..2) of that face the vertex is; parallel to vertex_faces.
  std::vector<uint8_t> vertex_face_corners;

  /// Distinct neighbours of each vertex (the 1-ring), same offsets/data layout.
  std::vector<uint32_t> vertex_vertex_offsets;
  std::vector<uint32_t> vertex_vertices;

  /// Undirected edges, edges[e][0] < edges[e][1], grouped by their smaller vertex
  /// (ascending), so the edges of vertex v as smaller end are
  /// [edge_offsets[v], edge_offsets[v+1]); edge_offsets has vertex_count + 1 entries.
  std::vector<EdgeKey> edges;
  std::vector<uint32_t> edge_offsets;
  /// First two faces on each edge (kNoIndex where absent), in increasing face order.
  std::vector<std::array<uint32_t, 2>> edge_faces;
  /// Number of valid faces on each edge: 1 boundary, 2 manifold, > 2 non-manifold.
  std::vector<uint32_t> edge_face_count;

  /// Edge of each face side: face_edges[f][j] joins corners j and (j+1)%3;
  /// kNoIndex for every side of an invalid face.
  std::vector<std::array<uint32_t, 3>> face_edges;
  /// 1 for faces with three distinct in-range vertex indices, else 0.
  std::vector<uint8_t> face_valid;

  /// 1 for vertices on a boundary or non-manifold edge, else 0.
  std::vector<uint8_t> vertex_on_boundary;

  /// Working storage of buildAdjacency (kept so rebuilding every frame allocates nothing).
  std::vector<uint32_t> scratch_seen, scratch_edge;

  size_t edgeCount() const { return edges.size(); }
  /// Index of the edge joining a and b, or kNoIndex (linear in the degree of min(a, b)).
  uint32_t findEdge(uint32_t a, uint32_t b) const;
};

/// Builds all of `out` from mesh.faces (positions are not read; only their count).
/// Reuses out's storage. O(F + V).
void buildAdjacency(const TriMesh& mesh, MeshAdjacency& out);

}  // namespace lodline
