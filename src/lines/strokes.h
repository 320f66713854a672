// Chaining line segments into strokes (polylines) by their exact point ids (lines.h), so
// that a closed contour becomes one closed stroke and stylisation/length tests see whole
// curves rather than per-face pieces.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "lines/lines.h"

namespace lodline {

/// Polylines, flat arrays (caller-owned, reused between frames).
struct StrokeSet {
  std::vector<glm::vec3> points;  ///< all strokes' points, model units
  std::vector<float> alpha;       ///< 1 per point
  /// Stroke s is points[offsets[s] .. offsets[s+1]); strokeCount()+1 entries (or empty).
  std::vector<uint32_t> offsets;
  std::vector<LineKind> kinds;    ///< 1 per stroke
  /// 1 per stroke: 1 when closed; a closed stroke repeats its first point at the end.
  std::vector<uint8_t> closed;

  size_t strokeCount() const { return kinds.size(); }
  void clear();
};

/// Scratch of chainStrokes(); reuse between calls.
struct ChainScratch {
  std::vector<uint32_t> partner;
  std::vector<uint8_t> used;
  // Per (point id, type): the first end seen and how many ends share it (kept reset).
  std::vector<uint32_t> first_end;
  std::vector<uint8_t> end_count;
};

/// Joins the segments of `lines` into strokes: two segment ends join when they have the same
/// type and point id and no third end shares that id (junctions of three or more ends, e.g.
/// crease corners, end strokes). Every segment appears in exactly one stroke.
/// O(S log S) for S segments; allocation-free after warm-up.
void chainStrokes(const LineSet& lines, StrokeSet& out, ChainScratch& scratch);

/// Keeps the strokes s for which keep(s) is true, in order, compacting `strokes` in place
/// (no allocation).
template <class Keep>
void keepStrokes(StrokeSet& strokes, Keep&& keep) {
  const size_t n = strokes.strokeCount();
  size_t out_stroke = 0;
  uint32_t out_point = 0;
  for (size_t s = 0; s < n; ++s) {
    const uint32_t begin = strokes.offsets[s], end = strokes.offsets[s + 1];
    if (!keep(s)) continue;
    if (out_point != begin) {
      std::copy(strokes.points.begin() + begin, strokes.points.begin() + end, strokes.points.begin() + out_point);
      std::copy(strokes.alpha.begin() + begin, strokes.alpha.begin() + end, strokes.alpha.begin() + out_point);
    }
    strokes.offsets[out_stroke] = out_point;
    strokes.kinds[out_stroke] = strokes.kinds[s];
    strokes.closed[out_stroke] = strokes.closed[s];
    out_point += end - begin;
    ++out_stroke;
  }
  if (out_stroke == n) return;
  strokes.points.resize(out_point);
  strokes.alpha.resize(out_point);
  strokes.kinds.resize(out_stroke);
  strokes.closed.resize(out_stroke);
  strokes.offsets.resize(out_stroke + 1);
  strokes.offsets[out_stroke] = out_point;
}

/// Strokes shorter than this on screen are "specks" (stats, capture metrics, viewer panel).
inline constexpr float kSpeckLengthPx = 3.0f;

/// How many of the stroke lengths `length_px` (pixels) are below kSpeckLengthPx.
inline size_t countSpecks(std::span<const float> length_px) {
  return static_cast<size_t>(std::count_if(length_px.begin(), length_px.end(), [](float len) { return len < kSpeckLengthPx; }));
}

/// Length of every stroke after projecting its points with `project` (glm::vec3 →
/// glm::vec2, e.g. to pixels): `out` gets strokeCount() floats in the projected units.
template <class Project>
void measureStrokeLengths(const StrokeSet& strokes, Project&& project, std::vector<float>& out) {
  out.assign(strokes.strokeCount(), 0.0f);
  for (size_t s = 0; s < strokes.strokeCount(); ++s) {
    const uint32_t begin = strokes.offsets[s], end = strokes.offsets[s + 1];
    if (end - begin < 2) continue;
    glm::vec2 prev = project(strokes.points[begin]);
    float len = 0.0f;
    for (uint32_t i = begin + 1; i < end; ++i) {
      const glm::vec2 cur = project(strokes.points[i]);
      len += glm::length(cur - prev);
      prev = cur;
    }
    out[s] = len;
  }
}

}  // namespace lodline
