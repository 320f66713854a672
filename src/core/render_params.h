// Parameters of the final image, shared by the CLI, scene files and the viewer so that a
// headless render reproduces what the viewer shows (docs/design.md §4, "Parameters"): the
// frame's (FrameParams: size, background, multisampling, the light) and each object's
// (ObjectStyle: style, toon ramp, chamfer highlights, line styles). Every default is
// documented next to its field.
#pragma once

#include <array>
#include <string>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core/line_kind.h"
#include "core/result.h"
#include "core/stroke_style.h"

namespace lodline {

enum class Style {
  kLines,  ///< lines only, on the background (faces only hide hidden lines)
  kToon,   ///< toon-shaded faces + lines (default)
  kShaded, ///< Blinn–Phong faces + chamfer edge highlights + lines
};

struct LineStyle {
  bool enabled = true;
  glm::vec4 color{0.0f, 0.0f, 0.0f, 1.0f};  ///< RGBA in [0,1]
  float width_px = 2.0f;                    ///< line width in pixels
  StrokeStyle stroke;                       ///< caps, profile, dashes, brush (default: plain)
};

/// Per-kind styles. Defaults: black contours 2.5 px, dark-grey suggestive contours 1.5 px,
/// creases 1.5 px dark blue-grey, boundaries 2 px black, intersections 1.5 px near-black;
/// off unless asked for (`--lines`): isophotes 1 px slate blue, topographic lines 1 px
/// sepia, parabolic lines 1.25 px dark green, ridges 1.5 px dark red, valleys 1.5 px dark
/// blue, suggestive highlights 2 px white (drawn over toon or shaded fills, as DeCarlo &
/// Rusinkiewicz 2007 draw them; give them a colour for `--style lines` on white), apparent
/// ridges 1.5 px near-black, principal highlights 2 px white (like suggestive highlights),
/// material boundaries 1.5 px dark grey.
struct LineStyles {
  std::array<LineStyle, kLineKindCount> kinds{{
      {true, {0.0f, 0.0f, 0.0f, 1.0f}, 2.5f},
      {true, {0.12f, 0.12f, 0.12f, 1.0f}, 1.5f},
      {true, {0.15f, 0.18f, 0.25f, 1.0f}, 1.5f},
      {true, {0.0f, 0.0f, 0.0f, 1.0f}, 2.0f},
      {true, {0.06f, 0.06f, 0.06f, 1.0f}, 1.5f},
      {false, {0.25f, 0.32f, 0.50f, 1.0f}, 1.0f},
      {false, {0.45f, 0.30f, 0.15f, 1.0f}, 1.0f},
      {false, {0.10f, 0.38f, 0.20f, 1.0f}, 1.25f},
      {false, {0.55f, 0.12f, 0.08f, 1.0f}, 1.5f},
      {false, {0.08f, 0.18f, 0.55f, 1.0f}, 1.5f},
      {false, {1.0f, 1.0f, 1.0f, 1.0f}, 2.0f},
      {false, {0.10f, 0.08f, 0.08f, 1.0f}, 1.5f},
      {false, {1.0f, 1.0f, 1.0f, 1.0f}, 2.0f},
      {false, {0.20f, 0.20f, 0.22f, 1.0f}, 1.5f},
  }};
  LineStyle& operator[](LineKind k) { return kinds[static_cast<int>(k)]; }
  const LineStyle& operator[](LineKind k) const { return kinds[static_cast<int>(k)]; }
  /// Scales every width by `s` (`--line-width` sets the contour width; others follow).
  void scaleWidths(float s);
};

/// Toon shading (Lake et al. 2000): max(n·l, 0) indexes a ramp of flat tones; l is the
/// frame's light (FrameParams::light_dir_eye).
struct ToonParams {
  glm::vec3 base_color{0.93f, 0.87f, 0.76f};  ///< warm paper-like tone
  /// Ramp tones (multipliers of base_color) and the n·l thresholds between them:
  /// n·l < thresholds[0] → tones[0], < thresholds[1] → tones[1], else tones[2].
  std::array<float, 3> tones{0.62f, 0.84f, 1.0f};
  std::array<float, 2> thresholds{0.18f, 0.55f};
};

/// Chamfer edge highlights (Wei, Shi, Yong, "Rendering chamfering structures of sharp edges",
/// Visual Computer 2014; docs/design.md §2.2): sharp edges drawn as rounded strips of radius
/// r_e, blended with W = K·r_e/(d·r_max). Also holds the Blinn–Phong material of the shaded
/// style, since a highlight integrates that same model over its strip (under the frame's
/// light, FrameParams::light_dir_eye).
/// How the chamfer layer is composed with the faces (docs/chamfer.md compares both with the
/// rounded-geometry ground truth).
enum class ChamferCompose {
  /// The paper's: the strip's mean colour I blended over the 1-px edge line with alpha W.
  kAlpha,
  /// The strip replaces the bands the two faces lose to the rounding: each pixel near the
  /// edge gets the strip's colour integrated over the part of the strip inside it (same
  /// closed form on a sub-arc) minus the faces' colours over the area they no longer cover.
  /// Needs the faces' own colours: shaded style only (over toon the alpha blend is used).
  kReplace,
};

struct ChamferParams {
  /// Draw the highlights with the shaded style. Default on (`--chamfer off` clears it).
  bool enabled = true;
  /// Also draw them over toon faces. Default off (`--chamfer on` sets it).
  bool over_toon = false;
  /// An edge is sharp when the angle between its two face normals is at least this, degrees.
  /// Default 30. Edges in TriMesh::marked_edges always are.
  float threshold_deg = 30.0f;
  /// Constant edge radius r_e in model units; 0 = auto, 0.004 × the model's bounding radius
  /// (default). A per-vertex radius given to ChamferLayer::setMesh overrides it.
  float radius = 0.0f;
  /// K of the blend weight, pixels; 0 = auto, the focal length in pixels
  /// (0.5·height/tan(fov/2)), which makes W the fraction of the 1-px edge line the strip
  /// covers (default). Orthographic: K·r_e is taken as pixels per model unit·r_e, d = 1.
  float k = 0.0f;
  /// Blinn–Phong exponent n (faces and highlights), 1..127 (the table covers n + 1 ≤ 128).
  float shininess = 32.0f;
  glm::vec3 ambient{0.20f, 0.19f, 0.17f};    ///< ambient colour
  glm::vec3 diffuse{0.70f, 0.65f, 0.57f};    ///< diffuse colour (warm paper-like tone)
  glm::vec3 specular{0.55f, 0.55f, 0.55f};   ///< specular colour
  /// Crease lines mark the same edges the highlights render: skip them while highlights are
  /// drawn. Default on.
  bool replace_creases = true;
  /// Composition with the faces. Default kReplace (2–10× closer to the rounded ground truth
  /// than the unhighlighted model; kAlpha, the paper's, is not always closer).
  ChamferCompose compose = ChamferCompose::kReplace;
};

/// What the whole frame shares: the image and the light.
struct FrameParams {
  int width = 1280;   ///< image width, px
  int height = 720;   ///< image height, px
  glm::vec4 background{1.0f, 1.0f, 1.0f, 1.0f};  ///< RGBA; alpha 0 = transparent PNG
  int msaa = 4;  ///< multisample count (1 = off); Mesa's llvmpipe supports up to 4
  /// Towards the key light in eye space (normalised before use): upper left, in front. The
  /// one light of toon shading, the shaded style and chamfer highlights; a scene file's
  /// "light" sets it.
  glm::vec3 light_dir_eye{-0.45f, 0.6f, 0.65f};
  float aspect() const { return static_cast<float>(width) / static_cast<float>(height); }
};

/// How the hidden parts of lines are drawn (technical illustration: grey dashes), all kinds
/// alike. Off by default (`--hidden-lines off`).
struct HiddenLineStyle {
  bool enabled = false;
  glm::vec4 color{0.55f, 0.55f, 0.55f, 1.0f};  ///< RGBA in [0,1]. Default mid grey
  float width_px = 1.0f;                       ///< Default 1 px
  /// Dash pattern along the line, pixels: `dash_on` drawn, `dash_off` skipped; dash_off 0
  /// draws solid lines. Default 4 on, 3 off.
  float dash_on = 4.0f;
  float dash_off = 3.0f;
};

/// How one object is drawn. A single model is a scene of one object in the frame's style.
struct ObjectStyle {
  Style style = Style::kToon;
  ToonParams toon;
  ChamferParams chamfer;
  LineStyles lines;
  HiddenLineStyle hidden;
  /// The stroke style applied to `lines` (a preset's name or a style file's path; default
  /// "plain"), kept to write it back (saved views).
  std::string stroke_style = "plain";
  /// The line kinds to extract and draw (LineStyle::enabled), indexed by LineKind.
  std::array<bool, kLineKindCount> enabledKinds() const;
};

/// The toon ramp both renderers shade with: 256 tones over n·l ∈ [0, 1] (texel i covers
/// n·l ∈ [i/256, (i+1)/256)), each a multiplier of ToonParams::base_color.
std::array<float, 256> toonRamp(const ToonParams& toon);

/// Parses "lines", "toon" or "shaded".
Result<Style> parseStyle(const std::string& s);
const char* styleName(Style s);
/// Parses a colour: "#rgb", "#rrggbb", "#rrggbbaa", "transparent", or a name (white, black,
/// paper, grey/gray, red, green, blue).
Result<glm::vec4> parseColor(const std::string& s);
/// Parses the value of --hidden-lines: "off", or COLOUR[:WIDTH][:dash=ON,OFF] (width in
/// (0, 64] px; dash lengths ≥ 0 px, OFF = 0 for solid lines), e.g. "#888:1:dash=4,3".
Result<HiddenLineStyle> parseHiddenLines(const std::string& s);
/// The --hidden-lines value that parseHiddenLines() reads back as `h`.
std::string formatHiddenLines(const HiddenLineStyle& h);

/// Parses "WxH" (each 16..16384).
Result<std::array<int, 2>> parseSize(const std::string& s);

}  // namespace lodline
