// Stable stroke ids across the frames of a sequence (`capture --svg DIR/`): a visible run
// keeps the id of the previous frame's run it continues, so a stroke can be followed from
// one frame's SVG to the next. Correspondence through the surface, as Kalnins et al. 2003
// ("Coherent stylized silhouettes") propagate strokes: the previous frame's runs are
// projected by this frame's camera (their samples' model-space positions), each run of this
// frame votes with its samples for the previous ids found within a few pixels, and takes the
// id with most votes when they cover enough of it. When one previous run continues as
// several (it split), the one with most votes keeps the id; the others, and runs with no
// predecessor, get new ids. Ids are never reused within a sequence.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/camera.h"
#include "export/visibility.h"

namespace lodline {

struct StrokeIdParams {
  /// A previous run's sample within this many pixels (Chebyshev) of a sample votes. Default 2.
  int radius_px = 2;
  /// A run continues a previous one when that one's votes reach this fraction of its
  /// samples. Default 0.5.
  float min_share = 0.5f;
};

class StrokeIdTracker {
 public:
  explicit StrokeIdTracker(StrokeIdParams params = {}) : params_(params) {}

  /// Gives every run of `visible` (one StrokeRuns per object) its id for this frame, seen by
  /// `camera` in a `width`×`height` image; the first call starts the sequence.
  void update(std::span<const StrokeRuns> visible, const Camera& camera, int width, int height);

  /// ids()[object][run]: the ids of the last update(), ≥ 1.
  const std::vector<std::vector<uint64_t>>& ids() const { return ids_; }

 private:
  StrokeIdParams params_;
  std::vector<std::vector<uint64_t>> ids_;
  std::vector<glm::vec3> prev_points_;  ///< samples of the previous frame's runs, model space
  std::vector<uint64_t> prev_ids_;      ///< 1 per sample
  std::vector<uint64_t> owner_;         ///< per pixel: a previous id found there, 0 none
  std::vector<glm::vec3> points_;       ///< this frame's samples (become prev_points_)
  std::vector<uint64_t> point_ids_;
  uint64_t next_id_ = 1;
};

}  // namespace lodline
