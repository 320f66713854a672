// One headless OpenGL renderer (context + shaders + offscreen target) drawing frames of a
// scene (or of one LineDrawing): shared by `render` (one frame), `capture` (many) and the
// benchmarks.
#pragma once

#include <memory>

#include "core/render_params.h"
#include "export/visibility.h"
#include "frame/line_drawing.h"
#include "frame/scene_drawing.h"
#include "gl/context.h"
#include "gl/renderer.h"
#include "io/image.h"

namespace lodline {

struct FrameTimes {
  double upload = 0.0;    ///< line buffer (and mesh) uploads, ms
  double render = 0.0;    ///< drawing up to glFinish, ms
  double readback = 0.0;  ///< resolve + glReadPixels, ms
};

class HeadlessRenderer {
 public:
  static Result<HeadlessRenderer> create(ContextBackend backend, const RenderParams& params);

  /// Uploads the surface (call when the mesh changes) of one drawing, as object 0.
  void setMesh(const LineDrawing& drawing);
  /// Draws `drawing`'s current lines from `camera`; the image is then in image().
  void draw(const LineDrawing& drawing, const Camera& camera, const RenderParams& params, bool upload_lines = true);

  /// Uploads the surface of every object of `scene` (`all`), or of those whose mesh changed
  /// in the last frame. Errors: shader compilation for new objects.
  Status setMeshes(const SceneDrawing& scene, bool all);
  /// Draws every object of `scene` from `camera` in its own style, uploading its lines;
  /// `frame` gives the background.
  void draw(const SceneDrawing& scene, const Camera& camera, const RenderParams& frame);
  /// The surface pass (after setMeshes()/setMesh()): each pixel's nearest world position and
  /// object id, for the motion-compensated coherence measure. Errors: framebuffer creation.
  Status drawSurface(const Camera& camera, SurfaceImage& out);
  /// Reads back the colour image of the last draw().
  Image readImage();
  /// Reads back the depth of the last draw() (for visibility of lines).
  DepthImage readDepth() const { return target_->readDepth(); }

  const GlContext& context() const { return *context_; }
  const Renderer& renderer() const { return *renderer_; }
  const FrameTimes& times() const { return times_; }

 private:
  HeadlessRenderer() = default;
  std::unique_ptr<GlContext> context_;
  // Optional-like holders: destroyed before the context (declared after it).
  std::unique_ptr<Renderer> renderer_;
  std::unique_ptr<OffscreenTarget> target_;
  std::unique_ptr<SurfaceTarget> surface_target_;  // created by the first drawSurface()
  FrameTimes times_;
  std::vector<RenderParams> styles_;
};

}  // namespace lodline
