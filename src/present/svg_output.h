// The visible strokes of a presented frame as an SVG drawing: one layer per object, each in
// its own line styles, on the frame's page (export/svg.h writes the file).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/result.h"
#include "export/svg.h"
#include "frame/scene_drawing.h"
#include "present/presenter.h"

namespace lodline {

/// The SVG style of one object's line styles (colours as #rrggbb, opacity from alpha).
SvgStyle svgStyleOf(const ObjectStyle& style, const FrameParams& frame);

/// Writes the visible strokes of `presenter`'s last present() of `scene` to `path`; with
/// `ids` (ids[object][visible run], e.g. StrokeIdTracker::ids()), each stroke carries its id.
Status writeFrameSvg(const std::filesystem::path& path, const SceneDrawing& scene, ScenePresenter& presenter,
                     const std::vector<std::vector<uint64_t>>* ids = nullptr);

/// The SVG writeFrameSvg() writes (without ids), as text.
Result<std::string> frameSvgText(const SceneDrawing& scene, ScenePresenter& presenter);

}  // namespace lodline
