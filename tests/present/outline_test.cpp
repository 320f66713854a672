// Outline completion on a known answer: a square facing an orthographic camera, with no
// contour drawn, and a piece of the mesh's silhouette along its top edge. A still draws
// every completing piece; in a sequence whose camera moves a new piece shorter than
// min_length_px waits, one that continues the previous frame's goes on, and a long new one
// is drawn at once; when the camera stops, every piece is drawn again.
#include <algorithm>
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "present/outline.h"
#include "present/screen_lines.h"

namespace lodline {
namespace {

constexpr int kSize = 200;  // 200×200 px; the square [-1, 1]² covers pixels 50..150

// `shift` moves the camera sideways (model units; 0.001 is 0.05 px): frames of a sequence
// whose camera moves.
Camera squareCamera(float shift = 0.0f) {
  Camera c;
  c.eye = {shift, 0.0f, 3.0f};
  c.target = {shift, 0.0f, 0.0f};
  c.orthographic = true;
  c.ortho_height = 4.0f;  // 50 px per unit
  c.near_plane = 1.0f;
  c.far_plane = 5.0f;
  return c;
}

// Window depth of the square (plane z = 0, eye depth 3) where it covers, 1 elsewhere.
DepthImage squareDepth() {
  const Camera c = squareCamera();
  DepthImage d;
  d.width = d.height = kSize;
  const float window = (3.0f - c.near_plane) / (c.far_plane - c.near_plane);
  d.depth.assign(static_cast<size_t>(kSize) * kSize, 1.0f);
  for (int y = 50; y < 150; ++y)
    for (int x = 50; x < 150; ++x) d.depth[static_cast<size_t>(y) * kSize + x] = window;
  return d;
}

// One contour run along y (model units) from model x x0 to x1, a point a pixel.
StrokeRuns contourRun(float x0, float x1, float y) {
  StrokeRuns runs;
  runs.offsets = {0};
  const int n = std::max(1, static_cast<int>(std::lround(50.0f * (x1 - x0))));
  for (int i = 0; i <= n; ++i) {
    const float x = x0 + (x1 - x0) * static_cast<float>(i) / static_cast<float>(n);
    runs.points.push_back({100.0f + 50.0f * x, 100.0f - 50.0f * y});
    runs.positions.push_back({x, y, 0.0f});
    runs.alpha.push_back(1.0f);
  }
  runs.offsets.push_back(static_cast<uint32_t>(runs.points.size()));
  runs.kinds.push_back(LineKind::kContour);
  runs.strokes.push_back(0);
  runs.opacity.push_back(1.0f);
  runs.length_px.push_back(50.0f * (x1 - x0));
  return runs;
}

// One silhouette stroke along the square's top edge from x0 to x1 (model units).
StrokeSet topEdge(float x0, float x1) {
  StrokeSet s;
  const int n = 8;
  s.offsets = {0};
  for (int i = 0; i <= n; ++i) {
    s.points.push_back({x0 + (x1 - x0) * static_cast<float>(i) / n, 0.99f, 0.0f});
    s.alpha.push_back(1.0f);
  }
  s.offsets.push_back(static_cast<uint32_t>(s.points.size()));
  s.kinds.push_back(LineKind::kContour);
  s.closed.push_back(0);
  return s;
}

// One frame; with a history, each call moves the camera a little (a sequence in motion)
// unless `at_rest` (the camera of the previous call).
double complete(const StrokeSet& silhouette, OutlineHistory* history, bool at_rest = false) {
  StrokeRuns visible;
  OutlineScratch scratch;
  uint64_t frame = history ? history->frames : 0;
  if (at_rest && frame > 0) --frame;
  const float shift = 0.001f * static_cast<float>(frame);
  return completeOutline(silhouette, squareCamera(shift), squareDepth(), VisibilityParams{}, OutlineParams{},
                         visible, scratch, history);
}

const StrokeSet kShort = topEdge(-0.2f, 0.2f);  // 20 px, under the default 32
const StrokeSet kLong = topEdge(-0.8f, 0.8f);   // 80 px

TEST(Outline, AStillDrawsEveryCompletingPiece) {
  EXPECT_NEAR(complete(kShort, nullptr), 20.0, 3.0);
  OutlineHistory first;  // the first frame of a sequence is drawn like a still
  EXPECT_NEAR(complete(kShort, &first), 20.0, 3.0);
  EXPECT_EQ(first.frames, 1u);
  EXPECT_FALSE(first.fill.empty());
}

TEST(Outline, ACompletingPieceAlongAStraightEdgeIsOneSegment) {
  // Its samples are a pixel apart, but the run keeps only its ends and corners: every point
  // is a joint where a drawn line can lose a row of samples (multisampled GL_LINES).
  StrokeRuns visible;
  OutlineScratch scratch;
  const double len = completeOutline(kLong, squareCamera(), squareDepth(), VisibilityParams{}, OutlineParams{},
                                     visible, scratch);
  EXPECT_NEAR(len, 80.0, 3.0);
  ASSERT_EQ(visible.strokeCount(), 1u);
  EXPECT_EQ(visible.offsets[1] - visible.offsets[0], 2u);
  EXPECT_NEAR(visible.length_px[0], 80.0f, 3.0f);
}

TEST(Outline, InASequenceANewShortPieceWaitsAndALongOneIsDrawn) {
  OutlineHistory h;
  EXPECT_EQ(complete(StrokeSet{}, &h), 0.0);  // frame 0: nothing to complete
  EXPECT_EQ(complete(kShort, &h), 0.0);       // frame 1: a new 20-px piece waits
  EXPECT_TRUE(h.fill.empty());
  EXPECT_NEAR(complete(kLong, &h), 80.0, 3.0);  // frame 2: a new 80-px piece is drawn
}

TEST(Outline, WhenTheCameraStopsEveryPieceIsDrawn) {
  OutlineHistory h;
  EXPECT_EQ(complete(StrokeSet{}, &h), 0.0);
  EXPECT_EQ(complete(kShort, &h), 0.0);  // moving: the new short piece waits
  EXPECT_NEAR(complete(kShort, &h, true), 20.0, 3.0);  // at rest: drawn like a still
  EXPECT_NEAR(complete(kShort, &h), 20.0, 3.0);        // moving again: it continues
}

TEST(Outline, APieceThatContinuesThePreviousFramesGoesOnWhateverItsLength) {
  OutlineHistory h;
  EXPECT_NEAR(complete(kLong, &h), 80.0, 3.0);
  EXPECT_NEAR(complete(kShort, &h), 20.0, 3.0);  // shrunk to 20 px: it continues the 80-px one
  EXPECT_NEAR(complete(kShort, &h), 20.0, 3.0);
  EXPECT_NEAR(complete(topEdge(0.5f, 0.9f), &h), 0.0, 0.0);  // elsewhere on the edge: new, short
}

// A completing piece grown over the end of the contour it continues is cut back to start
// exactly there, so that the two are drawn as one stroke (no overlap: no bead, no pinch).
TEST(Outline, APieceStartsWhereTheContourItContinuesEnds) {
  // The contour draws the top edge's left part, px x 60..90.5 (model x -0.8..-0.19), 0.6 px
  // inside it: the piece grown over its end starts at px 90, beside it.
  StrokeRuns visible;
  visible.offsets = {0};
  for (int i = 0; i <= 30; ++i) {
    const float x = -0.8f + 0.61f * static_cast<float>(i) / 30.0f;
    visible.points.push_back({100.0f + 50.0f * x, 100.0f - 50.0f * 0.978f});
    visible.positions.push_back({x, 0.978f, 0.0f});
    visible.alpha.push_back(1.0f);
  }
  visible.offsets.push_back(static_cast<uint32_t>(visible.points.size()));
  visible.kinds.push_back(LineKind::kContour);
  visible.strokes.push_back(0);
  visible.opacity.push_back(1.0f);
  visible.length_px.push_back(30.5f);
  const glm::vec2 contour_end = visible.points.back();
  OutlineScratch scratch;
  const double len = completeOutline(kLong, squareCamera(), squareDepth(), VisibilityParams{}, OutlineParams{},
                                     visible, scratch);
  // The rest of the edge, to px 140, completed from the contour's end.
  EXPECT_NEAR(len, 49.5, 1.0);
  ASSERT_EQ(visible.strokeCount(), 2u);
  const glm::vec2 piece_start = visible.points[visible.offsets[1]];
  EXPECT_EQ(piece_start, contour_end);
  JoinedRuns joined;
  joinRuns(visible, {}, JoinParams{}, joined);
  EXPECT_EQ(joined.runs.strokeCount(), 1u);
  EXPECT_NEAR(joined.runs.length_px[0], 80.0f, 1.0f);
}

// A contour run off the outline beside a completing piece is dropped however short it is:
// only a short stretch inside a run is kept (cutting it would leave a notch); a whole short
// run left beside the piece would be a burr on the outline.
TEST(Outline, AShortContourRunBesideAPieceIsDropped) {
  OutlineScratch scratch;
  StrokeRuns visible = contourRun(0.0f, 0.04f, 0.9f);  // 2 px long, 4.5 px inside the edge
  const double len = completeOutline(kLong, squareCamera(), squareDepth(), VisibilityParams{}, OutlineParams{},
                                     visible, scratch);
  EXPECT_NEAR(len, 80.0, 3.0);
  ASSERT_EQ(visible.strokeCount(), 1u);  // the piece alone
  EXPECT_NEAR(visible.length_px[0], 80.0f, 3.0f);
}

// A contour run along y(x) (model units), a point a pixel, from x0 to x1.
template <class Y>
StrokeRuns contourAlong(float x0, float x1, Y y) {
  StrokeRuns runs = contourRun(x0, x1, 0.0f);
  for (size_t i = 0; i < runs.points.size(); ++i) {
    const float yi = y(runs.positions[i].x);
    runs.positions[i].y = yi;
    runs.points[i].y = 100.0f - 50.0f * yi;
  }
  return runs;
}

// The silhouette zigzags about the contour by a pixel or two on a coarse mesh: the contour
// draws that outline already, within a line's width, and pieces drawn beside it were ticks.
TEST(Outline, APieceWithinTwoPixelsOfTheContourIsNotDrawn) {
  OutlineScratch scratch;
  // 1.5 px inside the edge (px row 52 against the silhouette's 50.5): no contour pixel
  // within 1 px of the silhouette, so the whole edge is missing, but within 2 px.
  StrokeRuns visible = contourRun(-0.8f, 0.8f, 0.96f);
  const double len = completeOutline(kLong, squareCamera(), squareDepth(), VisibilityParams{}, OutlineParams{},
                                     visible, scratch);
  EXPECT_EQ(len, 0.0);
  ASSERT_EQ(visible.strokeCount(), 1u);  // the contour alone
  EXPECT_NEAR(visible.length_px[0], 80.0f, 1.0f);
  // With the rules off, the same edge is drawn a second time beside the contour.
  OutlineParams off;
  off.splice_radius_px = 0.0f;
  StrokeRuns again = contourRun(-0.8f, 0.8f, 0.96f);
  EXPECT_GT(completeOutline(kLong, squareCamera(), squareDepth(), VisibilityParams{}, off, again, scratch), 70.0);
}

// A polygon corner that the contour cuts by 3 px: the contour run takes the silhouette's way
// there (one stroke), instead of a piece drawn beside it (a bump with two caps).
TEST(Outline, AShortPieceBesideOneContourRunIsSplicedIntoIt) {
  auto dip = [](float x) { return std::abs(x) < 0.1f ? 0.93f : 0.975f; };  // 3 px and 0.75 px inside
  OutlineScratch scratch;
  StrokeRuns visible = contourAlong(-0.8f, 0.8f, dip);
  const double len = completeOutline(kLong, squareCamera(), squareDepth(), VisibilityParams{}, OutlineParams{},
                                     visible, scratch);
  EXPECT_GT(len, 8.0);
  EXPECT_LT(len, 20.0);
  ASSERT_EQ(visible.strokeCount(), 1u);
  float top = 1e9f;
  for (uint32_t i = visible.offsets[0]; i < visible.offsets[1]; ++i) top = std::min(top, visible.points[i].y);
  EXPECT_LT(top, 51.0f);  // on the silhouette (row 50.5), not 3 px inside it
  // Without splicing: the run and a piece beside it.
  OutlineParams off;
  off.splice_max_px = 0.0f;
  StrokeRuns again = contourAlong(-0.8f, 0.8f, dip);
  completeOutline(kLong, squareCamera(), squareDepth(), VisibilityParams{}, off, again, scratch);
  EXPECT_GE(again.strokeCount(), 2u);
}

// The same with the run drawn the other way: the piece is spliced in the run's direction.
TEST(Outline, ASplicedPieceFollowsTheRunsDirection) {
  auto dip = [](float x) { return std::abs(x) < 0.1f ? 0.93f : 0.975f; };
  StrokeRuns visible = contourAlong(-0.8f, 0.8f, dip);
  std::reverse(visible.points.begin(), visible.points.end());
  std::reverse(visible.positions.begin(), visible.positions.end());
  OutlineScratch scratch;
  completeOutline(kLong, squareCamera(), squareDepth(), VisibilityParams{}, OutlineParams{}, visible, scratch);
  ASSERT_EQ(visible.strokeCount(), 1u);
  float top = 1e9f;
  for (uint32_t i = visible.offsets[0]; i < visible.offsets[1]; ++i) {
    top = std::min(top, visible.points[i].y);
    if (i > visible.offsets[0]) {
      EXPECT_LT(visible.points[i].x, visible.points[i - 1].x + 0.5f);
    }
  }
  EXPECT_LT(top, 51.0f);
}

// A piece closing the gap of a nearly closed contour run has its two ends beside the run's
// two ends, but the run goes elsewhere in between: it is not a corner to splice (splicing
// would replace the whole run by the piece).
TEST(Outline, APieceClosingARunsGapIsNotSplicedOverTheRun) {
  // From x 0.2 right along the edge (0.75 px inside), down 9.5 px, back left 4.75 px
  // under the edge to x -0.2, and up to the edge again: a 20-px gap at the top.
  StrokeRuns visible;
  visible.offsets = {0};
  auto add = [&](float x, float y) {
    visible.points.push_back({100.0f + 50.0f * x, 100.0f - 50.0f * y});
    visible.positions.push_back({x, y, 0.0f});
    visible.alpha.push_back(1.0f);
  };
  for (int i = 0; i <= 5; ++i) add(0.2f + 0.02f * static_cast<float>(i), 0.975f);
  for (int i = 1; i <= 9; ++i) add(0.3f, 0.975f - 0.02f * static_cast<float>(i));
  for (int i = 1; i <= 25; ++i) add(0.3f - 0.02f * static_cast<float>(i), 0.795f);
  for (int i = 1; i <= 9; ++i) add(-0.2f, 0.795f + 0.02f * static_cast<float>(i));
  visible.offsets.push_back(static_cast<uint32_t>(visible.points.size()));
  visible.kinds.push_back(LineKind::kContour);
  visible.strokes.push_back(0);
  visible.opacity.push_back(1.0f);
  visible.length_px.push_back(48.0f);
  OutlineScratch scratch;
  completeOutline(topEdge(-0.25f, 0.25f), squareCamera(), squareDepth(), VisibilityParams{}, OutlineParams{},
                  visible, scratch);
  float total = 0.0f;
  for (float l : visible.length_px) total += l;
  EXPECT_GT(total, 45.0f);  // the run's bottom (25 px) stays beside the piece (about 20)
}

// A few pixels of silhouette that leave the contour in the middle of a run and end beside no
// line are a spur on the outline, not a piece of it.
TEST(Outline, AShortSpurFromTheMiddleOfAContourRunIsNotDrawn) {
  StrokeSet spur;  // straight up from the top edge's middle, 5 px out of the square
  spur.offsets = {0};
  for (int i = 0; i <= 4; ++i) {
    spur.points.push_back({0.0f, 0.99f + 0.025f * static_cast<float>(i), 0.0f});
    spur.alpha.push_back(1.0f);
  }
  spur.offsets.push_back(static_cast<uint32_t>(spur.points.size()));
  spur.kinds.push_back(LineKind::kContour);
  spur.closed.push_back(0);
  OutlineScratch scratch;
  StrokeRuns visible = contourRun(-0.8f, 0.8f, 0.985f);  // on the edge
  EXPECT_EQ(completeOutline(spur, squareCamera(), squareDepth(), VisibilityParams{}, OutlineParams{}, visible,
                            scratch),
            0.0);
  EXPECT_EQ(visible.strokeCount(), 1u);
  // Near the run's end it goes on from the contour (the outline continues past it): drawn.
  StrokeRuns short_run = contourRun(-0.8f, 0.02f, 0.985f);
  EXPECT_GT(completeOutline(spur, squareCamera(), squareDepth(), VisibilityParams{}, OutlineParams{}, short_run,
                            scratch),
            2.0);
  OutlineParams off;
  off.spur_max_px = 0.0f;
  StrokeRuns again = contourRun(-0.8f, 0.8f, 0.985f);
  EXPECT_GT(completeOutline(spur, squareCamera(), squareDepth(), VisibilityParams{}, off, again, scratch), 2.0);
}

// A silhouette stroke along y (model units) from x0 to x1.
StrokeSet silhouetteAlong(float x0, float x1, float y) {
  StrokeSet s = topEdge(x0, x1);
  for (glm::vec3& p : s.points) p.y = y;
  return s;
}

StrokeSet bothOf(const StrokeSet& a, const StrokeSet& b) {
  StrokeSet s = a;
  for (size_t k = 0; k < b.points.size(); ++k) {
    s.points.push_back(b.points[k]);
    s.alpha.push_back(b.alpha[k]);
  }
  s.offsets.push_back(static_cast<uint32_t>(s.points.size()));
  s.kinds.push_back(b.kinds[0]);
  s.closed.push_back(0);
  return s;
}

// A fold of a coarse mesh lays silhouette edges over one another a pixel apart: the outline
// is drawn once, not as a thick double line.
TEST(Outline, APieceOverAnEarlierOneIsDrawnOnce) {
  const StrokeSet folded = bothOf(kLong, silhouetteAlong(-0.8f, 0.8f, 0.975f));  // 0.75 px apart
  OutlineScratch scratch;
  StrokeRuns visible;
  EXPECT_NEAR(completeOutline(folded, squareCamera(), squareDepth(), VisibilityParams{}, OutlineParams{}, visible,
                              scratch),
              80.0, 3.0);
  EXPECT_EQ(visible.strokeCount(), 1u);
  OutlineParams off;
  off.covered_px = 0.0f;
  StrokeRuns again;
  completeOutline(folded, squareCamera(), squareDepth(), VisibilityParams{}, off, again, scratch);
  EXPECT_EQ(again.strokeCount(), 2u);
}

// A dash of contour on a fold's silhouette, 2 px beside the piece that draws the outline:
// left to the piece (drawn, the two were one thick line).
TEST(Outline, AContourDashBesideAPieceIsLeftToThePiece) {
  // The outline's edge (px row 50.5) and a short fold edge 2 px in (row 51.5), with the dash
  // on the fold (row 52.5): the dash is on the outline (the fold's), the edge's piece passes
  // 2 px from it.
  const StrokeSet silhouette = bothOf(kLong, silhouetteAlong(0.0f, 0.1f, 0.97f));
  OutlineScratch scratch;
  StrokeRuns visible = contourRun(0.0f, 0.1f, 0.95f);
  completeOutline(silhouette, squareCamera(), squareDepth(), VisibilityParams{}, OutlineParams{}, visible, scratch);
  ASSERT_EQ(visible.strokeCount(), 1u);  // the piece alone
  EXPECT_NEAR(visible.length_px[0], 80.0f, 3.0f);
  OutlineParams off;
  off.covered_px = 0.0f;
  StrokeRuns again = contourRun(0.0f, 0.1f, 0.95f);
  completeOutline(silhouette, squareCamera(), squareDepth(), VisibilityParams{}, off, again, scratch);
  EXPECT_EQ(again.strokeCount(), 2u);
}

// `to` with the strokes of `from` appended.
StrokeSet withStrokes(StrokeSet to, const StrokeSet& from) {
  for (size_t k = 0; k < from.strokeCount(); ++k) {
    to.points.insert(to.points.end(), from.points.begin() + from.offsets[k], from.points.begin() + from.offsets[k + 1]);
    to.alpha.insert(to.alpha.end(), from.alpha.begin() + from.offsets[k], from.alpha.begin() + from.offsets[k + 1]);
    to.offsets.push_back(static_cast<uint32_t>(to.points.size()));
    to.kinds.push_back(from.kinds[k]);
    to.closed.push_back(from.closed[k]);
  }
  return to;
}

// Two silhouette strokes along the square's top edge, [x0, x1] and [x2, x3] (model units),
// with the edge between them not part of the silhouette (hidden, or turning elsewhere).
StrokeSet topEdgeInTwo(float x0, float x1, float x2, float x3) { return withStrokes(topEdge(x0, x1), topEdge(x2, x3)); }

// A contour that ends a few pixels short of where a completing piece starts, the gap lying
// along the outline (the cow's neck meeting its chest close up): the piece is carried on to
// the contour's end, so the outline does not break there. Not across a gap that leaves the
// outline, nor with the rule off.
TEST(Outline, APieceIsCarriedAcrossAShortGapAlongTheOutlineToTheContoursEnd) {
  // The contour draws the top edge from px x 60 to 120, 0.6 px inside it.
  auto contour = [] { return contourRun(-0.8f, 0.4f, 0.978f); };
  auto complete = [&](const StrokeSet& sil, const OutlineParams& params, glm::vec2& piece_start) {
    StrokeRuns visible = contour();
    OutlineScratch scratch;
    completeOutline(sil, squareCamera(), squareDepth(), VisibilityParams{}, params, visible, scratch);
    EXPECT_EQ(visible.strokeCount(), 2u);
    piece_start = visible.strokeCount() == 2 ? visible.points[visible.offsets[1]] : glm::vec2(0.0f);
    return visible.points[visible.offsets[1] - 1];  // the contour's end
  };
  // The silhouette along the contour to px 121, then from px 124.5 to 140: the second is
  // the piece; it starts 4.5 px from the contour's end, beyond the stitch's 1.5.
  const StrokeSet sil = topEdgeInTwo(-0.8f, 0.42f, 0.49f, 0.8f);
  glm::vec2 start;
  const glm::vec2 contour_end = complete(sil, OutlineParams{}, start);
  EXPECT_EQ(start, contour_end);
  // With the rule off, the piece starts where its silhouette does.
  OutlineParams off;
  off.corner_gap_px = 0.0f;
  complete(sil, off, start);
  EXPECT_NEAR(start.x, 124.5f, 0.6f);
  // A piece down the square's right edge, from 2 px below its top corner: the contour's end
  // (px 146, 0.6 px inside the top edge) is 3.6 px away along the outline, but the gap turns
  // the piece by 75°, and nothing is carried across it.
  StrokeSet down = topEdge(0.0f, 0.8f);  // turned down the right edge, from y 0.96 to 0.16
  for (size_t i = 0; i < down.points.size(); ++i) down.points[i] = {0.99f, 0.96f - 0.1f * static_cast<float>(i), 0.0f};
  const StrokeSet corner = withStrokes(topEdge(-0.8f, 0.92f), down);
  StrokeRuns visible = contourRun(-0.8f, 0.92f, 0.978f);
  OutlineScratch scratch;
  completeOutline(corner, squareCamera(), squareDepth(), VisibilityParams{}, OutlineParams{}, visible, scratch);
  ASSERT_EQ(visible.strokeCount(), 2u);
  EXPECT_NEAR(visible.points[visible.offsets[1]].y, 52.0f, 0.6f);  // the piece's start, as it was
}

// Pixel runs for takeOverContourEnds(): a polyline of pixels (model positions alongside).
StrokeRuns pixelRun(std::initializer_list<glm::vec2> pts) {
  StrokeRuns runs;
  runs.offsets = {0};
  float length = 0.0f;
  for (const glm::vec2 p : pts) {
    if (!runs.points.empty()) length += glm::length(p - runs.points.back());
    runs.points.push_back(p);
    runs.positions.push_back({p.x, p.y, 0.0f});
    runs.alpha.push_back(1.0f);
  }
  runs.offsets.push_back(static_cast<uint32_t>(runs.points.size()));
  runs.kinds.push_back(LineKind::kContour);
  runs.strokes.push_back(0);
  runs.opacity.push_back(1.0f);
  runs.length_px.push_back(length);
  return runs;
}

// Distance from q to the polyline of run r.
float distanceToRun(const StrokeRuns& runs, size_t r, glm::vec2 q) {
  float best = std::numeric_limits<float>::infinity();
  for (uint32_t k = runs.offsets[r]; k + 1 < runs.offsets[r + 1]; ++k) {
    const glm::vec2 a = runs.points[k], ab = runs.points[k + 1] - a;
    const float t = std::clamp(glm::dot(q - a, ab) / glm::dot(ab, ab), 0.0f, 1.0f);
    best = std::min(best, glm::length(q - (a + t * ab)));
  }
  return best;
}

// A piece whose end runs beside the start of a contour run, 3 px from it converging to
// 1.4 px over 20 px (the cow's neck close up: a doubled line), takes that stretch over: the
// contour is cut where it is nearest the piece's end and bends onto it over its first part
// only (the piece stays on the outline), and the two join into one stroke with no second
// line.
TEST(Outline, APieceEndBesideAContourRunsStartTakesTheStretchOver) {
  const StrokeRuns piece = pixelRun({{60.0f, 50.0f}, {120.0f, 50.0f}});
  // The contour: 3 px below the piece at x = 100, 1.4 px at x = 120, on along 51.4 to x = 200.
  const StrokeRuns contour = pixelRun({{100.0f, 53.0f}, {120.0f, 51.4f}, {200.0f, 51.4f}});
  OutlineParams params;
  StrokeRuns out;
  takeOverContourEnds(contour, piece, params, out);
  ASSERT_EQ(out.strokeCount(), 1u);
  const uint32_t n = out.offsets[1];
  EXPECT_EQ(out.points[0], piece.points[1]);  // it starts at the piece's end
  // Bent over its first part only: from max(3, 8 × 1.4) px on (to the next point at x = 200,
  // the stretch being straight), back on the line it was, and no point turns by more than
  // a few degrees.
  EXPECT_EQ(out.points[n - 1], contour.points[2]);
  for (uint32_t k = 0; k < n; ++k) {
    EXPECT_GE(out.points[k].x, 119.9f);  // nothing of the stretch beside the piece is left
    EXPECT_GE(out.points[k].y, 50.0f);
    EXPECT_LE(out.points[k].y, 51.4f);
  }
  for (uint32_t k = 1; k + 1 < n; ++k) {
    const glm::vec2 a = glm::normalize(out.points[k] - out.points[k - 1]);
    const glm::vec2 b = glm::normalize(out.points[k + 1] - out.points[k]);
    EXPECT_GT(glm::dot(a, b), std::cos(5.0f * 3.14159265f / 180.0f));
  }
  StrokeRuns all = out;
  appendStrokes(piece, all);
  JoinedRuns joined;
  joinRuns(all, {}, JoinParams{}, joined);
  ASSERT_EQ(joined.runs.strokeCount(), 1u);
  EXPECT_NEAR(joined.runs.length_px[0], 140.0f, 1.0f);
  // Every point of the input contour lies within 3 px of the joined stroke: no stretch lost.
  for (const glm::vec2 q : contour.points) EXPECT_LE(distanceToRun(joined.runs, 0, q), 3.0f);
}

// What is left as it was: ends the stitch meets (within 1.5 px), a contour that turns away
// from the piece, a contour farther than overlap_radius_px, a stretch longer than half the
// piece, and everything with the rule off.
TEST(Outline, OnlyAContourEndRunningBesideAPieceIsTakenOver) {
  const StrokeRuns piece = pixelRun({{60.0f, 50.0f}, {120.0f, 50.0f}});
  auto unchanged = [&](const StrokeRuns& fill, const StrokeRuns& contour, const OutlineParams& params) {
    StrokeRuns out;
    takeOverContourEnds(contour, fill, params, out);
    return out.points == contour.points;
  };
  const OutlineParams defaults;
  // Within 1.5 px of the piece's end: the stitch's.
  EXPECT_TRUE(unchanged(piece, pixelRun({{118.0f, 51.0f}, {160.0f, 51.0f}}), defaults));
  // Starts 3 px beside the piece but turns away from it.
  EXPECT_TRUE(unchanged(piece, pixelRun({{100.0f, 53.0f}, {110.0f, 70.0f}}), defaults));
  // 5 px beside it all along.
  EXPECT_TRUE(unchanged(piece, pixelRun({{100.0f, 55.0f}, {120.0f, 54.5f}, {160.0f, 54.5f}}), defaults));
  // The stretch (20 px) is more than half of a 30-px piece.
  EXPECT_TRUE(unchanged(pixelRun({{90.0f, 50.0f}, {120.0f, 50.0f}}),
                        pixelRun({{100.0f, 53.0f}, {120.0f, 51.4f}, {160.0f, 51.4f}}), defaults));
  OutlineParams off;
  off.overlap_radius_px = 0.0f;
  const StrokeRuns contour = pixelRun({{100.0f, 53.0f}, {120.0f, 51.4f}, {160.0f, 51.4f}});
  EXPECT_FALSE(unchanged(piece, contour, defaults));
  EXPECT_TRUE(unchanged(piece, contour, off));
}

}  // namespace
}  // namespace lodline
