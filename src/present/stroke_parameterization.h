// Coherent stroke parameterisation (Kalnins, Davidson, Markosian, Finkelstein, "Coherent
// stylized silhouettes", SIGGRAPH 2003, §4–5; docs/strokes.md): the arc-length parameter that
// places a brush texture, dashes and jitter along a stroke is carried from frame to frame,
// so that they stay on the surface instead of sliding along re-extracted strokes.
//
// Each frame, the previous frame's visible samples (their surface points and parameters) are
// projected into the current image; each lands on a current run of its kind within
// `match_px` (the nearest, or where several are that close, the one most samples of its
// previous run landed on: its successor, so samples at junctions stay with their stroke),
// at some arc length s there, and votes for the offset u − s (or u + s: a run may
// be chained the other way round; each run takes the direction most of its votes agree
// with). A run point's parameter is then u = s + the median of the votes within
// `window_px` of arc length (of the nearest `min_window_votes` where fewer are that close),
// or, where those votes straddle a seam, the offset of its nearest vote's side moved toward
// that median by at most `heal_px` per frame, so a stroke that slides
// unevenly over the surface keeps its texture on it piece by piece, a stroke that split
// inherits its parent's parameters on each part, and one that merged two parents keeps
// each part's with a seam where they meet. A run that no sample reaches starts afresh at u = s.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/camera.h"
#include "core/line_kind.h"
#include "export/visibility.h"
#include "present/segment_grid.h"

namespace lodline {

struct StrokeParameterizationParams {
  /// Farthest a previous sample may land from a current run to count as on it, px. Default 1.
  float match_px = 1.0f;
  /// ... and lie within this many pixels' worth (at its depth) of the run's own surface point
  /// there, else it does not persist (another piece of line lies over it in the image). 0:
  /// no such test. Default 8.
  float surface_px = 8.0f;
  /// A run needs at least this many landed samples to inherit; else it starts afresh.
  /// Default 1: even a short run that one sample reaches keeps that sample's texture.
  int min_votes = 1;
  /// Votes within this of the median offset agree (choosing the direction), px. Default 3.
  float inlier_px = 3.0f;
  /// Half-width of the window of votes whose median sets a point's offset, px of arc length.
  /// Default 8.
  float window_px = 8.0f;
  /// ... widened to the nearest this many votes where it holds fewer. Default 5.
  size_t min_window_votes = 5;
  /// Seams (where two parents' textures meet on a run): a point takes the offset of the
  /// votes on its nearest vote's side (within inlier_px of it), moved toward the window's
  /// median by at most this many pixels per frame, so a seam stays put on the surface and
  /// closes gradually. Default 2 (measured: docs/strokes.md); infinity: the median alone.
  float heal_px = 2.0f;
};

class StrokeParameterizer {
 public:
  /// The parameters of this frame's visible `runs` (one object's, seen by `camera` in a
  /// `width`×`height` image), carried from the previous update() when `coherent`, else
  /// u = s (the arc length from each run's first point). Either way the texture drift of
  /// the frame is measured (below).
  /// A closed run (a loop seen whole, its last point its first) has an arbitrary first point;
  /// when coherent it is rotated to start where a closed run of its kind started in the
  /// previous frame (within match_px of that point's projection), and a sample that lands
  /// near both of its ends takes the end it was nearer to before, so the loop's seam — the
  /// one place its parameter jumps — stays on the surface.
  void update(StrokeRuns& runs, const Camera& camera, int width, int height, bool coherent,
              const StrokeParameterizationParams& params = {});
  /// One per point of the runs of the last update() (indexed like runs.points), px.
  const std::vector<float>& parameters() const { return u_; }
  /// Of the last update(): previous samples that landed on a current run of their kind
  /// (the samples that persist), and the sum over them of |u here − u before|, px: how far
  /// the texture under a persisting surface point moved along its stroke.
  size_t persisting() const { return persisting_; }
  double driftSum() const { return drift_sum_; }
  /// Forgets the previous frame (a new sequence).
  void reset();

 private:
  struct Landing {
    uint32_t run;
    float s;  ///< arc length on the run where the previous sample landed
    float u;  ///< the previous sample's parameter
  };
  std::vector<glm::vec3> prev_positions_;
  std::vector<float> prev_fraction_;       ///< on a closed run: arc length / its length; else −1
  std::vector<glm::vec3> prev_seams_;      ///< first points of the previous closed runs
  std::vector<LineKind> prev_seam_kinds_;
  std::vector<float> prev_u_;
  std::vector<LineKind> prev_kinds_;
  std::vector<uint32_t> prev_runs_;  ///< the run each previous sample was on
  size_t prev_run_count_ = 0;
  std::vector<float> u_;
  size_t persisting_ = 0;
  double drift_sum_ = 0.0;
  // Scratch.
  std::vector<float> arc_;            // per current point, arc length within its run
  std::vector<uint32_t> point_run_;   // per current point, its run
  SegmentGrid grid_;  // the current runs' segments
  struct Candidate {
    uint32_t sample;  ///< previous sample
    uint32_t run;     ///< a current run within match_px
    float s, d;       ///< where on it, and how far
  };
  std::vector<Candidate> candidates_;
  std::vector<uint64_t> successor_keys_;
  std::vector<uint32_t> successor_;  ///< per previous run: the current run most of it landed on
  std::vector<uint32_t> successor_votes_;  ///< ... and how many samples of it landed there
  std::vector<Landing> landings_;
  std::vector<glm::vec2> seam_px_;
  std::vector<uint8_t> closed_;  ///< per current run
  std::vector<float> votes_, window_;
};

}  // namespace lodline
