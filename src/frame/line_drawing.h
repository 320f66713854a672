// The CPU half of a frame (docs/design.md §1: io → shape → lines): for one model, the
// surface arrays the renderer draws and, per view, the extracted lines grouped by kind.
// Both `lodline render` and the viewer drive this same object, so they draw the same thing.
#pragma once

#include <array>
#include <memory>
#include <span>

#include "core/camera.h"
#include "core/mesh.h"
#include "lines/lines.h"
#include "lines/ridge_lines.h"
#include "lines/strokes.h"
#include "frame/temporal_smoothing.h"
#include "shape/jet_fit.h"
#include "shape/shape_cache.h"

namespace lodline {

/// Milliseconds spent in each CPU stage by the last calls.
struct CpuTimings {
  double shape = 0.0;    ///< normals, curvature, derivatives (setMesh)
  double view = 0.0;     ///< per-view quantities (n·v, kr, Dw kr)
  double extract = 0.0;  ///< zero-set extraction
  double chain = 0.0;    ///< chaining segments into strokes
  double silhouette = 0.0;  ///< the mesh's own silhouette, extracted and chained
};

/// What a LineDrawing is given its full-detail mesh for.
enum class FullMesh {
  kDrawn,     ///< frames draw it: its whole shape (normals, curvature, derivatives) is computed
  /// A level of detail replaces it (updateMesh) before every frame: only what stays the full
  /// model's is computed — its feature size (curvature at the sampled vertices only,
  /// sampledFeatureSize) and its crease vertices — not a shape cache of the whole mesh.
  kReplaced,
};

class LineDrawing {
 public:
  /// Takes the full-detail mesh and computes its shape quantities (normals, curvature,
  /// derivatives), its bounds and its feature size (which stay those of the full-detail model
  /// when level of detail later replaces the mesh). `pool` runs the data-parallel loops; null:
  /// a pool of ShapeParams::threads threads of its own. Drawings of one scene share one pool
  /// (they run one after the other), so a scene wakes one set of workers, not one per object.
  /// With FullMesh::kReplaced, updateMesh() must come before the first update().
  /// `stored_to_drawn`: for a mesh renumbered for locality after loading (core/mesh_order.h),
  /// the new index of each vertex as stored, so the feature size samples the same vertices
  /// (computeFeatureSize); empty when the mesh is as stored. Unused with FullMesh::kReplaced
  /// (that feature size samples the stored mesh itself).
  explicit LineDrawing(TriMesh mesh, const LineParams& params = {}, const ShapeParams& shape_params = {},
                       std::shared_ptr<WorkerPool> pool = nullptr, FullMesh use = FullMesh::kDrawn,
                       std::span<const uint32_t> stored_to_drawn = {});

  /// Replaces the mesh by an adapted one (level of detail): `positions` per vertex slot,
  /// `faces` indexing them; `changed` lists the vertices whose position or incident faces
  /// changed since the last call. Shape quantities are updated incrementally (bit-identical
  /// to a full recompute). Unused slots may hold any finite position. `face_ids`, when given
  /// (one per face), names each face's face in the full-detail mesh, whose material it takes
  /// (material lines); without it the adapted mesh has no materials.
  void updateMesh(std::span<const glm::vec3> positions, std::span<const std::array<uint32_t, 3>> faces,
                  std::span<const uint32_t> changed, std::span<const uint32_t> face_ids = {});
  /// The same, taking `faces` by swapping buffers (it gets the previous face array back).
  void updateMesh(std::span<const glm::vec3> positions, std::vector<std::array<uint32_t, 3>>& faces,
                  std::span<const uint32_t> changed, std::span<const uint32_t> face_ids = {});

  /// Recomputes the lines for `camera`. Kinds disabled in `enabled` are not extracted.
  /// `smoothing` < 1 blends normals, kr and Dw kr with the previous frames' values by that
  /// weight (Jeong et al. 2005 §3.3, see temporal_smoothing.h); 1 uses this frame's values.
  /// In a sequence (`dt` > 0 seconds since the last frame, an image `image_height` px high)
  /// with smoothing, suggestive contours that slide fast are faded
  /// (LineParams::suggestive_motion_fade_*).
  void update(const Camera& camera, const std::array<bool, kLineKindCount>& enabled, float smoothing = 1.0f,
              int image_height = 0, float dt = 0.0f);

  /// Leaves out the strokes of `kind` whose whole length projected into a `width`×`height`
  /// image of `camera` (visible or not, in the image or not) is under `min_px` pixels (level
  /// of detail: DetailParams::min_suggestive_length). Call after update().
  void dropShortStrokes(LineKind kind, float min_px, const Camera& camera, int width, int height);

  /// The full-detail mesh is a closed surface seen from outside (isClosedOutward): its
  /// back faces, and those of any progressive-mesh level of it, are never visible from
  /// outside its bounds.
  bool closedOutward() const { return closed_outward_; }

  /// Vertices of the full-detail mesh that lie on a crease there (dihedral angle above
  /// LineParams::crease_angle_deg, marked or non-manifold edges): one byte per input vertex.
  std::span<const uint8_t> fullDetailCreaseVertices() const { return full_crease_vertices_; }
  /// Per vertex of the current mesh, whether a dihedral crease may pass through it (empty:
  /// everywhere). Level of detail sets it from fullDetailCreaseVertices().
  std::vector<uint8_t>& creaseMask() { return crease_mask_; }
  std::span<const uint8_t> creaseMask() const { return crease_mask_; }

  /// The smoothing state (level of detail moves it along the vertex hierarchy).
  TemporalSmoother& smoother() { return smoother_; }

  /// New thresholds; a new crease angle also recomputes fullDetailCreaseVertices() (and
  /// bumps creaseVersion()).
  void setParams(const LineParams& params);
  /// Counts changes of fullDetailCreaseVertices() (level of detail rebuilds its mask).
  uint64_t creaseVersion() const { return crease_version_; }
  const LineParams& params() const { return params_; }

  const TriMesh& mesh() const { return mesh_; }
  const Bounds& bounds() const { return bounds_; }
  /// Vertex normals for shading: the temporally smoothed ones after a smoothed update().
  std::span<const glm::vec3> normals() const;
  /// The extracted segments (all enabled kinds), as the lines stage produced them.
  const LineSet& segments() const { return segments_; }
  /// The full-detail model's feature size (model units; computeFeatureSize).
  float featureSize() const { return feature_size_; }
  const StrokeSet& strokes() const { return strokes_; }
  /// The mesh's own silhouette chained into strokes (kind contour), extracted with the
  /// contours when LineParams::complete_outline is set (else empty): what completes the
  /// outline where the interpolated contour leaves it.
  const StrokeSet& silhouetteStrokes() const { return silhouette_strokes_; }
  const CpuTimings& timings() const { return timings_; }
  const ShapeCache& shape() const { return shape_; }
  /// The threads of this drawing's data-parallel loops (shape stage, view quantities);
  /// level of detail runs its own on them too.
  WorkerPool& workers() { return *pool_; }
  const std::shared_ptr<WorkerPool>& sharedWorkers() const { return pool_; }

 private:
  std::shared_ptr<WorkerPool> pool_;  // ShapeParams::threads threads, caller included
  TriMesh mesh_;
  Bounds bounds_;
  LineParams params_;
  ShapeCache shape_;
  float feature_size_ = 1.0f;
  void updateFullCreaseVertices();
  // full_min_dot_ and full_min_dot_marked_ from the full mesh's adjacency and face normals.
  void computeFullCreaseDots(const MeshAdjacency& adj, std::span<const glm::vec3> face_normals);
  std::vector<uint8_t> full_crease_vertices_, crease_mask_;
  // Smallest n1·n2 over each full-detail vertex's edges, without / with marked and
  // non-manifold edges counted as creases (−2): see updateFullCreaseVertices().
  std::vector<float> full_min_dot_, full_min_dot_marked_;
  float crease_angle_ = -1.0f;
  bool marked_ = false;
  bool closed_outward_ = false;
  uint64_t crease_version_ = 0;
  TemporalSmoother smoother_;
  std::span<const glm::vec3> shading_normals_;
  ViewQuantities view_;
  std::vector<uint32_t> full_face_materials_;  // of the full-detail mesh (empty: one material)
  std::vector<std::array<uint32_t, 3>> faces_in_;  // updateMesh(span): copy, then swap in
  std::vector<uint32_t> moved_;      // updateMesh: the changed vertices whose position changed
  std::vector<uint32_t> needed_;     // vertices whose Dw kr this frame needs (lazy derivatives)
  std::vector<uint8_t> needed_mark_;
  std::vector<uint32_t> ridge_needed_;  // vertices whose tensor ridges read (lazy derivatives)
  // Ridges in sequences: smoothed principal directions and C(e,e,e); where the lazily
  // computed tensors are known this frame.
  std::vector<glm::vec3> ridge_dir1_, ridge_dir2_;
  std::vector<float> ridge_c1_, ridge_c2_;
  std::vector<uint8_t> ridge_valid_;
  FittedFields jet_fields_;  // ridges from fitted jets (LineParams::ridge_estimator)
  RidgeEstimator smoothed_ridge_estimator_ = RidgeEstimator::kTensor;  // of the C history
  ApparentRidgeQuantities apparent_;  // per view, when apparent ridges are drawn
  PrincipalHighlightQuantities principal_;  // per view, when principal highlights are drawn
  std::vector<float> motion_gain_;   // per vertex, the suggestive contours' motion fade
  LineScratch scratch_;
  LineSet segments_, silhouette_;
  StrokeSet strokes_, silhouette_strokes_;
  ChainScratch chain_scratch_;
  CpuTimings timings_;
};

}  // namespace lodline
