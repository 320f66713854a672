#include "app/headless.h"

#include <glad/gl.h>

#include "core/timer.h"

namespace lodline {

Result<HeadlessRenderer> HeadlessRenderer::create(ContextBackend backend, const RenderParams& params) {
  HeadlessRenderer h;
  auto context = createHeadlessContext(backend);
  if (!context) return context.error();
  h.context_ = std::move(context.value());
  auto renderer = Renderer::create();
  if (!renderer) return renderer.error();
  h.renderer_ = std::make_unique<Renderer>(std::move(renderer.value()));
  auto target = OffscreenTarget::create(params.width, params.height, params.msaa);
  if (!target) return target.error();
  h.target_ = std::make_unique<OffscreenTarget>(std::move(target.value()));
  return h;
}

void HeadlessRenderer::setMesh(const LineDrawing& drawing) {
  renderer_->setMesh(drawing.mesh().positions, drawing.normals(), drawing.mesh().faces,
                     drawing.mesh().marked_edges);
}

void HeadlessRenderer::draw(const LineDrawing& drawing, const Camera& camera, const RenderParams& params,
                            bool upload_lines) {
  Stopwatch sw;
  if (upload_lines) renderer_->setLines(drawing.lines());
  times_.upload = sw.lap();
  target_->bind();
  renderer_->draw(camera, params, params.width, params.height);
  glFinish();
  times_.render = sw.lap();
}

Status HeadlessRenderer::setMeshes(const SceneDrawing& scene, bool all) {
  if (renderer_->objectCount() != scene.size()) {
    if (Status s = renderer_->setObjectCount(scene.size()); !s) return s;
    all = true;
  }
  for (size_t i = 0; i < scene.size(); ++i) {
    const LodDrawing& d = *scene[i].drawing;
    if (!all && !d.meshChanged()) continue;
    const LineDrawing& ld = d.drawing();
    renderer_->setMesh(i, ld.mesh().positions, ld.normals(), ld.mesh().faces, ld.mesh().marked_edges);
  }
  return {};
}

void HeadlessRenderer::draw(const SceneDrawing& scene, const Camera& camera, const RenderParams& frame) {
  Stopwatch sw;
  styles_.clear();
  for (size_t i = 0; i < scene.size(); ++i) {
    renderer_->setLines(i, scene[i].drawing->drawing().lines());
    styles_.push_back(scene[i].style);
  }
  times_.upload = sw.lap();
  target_->bind();
  renderer_->draw(camera, frame, styles_, frame.width, frame.height);
  glFinish();
  times_.render = sw.lap();
}

Status HeadlessRenderer::drawSurface(const Camera& camera, SurfaceImage& out) {
  if (!surface_target_) {
    auto t = SurfaceTarget::create(target_->width(), target_->height());
    if (!t) return t.error();
    surface_target_ = std::make_unique<SurfaceTarget>(std::move(t.value()));
  }
  surface_target_->bindAndClear();
  renderer_->drawSurface(camera, target_->width(), target_->height());
  surface_target_->readback(out);
  return {};
}

Image HeadlessRenderer::readImage() {
  Stopwatch sw;
  Image image = target_->readback();
  times_.readback = sw.lap();
  return image;
}

}  // namespace lodline
