#include "export/text.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

// stb_truetype's implementation, private to this file (STBTT_STATIC), so it cannot clash with
// another copy (e.g. Debian's libstb). It trusts the font file: only fonts the user names.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#define STBTT_STATIC
#define STB_TRUETYPE_IMPLEMENTATION
#include <stb/stb_truetype.h>
#pragma GCC diagnostic pop

namespace lodline {

struct Font::Impl {
  std::vector<unsigned char> bytes;  // stbtt_fontinfo points into these
  stbtt_fontinfo info{};
  int ascent = 0, descent = 0;  // font units; descent < 0
};

Font::Font(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Font::Font(Font&&) noexcept = default;
Font& Font::operator=(Font&&) noexcept = default;
Font::~Font() = default;

Result<Font> Font::load(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error::runtime(path.string() + ": cannot read font: " + std::strerror(errno));
  auto impl = std::make_unique<Impl>();
  impl->bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  if (impl->bytes.size() < 12)
    return Error::runtime(path.string() + ": not a TrueType font (file too short)");
  const int offset = stbtt_GetFontOffsetForIndex(impl->bytes.data(), 0);
  if (offset < 0 || static_cast<size_t>(offset) >= impl->bytes.size() ||
      !stbtt_InitFont(&impl->info, impl->bytes.data(), offset))
    return Error::runtime(path.string() + ": not a TrueType font");
  int line_gap = 0;
  stbtt_GetFontVMetrics(&impl->info, &impl->ascent, &impl->descent, &line_gap);
  if (impl->ascent - impl->descent <= 0) return Error::runtime(path.string() + ": font has no vertical metrics");
  return Font(std::move(impl));
}

int32_t nextCodepoint(std::string_view text, size_t& pos) {
  const auto byte = [&](size_t i) { return static_cast<uint8_t>(text[i]); };
  const uint8_t b0 = byte(pos);
  int len = 0;
  int32_t cp = 0;
  if (b0 < 0x80) {
    ++pos;
    return b0;
  } else if ((b0 & 0xe0) == 0xc0) {
    len = 2;
    cp = b0 & 0x1f;
  } else if ((b0 & 0xf0) == 0xe0) {
    len = 3;
    cp = b0 & 0x0f;
  } else if ((b0 & 0xf8) == 0xf0) {
    len = 4;
    cp = b0 & 0x07;
  } else {
    ++pos;
    return -1;
  }
  if (pos + len > text.size()) {
    ++pos;
    return -1;
  }
  for (int i = 1; i < len; ++i) {
    const uint8_t b = byte(pos + i);
    if ((b & 0xc0) != 0x80) {
      ++pos;
      return -1;
    }
    cp = (cp << 6) | (b & 0x3f);
  }
  // Overlong forms, surrogates and values past U+10FFFF are invalid.
  static constexpr int32_t kMin[5] = {0, 0, 0x80, 0x800, 0x10000};
  if (cp < kMin[len] || (cp >= 0xd800 && cp <= 0xdfff) || cp > 0x10ffff) {
    ++pos;
    return -1;
  }
  pos += len;
  return cp;
}

float Font::measure(std::string_view text, float px) const {
  const float scale = stbtt_ScaleForPixelHeight(&impl_->info, px);
  float width = 0.0f;
  int32_t prev = -1;
  for (size_t pos = 0; pos < text.size();) {
    const int32_t cp = nextCodepoint(text, pos);
    if (cp < 0) continue;
    if (prev >= 0) width += scale * static_cast<float>(stbtt_GetCodepointKernAdvance(&impl_->info, prev, cp));
    int advance = 0, lsb = 0;
    stbtt_GetCodepointHMetrics(&impl_->info, cp, &advance, &lsb);
    width += scale * static_cast<float>(advance);
    prev = cp;
  }
  return width;
}

float Font::ascent(float px) const {
  return stbtt_ScaleForPixelHeight(&impl_->info, px) * static_cast<float>(impl_->ascent);
}

float Font::descent(float px) const {
  return -stbtt_ScaleForPixelHeight(&impl_->info, px) * static_cast<float>(impl_->descent);
}

void Font::draw(Image& image, float x, float baseline_y, std::string_view text, float px, Rgba8 colour) const {
  const float scale = stbtt_ScaleForPixelHeight(&impl_->info, px);
  const float base = std::floor(baseline_y);
  const float shift_y = baseline_y - base;
  std::vector<unsigned char> glyph;
  float pen = x;
  int32_t prev = -1;
  for (size_t pos = 0; pos < text.size();) {
    const int32_t cp = nextCodepoint(text, pos);
    if (cp < 0) continue;
    if (prev >= 0) pen += scale * static_cast<float>(stbtt_GetCodepointKernAdvance(&impl_->info, prev, cp));
    prev = cp;
    const float origin = std::floor(pen), shift_x = pen - origin;
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    stbtt_GetCodepointBitmapBoxSubpixel(&impl_->info, cp, scale, scale, shift_x, shift_y, &x0, &y0, &x1, &y1);
    const int w = x1 - x0, h = y1 - y0;
    if (w > 0 && h > 0) {
      glyph.assign(static_cast<size_t>(w) * h, 0);
      stbtt_MakeCodepointBitmapSubpixel(&impl_->info, glyph.data(), w, h, w, scale, scale, shift_x, shift_y, cp);
      const int left = static_cast<int>(origin) + x0, top = static_cast<int>(base) + y0;
      for (int gy = 0; gy < h; ++gy) {
        const int iy = top + gy;
        if (iy < 0 || iy >= image.height) continue;
        for (int gx = 0; gx < w; ++gx) {
          const int ix = left + gx;
          if (ix < 0 || ix >= image.width) continue;
          const float a = static_cast<float>(glyph[static_cast<size_t>(gy) * w + gx]) / 255.0f *
                          static_cast<float>(colour[3]) / 255.0f;
          if (a <= 0.0f) continue;
          uint8_t* p = image.pixel(ix, iy);
          for (int c = 0; c < 3; ++c)
            p[c] = static_cast<uint8_t>(std::lround(static_cast<float>(p[c]) * (1.0f - a) + static_cast<float>(colour[c]) * a));
          p[3] = static_cast<uint8_t>(std::lround(255.0f * a + static_cast<float>(p[3]) * (1.0f - a)));
        }
      }
    }
    int advance = 0, lsb = 0;
    stbtt_GetCodepointHMetrics(&impl_->info, cp, &advance, &lsb);
    pen += scale * static_cast<float>(advance);
  }
}

}  // namespace lodline
