// SVG export of 2D line drawings (strokes already projected to pixels and, if wanted,
// hidden-line tested by the caller). Written atomically: a temporary file in the target
// directory, renamed over the target, so a failure never leaves a half-written file.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "core/result.h"
#include "lines/lines.h"
#include "lines/stroke_curve.h"

namespace lodline {

/// How one line type is drawn.
struct SvgLineStyle {
  std::string colour = "#000000";  ///< any SVG colour. Default black
  float width = 1.5f;              ///< stroke width, px. Default 1.5
  float opacity = 1.0f;            ///< multiplied by the stroke's own opacity. Default 1
  std::string linecap = "round";   ///< "round", "butt" or "square". Default round
  std::array<float, 2> dash{0.0f, 0.0f};  ///< dash on, off px (off 0 = solid). Default solid
};

/// Per-kind styles and the page.
struct SvgStyle {
  /// Indexed by LineKind: contour black 2 px, suggestive dark grey 1.5 px, crease dark blue
  /// 1 px, boundary black 1.5 px, intersection near-black 1.5 px.
  std::array<SvgLineStyle, kLineKindCount> lines = {
      SvgLineStyle{"#000000", 2.0f, 1.0f}, SvgLineStyle{"#333333", 1.5f, 1.0f},
      SvgLineStyle{"#1f3a70", 1.0f, 1.0f}, SvgLineStyle{"#000000", 1.5f, 1.0f},
      SvgLineStyle{"#0f0f0f", 1.5f, 1.0f}};
  /// The hidden lines (all kinds), written only when `hidden_enabled`: a group of class
  /// "hidden" under the visible ones, dashed by `hidden_dash` (on, off px; off 0 = solid).
  bool hidden_enabled = false;
  SvgLineStyle hidden{"#8c8c8c", 1.0f, 1.0f};
  std::array<float, 2> hidden_dash{4.0f, 3.0f};
  bool background = true;             ///< fill the page first. Default true
  std::string background_colour = "#ffffff";  ///< Default white
  int decimals = 2;                   ///< digits after the point in coordinates. Default 2
  /// Strokes as paths of cubic Béziers within `curve.tolerance_px` of the strokes
  /// (lines/stroke_curve.h), not polylines. Default true.
  bool curves = true;
  /// The fit. Its smoothing defaults to 0 here: the presenter's runs arrive smoothed as they
  /// are drawn (present/screen_lines.h, smoothRuns()), so the paths follow the PNG's line.
  StrokeCurveParams curve = [] {
    StrokeCurveParams c;
    c.smoothing_px = 0.0f;
    return c;
  }();
};

/// 2D strokes in pixel coordinates (origin top-left, y down).
struct SvgStrokes {
  std::span<const glm::vec2> points;
  /// Stroke s is points[offsets[s] .. offsets[s+1]) (strokeCount + 1 entries, or empty).
  std::span<const uint32_t> offsets;
  std::span<const LineKind> kinds;   ///< 1 per stroke
  std::span<const float> opacity;    ///< optional, 1 per stroke, in [0, 1]
  /// Optional, 1 per stroke: written as the stroke's element id "s<N>" (stable stroke ids of
  /// a sequence, present/stroke_ids.h); ids must be unique within the file.
  std::span<const uint64_t> ids = {};
};

/// Writes a `width`×`height` px SVG (viewBox "0 0 width height") with one <path> of cubic
/// Béziers (or, with style.curves off, one <polyline>) per stroke of ≥ 2 points, grouped by
/// type. Errors (bad size, inconsistent arrays, unwritable
/// path) name the file; on error no file is left at `path`.
Status writeSvg(const std::filesystem::path& path, int width, int height,
                const SvgStrokes& strokes, const SvgStyle& style = {});

/// The strokes of one object of a scene, in its own line styles (`style.lines`,
/// `style.hidden*`, `style.decimals`; its page fields are unused).
struct SvgLayer {
  std::string name;  ///< written as the group's id (sanitised)
  SvgStrokes strokes;
  SvgStyle style;
  SvgStrokes hidden = {};  ///< the hidden runs (written when style.hidden_enabled)
  /// Strokes of varying width (tapered, or thicker by depth, strength or bend) as closed
  /// outline polygons, filled in their kind's colour and written above the kind's other
  /// strokes (points = the outline, opacity = the stroke's mean opacity).
  SvgStrokes outlines = {};
};

/// Several objects in one SVG, in order (later layers on top), each in a <g id="name">
/// group; the page (background) comes from `page`. One layer writes exactly what writeSvg()
/// writes.
Status writeSvgLayers(const std::filesystem::path& path, int width, int height, std::span<const SvgLayer> layers,
                      const SvgStyle& page);

/// The document writeSvgLayers() writes, as text (errors name "SVG").
Result<std::string> svgLayersText(int width, int height, std::span<const SvgLayer> layers, const SvgStyle& page);

}  // namespace lodline
