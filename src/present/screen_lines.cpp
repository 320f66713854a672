#include "present/screen_lines.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace lodline {
namespace {

void pushSegment(ScreenLines& out, const ScreenLineVertex& a, const ScreenLineVertex& b) {
  out.vertices.push_back(a);
  out.vertices.push_back(b);
}

// The segments of run r of `runs`, whole.
void runSegments(const StrokeRuns& runs, size_t r, ScreenLines& out) {
  for (uint32_t i = runs.offsets[r]; i + 1 < runs.offsets[r + 1]; ++i)
    pushSegment(out, {runs.points[i], runs.alpha[i]}, {runs.points[i + 1], runs.alpha[i + 1]});
}

// The parts of run r's polyline inside the dashes [k·period, k·period + on), arc length
// from the run's start.
void runDashes(const StrokeRuns& runs, size_t r, float on, float period, ScreenLines& out) {
  float s0 = 0.0f;  // arc length at the start of the current piece
  for (uint32_t i = runs.offsets[r]; i + 1 < runs.offsets[r + 1]; ++i) {
    const glm::vec2 a = runs.points[i], b = runs.points[i + 1];
    const float len = glm::length(b - a);
    if (!(len > 0.0f)) continue;
    const float s1 = s0 + len;
    // Dashes overlapping [s0, s1).
    for (float d = std::floor(s0 / period) * period; d < s1; d += period) {
      const float lo = std::max(d, s0), hi = std::min(d + on, s1);
      if (hi <= lo) continue;
      const float t0 = (lo - s0) / len, t1 = (hi - s0) / len;
      const float a0 = runs.alpha[i] + t0 * (runs.alpha[i + 1] - runs.alpha[i]);
      const float a1 = runs.alpha[i] + t1 * (runs.alpha[i + 1] - runs.alpha[i]);
      pushSegment(out, {a + t0 * (b - a), a0}, {a + t1 * (b - a), a1});
    }
    s0 = s1;
  }
}

}  // namespace

void buildScreenLines(const StrokeRuns& visible, const StrokeRuns& hidden, const HiddenLineStyle& hidden_style,
                      ScreenLines& out) {
  out.clear();
  for (int k = 0; k < kLineKindCount; ++k) {
    out.first[k] = static_cast<uint32_t>(out.vertices.size());
    for (size_t r = 0; r < visible.strokeCount(); ++r)
      if (static_cast<int>(visible.kinds[r]) == k) runSegments(visible, r, out);
    out.count[k] = static_cast<uint32_t>(out.vertices.size()) - out.first[k];
  }
  out.hidden_first = static_cast<uint32_t>(out.vertices.size());
  if (hidden_style.enabled) {
    const bool solid = !(hidden_style.dash_off > 0.0f);
    const float on = std::max(hidden_style.dash_on, 0.5f), period = on + std::max(hidden_style.dash_off, 0.0f);
    for (size_t r = 0; r < hidden.strokeCount(); ++r) {
      if (solid) runSegments(hidden, r, out);
      else runDashes(hidden, r, on, period, out);
    }
  }
  out.hidden_count = static_cast<uint32_t>(out.vertices.size()) - out.hidden_first;
}

}  // namespace lodline
