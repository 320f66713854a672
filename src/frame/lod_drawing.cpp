#include "frame/lod_drawing.h"

#include <numeric>

#include "core/timer.h"

namespace lodline {

LodDrawing::LodDrawing(TriMesh full, const LineParams& params) : drawing_(std::move(full), params) {}

LodDrawing::LodDrawing(TriMesh full, std::shared_ptr<const ProgressiveMesh> pm, const LineParams& params)
    : drawing_(std::move(full), params), pm_(std::move(pm)), lod_(std::make_unique<AdaptiveMesh>(*pm_)) {}

Status LodDrawing::adaptStep(const Camera& camera, int width, int height, const DetailParams& detail,
                             float dt) {
  mesh_changed_ = first_;
  if (!lod_) {
    first_ = false;
    return {};
  }
  Stopwatch sw;
  if (Status s = lod_->setView(camera, width, height, detail); !s) return s;
  lod_->adapt(dt);
  adapt_ms_ = sw.lap();
  const LodChanges& ch = lod_->changes();
  if (!first_ && !ch.everything && ch.dirty.empty()) return {};
  lod_->exportFaces(faces_);
  if (first_ || ch.everything) {
    changed_.resize(lod_->slotCount());
    std::iota(changed_.begin(), changed_.end(), 0u);
  } else {
    changed_.assign(ch.dirty.begin(), ch.dirty.end());
  }
  drawing_.updateMesh(lod_->positions(), faces_, changed_);
  mesh_changed_ = true;
  first_ = false;
  return {};
}

Status LodDrawing::frame(const Camera& camera, int width, int height, const DetailParams& detail, float dt,
                         const std::array<bool, kLineKindCount>& enabled) {
  if (Status s = adaptStep(camera, width, height, detail, dt); !s) return s;
  drawing_.update(camera, enabled);
  return {};
}

Result<int> LodDrawing::converge(const Camera& camera, int width, int height, const DetailParams& detail,
                                 float dt, int max_steps, const std::array<bool, kLineKindCount>& enabled) {
  int steps = 0;
  bool changed_any = first_;
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
