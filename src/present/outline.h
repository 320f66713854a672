// The exterior outline made complete (docs/visibility.md). On a coarse mesh the interpolated
// contour (n·v = 0 on vertex normals) runs inside the polygonal outline of the faces as
// drawn, partly over back-facing faces that the front ones hide, so the drawn outline
// breaks. Where that happens, the mesh's own silhouette (edges between front- and
// back-facing faces) is drawn instead: its visible samples that lie on a depth discontinuity
// (the object ends there: background or a farther surface next to them) and have no visible
// contour within a few pixels, extended a little along the silhouette so the pieces meet
// the contour's ends (while the camera moves in a sequence of frames, new pieces shorter
// than min_length_px wait until they are long enough, and pieces go on while they
// continue). Contour pieces
// running beside such a piece, off the outline, would double it: they are dropped. The
// interpolated contour stays wherever it draws the outline (and inside the object): it is
// smoother.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/mat4x4.hpp>

#include "core/camera.h"
#include "core/image.h"
#include "export/coherence.h"
#include "export/visibility.h"
#include "lines/strokes.h"

namespace lodline {

struct OutlineParams {
  /// An outline sample is drawn by the contour when a visible contour pixel lies within this
  /// many pixels (Chebyshev); a contour sample is on the outline when an outline sample lies
  /// this close. Default 1 (the outline is measured to 2 px from line centres: a contour
  /// 2 px inside is already too far).
  int contour_radius_px = 1;
  /// The depth discontinuity is looked for within this many pixels of a sample. Default 2.
  int discontinuity_radius_px = 2;
  /// A neighbour at least this fraction of the sample's eye depth farther than the sample
  /// (or the background) makes a discontinuity. Default 0.05.
  float depth_jump = 0.05f;
  /// Kept pieces grow by this many pixels along the silhouette at both ends. Default 2.
  float extend_px = 2.0f;
  /// In a sequence of frames (with an OutlineHistory, after its first frame), a new completing
  /// piece shorter than this (pixels, after growing) is not drawn: under detail control the
  /// mesh's silhouette changes from frame to frame, and the short pieces it would add
  /// flicker more than the few pixels of outline they close. Pieces continuing the previous
  /// frame's are kept whatever their length; stills, the first frame of a sequence that does
  /// not start in motion and frames whose camera has not moved (a viewer at rest) draw every
  /// piece. Default 32 (measured on the held-out captures: docs/visibility.md).
  float min_length_px = 32.0f;
  /// Contour samples off the outline within this many pixels of a completing piece are
  /// dropped (they would draw a second line beside it). Default 6.
  int double_radius_px = 6;
  /// Inside a contour run, only stretches of at least this many pixels of such contour are
  /// dropped: a shorter one is a sample or two off the outline, and cutting it would leave a
  /// notch. At a run's ends (and a whole run) any length is dropped. Default 4.
  float min_drop_px = 4.0f;
  /// Lines within this many pixels of one another draw one outline (docs/visibility.md,
  /// steps 2 and 3): a piece that runs this near the visible contour all along is not drawn
  /// (the mesh's silhouette zigzags about the contour; drawn, each tooth was a tick on the
  /// line); the stretches of a piece this near an earlier piece are not drawn again (a fold
  /// lays silhouette edges over one another); a contour run this near the pieces all along is
  /// left to them. 0 turns these three off. Default 2.
  float covered_px = 2.0f;
  /// A piece at most this long (pixels, after growing) with one end within splice_radius_px
  /// of a contour run, away from the run's ends, and the other beside no line (no contour,
  /// no other missing stretch of the silhouette) is a spur, and is not drawn. 0 turns this
  /// off. Default 8.
  float spur_max_px = 8.0f;
  /// A piece at most this long whose two ends both lie within splice_radius_px of one
  /// contour run is spliced into that run instead of drawn beside it: the run leaves the
  /// contour there and follows the silhouette (a polygon corner the contour cuts; drawn
  /// beside it, a bump with two caps). The run's stretch between the two ends must lie
  /// beside the piece (its middle within twice splice_radius_px of it), and a piece
  /// overlapping an earlier splice is drawn instead. 0 turns splicing off. Default 64.
  float splice_max_px = 64.0f;
  /// How near the contour a piece's end must be for the spur and splice rules. 0 turns
  /// those two and the first covered_px rule off. Default 3.
  float splice_radius_px = 3.0f;
  /// A spliced run moves from the contour onto the silhouette (and back) over this many
  /// pixels at each end of the piece, so it bends there instead of stepping. Default 3.
  float splice_ramp_px = 3.0f;
  /// A piece's end that runs beside the end of a contour run, this near it (pixels) all
  /// along for up to overlap_reach_px, takes that stretch over: the contour run is cut back
  /// to its point nearest the piece's end and bends onto the piece's end, so the two join
  /// into one stroke instead of drawing a doubled line (takeOverContourEnds(),
  /// docs/visibility.md, step 5). Ends within 1.5 px are met by the stitch alone. 0 turns
  /// this off. Default 4 (a 2.5-px line's width and 1.5 px).
  float overlap_radius_px = 4.0f;
  /// How far back from a piece's end (pixels of the piece) the contour run's end may lie
  /// for overlap_radius_px. Default 32.
  float overlap_reach_px = 32.0f;
  /// A piece's end that meets no contour end within 1.5 px is carried on to a free contour
  /// end this near it (pixels) when the gap lies along the outline (every pixel of it within
  /// 2 px of an outline sample), continues the piece within 60° and does not turn the
  /// contour back on itself: at a corner of the outline the contour can end a few pixels
  /// short of the silhouette, beyond the piece's growth (docs/visibility.md, step 5). 0 turns
  /// this off. Default 6 (extend_px and 4).
  float corner_gap_px = 6.0f;
  /// Hysteresis between frames (with an OutlineHistory): a piece with a sample within this
  /// many pixels of the previous frame's pieces (projected by this frame's camera, so the
  /// comparison follows the motion) continues one and is kept whatever its length, so a
  /// piece near min_length_px does not blink. Default 2.
  int follow_radius_px = 2;
};

/// What completeOutline() remembers of the previous frame of a sequence (one per object):
/// the world positions of its completing pieces' samples and the camera they were seen by.
struct OutlineHistory {
  std::vector<glm::vec3> fill;
  glm::mat4 view_proj{0.0f};  ///< projection · view of the previous frame
  uint64_t frames = 0;        ///< frames completed so far in the sequence
  /// The sequence is in motion from its first frame (a capture): that frame too leaves out
  /// short new pieces, which would otherwise vanish on the next. Otherwise (a viewer) the
  /// first frame is drawn like a still.
  bool starts_in_motion = false;
};

/// Scratch of completeOutline(); reuse between calls.
struct OutlineScratch {
  StrokeRuns silhouette, rebuilt, stitched;
  StrokeRuns taken;  ///< the runs after step 5's overlaps are taken over
  LineMask outline, contours, fill, previous;
  LineMask skipped;  ///< pieces left out because the contour beside them draws them
  LineMask spliced;  ///< pieces spliced into a contour run
  std::vector<uint8_t> flags, grown, dup;
  std::vector<glm::vec3> fill_samples;  ///< every sample of this frame's completing pieces
  /// The visible contour's samples by pixel (step 2), for the splices' nearest-sample search.
  struct ContourSample {
    uint32_t pixel, run, index;
    glm::vec2 px;
  };
  std::vector<ContourSample> contour_samples;
  std::vector<uint32_t> run_samples;  ///< per visible run: its sample count (contour runs)
  std::vector<uint32_t> run_first;    ///< per visible run: its first sample in run_px
  std::vector<glm::vec2> run_px;      ///< the contour runs' samples, run after run
  /// The silhouette's missing samples (no contour within contour_radius_px) by pixel.
  struct MissingSample {
    uint32_t pixel, run, index;
  };
  std::vector<MissingSample> missing;
  std::vector<uint8_t> sil_flags;   ///< per silhouette sample (step 3): missing, run after run
  std::vector<uint32_t> sil_first;  ///< per silhouette run: its first sample in sil_flags
};

/// Completes the exterior outline of one object in `visible` (its visible runs): appends
/// the pieces of `silhouette` (the mesh's own silhouette) that draw it where the contour
/// does not (runs of kind contour) and drops the contour pieces they would double. `camera`
/// and `depth` are the frame's. With `history` (frames of a sequence), pieces of the previous
/// frame continue with hysteresis and `history` becomes this frame's; without it (a still),
/// every piece is decided afresh. Returns the length of the pieces drawn (appended, or
/// spliced into a contour run), pixels.
double completeOutline(const StrokeSet& silhouette, const Camera& camera, const DepthImage& depth,
                       const VisibilityParams& visibility, const OutlineParams& params, StrokeRuns& visible,
                       OutlineScratch& scratch, OutlineHistory* history = nullptr);

/// Step 5's first half (completeOutline() calls it): where a completing piece's end runs
/// beside the end of a contour run, 1.5 to params.overlap_radius_px px from it all along the
/// contour's stretch (at least min_drop_px long, at most half the piece's length, within
/// overlap_reach_px of the piece's end), the two would draw a doubled line. The piece draws
/// that stretch: the contour run is cut back to its point nearest the piece's end and its
/// new end bends onto the piece's end (its points over its last max(splice_ramp_px, 8 × their
/// distance) px and on to its next point, moved by a weight rising linearly to 1), so that
/// the two join into one stroke and the piece stays on the outline. Ends the stitch meets
/// within 1.5 px are left as they are. `contours` holds the runs of every kind (only contour
/// runs are cut); `fill` the pieces, which do not change.
void takeOverContourEnds(const StrokeRuns& contours, const StrokeRuns& fill, const OutlineParams& params,
                         StrokeRuns& contours_out);

}  // namespace lodline
