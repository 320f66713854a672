// Measuring temporal coherence of line drawings (lodline's own measure; no published system
// reports one): per frame, the line pixels that appeared or vanished since the previous
// frame, with a small spatial tolerance so a line that slides by a pixel does not count.
//
// The raw measure (compareMasks) counts every line pixel the camera moves by more than the
// tolerance, so on a moving camera it mostly measures the motion. The motion-compensated one
// (compareMasksCompensated) first moves each line pixel of one frame by the image motion of
// the surface point under it — read from a surface buffer holding each pixel's visible world
// position — to where that point projects in the other frame, drops it if the point is
// hidden or off-screen there, and only then compares: what is left is lines popping in and
// out, not lines travelling with the surface.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "core/camera.h"
#include "core/image.h"
#include "export/visibility.h"

namespace lodline {

/// One byte per pixel: the opacity (1–255) of the most opaque visible line passing through
/// it, 0 where none does; row 0 = top.
struct LineMask {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> on;
  bool at(int x, int y) const { return on[static_cast<size_t>(y) * width + x] != 0; }
  /// The pixel's line opacity in [0, 1].
  float opacity(int x, int y) const { return static_cast<float>(on[static_cast<size_t>(y) * width + x]) / 255.0f; }
  /// Pixels on.
  uint64_t count() const;
  /// Sum of the pixels' opacities.
  double weight() const;
};

/// Marks the pixels under the visible strokes' samples (≤ 1 px apart, so strokes are
/// continuous) and under the straight pieces between them, each with the stroke's opacity
/// there (StrokeRuns::alpha, interpolated; at least 1/255). `out` is resized to w×h.
void rasterizeStrokes(const StrokeRuns& strokes, int width, int height, LineMask& out);

struct MaskChange {
  uint64_t line_pixels = 0;  ///< pixels on in the current mask
  uint64_t appeared = 0;     ///< on now, with nothing on within `tolerance` px before
  uint64_t vanished = 0;     ///< on before, with nothing on within `tolerance` px now
  /// (appeared + vanished) / line_pixels; 0 when there are no line pixels.
  double churn() const {
    return line_pixels ? static_cast<double>(appeared + vanished) / static_cast<double>(line_pixels) : 0.0;
  }
};

/// Compares two masks of the same size with a Chebyshev tolerance of `tolerance` pixels.
MaskChange compareMasks(const LineMask& previous, const LineMask& current, int tolerance = 1);

/// Where the level of detail changed the mesh in a frame, one byte per pixel (row 0 = top):
/// bit kNearOps within a radius of where a vertex was split or collapsed in that frame, bit
/// kNearMorph within it of a vertex that a geomorph moved. Built by the caller from the level of
/// detail's change lists (present/capture.cpp); compareMasksCompensated() attributes the popped
/// pixels to them (docs/temporal-coherence.md, "Where the popped pixels are").
struct ChangeZones {
  static constexpr uint8_t kNearOps = 1, kNearMorph = 2;
  int width = 0;
  int height = 0;
  std::vector<uint8_t> bits;
  /// Sizes the image and clears every bit.
  void reset(int w, int h);
  /// Sets `bit` on the pixels within Chebyshev distance `radius` of pixel position `px`.
  void mark(glm::vec2 px, int radius, uint8_t bit);
  uint8_t at(int x, int y) const { return bits[static_cast<size_t>(y) * width + x]; }
};

/// Where a compared frame's lines popped, per pixel of the current frame (row 0 = top), as
/// compareMasksCompensated() counts them: `appeared` holds, at a current line pixel, how much
/// more opaque it is than the most opaque line within the tolerance of where its surface point
/// was; `vanished` the same for a previous line pixel, marked where its point is now (the
/// larger where several land on one pixel). 0–255 like LineMask; 0: nothing popped there.
/// What `capture --pop-frames` draws (docs/capture.md).
struct PopMap {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> appeared, vanished;
  /// Sizes both planes and clears them.
  void reset(int w, int h);
};

/// The frame `frame` faded to a third of its contrast, with `pops` over it: vanished pixels in
/// red and appeared ones in green, each as opaque as it popped (what `capture --pop-frames`
/// writes). Where `pops` does not match the frame's size, the faded frame alone.
Image popImage(const Image& frame, const PopMap& pops);

struct CompensationParams {
  /// Chebyshev tolerance of the comparison after moving, pixels (as compareMasks). Default 1.
  int tolerance = 1;
  /// A line pixel with no surface under it (the outer half of a contour drawn across the
  /// silhouette) moves with the nearest surface pixel within this many pixels. Default 2.
  int search_radius = 2;
  /// A moved point is hidden when the farthest surface over the 3×3 pixels around its new
  /// position is nearer than it by more than this fraction of its depth (background next to
  /// it: visible). Default 0.01.
  float depth_tolerance = 0.01f;
  /// Where the mesh changed in the current frame (optional; used only when its size is the
  /// masks'): the popped and line pixels in it are counted (CompensatedChange::*_near_*).
  const ChangeZones* zones = nullptr;
  /// Where the popped pixels are (optional): reset to the masks' size and filled.
  PopMap* pops = nullptr;
};

struct CompensatedChange {
  uint64_t line_pixels = 0;  ///< pixels on in the current mask
  /// Current line pixels whose surface point was visible in the previous frame, with no
  /// previous line pixel within the tolerance of where that point was.
  uint64_t appeared = 0;
  /// Previous line pixels whose surface point is visible now, with no current line pixel
  /// within the tolerance of where that point now is.
  uint64_t vanished = 0;
  /// Line pixels not compared because their point is hidden or off-screen in the other
  /// frame (or no surface lies under or next to them): both directions together.
  uint64_t dropped = 0;
  /// (appeared + vanished) / line_pixels; 0 when there are no line pixels. The binary
  /// measure: a pixel counts whole, however faint its line.
  double churnBinary() const {
    return line_pixels ? static_cast<double>(appeared + vanished) / static_cast<double>(line_pixels) : 0.0;
  }
  /// The same counts weighted by opacity: each compared pixel adds how much more opaque it is
  /// than the most opaque line within the tolerance of its point in the other frame (a line
  /// fading in at 20% adds 0.2 where nothing was, and nothing where a stronger line was).
  double line_weight = 0.0;      ///< sum of the current line pixels' opacities
  double appeared_weight = 0.0;
  double vanished_weight = 0.0;
  /// (appeared_weight + vanished_weight) / line_weight: the churn lodline reports (fading is
  /// no way to hide popping from it: a half-faded pop counts half).
  double churn() const { return line_weight > 0.0 ? (appeared_weight + vanished_weight) / line_weight : 0.0; }
  /// With CompensationParams::zones (binary counts; a pixel may be in both zones): the popped
  /// pixels, appeared and vanished, that lie near a split or collapse and near a morphing
  /// vertex of the current frame (an appeared pixel where it is, a vanished one where its
  /// surface point is now), and the current line pixels that do, for comparison.
  uint64_t popped_near_ops = 0;
  uint64_t popped_near_morphs = 0;
  uint64_t lines_near_ops = 0;
  uint64_t lines_near_morphs = 0;
};

/// The motion-compensated comparison of two frames: `previous`/`current` line masks, the
/// surface images drawn with the same cameras, and those cameras. A line pixel moves by the
/// image motion of its surface point (its projection by the other camera minus its projection
/// by its own), so with an unchanged camera nothing moves and the result equals
/// compareMasks(). All images must have the same size (otherwise everything counts as
/// appeared).
CompensatedChange compareMasksCompensated(const LineMask& previous, const SurfaceImage& previous_surface,
                                          const Camera& previous_camera, const LineMask& current,
                                          const SurfaceImage& current_surface, const Camera& current_camera,
                                          const CompensationParams& params = {});

/// One frame's coherence against the previous one, raw and motion-compensated.
struct FrameCoherence {
  MaskChange raw;
  CompensatedChange compensated;
  bool compared = false;  ///< false for the first frame: nothing to compare with
};

/// The coherence measure of a sequence of frames: keeps the previous frame's line mask,
/// surface image and camera, and compares each new frame with it (both measures above).
class CoherenceMeter {
 public:
  /// Compares the frame (its visible line mask, surface image and camera, all of one size)
  /// with the previous one, then keeps it as the previous frame. `mask` and `surface` are
  /// swapped with the kept buffers (the caller gets the old ones back to refill: no copy).
  /// The first frame, or one after reset(), compares with nothing: its line pixels are
  /// counted, appeared and vanished are 0 and `compared` is false.
  FrameCoherence measure(LineMask& mask, SurfaceImage& surface, const Camera& camera,
                         const CompensationParams& params = {});
  /// Forgets the previous frame.
  void reset() { have_previous_ = false; }
  bool hasPrevious() const { return have_previous_; }

 private:
  LineMask previous_mask_;
  SurfaceImage previous_surface_;
  Camera previous_camera_;
  bool have_previous_ = false;
};

}  // namespace lodline
