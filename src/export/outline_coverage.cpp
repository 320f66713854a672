#include "export/outline_coverage.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace lodline {

OutlineCoverage measureOutlineCoverage(const DepthImage& depth, const LineMask& lines, float radius_px,
                                       uint32_t min_gap_px) {
  OutlineCoverage c;
  const int w = depth.width, h = depth.height;
  if (w <= 0 || h <= 0 || lines.width != w || lines.height != h) return c;
  auto covered = [&](int x, int y) { return depth.at(x, y) < 1.0f; };
  // 0: not outline, 1: covered outline pixel, 2: uncovered outline pixel.
  std::vector<uint8_t> state(static_cast<size_t>(w) * h, 0);
  const int r = static_cast<int>(std::ceil(radius_px));
  const float r2 = radius_px * radius_px;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!covered(x, y)) continue;
      const bool edge = (x > 0 && !covered(x - 1, y)) || (x + 1 < w && !covered(x + 1, y)) ||
                        (y > 0 && !covered(x, y - 1)) || (y + 1 < h && !covered(x, y + 1));
      if (!edge) continue;
      ++c.outline_px;
      bool found = false;
      for (int yy = std::max(0, y - r); yy <= std::min(h - 1, y + r) && !found; ++yy)
        for (int xx = std::max(0, x - r); xx <= std::min(w - 1, x + r) && !found; ++xx)
          found = lines.at(xx, yy) && static_cast<float>((xx - x) * (xx - x) + (yy - y) * (yy - y)) <= r2;
      c.covered_px += found;
      state[static_cast<size_t>(y) * w + x] = found ? 1 : 2;
    }
  // Gaps: 8-connected groups of uncovered outline pixels.
  std::vector<int> stack;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (state[static_cast<size_t>(y) * w + x] != 2) continue;
      uint32_t size = 0;
      stack.assign(1, y * w + x);
      state[static_cast<size_t>(y) * w + x] = 3;
      while (!stack.empty()) {
        const int i = stack.back();
        stack.pop_back();
        ++size;
        const int px = i % w, py = i / w;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = px + dx, ny = py + dy;
            if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
            uint8_t& s = state[static_cast<size_t>(ny) * w + nx];
            if (s != 2) continue;
            s = 3;
            stack.push_back(ny * w + nx);
          }
      }
      if (size >= min_gap_px) ++c.gaps;
      c.largest_gap_px = std::max(c.largest_gap_px, size);
    }
  return c;
}

}  // namespace lodline
