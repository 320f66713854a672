// The OpenGL presenter: gl/renderer.h drawing into an offscreen multisampled target of the
// frame's size, read back for files or copied to a window (the viewer), so the window shows
// exactly the pixels `render` writes.
#pragma once

#include <memory>

#include "gl/context.h"
#include "present/presenter.h"

namespace lodline {

// gl/renderer.h stays out of this header, so code that holds a presenter (the viewer)
// includes no drawing backend (docs/design.md §5).
class Renderer;
class OffscreenTarget;
class SurfaceTarget;

class GlPresenter final : public ScenePresenter {
 public:
  ~GlPresenter() override;
  /// Creates a headless context of kind `context` (EGL surfaceless, OSMesa) and an
  /// offscreen target of frame's size and multisampling. Errors: no context, shaders, a size
  /// above the GL limit.
  static Result<std::unique_ptr<GlPresenter>> createHeadless(ContextBackend context, const FrameParams& frame);
  /// Uses the current context (a window's); the offscreen target follows the frame's size.
  static Result<std::unique_ptr<GlPresenter>> createOnCurrentContext();

  /// Copies the last present()'s image into the bound draw framebuffer (a window).
  void blitToBound() const;

  Status check(const SceneDrawing&) const override { return {}; }
  Status readSurface(SurfaceImage& out) override;
  size_t facesDrawn(size_t object) const override;
  size_t segmentsDrawn(size_t object) const override;
  std::string backendName() const override;
  std::string description() const override { return description_; }

 protected:
  Status uploadMeshes(const SceneDrawing& scene, bool all_meshes) override;
  Status drawSurfaces(const Camera& camera, const FrameParams& frame, std::span<const ObjectStyle> styles) override;
  void readDepth(DepthImage& out) override;
  void uploadLines(size_t object, const ScreenLines& lines) override;
  void drawLines(const FrameParams& frame, std::span<const ObjectStyle> styles) override;
  Image readColour() override;

 private:
  GlPresenter() = default;
  Status ensureTarget(const FrameParams& frame);
  /// Makes this presenter's own context current (headless; a window's stays as it is).
  void bind() const;
  // Declared first, destroyed last: the GL objects below need the context.
  std::unique_ptr<GlContext> context_;  // null on a window's context
  std::unique_ptr<Renderer> renderer_;
  std::unique_ptr<OffscreenTarget> target_;
  std::unique_ptr<SurfaceTarget> surface_;
  std::string description_;
};

}  // namespace lodline
