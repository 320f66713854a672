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
  /// the silhouette is not hidden by its own faces. Default r = 1.
  int neighbourhood = 1;
  /// Samples per stroke segment are spaced at most this many pixels apart. Default 1.
  float sample_spacing_px = 1.0f;
};

/// Visible parts of strokes as 2D pixel polylines (origin top-left, y down).
struct VisibleStrokes {
  std::vector<glm::vec2> points;
  std::vector<uint32_t> offsets;  ///< stroke s is points[offsets[s], offsets[s+1]); count+1 entries
  std::vector<LineKind> kinds;    ///< 1 per stroke
  std::vector<float> opacity;     ///< 1 per stroke: mean alpha of its points
  std::vector<float> length_px;   ///< 1 per stroke

  size_t strokeCount() const { return kinds.size(); }
  void clear();
};

/// Appends the strokes of `from` to `to` (scenes: every object's visible strokes as one set).
void appendStrokes(const VisibleStrokes& from, VisibleStrokes& to);

/// True when the model-space point `p` is not hidden by the surface in `depth`, as seen by
/// `camera` (the camera `depth` was drawn with); points outside the image are not visible.
bool isPointVisible(const Camera& camera, const DepthImage& depth, glm::vec3 p,
                    const VisibilityParams& params = {});

/// Splits every stroke of `strokes` into its visible runs, sampled along the stroke.
void visibleStrokes(const StrokeSet& strokes, const Camera& camera, const DepthImage& depth,
                    const VisibilityParams& params, VisibleStrokes& out);

/// Segments of `lines` whose midpoint is visible, per LineKind.
std::array<uint32_t, kLineKindCount> countVisibleSegments(const LineSet& lines,
                                                          const Camera& camera,
                                                          const DepthImage& depth,
                                                          const VisibilityParams& params = {});

}  // namespace lodline
