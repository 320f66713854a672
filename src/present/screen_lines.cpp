#include "present/screen_lines.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace lodline {
namespace {

// Run r of `runs` as one stroke.
size_t runStroke(const StrokeRuns& runs, size_t r, float width, const StrokeGeometryParams& params,
                 ScreenLines& out, StrokeGeometryScratch& scratch) {
  const uint32_t b = runs.offsets[r], e = runs.offsets[r + 1];
  return appendStrokeGeometry(std::span(runs.points).subspan(b, e - b), std::span(runs.alpha).subspan(b, e - b),
                              width, params, out.vertices, scratch);
}

// The parts of run r's polyline inside the dashes [k·period, k·period + on), arc length
// from the run's start, each as a stroke.
size_t runDashes(const StrokeRuns& runs, size_t r, float on, float period, float width,
                 const StrokeGeometryParams& params, ScreenLines& out, StrokeGeometryScratch& scratch) {
  std::vector<glm::vec2> dash;
  std::vector<float> dash_alpha;
  size_t segments = 0;
  auto flush = [&] {
    if (dash.size() >= 2) segments += appendStrokeGeometry(dash, dash_alpha, width, params, out.vertices, scratch);
    dash.clear();
    dash_alpha.clear();
  };
  float s0 = 0.0f;  // arc length at the start of the current segment
  for (uint32_t i = runs.offsets[r]; i + 1 < runs.offsets[r + 1]; ++i) {
    const glm::vec2 a = runs.points[i], b = runs.points[i + 1];
    const float len = glm::length(b - a);
    if (!(len > 0.0f)) continue;
    const float s1 = s0 + len;
    for (float d = std::floor(s0 / period) * period; d < s1; d += period) {
      const float lo = std::max(d, s0), hi = std::min(d + on, s1);
      if (hi <= lo) continue;
      const float t0 = (lo - s0) / len, t1 = (hi - s0) / len;
      const float a0 = runs.alpha[i] + t0 * (runs.alpha[i + 1] - runs.alpha[i]);
      const float a1 = runs.alpha[i] + t1 * (runs.alpha[i + 1] - runs.alpha[i]);
      // A dash that began on an earlier segment continues through this one's start.
      if (lo > s0 || dash.empty()) {
        flush();
        dash.push_back(a + t0 * (b - a));
        dash_alpha.push_back(a0);
      }
      dash.push_back(a + t1 * (b - a));
      dash_alpha.push_back(a1);
      if (hi < d + on) continue;  // the dash goes on past this segment's end
      flush();
    }
    s0 = s1;
  }
  flush();
  return segments;
}

}  // namespace

void buildScreenLines(const StrokeRuns& visible, const StrokeRuns& hidden, const ObjectStyle& style,
                      ScreenLines& out, StrokeGeometryScratch& scratch) {
  out.clear();
  const StrokeGeometryParams round;  // round caps and joins
  for (int k = 0; k < kLineKindCount; ++k) {
    out.first[k] = static_cast<uint32_t>(out.vertices.size());
    const LineStyle& ls = style.lines.kinds[k];
    if (ls.enabled)
      for (size_t r = 0; r < visible.strokeCount(); ++r)
        if (static_cast<int>(visible.kinds[r]) == k)
          out.segments[k] += static_cast<uint32_t>(runStroke(visible, r, ls.width_px, round, out, scratch));
    out.count[k] = static_cast<uint32_t>(out.vertices.size()) - out.first[k];
  }
  out.hidden_first = static_cast<uint32_t>(out.vertices.size());
  const HiddenLineStyle& h = style.hidden;
  if (h.enabled) {
    StrokeGeometryParams butt;
    butt.cap = StrokeCap::kButt;
    const bool solid = !(h.dash_off > 0.0f);
    const float on = std::max(h.dash_on, 0.5f), period = on + std::max(h.dash_off, 0.0f);
    for (size_t r = 0; r < hidden.strokeCount(); ++r)
      out.hidden_segments += static_cast<uint32_t>(
          solid ? runStroke(hidden, r, h.width_px, butt, out, scratch)
                : runDashes(hidden, r, on, period, h.width_px, butt, out, scratch));
  }
  out.hidden_count = static_cast<uint32_t>(out.vertices.size()) - out.hidden_first;
}

}  // namespace lodline
