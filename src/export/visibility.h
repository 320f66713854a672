// Hidden-line removal for vector output and for counting what is really visible: line
// samples are tested against a depth image of the shaded surface (docs/design.md §3.7). The
// depth image comes from whichever renderer drew the faces (OpenGL or the software one);
// this file needs no GL.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "core/camera.h"
#include "core/image.h"
#include "lines/lines.h"
#include "lines/strokes.h"

namespace lodline {

struct VisibilityParams {
  /// A sample is visible when its eye-space depth exceeds the surface's by at most this
  /// fraction of the surface depth. Default 0.002 (0.2%): well below any real occluder's
  /// distance, above the faces' polygon offset and depth quantisation.
  float relative_tolerance = 0.002f;
  /// The surface depth is the farthest over a (2r+1)² pixel neighbourhood, so a contour on
  /// the silhouette is not hidden by its own faces: the depth slope within r pixels is the
  /// tolerance (docs/visibility.md). Default r = 1.
  int neighbourhood = 1;
  /// Samples per stroke segment are spaced at most this many pixels apart. Default 1.
  float sample_spacing_px = 1.0f;
  /// A stroke segment crosses one face, so its model-space length is the mesh's size there.
  /// For contours, a surface nearer than a sample by less than this many segment lengths is
  /// the sample's own neighbourhood (on a coarse mesh the interpolated contour runs over
  /// faces that turn away, just behind the rim's front faces), not an occluder. Other kinds
  /// get none. Default 0.5: the cow's contour alone covers 0.84 of its outline close up
  /// (0.78 with 0, 0.85 with 1), and the held-out captures under detail control churn as
  /// with the depth-tested drawing (1 let hidden lines show through on small, coarse views).
  float segment_tolerance = 0.5f;
  /// Model units; 0: none. A contour segment's slack is at most segment_tolerance times this.
  /// The presenter sets it to the median edge length of the object's drawn mesh: on a mesh of
  /// uneven edges (a CAD part's long slivers) half a long edge's length let hidden contour
  /// show through (the turbine's notch in models/machine.json; docs/visibility.md).
  float segment_tolerance_cap = 0.0f;
  /// A visible stretch of a stroke shorter than this (px), with hidden samples of the same
  /// stroke on both sides, is hidden. A hidden line that passes within a pixel of the outline
  /// sees the background in its neighbourhood there, which counts as nothing in front: the
  /// far contour of the bunny's ear showed as dots of ink along the near one's outline
  /// (docs/visibility.md). Default 2.5 (under a speck, kSpeckLengthPx); 0: off.
  float min_visible_between_hidden_px = 2.5f;
};

/// Runs of strokes in pixels: the visible (or the hidden) parts of a StrokeSet. A run's
/// points are its first and last samples and the stroke's own points between them (the
/// samples in between lie on the straight pieces, so nothing is lost).
struct StrokeRuns {
  std::vector<glm::vec2> points;     ///< pixels (origin top-left, y down)
  std::vector<glm::vec3> positions;  ///< 1 per point: the same point in model space
  std::vector<float> alpha;          ///< 1 per point: the stroke's opacity there
  std::vector<uint32_t> offsets;     ///< run r is points[offsets[r], offsets[r+1]); count+1 entries
  std::vector<LineKind> kinds;       ///< 1 per run
  std::vector<uint32_t> strokes;     ///< 1 per run: the index of its stroke in the StrokeSet
  std::vector<float> opacity;        ///< 1 per run: mean alpha of its samples
  std::vector<float> length_px;      ///< 1 per run

  size_t strokeCount() const { return kinds.size(); }
  /// Total length of the runs, pixels.
  double totalLength() const;
  void clear();
};

/// Appends the runs of `from` to `to` (scenes: every object's runs as one set).
void appendStrokes(const StrokeRuns& from, StrokeRuns& to);

/// True when the model-space point `p` is not hidden by the surface in `depth`, as seen by
/// `camera` (the camera `depth` was drawn with); points outside the image are not visible.
bool isPointVisible(const Camera& camera, const DepthImage& depth, glm::vec3 p,
                    const VisibilityParams& params = {});

/// Splits every stroke of `strokes` into its visible and its hidden runs, sampled along the
/// stroke at most params.sample_spacing_px apart (samples outside the image or behind the
/// eye belong to neither). Either output may be null. Runs of one sample are dropped.
void splitStrokes(const StrokeSet& strokes, const Camera& camera, const DepthImage& depth,
                  const VisibilityParams& params, StrokeRuns* visible, StrokeRuns* hidden);

/// The visible runs only (splitStrokes with no hidden output).
inline void visibleStrokes(const StrokeSet& strokes, const Camera& camera, const DepthImage& depth,
                           const VisibilityParams& params, StrokeRuns& out) {
  splitStrokes(strokes, camera, depth, params, &out, nullptr);
}

/// Segments of `lines` whose midpoint is visible, per LineKind.
std::array<uint32_t, kLineKindCount> countVisibleSegments(const LineSet& lines,
                                                          const Camera& camera,
                                                          const DepthImage& depth,
                                                          const VisibilityParams& params = {});
/// The same for the segments between consecutive points of the strokes of `strokes`.
std::array<uint32_t, kLineKindCount> countVisibleSegments(const StrokeSet& strokes, const Camera& camera,
                                                          const DepthImage& depth,
                                                          const VisibilityParams& params = {});

}  // namespace lodline
