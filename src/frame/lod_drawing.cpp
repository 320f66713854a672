#include "frame/lod_drawing.h"

#include <algorithm>
#include <numeric>

#include "core/timer.h"

namespace lodline {

LodDrawing::LodDrawing(TriMesh full, const LineParams& params, std::shared_ptr<WorkerPool> pool)
    : drawing_(std::move(full), params, {}, std::move(pool)) {}

namespace {
// Geomorphs start a split's new vertex at its parent's position, so adapted meshes routinely
// hold near-zero-length edges; Max's weights (∝ 1/(|a|·|b|)) let such slivers dominate a
// vertex normal, area weights give them none. Full detail keeps the more accurate default.
// The mesh changes every frame, so derivative tensors are computed only where suggestive
// contours are tested (ShapeParams::lazy_derivatives).
ShapeParams adaptiveShapeParams() {
  ShapeParams p;
  p.normal_weighting = NormalWeighting::kArea;
  p.lazy_derivatives = true;
  return p;
}
}  // namespace

LodDrawing::LodDrawing(TriMesh full, std::shared_ptr<const ProgressiveMesh> pm, const LineParams& params,
                       std::shared_ptr<WorkerPool> pool)
    : drawing_(std::move(full), params, adaptiveShapeParams(), std::move(pool)), pm_(std::move(pm)), lod_(std::make_unique<AdaptiveMesh>(*pm_)) {
  lod_->setWorkerPool(&drawing_.workers());
}

LodDrawing::LodDrawing(TriMesh full, const ClusterParams& cluster, const LineParams& params,
                       std::shared_ptr<WorkerPool> pool)
    : drawing_(full, params, adaptiveShapeParams(), std::move(pool)),
      cluster_(std::make_unique<VertexClustering>(std::move(full))),
      cluster_params_(cluster) {
  // Clustering folds the surface locally (non-manifold edges, small holes where collapsed
  // faces were): draw boundaries only for models that have some, and no non-manifold edges
  // as creases (the input's marked edges do not survive updateMesh anyway).
  const auto boundary = cluster_->boundaryVertices();
  cluster_has_boundary_ = std::find(boundary.begin(), boundary.end(), uint8_t{1}) != boundary.end();
  setLineParams(params);
}

void LodDrawing::setLineParams(LineParams params) {
  if (cluster_) {
    params.boundaries = params.boundaries && cluster_has_boundary_;
    params.marked_edges = false;
  }
  drawing_.setParams(params);
}

Status LodDrawing::adaptStep(const Camera& camera, int width, int height, const DetailParams& detail,
                             float dt) {
  mesh_changed_ = first_;
  if (cluster_) {
    Stopwatch sw;
    ClusterParams cp = cluster_params_;
    cp.foveation = detail.foveation;
    cp.focus_px = detail.focus_px;
    cp.cull = detail.cull;
    cluster_->cluster(camera, width, height, cp);
    adapt_ms_ = sw.lap();
    // Slots are the input vertices, so the full-detail crease vertices apply directly.
    const auto full = drawing_.fullDetailCreaseVertices();
    drawing_.creaseMask().assign(full.begin(), full.end());
    // Positions never move (a representative keeps its own); the shape cache finds the face
    // slots that changed itself, so the changed-vertex list stays empty.
    changed_.clear();
    drawing_.updateMesh(cluster_->mesh().positions, cluster_->faces(), changed_);
    mesh_changed_ = true;
    first_ = false;
    return {};
  }
  if (!lod_) {
    first_ = false;
    return {};
  }
  Stopwatch sw;
  if (Status s = lod_->setView(camera, width, height, detail); !s) return s;
  lod_->adapt(dt);
  drawing_.smoother().followHierarchy(*lod_);
  adapt_ms_ = sw.lap();
  const LodChanges& ch = lod_->changes();
  if (!first_ && !ch.everything && ch.dirty.empty() && crease_version_ == drawing_.creaseVersion()) return {};
  lod_->exportFaces(faces_);
  if (first_ || ch.everything) {
    changed_.resize(lod_->slotCount());
    std::iota(changed_.begin(), changed_.end(), 0u);
  } else {
    changed_.assign(ch.dirty.begin(), ch.dirty.end());
  }
  // Dihedral creases on the adapted mesh only where the full-detail mesh has them. A slot
  // changes its node only by a split or collapse, which marks it dirty, so only the changed
  // slots need a new entry.
  {
    const auto nodes = lod_->slotVertices();
    const auto full = drawing_.fullDetailCreaseVertices();
    auto& mask = drawing_.creaseMask();
    mask.resize(nodes.size(), 0);
    if (crease_version_ != drawing_.creaseVersion()) {  // a new crease angle: every slot
      crease_version_ = drawing_.creaseVersion();
      for (size_t s = 0; s < nodes.size(); ++s) mask[s] = nodes[s] != kPmNone && full[pm_->origin[nodes[s]]];
    }
    for (uint32_t s : changed_) mask[s] = nodes[s] != kPmNone && full[pm_->origin[nodes[s]]];
  }
  drawing_.updateMesh(lod_->positions(), faces_, changed_);
  mesh_changed_ = true;
  first_ = false;
  return {};
}

Status LodDrawing::frame(const Camera& camera, int width, int height, const DetailParams& detail, float dt,
                         const std::array<bool, kLineKindCount>& enabled, float smoothing) {
  const WorkerPool::Awake awake(&drawing_.workers());  // the stages' loops come back to back
  if (Status s = adaptStep(camera, width, height, detail, dt); !s) return s;
  drawing_.update(camera, enabled, smoothing);
  return {};
}

Result<int> LodDrawing::converge(const Camera& camera, int width, int height, const DetailParams& detail,
                                 float dt, int max_steps, const std::array<bool, kLineKindCount>& enabled) {
  const WorkerPool::Awake awake(&drawing_.workers());
  int steps = 0;
  bool changed_any = first_;
  if (cluster_) {  // clustering has no state between frames: one step is converged
    if (Status s = adaptStep(camera, width, height, detail, dt); !s) return s.error();
    drawing_.update(camera, enabled);
    return 1;
  }
  while (lod_ && steps < max_steps) {
    if (Status s = adaptStep(camera, width, height, detail, dt); !s) return s.error();
    ++steps;
    changed_any = changed_any || mesh_changed_;
    const LodStats& st = lod_->stats();
    if (st.splits == 0 && st.collapses == 0 && st.morphing == 0 && st.pending_collapses == 0) break;
  }
  mesh_changed_ = changed_any;
  drawing_.update(camera, enabled);
  return steps;
}

}  // namespace lodline
