// The lines of one object as the renderers draw them (GL and software alike): segments in
// pixels, already split into visible and hidden parts by the presenter (present/), so the
// renderers draw them over the faces with no depth test (docs/visibility.md).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "core/line_kind.h"

namespace lodline {

/// One end of a segment.
struct ScreenLineVertex {
  glm::vec2 px;        ///< pixels, origin top-left, y down (pixel centres at +0.5)
  float alpha = 1.0f;  ///< opacity multiplier (fading of weak lines), in [0, 1]
};

/// Segments (2 vertices each) in ranges: the visible lines of each kind, drawn in that kind's
/// style, and the hidden lines of every kind (dashes already cut), drawn in the hidden style.
struct ScreenLines {
  std::vector<ScreenLineVertex> vertices;
  std::array<uint32_t, kLineKindCount> first{};  ///< first vertex of each kind's visible lines
  std::array<uint32_t, kLineKindCount> count{};  ///< their vertex count (2 × segments)
  uint32_t hidden_first = 0;
  uint32_t hidden_count = 0;

  size_t segmentCount(LineKind k) const { return count[static_cast<int>(k)] / 2; }
  void clear() {
    vertices.clear();
    first.fill(0);
    count.fill(0);
    hidden_first = hidden_count = 0;
  }
};

}  // namespace lodline
