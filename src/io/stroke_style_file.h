// Stroke styles by name or from a file (docs/strokes.md, "Stroke styles"): the built-in
// presets `plain` (the default), `ink`, `pencil` and `marker`, or a JSON file of the same
// fields; and the brushes they use, generated here (`lodline generate brush-pencil` and
// `brush-marker` write them; models/brushes/ holds the committed copies).
#pragma once

#include <array>
#include <filesystem>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "core/image.h"
#include "core/render_params.h"
#include "core/result.h"

namespace lodline {

/// The built-in brushes: greyscale RGBA images, red = ink (255 full, 0 none), 256 × 32 px.
/// Deterministic: the same pixels on every machine.
enum class BrushKind { kPencil, kMarker };
Image makeBrush(BrushKind kind);
/// "pencil" or "marker" → the kind.
Result<BrushKind> parseBrushKind(const std::string& name);

/// `brush` box-filtered to `width` × `height` px (the size it is drawn at: one period of arc
/// length by the height across the stroke), so the renderers sample it without minifying.
Image resampleBrush(const Image& brush, int width, int height);

/// What a stroke style sets for each line kind: the stroke fields, and optionally the
/// colour and the width (a preset may change both; `--line-style` and `--line-width` apply
/// after it).
struct KindStrokeStyle {
  StrokeStyle stroke;
  bool set_color = false;
  glm::vec4 color{0.0f, 0.0f, 0.0f, 1.0f};
  float width_scale = 1.0f;  ///< the kind's width × this
};
struct NamedStrokeStyle {
  std::string name;  ///< the preset's name, or the file's path as given
  std::array<KindStrokeStyle, kLineKindCount> kinds;
};

/// The names of the presets, "plain, ink, pencil, marker".
std::string strokeStylePresetList();

/// A preset by name, or a JSON file (docs/strokes.md lists its keys: an object per line kind
/// and/or "all", applied first). Brush paths in a file are relative to it; "pencil" and
/// "marker" name the built-in brushes. Errors name the file and the key.
Result<NamedStrokeStyle> loadStrokeStyle(const std::string& name_or_path);

/// Applies `style` to `lines` (stroke fields, colours, width scales) and prepares its brushes
/// (resampled to their period).
void applyStrokeStyle(const NamedStrokeStyle& style, LineStyles& lines);

/// (Re)builds `s.brush` from `s.brush_path` ("pencil", "marker", a PNG path, or empty for
/// none) resampled to `s.brush_period_px`, as applyStrokeStyle leaves it: the viewer panel
/// calls it when the brush or its period is edited. Errors name the PNG.
Status prepareBrush(StrokeStyle& s);

/// Every stroke field of every kind of `lines` as a style file (an object per line kind; no
/// colours or widths, which the scene's `line-style` carries); brush paths relative to
/// `base_dir`. loadStrokeStyle() of the written file gives back the same fields.
nlohmann::json strokeStyleJson(const LineStyles& lines, const std::filesystem::path& base_dir);
/// Writes strokeStyleJson() to `path` (atomically); the viewer's "save view" writes an edited
/// style next to the view this way.
Status writeStrokeStyleFile(const std::filesystem::path& path, const LineStyles& lines);

}  // namespace lodline
