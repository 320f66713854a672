// Loading a model for the frame loop: the mesh file, and for detail control its progressive
// mesh from the cache (built and cached on first use). Options shared by render, view and
// capture.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "core/result.h"
#include "frame/lod_drawing.h"
#include "frame/temporal_smoothing.h"
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
  std::filesystem::path cache_dir;
  int max_adapt_frames = 300;
};

void addDetailOptions(CLI::App& cmd, DetailOptions& o);
Result<ResolvedDetail> resolveDetailOptions(const DetailOptions& o);

/// The default cache directory: $XDG_CACHE_HOME/lodline or ~/.cache/lodline.
std::filesystem::path defaultCacheDir();

/// Loads `model` and, unless `detail.full_detail`, its progressive mesh (cache or build, with
/// a progress bar on a terminal for builds over a second). `load_ms` and `pm_ms` receive the
/// time spent reading the mesh and getting the progressive mesh; `note` the cache outcome.
Result<std::unique_ptr<LodDrawing>> loadModel(const std::filesystem::path& model, const ResolvedDetail& detail,
                                              double* load_ms = nullptr, double* pm_ms = nullptr,
                                              std::string* note = nullptr);

/// Stderr progress bar for progressive-mesh builds: silent unless stderr is a terminal and
/// the build has run for more than a second.
PmProgress buildProgressBar(const std::string& label);

}  // namespace lodline
