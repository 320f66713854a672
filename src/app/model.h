// The detail-control options and loading what a command draws: a mesh file, a scene file
// (.json) or a glTF file. Scene "settings" are applied as the command's own options (the
// command line wins), so the CLI, scene files and the viewer fill the same parameter structs;
// the scene itself is built by frame/scene_builder.h.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "app/options.h"
#include "core/image.h"
#include "core/result.h"
#include "frame/scene_builder.h"
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
  float adapt_budget_ms = DetailParams{}.max_adapt_ms;
  float min_suggestive_length = DetailParams{}.min_suggestive_length;
  std::string cache_dir;
  int max_adapt_frames = 300;
  std::string smoothing = "on";
  float smoothing_alpha = SmoothingParams{}.alpha;
  float smoothing_time = SmoothingParams{}.seconds;
};

void addDetailOptions(CLI::App& cmd, DetailOptions& o);
/// Reads a detail map: a PNG whose grey level v at a pixel multiplies T by (v/255)·scale.
Result<std::shared_ptr<const DetailMap>> readDetailMap(const std::filesystem::path& path, float scale);
/// The detail map of an image (as readDetailMap() makes it of the PNG's pixels).
std::shared_ptr<const DetailMap> detailMapFromImage(const Image& image, float scale);
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

/// Reads the input named by `view.models` (mesh, scene or glTF; none: the default model), applies its settings to
/// `cmd`'s options not given on the command line (so `view` and `detail` are read after)
/// and resolves the frame's parameters (the scene's camera and light included) and each
/// object's style. `read_ms` (optional) receives the time spent.
Result<SceneInput> readInput(CLI::App& cmd, ViewOptions& view, DetailOptions& detail, double* read_ms = nullptr);

/// The default model, beside the running program: PREFIX/share/lodline/models/knot.off when
/// installed, else models/knot.off of the source tree the program was built in.
Result<std::filesystem::path> defaultModelPath();

/// readInput() for a scene already in memory (`view.models` names it in errors): the scene's
/// settings, the options and each object's style resolved as for a file.
Result<SceneInput> resolveInput(CLI::App& cmd, ViewOptions& view, DetailOptions& detail, Scene scene);

/// readInput(), then loads every object (frame/scene_builder.h): its mesh in world space and
/// its level of detail, with a progress bar for progressive-mesh builds on a terminal.
Result<std::unique_ptr<LoadedScene>> loadInput(CLI::App& cmd, ViewOptions& view, DetailOptions& detail);

/// The resolved style of every object of `scene`: the frame's options `view` with each
/// object's style keys applied.
Result<std::vector<ObjectStyle>> resolveObjectStyles(const Scene& scene, const ViewOptions& view);

/// Stderr progress bar for progressive-mesh builds: silent unless stderr is a terminal and
/// the build has run for more than a second.
PmProgress buildProgressBar(const std::string& label);

}  // namespace lodline
