// Loading what a command draws: a mesh file, a scene file (.json) or a glTF file, as a
// SceneDrawing of one or more objects, each with its level of detail (progressive mesh from
// the cache, built and cached on first use; vertex clustering; or full detail) and its style.
// Scene "settings" are applied as the command's own options (the command line wins), so
// the CLI, scene files and the viewer fill the same parameter structs.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "app/options.h"
#include "core/result.h"
#include "frame/camera_path.h"
#include "frame/scene_drawing.h"
#include "frame/temporal_smoothing.h"
#include "io/scene_file.h"
#include "lod/adaptive_mesh.h"

namespace lodline {

/// Raw detail-control options (checked by resolveDetailOptions()).
struct DetailOptions {
  bool full_detail = false;
  std::string lod = "pm";       ///< --lod pm|cluster|none (none = --full-detail)
  float pixel_error = ClusterParams{}.pixel_error;  ///< --pixel-error K (cluster), px²
  float target_area = DetailParams{}.target_area;
  float t_c = DetailParams{}.t_c;
  float t_s = DetailParams{}.t_s;
  std::string detail_map;
  float detail_map_scale = 8.0f;
  float depth_falloff = 0.0f;
  float foveation = 0.0f;
  std::string focus;
  float object_factor = 1.0f;
  std::string geomorphs = "on";
  float morph_time = DetailParams{}.morph_time;
  std::string cache_dir;
  int max_adapt_frames = 300;
  std::string smoothing = "on";
  float smoothing_alpha = SmoothingParams{}.alpha;
  float smoothing_time = SmoothingParams{}.seconds;
};

/// Level of detail: progressive mesh with detail control, per-frame vertex clustering, none.
enum class LodMode { kPm, kCluster, kNone };

struct ResolvedDetail {
  SmoothingParams smoothing;
  bool full_detail = false;  ///< mode == LodMode::kNone
  LodMode mode = LodMode::kPm;
  ClusterParams cluster;     ///< pixel error for LodMode::kCluster (foveation comes from params)
  DetailParams params;
  std::string detail_map_file;  ///< the --detail-map file (empty: none), for writing scenes back
  float detail_map_scale = 8.0f;
  std::filesystem::path cache_dir;
  int max_adapt_frames = 300;
};

void addDetailOptions(CLI::App& cmd, DetailOptions& o);
/// Reads a detail map: a PNG whose grey level v at a pixel multiplies T by (v/255)·scale.
Result<std::shared_ptr<const DetailMap>> readDetailMap(const std::filesystem::path& path, float scale);
Result<ResolvedDetail> resolveDetailOptions(const DetailOptions& o);

/// The default cache directory: $XDG_CACHE_HOME/lodline or ~/.cache/lodline.
std::filesystem::path defaultCacheDir();

/// Applies `scene.settings` (render options by long name, e.g. "target-area": 16) to the
/// options of `cmd` that the command line did not give, through the same option parsers.
/// Keys that are options of lodline's drawing commands but not of `cmd` are ignored (a scene
/// written for `capture` renders too); other keys are errors naming the file and the key.
Status applySceneSettings(const Scene& scene, CLI::App& cmd);

/// True when the option `--name` of `cmd` was given on the command line.
bool givenOnCommandLine(const CLI::App& cmd, const std::string& name);

/// What a command needs to draw its input.
struct LoadedScene {
  Scene scene;
  ResolvedView view;       ///< frame parameters (size, background, msaa, default style)
  ResolvedDetail detail;
  SceneDrawing drawing;    ///< one object per scene object, styles resolved
  double load_ms = 0.0;    ///< reading and checking mesh files
  double pm_ms = 0.0;      ///< progressive meshes from the cache or built
  std::string cache_note;  ///< what happened to the progressive-mesh caches
  /// The input's camera unless the command line gave --view: the scene file's view, pose or
  /// path; none: frame the scene with ResolvedView::orbit.
  std::optional<SceneCamera> camera;
};

/// Reads the input named by `view.models` (mesh, scene or glTF), applies its settings to
/// `cmd`'s options not given on the command line (so `view` and `detail` are read after),
/// resolves the frame's and each object's parameters and loads every object: its mesh in
/// world space and its level of detail. Objects share one worker pool.
Result<std::unique_ptr<LoadedScene>> loadInput(CLI::App& cmd, ViewOptions& view, DetailOptions& detail);

/// Loads the objects of `scene` with the given parameters (used by loadInput and by the
/// viewer). `view_options` are the frame's options before object overrides.
Result<std::unique_ptr<LoadedScene>> loadSceneObjects(Scene scene, const ViewOptions& view_options,
                                                      const ResolvedView& view, const ResolvedDetail& detail);

/// The frame's camera for an image of aspect `aspect`: the scene's camera (a path at its
/// start time), else the orbit of ResolvedView around the scene's bounds; clip planes fitted.
Result<Camera> initialCamera(const LoadedScene& loaded, float aspect);

/// The camera path of a capture: `name_or_file` (built-in name or .json), else the scene
/// file's path, around the scene's bounds.
Result<CameraPath> scenePath(const LoadedScene& loaded, const std::string& name_or_file, bool given,
                             double duration, float aspect);

/// Stderr progress bar for progressive-mesh builds: silent unless stderr is a terminal and
/// the build has run for more than a second.
PmProgress buildProgressBar(const std::string& label);

}  // namespace lodline
