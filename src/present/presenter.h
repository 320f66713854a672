// The last stage of a frame, with one owner (docs/design.md §1): upload what changed of a
// SceneDrawing, draw its faces (OpenGL or the software rasteriser), read the depth back,
// split every object's strokes into visible and hidden runs against it (per-sample
// visibility, docs/visibility.md), complete the exterior outline, and draw the runs as the
// frame's lines. `render`, `capture`, the viewer and the benchmarks all draw through a
// ScenePresenter, so they draw, read and count the same way.
//
//   auto presenter = createPresenter(PresenterBackend::kGl, ContextBackend::kAuto, scene);
//   (*presenter)->present(scene, camera, frame, /*all_meshes=*/true);
//   Image image = (*presenter)->readImage();
//   const auto& visible = (*presenter)->visible();   // per object: the runs drawn
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/image.h"
#include "core/line_buffer.h"
#include "core/render_params.h"
#include "core/result.h"
#include "export/coherence.h"
#include "export/visibility.h"
#include "frame/scene_drawing.h"
#include "gl/context.h"
#include "present/outline.h"
#include "present/screen_lines.h"
#include "present/stroke_fade.h"
#include "present/stroke_parameterization.h"

namespace lodline {

/// Which renderer draws: OpenGL (through a context) or the software rasteriser.
enum class PresenterBackend { kGl, kSoft };

/// Parses "gl" or "soft" (the values of --backend).
Result<PresenterBackend> parsePresenterBackend(const std::string& name);

/// Milliseconds of the last present() and of what was read after it.
struct PresentTimes {
  double upload = 0.0;      ///< meshes and lines to the renderer
  double render = 0.0;      ///< drawing faces and lines, until the image is complete (glFinish)
  double readback = 0.0;    ///< the colour image (readImage())
  /// Depth readback, the strokes' visible and hidden runs and the outline's completion.
  double visibility = 0.0;
  /// The runs made stroke geometry (present/stroke_geometry.h), every object; includes `fade`.
  double strokes = 0.0;
  /// Of `strokes`: fading new lines in (present/stroke_fade.h), every object; ~0 when off.
  double fade = 0.0;
};

class ScenePresenter {
 public:
  virtual ~ScenePresenter() = default;

  /// A usage error naming the object if this backend cannot draw one of the styles of
  /// `scene` (the software renderer has no shaded style); never a silent substitute.
  virtual Status check(const SceneDrawing& scene) const = 0;

  /// Draws `scene` from `camera` into the presenter's image: uploads every object's mesh
  /// when `all_meshes` (or when the object count changed), else only the meshes that
  /// changed in the last frame (LodDrawing::meshChanged()); draws every object's faces in
  /// its own style on frame's page; reads the depth back; splits each object's strokes
  /// (and intersection lines) into visible and hidden runs, completes its outline; draws
  /// the visible runs in their kind's style and, where enabled, the hidden runs in the
  /// hidden style. Successive calls are frames of one sequence: the outline's completing
  /// pieces continue from the previous call's (hysteresis, docs/visibility.md), so a frame
  /// drawn in a sequence can differ by a few short pieces from the same frame drawn alone
  /// (startSequence() starts afresh). Errors: shader compilation for new objects, a style
  /// check() refuses.
  Status present(const SceneDrawing& scene, const Camera& camera, const FrameParams& frame, bool all_meshes);
  /// As present(), and runs `overlap` on a second thread (at a lower priority than the
  /// drawing's: nice +10 on Linux) once the meshes are uploaded and
  /// each object's strokes, silhouette, median edge and bounds are copied, before the faces
  /// are drawn; present() returns when both are done. From then on present() reads only the
  /// objects' intersection lines, fixed when the scene is built. So the next frame's CPU
  /// stages (SceneDrawing::frameWhileDrawing) can run while this frame is drawn, its depth
  /// read back and its lines split and drawn (docs/performance.md, "Frames in a pipeline");
  /// the image is the one present() draws. `overlap` may advance `scene` (frame, converge),
  /// not add or remove objects; it must not touch this presenter or its GL context, nor
  /// throw. A null `overlap` is present().
  Status present(const SceneDrawing& scene, const Camera& camera, const FrameParams& frame, bool all_meshes,
                 const std::function<void()>& overlap);

  /// The next present() starts a new sequence (no hysteresis from earlier frames). With
  /// `in_motion` (a capture) its first frame is already drawn as a frame in motion, so the
  /// short outline pieces a still would add do not vanish on the second (docs/visibility.md).
  void startSequence(bool in_motion) {
    outline_history_.clear();
    sequence_in_motion_ = in_motion;
    for (StrokeParameterizer& p : parameterizers_) p.reset();
    for (StrokeFader& f : faders_) f.reset();
  }
  /// Lines that appear fade in (present/stroke_fade.h) gaining `step` of their opacity per
  /// frame (frame time / fade-in time; the viewer sets it every frame from its frame time).
  /// Default 0: off, as a still is drawn.
  void setFadeStep(float step) { fade_.step = step; }
  /// Of the last present(), visible line samples still fading in, over all objects.
  size_t fadingSamples() const;
  /// Whether brushes, dashes and jitter follow the surface from frame to frame (coherent
  /// parameterisation, present/stroke_parameterization.h) or start at each visible run's
  /// first point (u = arc length). Default on; a still's single frame is the same either way.
  void setStrokeCoherence(bool on) { stroke_coherence_ = on; }
  /// Of the last present(), over every object's previous line samples that persist: the
  /// mean movement, px, of the texture under them along their strokes (0 when none).
  double textureDrift() const;
  /// The stroke parameter of each point of an object's visible runs in the last present().
  const std::vector<float>& strokeParameters(size_t object) const { return parameterizers_[object].parameters(); }

  /// The colour image of the last present(), row 0 = top.
  Image readImage();
  /// The visible surface of the last present() (world position and object per pixel), for
  /// the motion-compensated coherence measure. Errors: framebuffer creation.
  virtual Status readSurface(SurfaceImage& out) = 0;
  /// Window depth of the last present()'s faces.
  const DepthImage& depth() const { return depth_; }
  /// The runs of each object's lines drawn by the last present(), one entry per object,
  /// tested against the depth of every object's faces (so one object hides another's
  /// lines): the visible ones (the outline's completion included, as contour runs) and the
  /// hidden ones (computed whether or not they are drawn).
  const std::vector<StrokeRuns>& visible() const { return visible_; }
  const std::vector<StrokeRuns>& hidden() const { return hidden_; }
  /// Of each object's visible contour runs, the length (pixels) that completes the outline.
  const std::vector<double>& outlineFill() const { return outline_fill_; }
  /// Every object's visible (hidden) runs as one set (for the line mask of the whole image).
  const StrokeRuns& visibleAll();
  const StrokeRuns& hiddenAll();

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
  /// Uploads meshes (all, or those that changed).
  virtual Status uploadMeshes(const SceneDrawing& scene, bool all_meshes) = 0;
  /// Draws every object's faces (a new image, cleared to the background).
  virtual Status drawSurfaces(const Camera& camera, const FrameParams& frame, std::span<const ObjectStyle> styles) = 0;
  virtual void readDepth(DepthImage& out) = 0;
  virtual void uploadLines(size_t object, const ScreenLines& lines) = 0;
  /// Draws the uploaded lines over the faces; returns when the image is complete.
  virtual void drawLines(const FrameParams& frame, std::span<const ObjectStyle> styles) = 0;
  virtual Image readColour() = 0;

 private:
  /// What the frame's later steps need of each object, taken from the scene before they
  /// run. The strokes are read in place, or, when the scene may change meanwhile
  /// (present()'s `overlap`), from copies.
  struct ObjectLines {
    const StrokeSet* strokes = nullptr;      ///< the drawing's, or `strokes_copy`
    const StrokeSet* silhouettes = nullptr;  ///< the drawing's, or `silhouettes_copy`
    StrokeSet strokes_copy, silhouettes_copy;
    const StrokeSet* intersections = nullptr;  ///< the scene's (fixed when it is built)
    bool intersections_on = false, contours_on = false;
    float median_edge = 0.0f;
    Bounds bounds;
  };
  void takeObjectLines(const SceneDrawing& scene, bool copy);
  void splitObjectLines();
  std::vector<ObjectLines> objects_;
  Camera camera_;
  FrameParams frame_;
  std::vector<ObjectStyle> styles_;
  PresentTimes times_;
  DepthImage depth_;
  std::vector<StrokeRuns> visible_, hidden_;
  std::vector<double> outline_fill_;
  StrokeRuns visible_all_, hidden_all_, scratch_, scratch2_;
  bool visible_all_valid_ = false, hidden_all_valid_ = false;
  OutlineScratch outline_scratch_;
  std::vector<float> edge_lengths_;  ///< splitObjectLines(): sampled edge lengths
  std::vector<OutlineHistory> outline_history_;
  bool sequence_in_motion_ = false;
  ScreenLines screen_lines_;
  ScreenLinesScratch stroke_scratch_;
  StrokeCurveScratch curve_scratch_;  // smoothRuns()
  std::vector<StrokeParameterizer> parameterizers_;
  bool stroke_coherence_ = true;
  std::vector<StrokeFader> faders_;
  StrokeFadeParams fade_;
};

/// A presenter for `scene` on `backend`: OpenGL through a headless context of kind
/// `context` with an offscreen target of frame's size and multisampling, or the software
/// rasteriser. Errors: no context, a style the backend cannot draw (a usage error).
Result<std::unique_ptr<ScenePresenter>> createPresenter(PresenterBackend backend, ContextBackend context,
                                                        const SceneDrawing& scene, const FrameParams& frame);

}  // namespace lodline
