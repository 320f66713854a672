#include "present/svg_output.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace lodline {
namespace {

std::string colourToHex(const glm::vec4& c) {
  char buf[8];
  auto byte = [](float v) { return static_cast<int>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
  std::snprintf(buf, sizeof(buf), "#%02x%02x%02x", byte(c.r), byte(c.g), byte(c.b));
  return buf;
}

}  // namespace

SvgStyle svgStyleOf(const ObjectStyle& style, const FrameParams& frame) {
  SvgStyle s;
  s.background = frame.background.a > 0.0f;
  s.background_colour = colourToHex(frame.background);
  for (int k = 0; k < kLineKindCount; ++k) {
    const LineStyle& ls = style.lines.kinds[k];
    s.lines[k] = {colourToHex(ls.color), ls.width_px, ls.color.a};
  }
  const HiddenLineStyle& h = style.hidden;
  s.hidden_enabled = h.enabled;
  s.hidden = {colourToHex(h.color), h.width_px, h.color.a};
  s.hidden_dash = {h.dash_on, h.dash_off};
  return s;
}

Status writeFrameSvg(const std::filesystem::path& path, const SceneDrawing& scene, ScenePresenter& presenter,
                     const std::vector<std::vector<uint64_t>>* ids) {
  const FrameParams& frame = presenter.frame();
  const std::vector<StrokeRuns>& visible = presenter.visible();
  const std::vector<StrokeRuns>& hidden = presenter.hidden();
  std::vector<SvgLayer> layers;
  for (size_t i = 0; i < scene.size(); ++i) {
    const StrokeRuns& v = visible[i];
    const StrokeRuns& h = hidden[i];
    SvgStrokes strokes{v.points, v.offsets, v.kinds, v.opacity};
    if (ids && i < ids->size() && (*ids)[i].size() == v.strokeCount()) strokes.ids = (*ids)[i];
    layers.push_back({scene[i].name, strokes,
                      svgStyleOf(scene[i].style, frame), SvgStrokes{h.points, h.offsets, h.kinds, h.opacity}});
  }
  ObjectStyle page_style;
  return writeSvgLayers(path, frame.width, frame.height, layers, svgStyleOf(page_style, frame));
}

}  // namespace lodline
