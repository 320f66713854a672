// View-dependent floating-cell vertex clustering, recomputed every frame: the dynamic half of
//
//   Pan, Zhou, Shi, "Real-time rendering algorithm based on hybrid static and dynamic
//   simplification methods" (docs/design.md §2.4): vertex weights C_i, frustum and back-face
//   culling marking vertices −1, and in weight order each unclustered vertex absorbing the
//   unclustered vertices inside a sphere of radius R = sqrt(K·W·H/(Width·Height))·|OP|/|OP'|.
//
// Derivation of R for lodline's Camera. W×H is the view window on the projection plane at
// distance |OP'| = n from the eye, spread over Width×Height pixels; for a perspective camera
// with vertical field of view φ and aspect Width/Height, W·H/(Width·Height) = (2n·tan(φ/2)/
// Height)², i.e. the area of one pixel on that plane. |OP|/|OP'| scales it to the vertex's
// depth z (eye-space distance along the view axis; the ratio is the same along the ray), so
//   R = sqrt(K) · 2·z·tan(φ/2) / Height,
// the world-space side of a K-pixel² square at the vertex's depth (K = 1: one pixel; K is an
// area, as in the paper). Orthographic: R = sqrt(K)·ortho_height/Height. With foveation the
// paper's factor (90°/(90°−q))² (q: angle between the vertex's ray and the gaze ray, clamped
// to 80°), raised to `foveation`, multiplies K.
//
// Everything is flat arrays over the input vertices; a uniform grid (counting sort into
// cells) makes a frame O(V + F) for a bounded spread of radii. Nothing is allocated after the
// first frames.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/camera.h"
#include "core/mesh.h"

namespace lodline {

/// Per-frame clustering settings.
struct ClusterParams {
  /// Pixel error K of Pan et al.: the clustering sphere of a vertex is as wide as a K-px²
  /// square at its depth (1 px² by default, the paper's "1 pixel error").
  float pixel_error = 1.0f;
  /// Exponent on the foveation factor (90°/(90°−q))² applied to K; 0 = off, 1 = the paper's.
  float foveation = 0.0f;
  /// Gaze point for foveation, pixels (origin top-left); negative: the image centre.
  glm::vec2 focus_px{-1.0f, -1.0f};
  /// Frustum and back-face culling mark vertices −1 (they are then never clustered).
  bool cull = true;
};

/// Statistics of the last cluster() call.
struct ClusterStats {
  uint32_t culled_vertices = 0;   ///< vertices marked −1
  uint32_t representatives = 0;   ///< visible vertices that head a cluster
  uint32_t absorbed = 0;          ///< visible vertices merged into another one
  uint32_t faces = 0;             ///< faces output
  uint32_t culled_faces = 0;      ///< faces dropped because all their vertices were culled
  uint32_t collapsed_faces = 0;   ///< faces dropped because two mapped corners coincide
  /// faces dropped as duplicates: the later of a same-orientation pair, both of a fold pair
  uint32_t duplicate_faces = 0;
};

/// Marker in representatives() for a culled vertex (the paper's −1); culled vertices keep
/// their own position and index in the output faces.
inline constexpr uint32_t kClusterCulled = 0xffffffffu;

class VertexClustering {
 public:
  /// Precomputes the weights C_i and the weight-sorted order of `mesh` (copied). Vertices on
  /// a boundary or a non-manifold edge get the maximal weight and are never absorbed.
  explicit VertexClustering(TriMesh mesh);

  /// Clusters for one view of a `width`×`height` image and fills faces(). O(V + F).
  void cluster(const Camera& camera, int width, int height, const ClusterParams& params);

  /// The input mesh (its positions are the output positions: a representative keeps its own).
  const TriMesh& mesh() const { return mesh_; }
  /// Output faces of the last cluster(), indexing mesh().positions; no face has two equal
  /// corners and no two faces share the same corner set. Slots are stable: a face that stays
  /// keeps its index from one frame to the next (freed slots are refilled, then the array is
  /// compacted by moving faces from the end), so incremental shape updates (ShapeCache
  /// compares face slots) touch only where the clustering changed.
  std::span<const std::array<uint32_t, 3>> faces() const { return out_faces_; }
  /// The input face each of faces() stands for, in the same order (its material, for
  /// material lines).
  std::span<const uint32_t> faceIds() const { return slot_face_; }
  /// Per input vertex: its representative (itself for a representative) or kClusterCulled.
  std::span<const uint32_t> representatives() const { return rep_; }
  /// Per input vertex: the clustering radius R of the last frame in model units (0 when
  /// culled); a vertex's distance to its representative is at most the representative's R.
  std::span<const float> radii() const { return radius_; }
  /// C_i per input vertex, radians (mean angle between the vertex normal and its faces').
  std::span<const float> weights() const { return weight_; }
  /// Vertex ids by decreasing weight (ties by index).
  std::span<const uint32_t> order() const { return order_; }
  std::span<const uint8_t> boundaryVertices() const { return boundary_; }
  const ClusterStats& stats() const { return stats_; }

 private:
  TriMesh mesh_;
  std::vector<glm::vec3> vertex_normal_;  // area-weighted, unit
  std::vector<glm::vec3> face_normal_;    // unit (zero if degenerate)
  std::vector<float> weight_;
  std::vector<uint32_t> order_;
  std::vector<uint8_t> boundary_;
  std::vector<uint32_t> vf_start_, vf_faces_;  // vertex → incident faces (CSR)
  // per frame
  std::vector<uint32_t> rep_;
  std::vector<float> radius_;
  std::vector<uint8_t> outside_;  // frustum outcodes per vertex (6 bits)
  std::vector<uint32_t> cell_of_, cell_start_, cell_items_;
  std::vector<std::array<uint32_t, 3>> out_faces_;   // per output slot
  std::vector<std::array<uint32_t, 3>> candidate_;   // per input face this frame (or all kClusterCulled)
  std::vector<uint32_t> face_slot_;                  // per input face: its output slot or kClusterCulled
  std::vector<uint32_t> slot_face_;                  // per output slot: its input face
  std::vector<uint32_t> free_slots_;
  std::vector<uint8_t> slot_free_;
  std::vector<uint32_t> hash_;
  ClusterStats stats_;
};

}  // namespace lodline
