// Strokes as geometry (docs/strokes.md): a run's polyline in pixels becomes a band of
// triangles of the stroke's width, with joins and caps, whose vertices carry each pixel's
// offset from the centre line so the renderers antialias it by coverage (strokeCoverage()
// in core/line_buffer.h) — the same picture with or without multisampling, in OpenGL and
// in the software renderer.
//
// The polyline is first simplified (Douglas–Peucker within `simplify_px`: a pixel-scale
// chord test that keeps corners, drops the near-collinear samples of the visibility test
// and so the short segments whose joins would fold). A join whose miter stays within
// `miter_limit` half widths is mitred (one shared pair of vertices); a sharper turn ends the
// band on both sides and a disc fills the outer wedge (a round join). The band reaches one
// pixel past the stroke's edge, where the coverage falls to zero.
#pragma once

#include <span>
#include <vector>

#include <glm/vec2.hpp>

#include "core/line_buffer.h"

namespace lodline {

struct StrokeGeometryParams {
  /// How both ends of a stroke are drawn. Default round.
  StrokeCap cap = StrokeCap::kRound;
  /// Longest miter, in half widths, before a join is drawn round. Default 2: joins that
  /// turn by up to 120 degrees are mitred.
  float miter_limit = 2.0f;
  /// Douglas–Peucker tolerance, px, of the polyline before extrusion. Default 0.25.
  float simplify_px = 0.25f;
};

/// Scratch of appendStrokeGeometry(); reuse between calls.
struct StrokeGeometryScratch {
  std::vector<glm::vec2> points;
  std::vector<float> alpha, width, u;  ///< per point: opacity, width (px), parameter (px)
  std::vector<uint8_t> keep;
  std::vector<std::pair<uint32_t, uint32_t>> stack;
};

/// Douglas–Peucker on scratch.points (with .alpha, .width and .u alongside, all the same
/// size) in place: keeps the ends and every point farther than `tol` px from its section's
/// chord, or whose width (or parameter, `with_u`) differs by more than `tol`
/// px, or opacity by more than tol/5, from the chord's interpolation.
void simplifyStroke(float tol, bool with_u, StrokeGeometryScratch& scratch);

/// Appends the triangles of one stroke through `points` (pixels) with opacity `alpha` and
/// width `width` (pixels) per point; a width under 1 px is drawn 1 px wide with the width as
/// opacity. The simplification keeps the points where the width changes by more than
/// simplify_px or the opacity by more than 0.05 from the chord's, so profiles survive it.
/// Vertices get the parameter `u` of their point (px along the stroke: the brush's
/// coordinate), or the arc length from the stroke's start when `u` is empty. A stroke of one point (or of zero length) is a dot with round or square caps
/// and nothing with butt caps; non-finite points are dropped. Returns the number of
/// polyline segments drawn (after simplification).
size_t appendStrokeGeometry(std::span<const glm::vec2> points, std::span<const float> alpha,
                            std::span<const float> width, std::span<const float> u,
                            const StrokeGeometryParams& params,
                            std::vector<StrokeVertex>& out, StrokeGeometryScratch& scratch);

}  // namespace lodline
