#include "export/coherence.h"

#include <algorithm>
#include <cmath>

namespace lodline {
namespace {

// Pixels of `a` with no pixel of `b` within `r` (Chebyshev distance).
uint64_t unmatched(const LineMask& a, const LineMask& b, int r) {
  uint64_t n = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      if (!a.at(x, y)) continue;
      bool found = false;
      for (int yy = std::max(0, y - r); yy <= std::min(b.height - 1, y + r) && !found; ++yy)
        for (int xx = std::max(0, x - r); xx <= std::min(b.width - 1, x + r) && !found; ++xx)
          found = b.at(xx, yy);
      n += !found;
    }
  return n;
}

}  // namespace

void rasterizeStrokes(const VisibleStrokes& strokes, int width, int height, LineMask& out) {
  out.width = width;
  out.height = height;
  out.on.assign(static_cast<size_t>(width) * height, 0);
  auto mark = [&](glm::vec2 p) {
    const int x = static_cast<int>(std::floor(p.x)), y = static_cast<int>(std::floor(p.y));
    if (x >= 0 && y >= 0 && x < width && y < height) out.on[static_cast<size_t>(y) * width + x] = 1;
  };
  for (size_t s = 0; s < strokes.strokeCount(); ++s)
    for (uint32_t i = strokes.offsets[s]; i < strokes.offsets[s + 1]; ++i) {
      const glm::vec2 p = strokes.points[i];
      mark(p);
      if (i + 1 < strokes.offsets[s + 1]) {
        const glm::vec2 q = strokes.points[i + 1];
        const int steps = std::min(4096, static_cast<int>(std::ceil(std::max(std::abs(q.x - p.x), std::abs(q.y - p.y)) * 2.0f)));
        for (int k = 1; k < steps; ++k) mark(p + (q - p) * (static_cast<float>(k) / static_cast<float>(steps)));
      }
    }
}

MaskChange compareMasks(const LineMask& previous, const LineMask& current, int tolerance) {
  MaskChange c;
  for (uint8_t v : current.on) c.line_pixels += v;
  if (previous.width != current.width || previous.height != current.height) {
    c.appeared = c.line_pixels;  // no comparable previous frame: everything is new
    return c;
  }
  c.appeared = unmatched(current, previous, tolerance);
  c.vanished = unmatched(previous, current, tolerance);
  return c;
}

}  // namespace lodline
