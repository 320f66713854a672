#include "present/presenter.h"

#include "core/timer.h"
#include "present/gl_presenter.h"
#include "present/soft_presenter.h"

namespace lodline {

Result<PresenterBackend> parsePresenterBackend(const std::string& name) {
  if (name == "gl") return PresenterBackend::kGl;
  if (name == "soft") return PresenterBackend::kSoft;
  return Error::usage("--backend: expected gl or soft, got '" + name + "'");
}

Status ScenePresenter::present(const SceneDrawing& scene, const Camera& camera, const FrameParams& frame,
                               bool all_meshes) {
  if (Status s = check(scene); !s) return s;
  Stopwatch sw;
  scene_ = &scene;
  camera_ = camera;
  frame_ = frame;
  styles_.clear();
  for (const auto& o : scene.objects()) styles_.push_back(o.style);
  if (Status s = upload(scene, all_meshes); !s) return s;
  times_.upload = sw.lap();
  if (Status s = draw(camera, frame, styles_); !s) return s;
  times_.render = sw.lap();
  times_.readback = times_.visibility = 0.0;
  depth_valid_ = visible_valid_ = visible_all_valid_ = false;
  return {};
}

Image ScenePresenter::readImage() {
  Stopwatch sw;
  Image image = readColour();
  times_.readback = sw.lap();
  return image;
}

const DepthImage& ScenePresenter::depth() {
  if (!depth_valid_) {
    Stopwatch sw;
    readDepth(depth_);
    depth_valid_ = true;
    times_.visibility += sw.lap();
  }
  return depth_;
}

const std::vector<VisibleStrokes>& ScenePresenter::visible() {
  if (!visible_valid_ && scene_) {
    const DepthImage& d = depth();
    Stopwatch sw;
    visible_.resize(scene_->size());
    for (size_t i = 0; i < scene_->size(); ++i)
      visibleStrokes((*scene_)[i].drawing->drawing().strokes(), camera_, d, {}, visible_[i]);
    visible_valid_ = true;
    times_.visibility += sw.lap();
  }
  return visible_;
}

const VisibleStrokes& ScenePresenter::visibleAll() {
  if (!visible_all_valid_) {
    visible_all_.clear();
    for (const VisibleStrokes& v : visible()) appendStrokes(v, visible_all_);
    visible_all_valid_ = true;
  }
  return visible_all_;
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
