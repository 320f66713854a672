// PNG input and output of 8-bit RGBA images (core/image.h) (libpng's simplified API). Rows are stored top
// to bottom.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "core/image.h"
#include "core/result.h"

namespace lodline {

/// Writes `image` as an RGBA PNG atomically (temporary file, then rename).
Status writePng(const std::filesystem::path& path, const Image& image);

/// Largest PNG readPng() accepts by default, in pixels: the largest image lodline writes
/// (16384 x 16384, see parseSize), 1 GiB as RGBA.
inline constexpr uint64_t kMaxPngPixels = 16384ull * 16384ull;

/// Largest detail map (`--detail-map`), in pixels: 4096 x 4096 (64 MiB as RGBA plus 64 MiB
/// of factors). A detail map is stretched over the image, so more pixels add nothing.
inline constexpr uint64_t kMaxDetailMapPixels = 4096ull * 4096ull;

/// Reads any PNG (grey, palette, RGB, with or without alpha, 8 or 16 bits) into 8-bit RGBA.
/// Images of more than `max_pixels` pixels are refused from their header, before any pixel
/// memory is allocated. Errors name the path: not a regular file, not a PNG, too large,
/// truncated or corrupt data.
Result<Image> readPng(const std::filesystem::path& path, uint64_t max_pixels = kMaxPngPixels);

}  // namespace lodline
