// Measuring temporal coherence of line drawings (lodline's own measure; no published system
// reports one): per frame, the line pixels that appeared or vanished since the previous
// frame, with a small spatial tolerance so a line that slides by a pixel does not count.
#pragma once

#include <cstdint>
#include <vector>

#include "export/visibility.h"

namespace lodline {

/// One byte per pixel, 1 where a visible line passes; row 0 = top.
struct LineMask {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> on;
  bool at(int x, int y) const { return on[static_cast<size_t>(y) * width + x] != 0; }
};

/// Marks the pixels under the visible strokes' samples (≤ 1 px apart, so strokes are
/// continuous) and under the straight pieces between them. `out` is resized to w×h.
void rasterizeStrokes(const VisibleStrokes& strokes, int width, int height, LineMask& out);

struct MaskChange {
  uint64_t line_pixels = 0;  ///< pixels on in the current mask
  uint64_t appeared = 0;     ///< on now, with nothing on within `tolerance` px before
  uint64_t vanished = 0;     ///< on before, with nothing on within `tolerance` px now
  /// (appeared + vanished) / line_pixels; 0 when there are no line pixels.
  double churn() const {
    return line_pixels ? static_cast<double>(appeared + vanished) / static_cast<double>(line_pixels) : 0.0;
  }
};

/// Compares two masks of the same size with a Chebyshev tolerance of `tolerance` pixels.
MaskChange compareMasks(const LineMask& previous, const LineMask& current, int tolerance = 1);

}  // namespace lodline
