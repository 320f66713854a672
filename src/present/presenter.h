// The last stage of a frame, with one owner (docs/design.md §1): upload what changed of a
// SceneDrawing, draw it (OpenGL or the software rasteriser), read back what was drawn and
// split every object's strokes into visible runs. `render`, `capture`, the viewer and the
// benchmarks all draw through a ScenePresenter, so they draw, read and count the same way.
//
//   auto presenter = createPresenter(PresenterBackend::kGl, ContextBackend::kAuto, scene);
//   (*presenter)->present(scene, camera, frame, /*all_meshes=*/true);
//   Image image = (*presenter)->readImage();
//   const auto& visible = (*presenter)->visible();   // per object, from the depth buffer
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/image.h"
#include "core/render_params.h"
#include "core/result.h"
#include "export/visibility.h"
#include "frame/scene_drawing.h"
#include "gl/context.h"

namespace lodline {

/// Which renderer draws: OpenGL (through a context) or the software rasteriser.
enum class PresenterBackend { kGl, kSoft };

/// Parses "gl" or "soft" (the values of --backend).
Result<PresenterBackend> parsePresenterBackend(const std::string& name);

/// Milliseconds of the last present() and of what was read after it.
struct PresentTimes {
  double upload = 0.0;      ///< meshes and lines to the renderer
  double render = 0.0;      ///< drawing, until the image is complete (glFinish)
  double readback = 0.0;    ///< the colour image (readImage())
  double visibility = 0.0;  ///< depth readback and the strokes' visible runs
};

class ScenePresenter {
 public:
  virtual ~ScenePresenter() = default;

  /// A usage error naming the object if this backend cannot draw one of the styles of
  /// `scene` (the software renderer has no shaded style); never a silent substitute.
  virtual Status check(const SceneDrawing& scene) const = 0;

  /// Draws `scene` from `camera` into the presenter's image: uploads every object's mesh
  /// when `all_meshes` (or when the object count changed), else only the meshes that
  /// changed in the last frame (LodDrawing::meshChanged()), and every object's lines; then
  /// draws each object in its own style on frame's page. Errors: shader compilation for new
  /// objects, a style check() refuses.
  Status present(const SceneDrawing& scene, const Camera& camera, const FrameParams& frame, bool all_meshes);

  /// The colour image of the last present(), row 0 = top.
  Image readImage();
  /// The visible surface of the last present() (world position and object per pixel), for
  /// the motion-compensated coherence measure. Errors: framebuffer creation.
  virtual Status readSurface(SurfaceImage& out) = 0;
  /// Window depth of the last present()'s faces (read back on first use after it).
  const DepthImage& depth();
  /// The visible runs of each object's strokes in the last present(), tested against the
  /// depth of every object's faces (so one object hides another's lines); one entry per
  /// object. Computed on first use after present().
  const std::vector<VisibleStrokes>& visible();
  /// Every object's visible strokes as one set (for the line mask of the whole image).
  const VisibleStrokes& visibleAll();

  /// Faces and line segments the backend drew for `object` in the last present().
  virtual size_t facesDrawn(size_t object) const = 0;
  virtual size_t segmentsDrawn(size_t object) const = 0;
  /// "egl", "osmesa" or "soft".
  virtual std::string backendName() const = 0;
  /// What draws: the GL version and renderer, or "software rasteriser".
  virtual std::string description() const = 0;

  const PresentTimes& times() const { return times_; }
  const Camera& camera() const { return camera_; }
  const FrameParams& frame() const { return frame_; }

 protected:
  /// Uploads meshes (all, or those that changed) and every object's lines.
  virtual Status upload(const SceneDrawing& scene, bool all_meshes) = 0;
  /// Draws the uploaded scene; returns when the image is complete. Errors: a target of the
  /// frame's size cannot be made.
  virtual Status draw(const Camera& camera, const FrameParams& frame, std::span<const ObjectStyle> styles) = 0;
  virtual Image readColour() = 0;
  virtual void readDepth(DepthImage& out) = 0;

 private:
  const SceneDrawing* scene_ = nullptr;
  Camera camera_;
  FrameParams frame_;
  std::vector<ObjectStyle> styles_;
  PresentTimes times_;
  DepthImage depth_;
  bool depth_valid_ = false, visible_valid_ = false, visible_all_valid_ = false;
  std::vector<VisibleStrokes> visible_;
  VisibleStrokes visible_all_;
};

/// A presenter for `scene` on `backend`: OpenGL through a headless context of kind
/// `context` with an offscreen target of frame's size and multisampling, or the software
/// rasteriser. Errors: no context, a style the backend cannot draw (a usage error).
Result<std::unique_ptr<ScenePresenter>> createPresenter(PresenterBackend backend, ContextBackend context,
                                                        const SceneDrawing& scene, const FrameParams& frame);

}  // namespace lodline
