// Several objects drawn together: a scene (io/scene_file.h). Each object is its own
// LodDrawing — its own progressive mesh, adapted against the shared camera with its own
// factor on the target area T (Jeong, Ni, Lee, Markosian 2005, §3.1: "the background is drawn
// with less detail than the character") — and has its own style. Lines are extracted per
// object; the renderer draws every object's faces before any line, so one object hides
// another's lines. A single model is a scene of one object, so `render`, `view`, `capture`
// and `bench` drive this one type.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/render_params.h"
#include "frame/lod_drawing.h"
#include "lines/strokes.h"

namespace lodline {

class SceneDrawing {
 public:
  struct Object {
    std::string name;
    std::unique_ptr<LodDrawing> drawing;
    /// This object's style, toon, chamfer and line styles. Its enabled line kinds are the
    /// ones extracted.
    ObjectStyle style;
    /// Multiplies DetailParams::object_factor for this object (> 0; > 1: coarser).
    float detail_factor = 1.0f;
    size_t input_vertices = 0;  ///< of the full-detail mesh, in world space
    size_t input_faces = 0;
    /// Where this object's surface crosses another object's (of a higher index) or itself:
    /// polylines on the full-detail meshes in world space, kind LineKind::kIntersection,
    /// computed once when the scene is built (objects are rigid).
    StrokeSet intersections;
  };

  /// Adds an object (its drawing must be non-null). Bounds grow to include it.
  void add(Object object);

  size_t size() const { return objects_.size(); }
  Object& operator[](size_t i) { return objects_[i]; }
  const Object& operator[](size_t i) const { return objects_[i]; }
  std::span<Object> objects() { return objects_; }
  std::span<const Object> objects() const { return objects_; }

  /// Bounds of all objects together (world space).
  const Bounds& bounds() const { return bounds_; }
  /// Vertices and faces of the objects' full-detail meshes, summed.
  size_t inputVertexCount() const;
  size_t inputFaceCount() const;
  /// True when any object's level of detail changes with the view.
  bool detailControlled() const;

  /// One frame of every object (LodDrawing::frame), T scaled by each object's factor.
  Status frame(const Camera& camera, int width, int height, const DetailParams& detail, float dt,
               float smoothing = 1.0f);
  /// frame(), for a caller that runs it while a frame is drawn (ScenePresenter::present's
  /// overlap): the objects' worker pools are quiet meanwhile (WorkerPool::setQuiet), so the
  /// stages run on the calling thread alone and the workers sleep, leaving the other cores
  /// to the drawing. The result is frame()'s.
  Status frameWhileDrawing(const Camera& camera, int width, int height, const DetailParams& detail, float dt,
                           float smoothing = 1.0f);
  /// The step by which converging for a still advances time: longer than any geomorph, so
  /// splits and collapses show at once (a still needs no morphs, and waiting for them took
  /// hundreds of steps on a 1M-face model). Where the adaptation stops depends on the step,
  /// so `render`, the viewer's first frame and the walkthrough's warm-up all use this one.
  static constexpr float kConvergeStepSeconds = 1.0f;
  /// Converges every object (LodDrawing::converge); returns the largest step count.
  Result<int> converge(const Camera& camera, int width, int height, const DetailParams& detail, float dt,
                       int max_steps);

  /// Sums over the objects of the last frame's adapt milliseconds and CPU stage timings.
  double adaptMs() const;
  CpuTimings timings() const;

 private:
  DetailParams objectDetail(const DetailParams& detail, const Object& o) const;
  WorkerPool* pool() const;  // the first object's (scenes built by the app share one)
  std::vector<Object> objects_;
  Bounds bounds_;
  std::vector<WorkerPool*> quiet_pools_;  // frameWhileDrawing(): the distinct pools it quietened
};

/// The smallest box, and a sphere around its centre, that hold `a` and `b` (radius: the
/// farthest of the two spheres from that centre).
Bounds unionBounds(const Bounds& a, const Bounds& b);

}  // namespace lodline
