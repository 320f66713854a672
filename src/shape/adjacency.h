// Mesh adjacency over flat arrays (docs/design.md §6): vertex→face rings, an undirected edge list
// with its adjacent faces, and the three edges of every face. Built once per connectivity,
// or brought up to date in place when a few face slots change (a view-dependent mesh splits
// and collapses a few hundred vertices per frame); the per-frame stages (shape, lines) only
// read it.
//
// Robustness: faces with a repeated or out-of-range vertex index are "invalid": they are
// listed in no ring and own no edge. Edges shared by more than two faces (non-manifold)
// are kept, with their face count; boundary edges have exactly one face.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "core/mesh.h"

namespace lodline {

/// Marks "no face / no edge" in the index arrays below.
inline constexpr uint32_t kNoIndex = std::numeric_limits<uint32_t>::max();

struct MeshAdjacency {
  uint32_t vertex_count = 0;
  uint32_t face_count = 0;

  /// Faces around each vertex: the faces of vertex v are
  /// vertex_faces[vertex_face_begin[v] .. vertex_face_end[v]), in increasing face order
  /// (the same order after in-place updates, so gathers over a ring are reproducible).
  /// Rings are stored with some slack, so ring v + 1 need not start where ring v ends.
  std::vector<uint32_t> vertex_face_begin;
  std::vector<uint32_t> vertex_face_end;
  std::vector<uint32_t> vertex_faces;
  /// Which corner (0..2) of that face the vertex is; parallel to vertex_faces.
  std::vector<uint8_t> vertex_face_corners;

  /// Undirected edges, edges[e][0] < edges[e][1]. After updateAdjacency() some entries may
  /// be unused: those have edge_face_count 0 and edges[e] = {0, 0}.
  std::vector<EdgeKey> edges;
  /// First two faces on each edge (kNoIndex where absent), in increasing face order.
  std::vector<std::array<uint32_t, 2>> edge_faces;
  /// Number of valid faces on each edge: 1 boundary, 2 manifold, > 2 non-manifold, 0 unused.
  std::vector<uint32_t> edge_face_count;

  /// Edge of each face side: face_edges[f][j] joins corners j and (j+1)%3;
  /// kNoIndex for every side of an invalid face.
  std::vector<std::array<uint32_t, 3>> face_edges;
  /// 1 for faces with three distinct in-range vertex indices, else 0.
  std::vector<uint8_t> face_valid;

  /// 1 for vertices on a boundary or non-manifold edge, else 0.
  std::vector<uint8_t> vertex_on_boundary;

  /// Working storage (kept so rebuilding or updating every frame allocates nothing).
  std::vector<uint32_t> scratch_seen, scratch_edge, scratch_added, free_edges, ring_limit;
  std::vector<uint8_t> scratch_mark, scratch_kept;

  size_t edgeCount() const { return edges.size(); }
  /// Faces of v, in increasing order.
  std::span<const uint32_t> facesOf(uint32_t v) const {
    return {vertex_faces.data() + vertex_face_begin[v], vertex_face_end[v] - vertex_face_begin[v]};
  }
  /// Index of the edge joining a and b, or kNoIndex (linear in the degree of a).
  uint32_t findEdge(uint32_t a, uint32_t b) const;
};

/// Builds all of `out` from mesh.faces (positions are not read; only their count).
/// Reuses out's storage. O(F + V).
void buildAdjacency(const TriMesh& mesh, MeshAdjacency& out);
/// The same from the face triples over `vertex_count` vertices.
void buildAdjacency(std::span<const std::array<uint32_t, 3>> faces, uint32_t vertex_count,
                    MeshAdjacency& out);
/// 1 for a face with three distinct indices below vertex_count ("valid", as above), else 0.
inline uint8_t faceIsValid(const std::array<uint32_t, 3>& t, uint32_t vertex_count) {
  return t[0] < vertex_count && t[1] < vertex_count && t[2] < vertex_count && t[0] != t[1] &&
         t[1] != t[2] && t[2] != t[0];
}

/// Brings `adj`, built (or updated) for the faces `old_faces` over at most as many vertices
/// as mesh has, up to date with mesh.faces. `changed` lists every face slot whose triple
/// differs: slots below both sizes whose triple changed, the slots added at the end and the
/// slots removed from the end (any order, no repeats). O(changed · degree). The result
/// describes the same rings, in the same order, and the same edges with the same faces as
/// buildAdjacency(mesh) would; only edge numbering differs. Returns false, leaving `adj` as
/// it was, when a rebuild is the better choice (more than an eighth of the slots changed,
/// or the ring storage has grown to twice what a rebuild needs).
bool updateAdjacency(const TriMesh& mesh, std::span<const std::array<uint32_t, 3>> old_faces,
                     std::span<const uint32_t> changed, MeshAdjacency& adj);

/// True when mesh.faces is a closed surface seen from outside: every face valid, every edge
/// on exactly two faces that run along it in opposite directions (consistent orientation),
/// and each connected piece of positive signed volume (counter-clockwise seen from outside).
/// Its back faces are then never visible from outside it, so drawing may cull them. O(F + E).
bool isClosedOutward(const TriMesh& mesh, const MeshAdjacency& adj);

/// "" if `adj` describes mesh.faces exactly as buildAdjacency would (up to edge numbering),
/// else the first difference. For tests; O(F + V).
std::string checkAdjacency(const TriMesh& mesh, const MeshAdjacency& adj);

}  // namespace lodline
