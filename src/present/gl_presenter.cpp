#include "present/gl_presenter.h"

#include <glad/gl.h>

#include "gl/renderer.h"

namespace lodline {

// The GL objects are deleted in this presenter's own context (another may be current).
GlPresenter::~GlPresenter() { bind(); }

void GlPresenter::bind() const {
  if (context_) context_->makeCurrent();
}

size_t GlPresenter::facesDrawn(size_t object) const { return renderer_->faceCount(object); }
size_t GlPresenter::segmentsDrawn(size_t object) const { return renderer_->segmentsDrawn(object); }
Image GlPresenter::readColour() {
  bind();
  return target_->readback();
}
void GlPresenter::readDepth(DepthImage& out) {
  bind();
  target_->readDepth(out);
}

Result<std::unique_ptr<GlPresenter>> GlPresenter::createOnCurrentContext() {
  std::unique_ptr<GlPresenter> p(new GlPresenter());
  auto renderer = Renderer::create();
  if (!renderer) return renderer.error();
  p->renderer_ = std::make_unique<Renderer>(std::move(renderer.value()));
  p->description_ = currentContextDescription();
  return p;
}

Result<std::unique_ptr<GlPresenter>> GlPresenter::createHeadless(ContextBackend context, const FrameParams& frame) {
  auto ctx = createHeadlessContext(context);
  if (!ctx) return ctx.error();
  auto p = createOnCurrentContext();
  if (!p) return p.error();
  (*p)->context_ = std::move(ctx.value());
  if (Status s = (*p)->ensureTarget(frame); !s) return s.error();
  return p;
}

std::string GlPresenter::backendName() const { return context_ ? lodline::backendName(context_->backend()) : "window"; }

Status GlPresenter::ensureTarget(const FrameParams& frame) {
  bind();
  if (target_ && target_->width() == frame.width && target_->height() == frame.height) return {};
  auto target = OffscreenTarget::create(frame.width, frame.height, frame.msaa);
  if (!target) return target.error();
  target_ = std::make_unique<OffscreenTarget>(std::move(target.value()));
  surface_.reset();
  return {};
}

Status GlPresenter::uploadMeshes(const SceneDrawing& scene, bool all_meshes) {
  bind();
  if (renderer_->objectCount() != scene.size()) {
    if (Status s = renderer_->setObjectCount(scene.size()); !s) return s;
    all_meshes = true;
  }
  for (size_t i = 0; i < scene.size(); ++i) {
    const LodDrawing& d = *scene[i].drawing;
    const LineDrawing& ld = d.drawing();
    if (all_meshes || d.meshChanged())
      renderer_->setMesh(i, ld.mesh().positions, ld.normals(), ld.mesh().faces, ld.mesh().marked_edges);
    renderer_->setBackFaceCulling(i, d.backFacesHidden(), d.bounds().center, d.bounds().radius);
  }
  return {};
}

Status GlPresenter::drawSurfaces(const Camera& camera, const FrameParams& frame, std::span<const ObjectStyle> styles) {
  bind();
  if (Status s = ensureTarget(frame); !s) return s;
  GLint previous = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous);
  target_->bind();
  renderer_->drawSurfaces(camera, frame, styles);
  glFinish();  // the depth is read next; finishing here keeps the two timings apart
  glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(previous));
  return {};
}

void GlPresenter::uploadLines(size_t object, const ScreenLines& lines) {
  bind();
  renderer_->setLines(object, lines);
}

void GlPresenter::drawLines(const FrameParams& frame, std::span<const ObjectStyle> styles) {
  bind();
  GLint previous = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous);
  target_->bind();
  renderer_->drawLines(frame, styles);
  glFinish();
  glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(previous));
}

void GlPresenter::blitToBound() const {
  if (target_) target_->blitToBound();
}

Status GlPresenter::readSurface(SurfaceImage& out) {
  bind();
  if (!surface_) {
    auto t = SurfaceTarget::create(target_->width(), target_->height());
    if (!t) return t.error();
    surface_ = std::make_unique<SurfaceTarget>(std::move(t.value()));
  }
  surface_->bindAndClear();
  renderer_->drawSurface(camera(), target_->width(), target_->height());
  surface_->readback(out);
  return {};
}

}  // namespace lodline
