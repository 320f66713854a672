#include "frame/lod_drawing.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/mesh_order.h"
#include "core/timer.h"

namespace lodline {

// The full-detail stages run over the whole mesh every frame: neighbours near each other in
// memory (core/mesh_order.h). Detail control has its own order (the progressive mesh's).
LodDrawing::OrderedMesh::OrderedMesh(TriMesh m) : mesh(std::move(m)) {
  std::vector<float> lengths;
  median_edge = lodline::medianEdgeLength(mesh, lengths);
  orderForLocality(mesh, &stored_to_drawn);
}

LodDrawing::LodDrawing(TriMesh full, const LineParams& params, std::shared_ptr<WorkerPool> pool)
    : LodDrawing(OrderedMesh(std::move(full)), params, std::move(pool)) {}

LodDrawing::LodDrawing(OrderedMesh&& full, const LineParams& params, std::shared_ptr<WorkerPool> pool)
    : drawing_(std::move(full.mesh), params, {}, std::move(pool), FullMesh::kDrawn, full.stored_to_drawn),
      full_median_edge_(full.median_edge) {}

float LodDrawing::medianEdgeLength(std::vector<float>& lengths) const {
  if (std::holds_alternative<FullLevel>(level_)) return full_median_edge_;
  return lodline::medianEdgeLength(drawing_.mesh(), lengths);
}

namespace {
// Converging for a still stops once no more than max(kCycleOps, active vertices /
// kCycleFraction) splits and collapses happen in each of kQuietSteps steps in a row.
constexpr uint32_t kCycleOps = 8;
constexpr uint32_t kCycleFraction = 2000;
constexpr int kQuietSteps = 4;

// A geomorph moves its vertex a little every frame; recomputing the vertex's rings each time
// was two thirds of the shape stage's work on a detail-controlled orbit. Its normals and
// curvature wait until it has moved 0.3·√(point area), or stopped (ShapeParams::move_tolerance;
// docs/performance.md, "Morphing vertices recomputed every few frames"): a third fewer
// curvature updates on the 1.1M knot at T = 7 px², the CPU stages 4-10% faster, and the
// captures' churn within ±3%.
constexpr float kMorphShapeTolerance = 0.3f;

// Geomorphs start a split's new vertex at its parent's position, so adapted meshes routinely
// hold near-zero-length edges; Max's weights (∝ 1/(|a|·|b|)) let such slivers dominate a
// vertex normal, area weights give them none. Full detail keeps the more accurate default.
// The mesh changes every frame, so derivative tensors are computed only where suggestive
// contours are tested (ShapeParams::lazy_derivatives).
ShapeParams adaptiveShapeParams() {
  ShapeParams p;
  p.normal_weighting = NormalWeighting::kArea;
  p.lazy_derivatives = true;
  p.move_tolerance = kMorphShapeTolerance;
  return p;
}
}  // namespace

LodDrawing::LodDrawing(TriMesh full, std::shared_ptr<const ProgressiveMesh> pm, const LineParams& params,
                       std::shared_ptr<WorkerPool> pool)
    : drawing_(std::move(full), params, adaptiveShapeParams(), std::move(pool), FullMesh::kReplaced) {
  PmLevel level{std::move(pm), nullptr};
  level.mesh = std::make_unique<AdaptiveMesh>(*level.pm);
  level.mesh->setWorkerPool(&drawing_.workers());
  level_ = std::move(level);
}

LodDrawing::LodDrawing(TriMesh full, const ClusterParams& cluster, const LineParams& params,
                       std::shared_ptr<WorkerPool> pool)
    : drawing_(full, params, adaptiveShapeParams(), std::move(pool), FullMesh::kReplaced) {
  ClusterLevel level{std::make_unique<VertexClustering>(std::move(full)), cluster, false};
  // Clustering folds the surface locally (non-manifold edges, small holes where collapsed
  // faces were): draw boundaries only for models that have some, and no non-manifold edges
  // as creases (the input's marked edges do not survive updateMesh anyway).
  const auto boundary = level.clustering->boundaryVertices();
  level.has_boundary = std::find(boundary.begin(), boundary.end(), uint8_t{1}) != boundary.end();
  level_ = std::move(level);
  setLineParams(params);
}

const AdaptiveMesh* LodDrawing::lod() const {
  const auto* level = std::get_if<PmLevel>(&level_);
  return level ? level->mesh.get() : nullptr;
}

const VertexClustering* LodDrawing::clustering() const {
  const auto* level = std::get_if<ClusterLevel>(&level_);
  return level ? level->clustering.get() : nullptr;
}

void LodDrawing::setLineParams(LineParams params) {
  if (const auto* level = std::get_if<ClusterLevel>(&level_)) {
    params.boundaries = params.boundaries && level->has_boundary;
    params.marked_edges = false;
  }
  drawing_.setParams(params);
}

void LodDrawing::adaptCluster(ClusterLevel& level, const Camera& camera, int width, int height,
                              const DetailParams& detail) {
  Stopwatch sw;
  ClusterParams cp = level.params;
  cp.foveation = detail.foveation;
  cp.focus_px = detail.focus_px;
  cp.cull = detail.cull;
  level.clustering->cluster(camera, width, height, cp);
  adapt_ms_ = sw.lap();
  // Slots are the input vertices, so the full-detail crease vertices apply directly.
  const auto full = drawing_.fullDetailCreaseVertices();
  drawing_.creaseMask().assign(full.begin(), full.end());
  // Positions never move (a representative keeps its own); the shape cache finds the face
  // slots that changed itself, so the changed-vertex list stays empty.
  changed_.clear();
  drawing_.updateMesh(level.clustering->mesh().positions, level.clustering->faces(), changed_,
                      level.clustering->faceIds());
  mesh_changed_ = true;
}

Status LodDrawing::adaptPm(PmLevel& level, const Camera& camera, int width, int height, const DetailParams& detail,
                           float dt) {
  AdaptiveMesh& lod = *level.mesh;
  Stopwatch sw;
  if (Status s = lod.setView(camera, width, height, detail); !s) return s;
  lod.adapt(dt);
  drawing_.smoother().followHierarchy(lod);
  adapt_ms_ = sw.lap();
  const LodChanges& ch = lod.changes();
  // (Vertices whose small moves wait are recomputed once they stop: an update with nothing
  // changed does that.)
  if (!first_ && !ch.everything && ch.dirty.empty() && crease_version_ == drawing_.creaseVersion() &&
      drawing_.shape().waitingVertices().empty())
    return {};
  lod.exportFaces(faces_);
  if (first_ || ch.everything) {
    changed_.resize(lod.slotCount());
    std::iota(changed_.begin(), changed_.end(), 0u);
  } else {
    changed_.assign(ch.dirty.begin(), ch.dirty.end());
  }
  // Dihedral creases on the adapted mesh only where the full-detail mesh has them. A slot
  // changes its node only by a split or collapse, which marks it dirty, so only the changed
  // slots need a new entry.
  {
    const auto nodes = lod.slotVertices();
    const auto full = drawing_.fullDetailCreaseVertices();
    const auto& origin = level.pm->origin;
    auto& mask = drawing_.creaseMask();
    mask.resize(nodes.size(), 0);
    if (crease_version_ != drawing_.creaseVersion()) {  // a new crease angle: every slot
      crease_version_ = drawing_.creaseVersion();
      for (size_t s = 0; s < nodes.size(); ++s) mask[s] = nodes[s] != kPmNone && full[origin[nodes[s]]];
    }
    for (uint32_t s : changed_) mask[s] = nodes[s] != kPmNone && full[origin[nodes[s]]];
  }
  drawing_.updateMesh(lod.positions(), faces_, changed_, lod.activeFaceIds());
  mesh_changed_ = true;
  return {};
}

Status LodDrawing::adaptStep(const Camera& camera, int width, int height, const DetailParams& detail,
                             float dt) {
  mesh_changed_ = first_;
  Status status;
  if (auto* pm = std::get_if<PmLevel>(&level_)) status = adaptPm(*pm, camera, width, height, detail, dt);
  else if (auto* cluster = std::get_if<ClusterLevel>(&level_)) adaptCluster(*cluster, camera, width, height, detail);
  if (status) first_ = false;
  return status;
}

void LodDrawing::dropStrokesBelowScale(const Camera& camera, int width, int height, const DetailParams& detail) {
  const AdaptiveMesh* pm = lod();
  if (!pm || !(detail.min_suggestive_length > 0.0f)) return;
  const float scale_px = std::sqrt(std::max(pm->stats().target_area, 0.0f));
  drawing_.dropShortStrokes(LineKind::kSuggestive, detail.min_suggestive_length * scale_px, camera, width, height);
}

Status LodDrawing::frame(const Camera& camera, int width, int height, const DetailParams& detail, float dt,
                         const std::array<bool, kLineKindCount>& enabled, float smoothing) {
  const WorkerPool::Awake awake(&drawing_.workers());  // the stages' loops come back to back
  if (Status s = adaptStep(camera, width, height, detail, dt); !s) return s;
  drawing_.update(camera, enabled, smoothing, height, dt);
  dropStrokesBelowScale(camera, width, height, detail);
  return {};
}

Result<int> LodDrawing::converge(const Camera& camera, int width, int height, const DetailParams& detail,
                                 float dt, int max_steps, const std::array<bool, kLineKindCount>& enabled) {
  const WorkerPool::Awake awake(&drawing_.workers());
  int steps = 0;
  bool changed_any = first_;
  if (std::holds_alternative<ClusterLevel>(level_)) {  // no state between frames: one step is converged
    if (Status s = adaptStep(camera, width, height, detail, dt); !s) return s.error();
    drawing_.update(camera, enabled);
    return 1;
  }
  // A still shows the converged detail whatever the frames' budgets: without them here, and
  // a budget's few operations a step are not mistaken for the quiet of a limit cycle below.
  DetailParams unbudgeted = detail;
  unbudgeted.max_adapt_ms = 0.0f;
  unbudgeted.max_operations = 0;
  int quiet = 0;
  while (std::holds_alternative<PmLevel>(level_) && steps < max_steps) {
    if (Status s = adaptStep(camera, width, height, unbudgeted, dt); !s) return s.error();
    ++steps;
    changed_any = changed_any || mesh_changed_;
    const LodStats& st = lod()->stats();
    // Settled: no morph running, and no vertex whose last small moves wait in the shape
    // stage (the next step, with nothing to change, recomputes them).
    const bool settled = st.morphing == 0 && st.pending_collapses == 0 && drawing_.shape().waitingVertices().empty();
    if (settled && st.splits == 0 && st.collapses == 0) break;
    // At a fixed view a handful of vertices can keep trading splits and collapses: a visible
    // vertex whose split needs invisible neighbours split first, which then coarsen again
    // (docs/temporal-coherence.md, "Limit cycles at a fixed view"). Once only such a handful
    // change, step after step, the picture is settled.
    const uint32_t few = std::max<uint32_t>(kCycleOps, st.active_vertices / kCycleFraction);
    quiet = settled && st.splits + st.collapses <= few ? quiet + 1 : 0;
    if (quiet >= kQuietSteps) break;
  }
  mesh_changed_ = changed_any;
  drawing_.update(camera, enabled);
  dropStrokesBelowScale(camera, width, height, detail);
  return steps;
}

}  // namespace lodline
