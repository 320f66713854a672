// Opacity that ramps in for lines that appear (docs/temporal-coherence.md, "Fading lines in"):
// in a sequence, a visible line sample whose surface point had no line within `match_px` in
// the previous frame starts faint and reaches full opacity over a short time, so a line that
// shows for a frame or two (a contour loop at a cusp, a suggestive contour at its threshold,
// a piece the level of detail brings and takes back) flickers at a fraction of its opacity.
// The correspondence is made through the surface: the previous frame's samples are projected
// by the current camera (motion compensation, as the coherence measure and the stroke
// parameterisation do), Kalnins et al. 2003 §4's way of following strokes over frames.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "core/camera.h"
#include "export/visibility.h"

namespace lodline {

struct StrokeFadeParams {
  /// Opacity gained per frame by a sample with no line under its surface point before:
  /// frame time / fade-in time. 0: off (every sample at full opacity).
  float step = 0.0f;
  /// How far (px, Chebyshev) from a previous sample's projection a current sample still
  /// continues it. Default 2.
  int match_px = 2;
};

class StrokeFader {
 public:
  /// Multiplies `runs.alpha` (one object's visible runs, seen by `camera` in a
  /// `width`×`height` image) by each sample's ramp, carried from the previous update(): the
  /// largest ramp among the previous samples whose surface point now projects within
  /// match_px, plus `step`, at most 1; `step` alone where there is none. The first frame of a
  /// sequence (after reset()) is drawn at full opacity.
  void update(StrokeRuns& runs, const Camera& camera, int width, int height, const StrokeFadeParams& params);
  /// Forgets the previous frame (a new sequence).
  void reset() {
    prev_positions_.clear();
    prev_points_.clear();
    prev_ramp_.clear();
    started_ = false;
  }
  /// Of the last update(): samples that were fading in (ramp < 1).
  size_t fading() const { return fading_; }

 private:
  std::vector<glm::vec3> prev_positions_;
  std::vector<glm::vec2> prev_points_;
  std::vector<float> prev_ramp_;
  bool started_ = false;
  size_t fading_ = 0;
  // Scratch: the previous samples' ramps splatted per pixel (only `touched_` are non-zero).
  std::vector<float> splat_;
  std::vector<uint32_t> touched_;
  std::vector<float> ramp_;
};

}  // namespace lodline
