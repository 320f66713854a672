#include "frame/scene_drawing.h"

#include <algorithm>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace lodline {

Bounds unionBounds(const Bounds& a, const Bounds& b) {
  Bounds u;
  u.min = glm::min(a.min, b.min);
  u.max = glm::max(a.max, b.max);
  u.center = 0.5f * (u.min + u.max);
  u.radius = std::max(glm::length(a.center - u.center) + a.radius, glm::length(b.center - u.center) + b.radius);
  return u;
}

void SceneDrawing::add(Object object) {
  bounds_ = objects_.empty() ? object.drawing->bounds() : unionBounds(bounds_, object.drawing->bounds());
  objects_.push_back(std::move(object));
}

size_t SceneDrawing::inputVertexCount() const {
  size_t n = 0;
  for (const Object& o : objects_) n += o.input_vertices;
  return n;
}

size_t SceneDrawing::inputFaceCount() const {
  size_t n = 0;
  for (const Object& o : objects_) n += o.input_faces;
  return n;
}

bool SceneDrawing::detailControlled() const {
  return std::any_of(objects_.begin(), objects_.end(), [](const Object& o) { return o.drawing->detailControlled(); });
}

DetailParams SceneDrawing::objectDetail(const DetailParams& detail, const Object& o) const {
  DetailParams d = detail;
  d.object_factor *= o.detail_factor;
  return d;
}

Status SceneDrawing::frame(const Camera& camera, int width, int height, const DetailParams& detail, float dt,
                           float smoothing) {
  const WorkerPool::Awake awake(pool());  // one wake-up for all objects' stages
  for (Object& o : objects_)
    if (Status s = o.drawing->frame(camera, width, height, objectDetail(detail, o), dt, o.style.enabledKinds(), smoothing);
        !s)
      return s;
  return {};
}

Status SceneDrawing::frameWhileDrawing(const Camera& camera, int width, int height, const DetailParams& detail,
                                       float dt, float smoothing) {
  quiet_pools_.clear();
  for (Object& o : objects_) {
    WorkerPool* p = o.drawing->drawing().sharedWorkers().get();
    if (p && std::find(quiet_pools_.begin(), quiet_pools_.end(), p) == quiet_pools_.end()) {
      p->setQuiet(true);
      quiet_pools_.push_back(p);
    }
  }
  struct Restore {
    std::vector<WorkerPool*>& pools;
    ~Restore() {
      for (WorkerPool* p : pools) p->setQuiet(false);
    }
  } restore{quiet_pools_};
  return frame(camera, width, height, detail, dt, smoothing);
}

Result<int> SceneDrawing::converge(const Camera& camera, int width, int height, const DetailParams& detail, float dt,
                                   int max_steps) {
  const WorkerPool::Awake awake(pool());
  int steps = 0;
  for (Object& o : objects_) {
    auto s = o.drawing->converge(camera, width, height, objectDetail(detail, o), dt, max_steps, o.style.enabledKinds());
    if (!s) return s.error();
    steps = std::max(steps, *s);
  }
  return steps;
}

WorkerPool* SceneDrawing::pool() const {
  return objects_.empty() ? nullptr : objects_.front().drawing->drawing().sharedWorkers().get();
}

double SceneDrawing::adaptMs() const {
  double ms = 0.0;
  for (const Object& o : objects_) ms += o.drawing->adaptMs();
  return ms;
}

CpuTimings SceneDrawing::timings() const {
  CpuTimings t;
  for (const Object& o : objects_) {
    const CpuTimings& ot = o.drawing->drawing().timings();
    t.shape += ot.shape;
    t.view += ot.view;
    t.extract += ot.extract;
    t.chain += ot.chain;
    t.silhouette += ot.silhouette;
  }
  return t;
}

}  // namespace lodline
