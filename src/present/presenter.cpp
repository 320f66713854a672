#include "present/presenter.h"

#include <algorithm>
#include <cmath>
#include <thread>
#include <vector>

#include <glm/geometric.hpp>

#if defined(__linux__)
#include <sys/resource.h>
#include <unistd.h>

#include <cerrno>
#endif

#include "core/timer.h"
#include "present/gl_presenter.h"
#include "present/outline.h"
#include "present/screen_lines.h"
#include "present/soft_presenter.h"

namespace lodline {

namespace {
// The overlapped stages run at a lower priority than the drawing (nice +10, this thread only,
// on Linux): the frame ends when the drawing ends, so the drawing should not wait for a core
// while the stages fill the time in which it leaves one idle (llvmpipe's binning, the depth
// read-back, the strokes). Measured on the 1.1M knot at T = 7 on two cores: the pipelined
// frame went from 1.15-1.20 to 1.05-1.15 times the present alone (docs/performance.md, "Frames
// in a pipeline").
void yieldToTheDrawing() {
#if defined(__linux__)
  const id_t tid = static_cast<id_t>(gettid());
  errno = 0;
  const int nice = getpriority(PRIO_PROCESS, tid);
  if (errno == 0) (void)setpriority(PRIO_PROCESS, tid, std::min(nice + 10, 19));
#endif
}
}  // namespace

Result<PresenterBackend> parsePresenterBackend(const std::string& name) {
  if (name == "gl") return PresenterBackend::kGl;
  if (name == "soft") return PresenterBackend::kSoft;
  return Error::usage("--backend: expected gl or soft, got '" + name + "'");
}

Status ScenePresenter::present(const SceneDrawing& scene, const Camera& camera, const FrameParams& frame,
                               bool all_meshes) {
  return present(scene, camera, frame, all_meshes, {});
}

Status ScenePresenter::present(const SceneDrawing& scene, const Camera& camera, const FrameParams& frame,
                               bool all_meshes, const std::function<void()>& overlap) {
  if (Status s = check(scene); !s) return s;
  Stopwatch sw;
  camera_ = camera;
  frame_ = frame;
  styles_.clear();
  for (const auto& o : scene.objects()) styles_.push_back(o.style);
  if (Status s = uploadMeshes(scene, all_meshes); !s) return s;
  takeObjectLines(scene, /*copy=*/static_cast<bool>(overlap));
  times_.upload = sw.lap();
  // With an overlap, the scene is not read from here on (the lines were copied): `overlap` may
  // change it. It starts before the faces are drawn, so that on a GPU it runs while the GPU
  // draws.
  std::thread worker;
  struct Join {
    std::thread& t;
    ~Join() {
      if (t.joinable()) t.join();
    }
  } join{worker};
  if (overlap)
    worker = std::thread([&overlap] {
      yieldToTheDrawing();
      overlap();
    });
  if (Status s = drawSurfaces(camera, frame, styles_); !s) return s;
  times_.render = sw.lap();
  readDepth(depth_);
  splitObjectLines();
  times_.visibility = sw.lap();
  times_.strokes = 0.0;
  times_.fade = 0.0;
  const size_t n = objects_.size();
  parameterizers_.resize(n);
  faders_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    faders_[i].update(visible_[i], camera, frame.width, frame.height, fade_);
    times_.fade += sw.elapsed();
    parameterizers_[i].update(visible_[i], camera, frame.width, frame.height, stroke_coherence_);
    const Bounds& b = objects_[i].bounds;
    const StrokeView view{camera.eye, camera.forward(), b.center, b.radius};
    buildScreenLines(visible_[i], hidden_[i], styles_[i], view, parameterizers_[i].parameters(), screen_lines_,
                     stroke_scratch_);
    times_.strokes += sw.lap();
    uploadLines(i, screen_lines_);
    times_.upload += sw.lap();
  }
  drawLines(frame, styles_);
  times_.render += sw.lap();
  times_.readback = 0.0;
  visible_all_valid_ = hidden_all_valid_ = false;
  return {};
}

void ScenePresenter::takeObjectLines(const SceneDrawing& scene, bool copy) {
  objects_.resize(scene.size());
  for (size_t i = 0; i < scene.size(); ++i) {
    const SceneDrawing::Object& obj = scene[i];
    const LineDrawing& d = obj.drawing->drawing();
    ObjectLines& o = objects_[i];
    o.strokes = &d.strokes();
    o.silhouettes = &d.silhouetteStrokes();
    if (copy) {  // assignment keeps the vectors' capacity: no allocation once warm
      o.strokes_copy = d.strokes();
      o.silhouettes_copy = d.silhouetteStrokes();
      o.strokes = &o.strokes_copy;
      o.silhouettes = &o.silhouettes_copy;
    }
    o.intersections = &obj.intersections;
    o.intersections_on = obj.style.lines[LineKind::kIntersection].enabled && obj.intersections.strokeCount() > 0;
    o.contours_on = obj.style.lines[LineKind::kContour].enabled;
    o.median_edge = obj.drawing->medianEdgeLength(edge_lengths_);
    o.bounds = obj.drawing->bounds();
  }
}

void ScenePresenter::splitObjectLines() {
  const size_t n = objects_.size();
  visible_.resize(n);
  hidden_.resize(n);
  outline_fill_.assign(n, 0.0);
  if (outline_history_.size() != n) {
    OutlineHistory fresh;
    fresh.starts_in_motion = sequence_in_motion_;
    outline_history_.assign(n, fresh);
  }
  for (size_t i = 0; i < n; ++i) {
    const ObjectLines& o = objects_[i];
    VisibilityParams visibility;
    visibility.segment_tolerance_cap = o.median_edge;
    splitStrokes(*o.strokes, camera_, depth_, visibility, &visible_[i], &hidden_[i]);
    // Intersection lines (static, world space) through the same test.
    if (o.intersections_on) {
      splitStrokes(*o.intersections, camera_, depth_, visibility, &scratch_, &scratch2_);
      appendStrokes(scratch_, visible_[i]);
      appendStrokes(scratch2_, hidden_[i]);
    }
    // The exterior outline, completed where the interpolated contour leaves it.
    if (o.silhouettes->strokeCount() > 0 && o.contours_on)
      outline_fill_[i] = completeOutline(*o.silhouettes, camera_, depth_, visibility, OutlineParams{}, visible_[i],
                                         outline_scratch_, &outline_history_[i]);
    else
      outline_history_[i].fill.clear();
    // What is drawn, measured and written: the runs smoothed in the image (StrokeStyle).
    if (i < styles_.size()) {
      smoothRuns(visible_[i], styles_[i].lines, curve_scratch_);
      smoothRuns(hidden_[i], styles_[i].lines, curve_scratch_);
    }
  }
}

size_t ScenePresenter::fadingSamples() const {
  size_t n = 0;
  for (const StrokeFader& f : faders_) n += f.fading();
  return n;
}

double ScenePresenter::textureDrift() const {
  double sum = 0.0;
  size_t n = 0;
  for (const StrokeParameterizer& p : parameterizers_) {
    sum += p.driftSum();
    n += p.persisting();
  }
  return n > 0 ? sum / static_cast<double>(n) : 0.0;
}

Image ScenePresenter::readImage() {
  Stopwatch sw;
  Image image = readColour();
  times_.readback = sw.lap();
  return image;
}

const StrokeRuns& ScenePresenter::visibleAll() {
  if (!visible_all_valid_) {
    visible_all_.clear();
    for (const StrokeRuns& v : visible_) appendStrokes(v, visible_all_);
    visible_all_valid_ = true;
  }
  return visible_all_;
}

const StrokeRuns& ScenePresenter::hiddenAll() {
  if (!hidden_all_valid_) {
    hidden_all_.clear();
    for (const StrokeRuns& v : hidden_) appendStrokes(v, hidden_all_);
    hidden_all_valid_ = true;
  }
  return hidden_all_;
}

Result<std::unique_ptr<ScenePresenter>> createPresenter(PresenterBackend backend, ContextBackend context,
                                                        const SceneDrawing& scene, const FrameParams& frame) {
  std::unique_ptr<ScenePresenter> p;
  if (backend == PresenterBackend::kSoft) {
    // The scene's worker pool runs the rasteriser too (the CPU stages are done by then).
    p = std::make_unique<SoftPresenter>(scene.size() > 0 ? scene[0].drawing->drawing().sharedWorkers() : nullptr);
  } else {
    auto gl = GlPresenter::createHeadless(context, frame);
    if (!gl) return gl.error();
    p = std::move(gl.value());
  }
  if (Status s = p->check(scene); !s) return s.error();
  return p;
}

}  // namespace lodline
