// From stroke runs to what the renderers draw (core/line_buffer.h): the visible runs grouped
// by kind as stroke geometry in their kind's style, the hidden runs in the hidden style
// (docs/visibility.md, docs/strokes.md).
#pragma once

#include <array>
#include <span>

#include "core/camera.h"
#include "core/line_buffer.h"
#include "core/mesh.h"
#include "core/render_params.h"
#include "export/visibility.h"
#include "lines/stroke_curve.h"
#include "present/segment_grid.h"
#include "present/stroke_geometry.h"

namespace lodline {

/// Where the strokes are seen from, for the styles' depth terms: the camera and the object's
/// bounding sphere (depth 0 at its nearest point, 1 at its farthest).
struct StrokeView {
  glm::vec3 eye{0.0f};
  glm::vec3 forward{0.0f, 0.0f, -1.0f};
  glm::vec3 center{0.0f};
  float radius = 1.0f;
};

/// Smooths each run of `runs` in the image by its kind's StrokeStyle::smoothing_px
/// (`style.lines`; smoothPolyline(): a Gaussian along the arc length, corners over 50° and
/// the ends kept) and updates its length_px. First, where a run turns back over itself
/// (within 3/4 of its kind's width) by at least that width and comes out ahead of the turn
/// within four widths, the excursion is straightened: a fold of a coarse mesh's zero set,
/// drawn as a knot in the line. The zero crossings of a coarse mesh zig-zag from face to
/// face by a pixel or so, and the zig-zag changes as the mesh adapts: drawn as found, the
/// strokes looked shaky close up and popped pixels from frame to frame (docs/strokes.md,
/// "Smoothing"). Only the pixel positions move; the model-space positions stay.
void smoothRuns(StrokeRuns& runs, const LineStyles& style, StrokeCurveScratch& scratch);

/// Runs joined where they meet (joinRuns()), and its scratch; reuse between calls.
struct JoinedRuns {
  StrokeRuns runs;
  std::vector<float> u;             ///< the parameter per point, when one was given
  std::vector<uint32_t> first_run;  ///< per joined run: the index of its first run in the input
  std::vector<int32_t> link;        ///< per run end (2r start, 2r + 1 end): the end it joins, or -1
  std::vector<uint8_t> overlapping;  ///< per run end: joined side by side (JoinParams::overlap_px)
  std::vector<uint8_t> side_step;    ///< per run end: joined beside the other's end (JoinParams::step_px)
  std::vector<uint32_t> skipped;     ///< per run end: its points left out there (entered side by side, or a hook)
  std::vector<std::pair<uint64_t, uint32_t>> bins;  ///< run ends by grid cell
  std::vector<uint8_t> done;        ///< per run: already in a chain
  std::vector<uint8_t> covered;     ///< per run: lies along longer runs (JoinParams::along_px)
  SegmentGrid grid;                 ///< the runs' segments (runs lying along others)
  std::vector<uint32_t> run_of;     ///< per point: its run
  std::vector<uint32_t> order;      ///< runs, shortest first
  std::vector<uint32_t> linking;    ///< runs beside a longer one, kept for linking two ends
};

/// Scratch of buildScreenLines(); reuse between calls.
struct ScreenLinesScratch {
  std::vector<glm::vec2> points;
  std::vector<float> alpha, width, arc, u, depth, bend;
  std::vector<glm::vec2> piece;
  std::vector<float> piece_alpha, piece_width, piece_u;
  std::vector<std::pair<float, float>> dash_spans;
  JoinedRuns joined;
  StrokeGeometryScratch geometry;
};

/// The profile of run r of `runs` in style `st` at width `width_px`, into sc.points (jitter
/// applied along the parameter), sc.width (px), sc.alpha (opacity), sc.arc (arc length from
/// the run's start) and sc.u (the parameter: `u`, one per point of `runs`, or the arc length
/// when `u` is empty), one entry per point of the run. False (and nothing to
/// draw) when the run is shorter than the style's minimum length or empty. The renderers'
/// geometry and the SVG's variable-width outlines both come from it.
bool strokeProfile(const StrokeRuns& runs, size_t r, float width_px, const StrokeStyle& st, const StrokeView& view,
                   std::span<const float> u, ScreenLinesScratch& sc);

/// When runs' ends are joined (joinRuns()).
struct JoinParams {
  /// Ends this close meet, whatever their directions, px. Default 0.75.
  float touch_px = 0.75f;
  /// Ends still free that are this close are bridged by a straight piece when the line
  /// goes on through the gap: each end's outward direction turns by at most `max_turn_deg`
  /// into the other's inward direction and into the gap, px. Default 3 (the visibility
  /// test and the outline's completion leave gaps of a pixel or two between pieces of one
  /// line; 0: no bridging). Where the kind's width is known (width_px), gaps up to that
  /// width + 1.5 px are bridged when that is more: round caps close w px of a gap, so a
  /// wider one shows as a break in the line (the elephant's trunk close up, gaps of
  /// 3.5–3.9 px between pieces of a 2.5-px outline; docs/strokes.md). Gaps up to that width
  /// + 3 px are bridged too where both ends and the gap agree within 30° and no segment of
  /// another run crosses the gap (needs along_px > 0, whose grid of segments answers that).
  float bridge_px = 3.0f;
  /// Default 60°.
  float max_turn_deg = 60.0f;
  /// A run lying within this many pixels of longer runs of its kind all along is not drawn:
  /// it would only thicken that line, or darken it where translucent (on coarse meshes a
  /// short piece of interpolated contour lies along the outline's completing piece). A run of
  /// another kind lying so along contours (within the wider of its and the contour's reach,
  /// whatever the lengths; where contours are drawn, their width known) is not drawn either:
  /// a crease that is also the silhouette, a suggestive contour beside the outline; the
  /// outline is drawn there once, in the contour's style. Default 1.5; 0: every run is drawn.
  float along_px = 1.5f;
  /// A run lying beside one run of its kind at least three times its length, within its
  /// kind's width + burr_px of it all along, is not drawn, unless both its ends lie within a
  /// bridge's reach (the width + 3 px) of other runs' ends, which it then links: close up
  /// on a coarse mesh, dashes of 4–10 px of contour stood 1.5–4.5 px beside the outline,
  /// burrs and ticks on the line, and longer branches of the contour ran beside it, a
  /// doubled line or a lens (docs/strokes.md). Needs the kind's width. Default 2; 0: off.
  float burr_px = 2.0f;
  /// Ends of two runs of a kind that overlap side by side are joined: each end lies at most
  /// this far behind the other, within the reach below (along_px or the kind's width) of
  /// the line through it, and the two run the same way (within max_turn_deg). The run
  /// entered leaves out its points behind the end it is joined to. On a coarse mesh the
  /// interpolated contour and the outline's completing piece overlap so for a few pixels,
  /// a doubled knot in the line. Default 8; 0: no such joins.
  float overlap_px = 8.0f;
  /// Ends of two runs of a kind that meet side by side (the two going the same way within
  /// 15°, one end beside the other, more than touch_px and at most the kind's reach across,
  /// neither behind the other by more than touch_px) are joined, the chain's end bending over
  /// onto the entered run's line over its last max(step_px, 4 × the offset) px: bridged
  /// straight, the stroke stepped across (the cow's back close up, pieces 1.7 px apart).
  /// Both runs must be at least four times this long (a shorter one's direction says little
  /// about its line). Default 3; 0: no such joins.
  float step_px = 3.0f;
  /// A free end of a joined stroke that turns back by over 75° within max(hook_px, 1.5 ×
  /// the kind's width) of its end is cut at the turn, when the run is at least three times
  /// that long: on a coarse mesh a contour's end, where it goes behind the surface at a
  /// cusp, keeps a pixel or two of the turned branch in front of the depth test, a hook on
  /// the line (the elephant close up; docs/strokes.md). Default 2.5; 0: ends kept as found.
  float hook_px = 2.5f;
  /// Per kind, the stroke's width (px; 0: not known). A run counts as lying along a longer
  /// one within max(along_px, its kind's width): two strokes of width w whose centre lines
  /// are under w apart draw one thicker line, a knot where the shorter one lies (the
  /// elephant's trunk close up, dashes 1.9 px beside a 2.5-px contour; docs/strokes.md).
  std::array<float, kLineKindCount> width_px{};
};

/// Appends to `out` the points of run r of `runs` as a path of its own that draws what the
/// joined stroke draws there (the SVG's constant-width paths, which keep one id per run):
/// without the points an overlap join or a hook's cut left out at either end (unbent), and reaching over to
/// the next run where `joined` (joinRuns() of `runs`) goes on to it (a bridged gap, or the
/// step of an overlap join), that piece drawn by the run of the lower end. Nothing for a run
/// left out as lying along another.
void appendRunAlone(const StrokeRuns& runs, const JoinedRuns& joined, size_t r, std::vector<glm::vec2>& out);

/// JoinParams with each kind's width from `style` (enabled kinds; 0 for the others).
JoinParams joinParamsFor(const LineStyles& style);

/// Runs of one kind whose ends meet (JoinParams) joined into one run each, into out.runs
/// (and their parameters into out.u when `u` is given): the visibility test and the
/// outline's completion cut a line into runs that meet end to end, and drawn apart each
/// junction would get two caps (a bead where a translucent stroke overlaps itself) and two
/// tapers (a pinch). A run is reversed where needed; each end joins at most one other (the
/// nearest), so a junction of three keeps one run apart; a run lying along longer ones is
/// left out. Opacity is the length-weighted
/// mean, length the sum (bridges included), the stroke index the first run's
/// (out.first_run: that run's index in `runs`).
void joinRuns(const StrokeRuns& runs, std::span<const float> u, const JoinParams& params, JoinedRuns& out);

/// Fills `out` with the strokes of `visible` (joined where they meet end to end, joinRuns();
/// per kind, in style.lines' colours, widths and
/// stroke styles: profile, dashes, jitter, minimum length; docs/strokes.md) and, when
/// style.hidden is enabled, of `hidden` in the hidden style (its width and colour, dashes of
/// hidden.dash_on pixels every dash_on + dash_off pixels, butt ends). Kinds that are not
/// enabled are left out. `visible_u` (one per point of `visible`, or empty for u = arc
/// length from each run's start) places the brush, dashes and jitter along the runs
/// (present/stroke_parameterization.h).
void buildScreenLines(const StrokeRuns& visible, const StrokeRuns& hidden, const ObjectStyle& style,
                      const StrokeView& view, std::span<const float> visible_u, ScreenLines& out,
                      ScreenLinesScratch& scratch);

}  // namespace lodline
