// What a presented frame drew, counted once for every consumer: `render --stats`, the
// `capture --metrics` rows and summary, the viewer's panel and the benchmarks all read a
// FrameReport (docs/stats.md defines each field). One definition per count: a speck is a
// *visible* stroke shorter than kSpeckLengthPx on screen, a stroke is a visible stroke (after
// splitting at hidden parts), active faces are the faces of the mesh drawn.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "export/coherence.h"
#include "export/outline_coverage.h"
#include "frame/scene_drawing.h"
#include "lod/vertex_clustering.h"
#include "present/presenter.h"

namespace lodline {

/// The adapted progressive mesh of an object (or the sums over objects).
struct LodReport {
  uint64_t active_vertices = 0;
  uint64_t active_faces = 0;
  uint64_t visible_faces = 0;  ///< in the frustum and front-facing, current view
  uint64_t splits = 0, collapses = 0, morphing = 0;  ///< in the last frame
  /// Fraction of visible faces whose image area is in [t_c·T/2, 2·t_s·T], current view
  /// (totals: the mean weighted by visible faces).
  double band_fraction = 0.0;
  /// As band_fraction, with faces outside the band only where the progressive mesh has no
  /// finer or coarser level counted as in it (LodStats::band_or_limit_fraction).
  double band_or_limit_fraction = 0.0;
  double target_area = 0.0;  ///< T × the object's factors, px²
  /// Faces turned over against their full-detail normals, each under 1 px² when folded
  /// (LodStats::folded_faces; docs/detail-control.md §7).
  uint64_t folded_faces = 0;
};

struct ObjectReport {
  std::string name;
  uint64_t input_vertices = 0, input_faces = 0;  ///< the full-detail mesh
  float detail_factor = 1.0f;
  Style style = Style::kToon;
  uint64_t active_faces = 0;   ///< faces of the mesh drawn (adapted, clustered or full)
  uint64_t faces_drawn = 0;    ///< triangles the backend drew
  uint64_t line_segments = 0;  ///< segments the backend drew (enabled kinds)
  std::array<uint64_t, kLineKindCount> lines{};            ///< visible segments per kind
  std::array<uint64_t, kLineKindCount> lines_extracted{};  ///< extracted segments per kind
  uint64_t strokes_extracted = 0;  ///< strokes after chaining, visible or not
  uint64_t strokes = 0;            ///< visible strokes (runs after hidden-line removal)
  uint64_t specks = 0;             ///< visible strokes shorter than kSpeckLengthPx
  std::array<uint64_t, kLineKindCount> specks_by_kind{};  ///< the specks per kind
  uint64_t line_pixels = 0;        ///< pixels under the visible strokes (centre lines)
  uint64_t hidden_line_pixels = 0; ///< pixels under the hidden runs (drawn or not)
  /// Length of the visible contour that completes the exterior outline (the mesh's own
  /// silhouette where the interpolated contour leaves it), pixels.
  double outline_fill_px = 0.0;
  std::optional<LodReport> lod;        ///< progressive mesh only
  std::optional<ClusterStats> cluster; ///< vertex clustering only
};

/// Milliseconds of the frame's stages (sums over the objects).
struct StageTimes {
  double adapt = 0.0, shape = 0.0, view = 0.0, extract = 0.0, chain = 0.0;  ///< CPU stages
  double upload = 0.0, render = 0.0, readback = 0.0, visibility = 0.0, strokes = 0.0;  ///< presenting
};

struct FrameReport {
  std::vector<ObjectReport> objects;
  /// How much of the exterior outline of the faces as drawn has a visible line on it
  /// (export/outline_coverage.h).
  OutlineCoverage outline;
  /// Sums over the objects (line_pixels: a pixel two objects' lines share counts once;
  /// lod.band_fraction: weighted by visible faces). name "total".
  ObjectReport total;
  StageTimes ms;
  /// Mean movement, px, of the texture under the line samples that persist from the
  /// previous frame, along their strokes (ScenePresenter::textureDrift()); 0 for a first frame.
  double texture_drift = 0.0;
};

/// Counts the last present() of `presenter` of `scene` (reads the depth and computes the
/// visible strokes if that has not happened yet). `image_mask`, if given, receives the
/// line mask of the whole image (every object's visible strokes; export/coherence.h).
FrameReport reportFrame(const SceneDrawing& scene, ScenePresenter& presenter, LineMask* image_mask = nullptr);

/// The frame's counts in the `--stats` schema (docs/stats.md): faces_drawn, line_segments,
/// lines, lines_extracted, strokes, specks, line_pixels, lod (when any object has one),
/// cluster (a single clustered object) and objects. The caller adds model, image, context
/// and ms.
nlohmann::json frameStatsJson(const FrameReport& report);

/// The header line of the `capture --metrics` CSV (docs/capture.md), with its newline.
std::string metricsCsvHeader();
/// One row of the metrics CSV for frame `frame`: the coherence against the previous frame,
/// the report's counts and the frame's wall time in ms.
void writeMetricsRow(std::ostream& out, int64_t frame, const FrameReport& report, const FrameCoherence& coherence,
                     double ms_total);

}  // namespace lodline
