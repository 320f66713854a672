// The state and frame loop of `lodline view`, without a window: the loaded scene, the
// camera (orbit, pan, zoom), the parameters the panel edits, and drawing into whatever
// framebuffer is bound. The GLFW front end (cmd_view.cpp) feeds it input; tests drive it
// headlessly (EGL), which is how "the viewer shows what `render` shows" is checked.
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
#include "gl/renderer.h"

namespace lodline {

/// Live statistics of the last frame, summed over the objects (the panel shows them).
struct ViewerStats {
  double adapt_ms = 0.0, shape_ms = 0.0, view_ms = 0.0, extract_ms = 0.0, chain_ms = 0.0;
  double upload_ms = 0.0, draw_ms = 0.0;  ///< CPU time submitting the draw (GL runs async)
  size_t active_faces = 0;                ///< faces of the meshes drawn
  size_t visible_faces = 0;               ///< in the frustum and front-facing (detail control only)
  size_t strokes = 0;                     ///< extracted strokes, before hidden-line removal
  size_t specks = 0;                      ///< of those, shorter than 3 px on screen
  size_t splits = 0, collapses = 0, morphing = 0;
};

class ViewerSession {
 public:
  /// Takes the loaded input; needs a current GL context (compiles the renderer). `options`
  /// are the frame's raw view options (for writing the scene back).
  static Result<std::unique_ptr<ViewerSession>> create(std::unique_ptr<LoadedScene> loaded, const ViewOptions& options);

  /// The camera for a `width`×`height` framebuffer.
  Camera camera(int width, int height) const;

  /// One frame for a `width`×`height` framebuffer after `dt` seconds: the first converges,
  /// later ones adapt (every frame under detail control, else only when something changed),
  /// then uploads what changed. Errors come from invalid detail parameters only.
  Status frame(int width, int height, float dt);
  /// Draws the scene into the bound framebuffer (cleared first).
  void draw(int width, int height);

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
  RenderParams& frameParams() { return loaded_->view.render; }
  DetailParams& detail() { return loaded_->detail.params; }
  SmoothingParams& smoothing() { return loaded_->detail.smoothing; }
  LodMode lodMode() const { return loaded_->detail.mode; }
  const LineParams& lineParams() const { return loaded_->view.line_params; }
  void setLineParams(const LineParams& p);
  /// Reads a detail-map PNG (empty path: none) with `scale` at white; errors name the file.
  Status setDetailMap(const std::string& path, float scale);
  const std::string& detailMapFile() const { return loaded_->detail.detail_map_file; }
  float detailMapScale() const { return loaded_->detail.detail_map_scale; }
  /// Every object's style (the panel's global style control).
  void setStyleAll(Style style);
  SceneDrawing& scene() { return loaded_->drawing; }
  const SceneDrawing& scene() const { return loaded_->drawing; }
  const LoadedScene& loaded() const { return *loaded_; }
  /// The scene as described (the panel keeps object style keys in step with its edits).
  Scene& description() { return loaded_->scene; }
  float fov() const { return fov_deg_; }

  const ViewerStats& stats() const { return stats_; }
  const Renderer& renderer() const { return *renderer_; }

  /// Writes the current camera, parameters and objects (with their detail factors and
  /// styles) as a scene file that `lodline render` reproduces; paths are written relative to
  /// the new file's folder. Atomic; errors name the file. `width`×`height`: the image size.
  Status saveView(const std::filesystem::path& path, int width, int height) const;

 private:
  ViewerSession() = default;
  std::unique_ptr<LoadedScene> loaded_;
  ViewOptions options_;
  std::unique_ptr<Renderer> renderer_;
  std::vector<RenderParams> styles_;
  OrbitView orbit_, initial_orbit_;
  glm::vec3 pan_{0.0f}, initial_pan_{0.0f};
  float fov_deg_ = 35.0f;
  std::optional<CameraPath> path_;
  double play_time_ = 0.0;
  bool dirty_ = true, first_ = true;
  float mean_dt_ = 1.0f / 20.0f;
  ViewerStats stats_;
  std::vector<float> stroke_lengths_;
};

/// The render options (long names) that reproduce `params`, `detail` and `lines` — the
/// "settings" of a saved view. Paths (the detail map) are written relative to `base_dir`.
nlohmann::json settingsOf(const RenderParams& params, const ResolvedDetail& detail, const LineParams& lines,
                          const std::filesystem::path& base_dir);

}  // namespace lodline
