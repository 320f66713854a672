#include "present/stroke_fade.h"

#include <algorithm>
#include <cmath>

namespace lodline {

void StrokeFader::update(StrokeRuns& runs, const Camera& camera, int width, int height,
                         const StrokeFadeParams& params) {
  const size_t np = runs.points.size();
  const bool has_positions = runs.positions.size() == np;
  if (runs.alpha.size() != np) runs.alpha.assign(np, 1.0f);
  fading_ = 0;
  ramp_.assign(np, 1.0f);
  if (params.step > 0.0f && started_ && has_positions && width > 0 && height > 0) {
    // The previous samples' ramps, splatted where their surface points now project.
    splat_.resize(static_cast<size_t>(width) * height, 0.0f);
    const PixelProjector projector(camera, width, height);
    auto splat = [&](glm::vec2 px, float ramp) {
      if (!(px.x >= 0.0f && px.y >= 0.0f && px.x < static_cast<float>(width) && px.y < static_cast<float>(height)))
        return;
      const size_t k = static_cast<size_t>(px.y) * width + static_cast<size_t>(px.x);
      if (splat_[k] == 0.0f) touched_.push_back(static_cast<uint32_t>(k));
      splat_[k] = std::max(splat_[k], ramp);
    };
    for (size_t j = 0; j < prev_positions_.size(); ++j) {
      // Where its surface point went (lines on the surface), and where it was in the image
      // (contours, which slide over the surface as the view turns but stay on the outline).
      glm::vec2 px;
      float depth = 0.0f;
      if (projector.project(prev_positions_[j], px, depth)) splat(px, prev_ramp_[j]);
      splat(prev_points_[j], prev_ramp_[j]);
    }
    // A run continues the most opaque line any of its samples lands near: only runs that
    // are new as a whole fade in (a line that only partly keeps its correspondence, moving
    // faster than match_px in places, must not dim and come back).
    const int r = std::max(0, params.match_px);
    for (size_t run = 0; run < runs.strokeCount(); ++run) {
      float before = 0.0f;
      for (uint32_t i = runs.offsets[run]; i < runs.offsets[run + 1]; ++i) {
        const glm::vec2 p = runs.points[i];
        if (!(std::isfinite(p.x) && std::isfinite(p.y))) continue;
        const int x = static_cast<int>(std::floor(p.x)), y = static_cast<int>(std::floor(p.y));
        for (int yy = std::max(0, y - r); yy <= std::min(height - 1, y + r); ++yy)
          for (int xx = std::max(0, x - r); xx <= std::min(width - 1, x + r); ++xx)
            before = std::max(before, splat_[static_cast<size_t>(yy) * width + xx]);
      }
      const float ramp = std::min(1.0f, before + params.step);
      for (uint32_t i = runs.offsets[run]; i < runs.offsets[run + 1]; ++i) {
        ramp_[i] = ramp;
        runs.alpha[i] *= ramp;
      }
      if (ramp < 1.0f) fading_ += runs.offsets[run + 1] - runs.offsets[run];
    }
    for (uint32_t k : touched_) splat_[k] = 0.0f;
    touched_.clear();
  }
  // This frame's samples, for the next.
  prev_positions_.clear();
  prev_points_.clear();
  prev_ramp_.clear();
  if (has_positions) {
    prev_positions_.assign(runs.positions.begin(), runs.positions.end());
    prev_points_.assign(runs.points.begin(), runs.points.end());
    prev_ramp_.assign(ramp_.begin(), ramp_.end());
  }
  started_ = true;
}

}  // namespace lodline
