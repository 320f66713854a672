// Text on 8-bit RGBA images, for labels on contact sheets: TrueType glyphs rasterised by
// stb_truetype (Debian's libstb-dev) from a font file, alpha-blended onto the image.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string_view>

#include "core/result.h"
#include "io/image.h"

namespace lodline {

/// DejaVu Sans from Debian's fonts-dejavu-core (installed by scripts/setup.sh).
inline constexpr const char* kDefaultFontPath = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

/// 8-bit sRGB colour with alpha.
using Rgba8 = std::array<uint8_t, 4>;

/// A TrueType font loaded from a file. Sizes are pixel heights: `px` is the distance from
/// the highest ascender to the lowest descender. Move-only; the file's bytes are owned.
class Font {
 public:
  /// Reads and parses `path` (a .ttf, or the first face of a .ttc). Errors name the file.
  static Result<Font> load(const std::filesystem::path& path);

  Font(Font&&) noexcept;
  Font& operator=(Font&&) noexcept;
  ~Font();

  /// Advance width in pixels of the UTF-8 `text` at size `px`, kerning included.
  float measure(std::string_view text, float px) const;
  /// Distance from the baseline up to the ascender / down to the descender (positive), px.
  float ascent(float px) const;
  float descent(float px) const;

  /// Draws the UTF-8 `text` at size `px` with its baseline at `baseline_y` and its pen
  /// starting at `x` (pixels, y down), blended over `image` with `colour` (its alpha scales
  /// the glyph coverage). Glyphs are clipped to the image. Unknown code points draw the
  /// font's missing-glyph box; invalid UTF-8 bytes are skipped.
  void draw(Image& image, float x, float baseline_y, std::string_view text, float px, Rgba8 colour) const;

 private:
  struct Impl;
  explicit Font(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

/// Decodes the next code point of UTF-8 `text` starting at `pos` and advances `pos`;
/// returns -1 (and skips one byte) for an invalid sequence.
int32_t nextCodepoint(std::string_view text, size_t& pos);

}  // namespace lodline
