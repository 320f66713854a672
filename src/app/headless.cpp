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

Image HeadlessRenderer::readImage() {
  Stopwatch sw;
  Image image = target_->readback();
  times_.readback = sw.lap();
  return image;
}

}  // namespace lodline
