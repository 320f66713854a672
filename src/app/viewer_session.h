// The state and frame loop of `lodline view`, without a window: the loaded scene, the
// camera (orbit, pan, zoom), the parameters the panel edits, and presenting frames through
// the GL presenter (present/gl_presenter.h) — the same drawing and counting `render` uses.
// The GLFW front end (cmd_view.cpp) feeds it input; tests drive it headlessly (EGL), which is
// how "the viewer shows what `render` shows" is checked.
//
// The first frame converges the detail for the initial camera (as `render` does), so the
// viewer opens on the picture `render` would write; later frames adapt with geomorphs and
// temporal smoothing at the measured frame rate (Jeong et al. 2005 §3.2–3.3).
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/model.h"
#include "present/frame_report.h"
#include "present/gl_presenter.h"

namespace lodline {

class ViewerSession {
 public:
  /// Takes the loaded input; needs a current GL context (compiles the renderer). `options`
  /// are the frame's raw view options.
  static Result<std::unique_ptr<ViewerSession>> create(std::unique_ptr<LoadedScene> loaded, const ViewOptions& options);

  /// The camera for a `width`×`height` framebuffer.
  Camera camera(int width, int height) const;

  /// One frame for a `width`×`height` framebuffer after `dt` seconds: the first converges,
  /// later ones adapt (every frame under detail control, else only when something changed);
  /// then the frame is presented (drawn offscreen) and counted (report()). Errors come from
  /// invalid detail parameters only.
  Status frame(int width, int height, float dt);
  /// Copies the last presented frame into the bound framebuffer (the window).
  void draw() const { presenter_->blitToBound(); }

  // ---- input (the window's mouse and keys, the panel) ----
  void orbit(float d_azimuth_deg, float d_elevation_deg);
  /// Moves the orbit centre by `dx`, `dy` pixels of a `height`-px framebuffer.
  void pan(float dx_px, float dy_px, int width, int height);
  void zoom(float factor);
  void resetView();
  /// Marks lines for recomputation (line kinds, thresholds or style changed).
  void touch() { dirty_ = true; }
  /// Playback of a camera path (looping) overrides the orbit while set.
  void play(std::optional<CameraPath> path);
  bool playing() const { return path_.has_value(); }
  void advancePlayback(double seconds) { play_time_ += seconds; dirty_ = true; }

  // ---- parameters the panel edits (call touch() or setLineParams() after a change) ----
  /// The style the panel's global controls edit (objects without style keys of their own).
  ObjectStyle& defaultStyle() { return loaded_->view.style; }
  DetailParams& detail() { return loaded_->detail.params; }
  SmoothingParams& smoothing() { return loaded_->detail.smoothing; }
  const LodChoice& lod() const { return loaded_->detail.lod; }
  const LineParams& lineParams() const { return loaded_->view.line_params; }
  void setLineParams(const LineParams& p);
  /// Reads a detail-map PNG (empty path: none) with `scale` at white; errors name the file.
  Status setDetailMap(const std::string& path, float scale);
  const std::string& detailMapFile() const { return loaded_->detail.detail_map_file; }
  float detailMapScale() const { return loaded_->detail.detail_map_scale; }
  /// Every object's style (the panel's global style control).
  void setStyleAll(Style style);
  /// Sets line kind `kind`'s stroke fields (every kind's when `kind` < 0) on every object, as
  /// the panel's stroke fields do; the style is then an edited one (kEditedStrokeStyle),
  /// which "save view" writes as a style file next to the view.
  void setStrokeStyle(int kind, const StrokeStyle& style);
  /// The stroke style's name once its fields were edited in the panel.
  static constexpr const char* kEditedStrokeStyle = "edited";
  /// True when some object has intersection lines (found when the scene was loaded).
  bool hasIntersectionLines() const;
  SceneDrawing& scene() { return loaded_->drawing; }
  const SceneDrawing& scene() const { return loaded_->drawing; }
  const LoadedScene& loaded() const { return *loaded_; }
  /// The scene as described (the panel keeps object style keys in step with its edits).
  Scene& description() { return loaded_->scene; }
  float fov() const { return fov_deg_; }

  /// What the last frame drew (the panel's statistics; the same counts as --stats).
  const FrameReport& report() const { return report_; }
  const ScenePresenter& presenter() const { return *presenter_; }

  /// The width, px, the panel covers at the window's left (0: none). The scene is framed in
  /// the rest: its centre at the free part's centre and, while the view is the initial one,
  /// its distance scaled to the free part's aspect.
  void setInset(int left_px) {
    if (left_px != inset_px_) dirty_ = true;
    inset_px_ = left_px;
  }

  /// Writes the current camera, parameters and objects (with their detail factors and
  /// styles) as a scene file that `lodline render` reproduces (io/scene_file.h's writer);
  /// paths are written relative to the new file's folder. Atomic; errors name the file.
  /// `width`×`height`: the image size. The camera saved is the one framing the scene in the
  /// whole image (the panel's inset left out), so `lodline render` centres what the viewer
  /// showed in the free part.
  Status saveView(const std::filesystem::path& path, int width, int height) const;

 private:
  ViewerSession() = default;
  std::unique_ptr<LoadedScene> loaded_;
  ViewOptions options_;
  std::unique_ptr<GlPresenter> presenter_;
  Camera cameraFor(int width, int height, int inset_px) const;
  OrbitView orbit_, initial_orbit_;
  glm::vec3 pan_{0.0f}, initial_pan_{0.0f};
  int inset_px_ = 0;
  /// The initial distance (given or framing the scene) and the aspect it was meant for: while
  /// the view is still the initial one, it is scaled so the scene fills the part of the
  /// window the panel leaves free as it would have filled that aspect.
  float base_distance_ = 0.0f;
  float base_aspect_ = 1.0f;
  int fitted_for_[3] = {0, 0, -1};  ///< width, height, inset the distance was fitted for
  float fov_deg_ = 35.0f;
  std::optional<CameraPath> path_;
  double play_time_ = 0.0;
  bool dirty_ = true, first_ = true;
  float mean_dt_ = 1.0f / 20.0f;
  FrameReport report_;
};

}  // namespace lodline
