// Parameters of the final image, shared by the CLI, scene files and the viewer so that a
// headless render reproduces what the viewer shows (STYLE.md §6). Every default is
// documented next to its field.
#pragma once

#include <array>
#include <string>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core/result.h"

namespace lodline {

enum class Style {
  kLines,  ///< lines only, on the background (faces only hide hidden lines)
  kToon,   ///< toon-shaded faces + lines (default)
};

/// Line kinds, in drawing order; indexes LineStyles::kinds.
enum class LineKind : int { kContour = 0, kSuggestive = 1, kCrease = 2, kBoundary = 3 };
inline constexpr int kLineKindCount = 4;
const char* lineKindName(LineKind k);

struct LineStyle {
  bool enabled = true;
  glm::vec4 color{0.0f, 0.0f, 0.0f, 1.0f};  ///< RGBA in [0,1]
  float width_px = 2.0f;                    ///< line width in pixels
};

/// Per-kind styles. Defaults: black contours 2.5 px, dark-grey suggestive contours 1.5 px,
/// creases 1.5 px dark blue-grey, boundaries 2 px black.
struct LineStyles {
  std::array<LineStyle, kLineKindCount> kinds{{
      {true, {0.0f, 0.0f, 0.0f, 1.0f}, 2.5f},
      {true, {0.12f, 0.12f, 0.12f, 1.0f}, 1.5f},
      {true, {0.15f, 0.18f, 0.25f, 1.0f}, 1.5f},
      {true, {0.0f, 0.0f, 0.0f, 1.0f}, 2.0f},
  }};
  LineStyle& operator[](LineKind k) { return kinds[static_cast<int>(k)]; }
  const LineStyle& operator[](LineKind k) const { return kinds[static_cast<int>(k)]; }
  /// Scales every width by `s` (`--line-width` sets the contour width; others follow).
  void scaleWidths(float s);
};

/// Toon shading (Lake et al. 2000): max(n·l, 0) indexes a ramp of flat tones.
struct ToonParams {
  glm::vec3 base_color{0.93f, 0.87f, 0.76f};  ///< warm paper-like tone
  /// Towards the light in eye space (normalised before use): upper left, in front.
  glm::vec3 light_dir_eye{-0.45f, 0.6f, 0.65f};
  /// Ramp tones (multipliers of base_color) and the n·l thresholds between them:
  /// n·l < thresholds[0] → tones[0], < thresholds[1] → tones[1], else tones[2].
  std::array<float, 3> tones{0.62f, 0.84f, 1.0f};
  std::array<float, 2> thresholds{0.18f, 0.55f};
};

struct RenderParams {
  int width = 1280;   ///< image width, px
  int height = 720;   ///< image height, px
  Style style = Style::kToon;
  glm::vec4 background{1.0f, 1.0f, 1.0f, 1.0f};  ///< RGBA; alpha 0 = transparent PNG
  int msaa = 4;  ///< multisample count (1 = off); Mesa's llvmpipe supports up to 4
  ToonParams toon;
  LineStyles lines;
};

/// Parses "toon" or "lines".
Result<Style> parseStyle(const std::string& s);
const char* styleName(Style s);
/// Parses a colour: "#rgb", "#rrggbb", "#rrggbbaa", "transparent", or a name (white, black,
/// paper, grey/gray, red, green, blue).
Result<glm::vec4> parseColor(const std::string& s);
/// Parses "WxH" (each 16..16384).
Result<std::array<int, 2>> parseSize(const std::string& s);

}  // namespace lodline
