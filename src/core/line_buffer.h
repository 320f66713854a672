// The lines of one object as the renderers draw them (GL and software alike): stroke
// geometry in pixels — triangles extruded from the presenter's visible and hidden runs
// (present/stroke_geometry.h), so the renderers draw them over the faces with no depth test
// (docs/visibility.md) and antialias them by coverage, with or without multisampling
// (docs/strokes.md).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "core/line_kind.h"

namespace lodline {

/// How a stroke ends: cut square at its end, a half disc, or a half square of its width.
enum class StrokeCap : uint8_t { kButt = 0, kRound = 1, kSquare = 2 };

/// One vertex of stroke geometry. `local` is the pixel's offset from the stroke's centre
/// line: y across it (signed), x beyond the stroke's end in a cap (0 along its body), so
/// strokeCoverage() can tell how much of a pixel the stroke covers.
struct StrokeVertex {
  glm::vec2 px;          ///< pixels, origin top-left, y down (pixel centres at +0.5)
  glm::vec2 local;       ///< pixels: x beyond the end (caps and round joins), y across
  float half_width = 1;  ///< half the stroke's width here, pixels (≥ 0.5)
  float alpha = 1.0f;    ///< opacity multiplier (fading of weak lines), in [0, 1]
  float cap = 0.0f;      ///< the StrokeCap of the piece this vertex belongs to, as a float
  float u = 0.0f;        ///< arc length along the stroke, pixels (brush texture coordinate)
};

/// The fraction of a pixel centred at `local` that a stroke of half width `half_width`
/// covers: a 1-px box filter across the edge (|y| against half_width), and beyond the end
/// by the cap's shape. The one formula of the GL fragment shader (shaders/stroke.frag) and
/// the software renderer.
inline float strokeCoverage(glm::vec2 local, float half_width, float cap) {
  const float beyond = std::max(local.x, 0.0f);
  float d;
  if (cap < 0.5f) {  // butt: the ink stops within a pixel of the end
    return std::clamp(half_width + 0.5f - std::abs(local.y), 0.0f, 1.0f) *
           std::clamp(1.0f - local.x, 0.0f, 1.0f);
  } else if (cap < 1.5f) {
    d = std::sqrt(beyond * beyond + local.y * local.y);
  } else {
    d = std::max(beyond, std::abs(local.y));
  }
  return std::clamp(half_width + 0.5f - d, 0.0f, 1.0f);
}

/// Where a brush of `period_px` is sampled for a pixel at arc length `u` and offset `local`
/// from a stroke of half width `half_width`: (u / period, across in [0, 1], 0 on the left
/// edge), the texture coordinates of shaders/stroke.frag (repeat along, clamp across).
inline glm::vec2 brushCoordinates(float u, glm::vec2 local, float half_width, float period_px) {
  return {u / period_px, std::clamp(0.5f - 0.5f * local.y / half_width, 0.0f, 1.0f)};
}

/// Triangles (3 vertices each) in ranges: the visible strokes of each kind, drawn in that
/// kind's colour, and the hidden strokes of every kind (dashes already cut), drawn in the
/// hidden style's colour. Widths are already in the geometry.
struct ScreenLines {
  std::vector<StrokeVertex> vertices;
  std::array<uint32_t, kLineKindCount> first{};     ///< first vertex of each kind's visible strokes
  std::array<uint32_t, kLineKindCount> count{};     ///< their vertex count (3 × triangles)
  std::array<uint32_t, kLineKindCount> segments{};  ///< polyline segments they were made of
  uint32_t hidden_first = 0;
  uint32_t hidden_count = 0;
  uint32_t hidden_segments = 0;

  size_t segmentCount(LineKind k) const { return segments[static_cast<int>(k)]; }
  void clear() {
    vertices.clear();
    first.fill(0);
    count.fill(0);
    segments.fill(0);
    hidden_first = hidden_count = hidden_segments = 0;
  }
};

}  // namespace lodline
