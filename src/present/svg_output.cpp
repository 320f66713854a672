#include "present/svg_output.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <glm/geometric.hpp>

#include "present/screen_lines.h"
#include "present/stroke_geometry.h"

namespace lodline {
namespace {

std::string colourToHex(const glm::vec4& c) {
  char buf[8];
  auto byte = [](float v) { return static_cast<int>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
  std::snprintf(buf, sizeof(buf), "#%02x%02x%02x", byte(c.r), byte(c.g), byte(c.b));
  return buf;
}

const char* capName(StrokeCap c) { return c == StrokeCap::kButt ? "butt" : c == StrokeCap::kSquare ? "square" : "round"; }

// A style whose width varies along a stroke: its strokes become filled outlines.
bool variableWidth(const StrokeStyle& s) {
  return s.taper_in_px > 0.0f || s.taper_out_px > 0.0f || s.depth_thickness != 0.0f || s.strength_thickness != 0.0f ||
         s.curvature_thickness != 0.0f || s.jitter_px > 0.0f;
}

// One layer's runs as the SVG writes them: constant-width runs kept as strokes (those the
// style's minimum length keeps), the others as closed outlines of their profile.
struct LayerStrokes {
  std::vector<glm::vec2> points, outline_points;
  std::vector<uint32_t> offsets{0}, outline_offsets{0};
  std::vector<LineKind> kinds, outline_kinds;
  std::vector<float> opacity, outline_opacity;
  std::vector<uint64_t> ids, outline_ids;
};

// The outline of the profile in sc (points, width; simplified): the left side forward, the
// end cap, the right side back, the start cap (round caps as 8-gons).
void appendOutline(const ScreenLinesScratch& sc, StrokeCap cap, std::vector<glm::vec2>& out) {
  const auto& P = sc.geometry.points;
  const auto& W = sc.geometry.width;
  const size_t n = P.size();
  auto normal = [&](size_t i) {
    const glm::vec2 d = P[std::min(i + 1, n - 1)] - P[i > 0 ? i - 1 : 0];
    const float len = glm::length(d);
    return len > 0.0f ? glm::vec2(-d.y, d.x) / len : glm::vec2(0.0f, 1.0f);
  };
  auto end_cap = [&](size_t i, glm::vec2 dir) {  // from the left side round to the right side
    const glm::vec2 nrm(-dir.y, dir.x);
    const float r = 0.5f * W[i];
    if (cap == StrokeCap::kRound) {
      for (int k = 1; k < 8; ++k) {
        const float a = static_cast<float>(k) * 3.14159265f / 8.0f;
        out.push_back(P[i] + r * (std::cos(a) * nrm + std::sin(a) * dir));
      }
    } else if (cap == StrokeCap::kSquare) {
      out.push_back(P[i] + r * (nrm + dir));
      out.push_back(P[i] + r * (dir - nrm));
    }
  };
  for (size_t i = 0; i < n; ++i) out.push_back(P[i] + 0.5f * W[i] * normal(i));
  end_cap(n - 1, glm::normalize(P[n - 1] - P[n - 2]));
  for (size_t i = n; i-- > 0;) out.push_back(P[i] - 0.5f * W[i] * normal(i));
  end_cap(0, glm::normalize(P[0] - P[1]));
}

void collect(const StrokeRuns& runs, const ObjectStyle& style, const StrokeView& view, std::span<const float> u,
             const std::vector<uint64_t>* ids, LayerStrokes& out, ScreenLinesScratch& sc) {
  // The runs joined where they meet, as the renderers draw them; runs lying along longer
  // ones of their kind are left out of both paths below, as the renderers leave them out.
  joinRuns(runs, u, joinParamsFor(style.lines), sc.joined);
  const std::vector<uint8_t>& covered = sc.joined.covered;
  // Constant-width strokes: each run a path of its own (appendRunAlone: less the points a
  // side-by-side join leaves out, reaching over the gaps the renderers bridge).
  for (size_t r = 0; r < runs.strokeCount(); ++r) {
    const LineStyle& ls = style.lines[runs.kinds[r]];
    if (variableWidth(ls.stroke) || (r < covered.size() && covered[r])) continue;
    if (ls.stroke.min_length_px > 0.0f && runs.length_px[r] < ls.stroke.min_length_px) continue;
    appendRunAlone(runs, sc.joined, r, out.points);
    out.offsets.push_back(static_cast<uint32_t>(out.points.size()));
    out.kinds.push_back(runs.kinds[r]);
    out.opacity.push_back(runs.opacity[r]);
    if (ids) out.ids.push_back((*ids)[r]);
  }
  // Varying width: the joined runs, each the outline of its profile (the id of its first run).
  const StrokeRuns& joined = sc.joined.runs;
  const std::vector<float>& joined_u = sc.joined.u;
  const std::vector<uint32_t>& first = sc.joined.first_run;
  for (size_t r = 0; r < joined.strokeCount(); ++r) {
    const LineStyle& ls = style.lines[joined.kinds[r]];
    const StrokeStyle& st = ls.stroke;
    if (!variableWidth(st)) continue;
    if (!strokeProfile(joined, r, ls.width_px, st, view, joined_u, sc) || sc.points.size() < 2) continue;
    StrokeGeometryScratch& g = sc.geometry;
    g.points = sc.points;
    g.width = sc.width;
    g.alpha = sc.alpha;
    g.u = sc.arc;
    simplifyStroke(0.25f, false, g);
    if (g.points.size() < 2) continue;
    float mean_alpha = 0.0f;
    for (float a : sc.alpha) mean_alpha += a;
    appendOutline(sc, st.cap, out.outline_points);
    out.outline_offsets.push_back(static_cast<uint32_t>(out.outline_points.size()));
    out.outline_kinds.push_back(joined.kinds[r]);
    out.outline_opacity.push_back(mean_alpha / static_cast<float>(sc.alpha.size()));
    if (ids) out.outline_ids.push_back((*ids)[first[r]]);
  }
}

}  // namespace

SvgStyle svgStyleOf(const ObjectStyle& style, const FrameParams& frame) {
  SvgStyle s;
  s.background = frame.background.a > 0.0f;
  s.background_colour = colourToHex(frame.background);
  for (int k = 0; k < kLineKindCount; ++k) {
    const LineStyle& ls = style.lines.kinds[k];
    const StrokeStyle& st = ls.stroke;
    s.lines[k] = {colourToHex(ls.color), ls.width_px, ls.color.a, capName(st.cap), {0.0f, 0.0f}};
    if (st.dash_on > 0.0f && st.dash_off > 0.0f) s.lines[k].dash = {st.dash_on, st.dash_off};
  }
  const HiddenLineStyle& h = style.hidden;
  s.hidden_enabled = h.enabled;
  s.hidden = {colourToHex(h.color), h.width_px, h.color.a, "butt", {h.dash_on, h.dash_off}};
  s.hidden_dash = {h.dash_on, h.dash_off};
  return s;
}

namespace {

// Builds the layers of the last present() and hands them to `write`.
template <typename Write>
auto withFrameLayers(const SceneDrawing& scene, ScenePresenter& presenter, const std::vector<std::vector<uint64_t>>* ids,
                     Write&& write) {
  const FrameParams& frame = presenter.frame();
  const Camera& camera = presenter.camera();
  const std::vector<StrokeRuns>& visible = presenter.visible();
  const std::vector<StrokeRuns>& hidden = presenter.hidden();
  std::vector<LayerStrokes> kept(scene.size());
  ScreenLinesScratch scratch;
  std::vector<SvgLayer> layers;
  for (size_t i = 0; i < scene.size(); ++i) {
    const StrokeRuns& v = visible[i];
    const StrokeRuns& h = hidden[i];
    const Bounds& b = scene[i].drawing->bounds();
    const StrokeView view{camera.eye, camera.forward(), b.center, b.radius};
    const std::vector<uint64_t>* object_ids =
        ids && i < ids->size() && (*ids)[i].size() == v.strokeCount() ? &(*ids)[i] : nullptr;
    LayerStrokes& k = kept[i];
    collect(v, scene[i].style, view, presenter.strokeParameters(i), object_ids, k, scratch);
    SvgStrokes strokes{k.points, k.offsets, k.kinds, k.opacity};
    if (object_ids) strokes.ids = k.ids;
    SvgStrokes outlines{k.outline_points, k.outline_offsets, k.outline_kinds, k.outline_opacity};
    if (object_ids) outlines.ids = k.outline_ids;
    layers.push_back({scene[i].name, strokes, svgStyleOf(scene[i].style, frame),
                      SvgStrokes{h.points, h.offsets, h.kinds, h.opacity}, outlines});
  }
  ObjectStyle page_style;
  return write(frame.width, frame.height, std::span<const SvgLayer>(layers), svgStyleOf(page_style, frame));
}

}  // namespace

Status writeFrameSvg(const std::filesystem::path& path, const SceneDrawing& scene, ScenePresenter& presenter,
                     const std::vector<std::vector<uint64_t>>* ids) {
  return withFrameLayers(scene, presenter, ids,
                         [&](int w, int h, std::span<const SvgLayer> layers, const SvgStyle& page) {
                           return writeSvgLayers(path, w, h, layers, page);
                         });
}

Result<std::string> frameSvgText(const SceneDrawing& scene, ScenePresenter& presenter) {
  return withFrameLayers(scene, presenter, nullptr,
                         [&](int w, int h, std::span<const SvgLayer> layers, const SvgStyle& page) {
                           return svgLayersText(w, h, layers, page);
                         });
}

}  // namespace lodline
