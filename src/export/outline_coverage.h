// Outline coverage: how much of the drawn objects' exterior outline has a line on it. The
// outline is the boundary of the coverage mask (the pixels the faces as drawn cover: depth
// below 1): covered pixels with a 4-neighbour the faces do not cover, the image border
// aside. An outline pixel is covered when a line pixel (the centre lines of the visible
// strokes) lies within `radius_px` (Euclidean). The uncovered outline pixels form gaps:
// 8-connected groups; a gap of `min_gap_px` pixels or more is counted (docs/visibility.md).
#pragma once

#include <cstdint>

#include "core/image.h"
#include "export/coherence.h"

namespace lodline {

struct OutlineCoverage {
  uint64_t outline_px = 0;     ///< outline pixels
  uint64_t covered_px = 0;     ///< of those, with a line pixel within the radius
  uint32_t gaps = 0;           ///< groups of uncovered outline pixels of min_gap_px or more
  uint32_t largest_gap_px = 0; ///< pixels of the largest group
  /// covered / outline; 1 when there is no outline.
  double coverage() const {
    return outline_px ? static_cast<double>(covered_px) / static_cast<double>(outline_px) : 1.0;
  }
};

/// Measures the coverage of the outline of `depth`'s covered pixels by `lines` (same size).
OutlineCoverage measureOutlineCoverage(const DepthImage& depth, const LineMask& lines, float radius_px = 2.0f,
                                       uint32_t min_gap_px = 5);

}  // namespace lodline
