// The segments of a set of runs (point i to point i + 1 of one run) binned by the cells of a
// uniform grid that their bounding boxes cover (a counting sort, no allocation once warm),
// for the per-frame "which segments pass near this point" queries of the stroke
// parameterisation (landing previous samples) and of joining runs (runs lying along others).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "export/visibility.h"

namespace lodline {

/// The parameter in [0, 1] of the point of the segment from `a` along `ab` nearest to `p` (0
/// where the segment has no length): the closest-point query of every per-segment test on
/// runs of pixels.
inline float nearestOnSegment(glm::vec2 p, glm::vec2 a, glm::vec2 ab) {
  const float len2 = glm::dot(ab, ab);
  return len2 > 0.0f ? std::clamp(glm::dot(p - a, ab) / len2, 0.0f, 1.0f) : 0.0f;
}

class SegmentGrid {
 public:
  /// Bins every segment of `runs` whose two ends `keep(point)` accepts into a `gw`×`gh` grid
  /// of square cells `cell_px` wide with its corner at `origin`; points beyond the grid fall
  /// into its border cells.
  template <class Keep>
  void build(const StrokeRuns& runs, glm::vec2 origin, float cell_px, int gw, int gh, Keep&& keep) {
    origin_ = origin;
    cell_px_ = cell_px;
    gw_ = std::max(gw, 1);
    gh_ = std::max(gh, 1);
    start_.assign(static_cast<size_t>(gw_) * gh_ + 1, 0);
    auto forCells = [&](uint32_t i, auto&& f) {
      const glm::vec2 a = runs.points[i], b = runs.points[i + 1];
      if (!keep(a) || !keep(b)) return;
      int x0, y0, x1, y1;
      cellOf(glm::min(a, b), x0, y0);
      cellOf(glm::max(a, b), x1, y1);
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) f(static_cast<size_t>(y) * gw_ + x);
    };
    const size_t nr = runs.strokeCount();
    for (size_t r = 0; r < nr; ++r)
      for (uint32_t i = runs.offsets[r]; i + 1 < runs.offsets[r + 1]; ++i) forCells(i, [&](size_t c) { ++start_[c + 1]; });
    for (size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    items_.assign(start_.back(), 0);
    fill_.assign(start_.begin(), start_.end() - 1);
    for (size_t r = 0; r < nr; ++r)
      for (uint32_t i = runs.offsets[r]; i + 1 < runs.offsets[r + 1]; ++i)
        forCells(i, [&](size_t c) { items_[fill_[c]++] = i; });
  }

  /// Calls f(i) for the segments (i: their first point) binned in the cells that the square
  /// of half-width `r_px` around `p` touches, cell by cell; a segment covering several of
  /// those cells comes once per cell. `p` must be finite.
  template <class F>
  void forEachNear(glm::vec2 p, float r_px, F&& f) const {
    int x0, y0, x1, y1;
    cellOf(p - glm::vec2(r_px), x0, y0);
    cellOf(p + glm::vec2(r_px), x1, y1);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const size_t c = static_cast<size_t>(y) * gw_ + x;
        for (uint32_t k = start_[c]; k < start_[c + 1]; ++k) f(items_[k]);
      }
  }

 private:
  void cellOf(glm::vec2 p, int& x, int& y) const {
    x = std::clamp(static_cast<int>(std::floor((p.x - origin_.x) / cell_px_)), 0, gw_ - 1);
    y = std::clamp(static_cast<int>(std::floor((p.y - origin_.y) / cell_px_)), 0, gh_ - 1);
  }

  glm::vec2 origin_{0.0f};
  float cell_px_ = 1.0f;
  int gw_ = 1, gh_ = 1;
  std::vector<uint32_t> start_, items_, fill_;  ///< per cell: first item; segments; fill cursor
};

}  // namespace lodline
