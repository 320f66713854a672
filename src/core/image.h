// The images a frame produces, row 0 at the top: colour (RGBA8), window depth, and the
// surface buffer (each pixel's nearest world position and object). Every backend (gl/,
// raster/) writes them and every consumer (export/, present/) reads them; PNG input and
// output live in io/image.h.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

namespace lodline {

/// 8-bit RGBA, straight alpha.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgba;  ///< width·height·4 bytes, row 0 = top

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgba(static_cast<size_t>(w) * h * 4, 0) {}
  uint8_t* pixel(int x, int y) { return &rgba[(static_cast<size_t>(y) * width + x) * 4]; }
  const uint8_t* pixel(int x, int y) const { return &rgba[(static_cast<size_t>(y) * width + x) * 4]; }
};

/// Window-space depths in [0, 1] (1 = far plane / background), row 0 = top of the image.
struct DepthImage {
  int width = 0;
  int height = 0;
  std::vector<float> depth;  ///< width·height values
  float at(int x, int y) const { return depth[static_cast<size_t>(y) * width + x]; }
};

/// The visible surface of a frame, one texel per pixel, row 0 = top: xyz the world position
/// of the nearest surface, w the object id + 1 (0: background).
struct SurfaceImage {
  int width = 0;
  int height = 0;
  std::vector<glm::vec4> texels;
  const glm::vec4& at(int x, int y) const { return texels[static_cast<size_t>(y) * width + x]; }
};

}  // namespace lodline
