// The line geometry handed from the lines stage to the renderers (GL and SVG): segment
// endpoints grouped by line kind in one flat array.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "core/render_params.h"

namespace lodline {

/// One line endpoint.
struct LineVertex {
  glm::vec3 position;  ///< model space
  float alpha = 1.0f;  ///< opacity multiplier (fading of weak lines), in [0, 1]
};

/// Segments of each kind occupy a contiguous range of `vertices` (2 per segment).
struct LineBuffer {
  std::vector<LineVertex> vertices;
  std::array<uint32_t, kLineKindCount> first{};  ///< first vertex of each kind
  std::array<uint32_t, kLineKindCount> count{};  ///< vertex count (2 × segments) per kind

  size_t segmentCount(LineKind k) const { return count[static_cast<int>(k)] / 2; }
  void clear() {
    vertices.clear();
    first.fill(0);
    count.fill(0);
  }
};

}  // namespace lodline
