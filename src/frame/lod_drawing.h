// One model through the whole CPU pipeline of a frame (docs/design.md §1: io → pm → lod →
// shape → lines): at full detail, as a progressive mesh selectively refined every frame so
// visible triangles keep a target image area (Jeong et al. 2005 §3.1–3.2), or clustered per
// view (Pan, Zhou, Shi), feeding the same LineDrawing. `render`, `view`, `capture` and
// `bench` all drive this object, so they agree.
#pragma once

#include <memory>
#include <variant>
#include <vector>

#include "frame/line_drawing.h"
#include "lod/adaptive_mesh.h"
#include "lod/vertex_clustering.h"
#include "pm/progressive_mesh.h"

namespace lodline {

class LodDrawing {
 public:
  /// Full detail: the mesh is drawn as it is, its vertices and faces renumbered for memory
  /// locality where that helps (orderForLocality, core/mesh_order.h: the same surface, other
  /// indices). In every constructor, `pool` runs the data-parallel loops (null: a pool of its
  /// own; see LineDrawing).
  explicit LodDrawing(TriMesh full, const LineParams& params = {}, std::shared_ptr<WorkerPool> pool = nullptr);
  /// Detail control: `full` is the input mesh (for bounds and feature size), `pm` its
  /// progressive mesh. Starts at the base mesh.
  LodDrawing(TriMesh full, std::shared_ptr<const ProgressiveMesh> pm, const LineParams& params = {},
             std::shared_ptr<WorkerPool> pool = nullptr);

  /// View-dependent vertex clustering every frame (Pan, Zhou, Shi; lod/vertex_clustering.h):
  /// `full` is clustered for each view with `cluster` (its foveation and focus are taken from
  /// the DetailParams passed to frame()).
  LodDrawing(TriMesh full, const ClusterParams& cluster, const LineParams& params = {},
             std::shared_ptr<WorkerPool> pool = nullptr);

  /// True for any level of detail that changes with the view (progressive mesh or clustering).
  bool detailControlled() const { return !std::holds_alternative<FullLevel>(level_); }

  /// One frame: adapts the mesh to the view (advancing geomorphs by `dt` seconds), updates
  /// the shape quantities of what changed and extracts the lines. Errors come only from
  /// invalid detail parameters.
  /// `smoothing`: weight of this frame's values in the temporal blend (1 = no smoothing;
  /// smoothingWeight() gives it from α, t and the frame rate).
  Status frame(const Camera& camera, int width, int height, const DetailParams& detail, float dt,
               const std::array<bool, kLineKindCount>& enabled, float smoothing = 1.0f);

  /// Adapts without geomorphs (changes show at once), `dt` per step, until a step changes
  /// nothing or `max_steps` steps ran; then extracts the lines. Returns the steps. This is
  /// the detail a still image shows, and where captures start.
  Result<int> converge(const Camera& camera, int width, int height, const DetailParams& detail,
                       float dt, int max_steps, const std::array<bool, kLineKindCount>& enabled);

  /// New line thresholds (the viewer's panel); they apply from the next frame.
  void setLineParams(LineParams params);

  const LineDrawing& drawing() const { return drawing_; }
  /// The median edge length of the drawn mesh (core/mesh.h, medianEdgeLength; `lengths` is
  /// scratch). At full detail that of the mesh as stored, so it does not depend on the
  /// renumbering (its samples are faces by index).
  float medianEdgeLength(std::vector<float>& lengths) const;
  const Bounds& bounds() const { return drawing_.bounds(); }
  /// The adapted progressive mesh; null at full detail and with clustering.
  const AdaptiveMesh* lod() const;
  /// The clustering; null unless clustering.
  const VertexClustering* clustering() const;
  /// Milliseconds of the last adapt step (0 at full detail).
  double adaptMs() const { return adapt_ms_; }
  /// True when the mesh (positions or faces) changed in the last frame(): re-upload it.
  bool meshChanged() const { return mesh_changed_; }
  /// Whether drawing may cull back faces: the model is closed and seen from outside
  /// (LineDrawing::closedOutward), at full detail or a progressive-mesh level (collapses keep
  /// a closed surface closed and its orientation); never with clustering, whose cells can
  /// merge and flip faces.
  bool backFacesHidden() const { return drawing_.closedOutward() && clustering() == nullptr; }

 private:
  // A full-detail mesh in locality order, with the new index of each stored vertex (empty
  // when it kept its order).
  struct OrderedMesh {
    explicit OrderedMesh(TriMesh m);
    TriMesh mesh;
    std::vector<uint32_t> stored_to_drawn;
    float median_edge = 0.0f;  ///< of the mesh as stored
  };
  LodDrawing(OrderedMesh&& full, const LineParams& params, std::shared_ptr<WorkerPool> pool);

  // The level of detail: one of three, chosen at construction.
  struct FullLevel {};
  struct PmLevel {
    std::shared_ptr<const ProgressiveMesh> pm;
    std::unique_ptr<AdaptiveMesh> mesh;
  };
  struct ClusterLevel {
    std::unique_ptr<VertexClustering> clustering;
    ClusterParams params;
    bool has_boundary = false;  // the input has boundary edges (else none are drawn)
  };
  Status adaptPm(PmLevel& level, const Camera& camera, int width, int height, const DetailParams& detail, float dt);
  void adaptCluster(ClusterLevel& level, const Camera& camera, int width, int height, const DetailParams& detail);
  Status adaptStep(const Camera& camera, int width, int height, const DetailParams& detail, float dt);
  // DetailParams::min_suggestive_length, after the lines' update (progressive mesh only).
  void dropStrokesBelowScale(const Camera& camera, int width, int height, const DetailParams& detail);
  LineDrawing drawing_;
  std::variant<FullLevel, PmLevel, ClusterLevel> level_;
  std::vector<std::array<uint32_t, 3>> faces_;
  std::vector<uint32_t> changed_;
  uint64_t crease_version_ = 0;  // LineDrawing::creaseVersion() the crease mask was built for
  double adapt_ms_ = 0.0;
  float full_median_edge_ = 0.0f;  ///< full detail: the stored mesh's median edge length
  bool mesh_changed_ = true;
  bool first_ = true;
};

}  // namespace lodline
