// Screen-space stroke curves: a stroke's polyline (pixels) made a smooth curve with its
// corners kept, and that curve as a chain of cubic Bézier segments within a pixel tolerance,
// for vector output worth editing (SVG paths with a few points per stroke instead of one
// per mesh face crossed).
//
// Smoothing: the polyline is resampled at a fixed arc-length spacing and convolved with a
// Gaussian along its arc length; ends and corners stay fixed (beyond them the section is
// continued by its point reflection), so the curve keeps its ends and its sharp turns while
// the zig-zag of mesh-space zero crossings (segments from face to face) is removed.
// Fitting: Schneider, "An algorithm for automatically fitting digitized curves" (Graphics
// Gems, 1990), after a test for a straight piece (every sample within the tolerance of the
// chord: a segment with its controls on the chord, at 1/3 and 2/3): chord-length parameters, least-squares control points with the end tangents
// fixed, Newton–Raphson reparameterisation, and a split at the point of largest error
// (with a shared tangent there, so the chain is G1) until every sample is within the
// tolerance.
#pragma once

#include <span>
#include <vector>

#include <glm/vec2.hpp>

namespace lodline {

struct StrokeCurveParams {
  /// Largest distance, px, from a smoothed sample to the fitted curve. Default 0.25.
  float tolerance_px = 0.25f;
  /// Standard deviation, px of arc length, of the Gaussian smoothing; 0 keeps the polyline
  /// as it is (fitted only). Default 3: removes the face-to-face zig-zag of a contour (a
  /// pixel or so over faces of 4–8 px, T = 16 px²) and moves a curve of radius r by about
  /// 4.5/r px (0.45 px at r = 10 px).
  float smoothing_px = 3.0f;
  /// A polyline point where the direction turns by more than this (degrees, measured
  /// between the directions to points `corner_reach_px` away on each side) is a corner: the
  /// curve is split there and not smoothed across it. Default 50.
  float corner_deg = 50.0f;
  /// Default 3 px: turns sharper than this over a few pixels are corners, not zig-zag.
  float corner_reach_px = 3.0f;
  /// Arc-length spacing of the resampled curve, px. Default 1.
  float spacing_px = 1.0f;
  /// smoothPolyline() only: no point moves farther than this, px (0: no limit). The
  /// zig-zag is about a pixel; a larger move reshapes a small, tight line, and more so as a
  /// model shrinks in the image: unlimited, the T = 16 zoom-outs churned 1.5–2.1× as much
  /// (docs/strokes.md, "Smoothing"). Default 0.5.
  float max_shift_px = 0.5f;
};

/// Scratch of fitStrokeCurve(); reuse between calls.
struct StrokeCurveScratch {
  std::vector<glm::vec2> clean, samples, smooth;
  std::vector<float> arc, params;
  std::vector<float> weights;  ///< the smoothing Gaussian's weights, by offset
  std::vector<size_t> corners;
};

/// The smooth curve of `polyline` (pixels, ≥ 2 points) as cubic Bézier segments, appended
/// to `out`: its start point, then three points per segment (two controls and the end).
/// A polyline of one point or of zero length appends nothing. Returns the segment count.
size_t fitStrokeCurve(std::span<const glm::vec2> polyline, const StrokeCurveParams& params,
                      std::vector<glm::vec2>& out, StrokeCurveScratch& scratch);

/// Moves each point of `polyline` (pixels) towards fitStrokeCurve()'s smoothed curve at the
/// point's own arc length, by at most params.max_shift_px: the same Gaussian, corners and
/// ends, without the fitting, so a polyline drawn point to point loses the zig-zag of its
/// face crossings. The ends and the corners stay where they are; a polyline with a
/// non-finite point is left as it is.
void smoothPolyline(std::span<glm::vec2> polyline, const StrokeCurveParams& params, StrokeCurveScratch& scratch);

/// True when the cubic p[0..3] is a straight piece as fitStrokeCurve() writes one (controls
/// at 1/3 and 2/3 of the chord, within 1e-3 px): vector output may write it as a line.
bool isStraightSegment(const glm::vec2* p);

/// Point of the cubic Bézier with control points p[0..3] at parameter t in [0, 1].
glm::vec2 bezierPoint(const glm::vec2* p, float t);

}  // namespace lodline
