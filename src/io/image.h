// 8-bit RGBA images and PNG input/output (libpng's simplified API). Rows are stored top
// to bottom.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "core/result.h"

namespace lodline {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgba;  ///< width·height·4 bytes, row 0 = top

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgba(static_cast<size_t>(w) * h * 4, 0) {}
  uint8_t* pixel(int x, int y) { return &rgba[(static_cast<size_t>(y) * width + x) * 4]; }
  const uint8_t* pixel(int x, int y) const { return &rgba[(static_cast<size_t>(y) * width + x) * 4]; }
};

/// Writes `image` as an RGBA PNG atomically (temporary file, then rename).
Status writePng(const std::filesystem::path& path, const Image& image);

/// Reads any PNG into RGBA.
Result<Image> readPng(const std::filesystem::path& path);

}  // namespace lodline
