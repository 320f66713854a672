// Stroke geometry (present/stroke_geometry.h) drawn by the software renderer: the ink a
// stroke leaves is its width × its length (plus its caps), a stroke never leaves a gap where
// its centre line passes and never spills far from it, and a translucent stroke blends each
// pixel once where its joins are mitred.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "present/screen_lines.h"
#include "present/stroke_geometry.h"
#include "raster/soft_renderer.h"

namespace lodline {
namespace {

constexpr int kW = 160, kH = 120;

// Ink (1 = black) of each pixel after drawing `points` in black at `opacity` on white.
std::vector<float> draw(const std::vector<glm::vec2>& points, float width, const StrokeGeometryParams& params,
                        float opacity = 1.0f, size_t* segments = nullptr) {
  std::vector<StrokeVertex> v;
  StrokeGeometryScratch scratch;
  const std::vector<float> alpha(points.size(), 1.0f);
  const std::vector<float> widths(points.size(), width);
  const size_t n = appendStrokeGeometry(points, alpha, widths, {}, params, v, scratch);
  if (segments) *segments = n;
  Image img(kW, kH);
  std::fill(img.rgba.begin(), img.rgba.end(), 255);
  WorkerPool pool(2);
  drawStrokeTriangles(v, glm::vec4(0.0f, 0.0f, 0.0f, opacity), nullptr, img, pool);
  std::vector<float> ink(static_cast<size_t>(kW) * kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) ink[static_cast<size_t>(y) * kW + x] = 1.0f - img.pixel(x, y)[0] / 255.0f;
  return ink;
}

double total(const std::vector<float>& ink) {
  double s = 0.0;
  for (float i : ink) s += i;
  return s;
}

float distanceToPolyline(glm::vec2 p, const std::vector<glm::vec2>& line) {
  float best = std::numeric_limits<float>::max();
  for (size_t i = 0; i + 1 < line.size(); ++i) {
    const glm::vec2 a = line[i], ab = line[i + 1] - a;
    const float t = std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0f, 1.0f);
    best = std::min(best, glm::length(p - (a + t * ab)));
  }
  return best;
}

StrokeGeometryParams withCap(StrokeCap cap) {
  StrokeGeometryParams p;
  p.cap = cap;
  return p;
}

TEST(StrokeGeometry, InkIsWidthTimesLengthPlusCaps) {
  // A slanted stroke 100 px long through many collinear samples (simplified to one segment).
  std::vector<glm::vec2> line;
  const glm::vec2 a(20.3f, 30.7f), d = glm::normalize(glm::vec2(0.8f, 0.6f));
  for (int i = 0; i <= 100; ++i) line.push_back(a + static_cast<float>(i) * d);
  for (float w : {1.0f, 2.5f, 4.0f}) {
    size_t segments = 0;
    const double butt = total(draw(line, w, withCap(StrokeCap::kButt), 1.0f, &segments));
    EXPECT_EQ(segments, 1u);
    EXPECT_NEAR(butt, 101.0 * w, 0.02 * 101.0 * w) << w;  // half a pixel more at each end
    const double round = total(draw(line, w, withCap(StrokeCap::kRound)));
    EXPECT_NEAR(round, 100.0 * w + std::numbers::pi * w * w / 4.0, 0.02 * 100.0 * w) << w;
    const double square = total(draw(line, w, withCap(StrokeCap::kSquare)));
    EXPECT_NEAR(square, 100.0 * w + w * w, 0.02 * 100.0 * w) << w;
  }
  // Under a pixel wide: drawn 1 px wide with the width as opacity, so the ink is the same.
  EXPECT_NEAR(total(draw(line, 0.5f, withCap(StrokeCap::kButt))), 101.0 * 0.5, 0.02 * 50.5);
}

TEST(StrokeGeometry, ADotIsADisc) {
  const std::vector<glm::vec2> dot = {{50.2f, 40.6f}};
  EXPECT_NEAR(total(draw(dot, 6.0f, withCap(StrokeCap::kRound))), std::numbers::pi * 9.0, 0.03 * 28.3);
  EXPECT_NEAR(total(draw(dot, 6.0f, withCap(StrokeCap::kSquare))), 36.0, 0.03 * 36.0);
  EXPECT_EQ(total(draw(dot, 6.0f, withCap(StrokeCap::kButt))), 0.0);
}

// Every pixel whose centre is within half the width (less the coverage ramp and the
// simplification's 0.25 px) of the centre line is fully inked, whatever the turns; with
// round joins nothing is inked beyond half the width plus the ramp.
TEST(StrokeGeometry, NoGapsAlongTheCentreLineAndNoSpill) {
  std::vector<std::vector<glm::vec2>> lines;
  std::vector<glm::vec2> circle;  // radius 30, a sample every ~1 px (mitred joins)
  for (int i = 0; i <= 190; ++i) {
    const float t = 2.0f * std::numbers::pi_v<float> * static_cast<float>(i) / 190.0f;
    circle.push_back(glm::vec2(80.0f, 60.0f) + 30.0f * glm::vec2(std::cos(t), std::sin(t)));
  }
  lines.push_back(circle);
  // A zigzag turning by 150 degrees at every corner (round joins).
  lines.push_back({{20, 20}, {60, 30.7f}, {20, 41.4f}, {60, 52.1f}, {20, 62.8f}});
  // A right-angle turn (mitred) and a hairpin.
  lines.push_back({{30.5f, 100.2f}, {120.5f, 100.2f}, {120.5f, 20.6f}, {118.5f, 60.3f}});
  const float w = 3.0f, hw = 1.5f;
  for (size_t l = 0; l < lines.size(); ++l) {
    const std::vector<float> ink = draw(lines[l], w, withCap(StrokeCap::kRound));
    int misses = 0, spills = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const float d = distanceToPolyline({x + 0.5f, y + 0.5f}, lines[l]);
        const float i = ink[static_cast<size_t>(y) * kW + x];
        if (d <= hw - 0.5f - 0.26f && i < 0.99f) ++misses;
        // Mitred joins reach past the round outline (up to the miter limit); only lines 0
        // and 1 have no mitre longer than 0.1 px past it.
        if (l < 2 && d >= hw + 0.5f + 0.26f + 0.1f && i > 0.0f) ++spills;
      }
    EXPECT_EQ(misses, 0) << "line " << l;
    EXPECT_EQ(spills, 0) << "line " << l;
  }
}

// A translucent stroke with mitred joins covers each pixel once: nowhere darker than its
// opacity (a strip of separate segments would double up at every joint).
TEST(StrokeGeometry, TranslucentMitredStrokesBlendOnce) {
  std::vector<glm::vec2> circle;  // three quarters (a closed loop would meet its own cap)
  for (int i = 0; i <= 45; ++i) {
    const float t = 2.0f * std::numbers::pi_v<float> * static_cast<float>(i) / 60.0f;
    circle.push_back(glm::vec2(80.0f, 60.0f) + 40.0f * glm::vec2(std::cos(t), std::sin(t)));
  }
  for (const auto& line : {circle, std::vector<glm::vec2>{{20.5f, 20.5f}, {100.5f, 20.5f}, {100.5f, 100.5f}}}) {
    const std::vector<float> ink = draw(line, 5.0f, withCap(StrokeCap::kButt), 0.5f);
    float darkest = 0.0f;
    for (float i : ink) darkest = std::max(darkest, i);
    EXPECT_NEAR(darkest, 0.5f, 0.01f);
  }
}

TEST(StrokeGeometry, NonFinitePointsAreDroppedAndNothingIsWrittenForNoWidth) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<glm::vec2> line = {{10, 10}, {nan, 5}, {50, 10}};
  std::vector<StrokeVertex> v;
  StrokeGeometryScratch scratch;
  const std::vector<float> alpha(3, 1.0f);
  EXPECT_EQ(appendStrokeGeometry(line, alpha, std::vector<float>(3, 2.0f), {}, {}, v, scratch), 1u);
  for (const StrokeVertex& s : v) ASSERT_TRUE(std::isfinite(s.px.x) && std::isfinite(s.px.y));
  EXPECT_GT(total(draw(line, 2.0f, {})), 80.0);
  v.clear();
  EXPECT_EQ(appendStrokeGeometry(line, alpha, std::vector<float>(3, 0.0f), {}, {}, v, scratch), 0u);
  EXPECT_EQ(appendStrokeGeometry(line, alpha, std::vector<float>(3, nan), {}, {}, v, scratch), 0u);
  EXPECT_TRUE(v.empty());
}

// A run along y = 40.5 from x = 20 to 120, sampled every pixel, of `kind`.
StrokeRuns straightRun(LineKind kind = LineKind::kContour, float length = 100.0f) {
  StrokeRuns r;
  r.offsets.push_back(0);
  for (int i = 0; i <= static_cast<int>(length); ++i) {
    r.points.push_back({20.0f + static_cast<float>(i), 40.5f});
    r.positions.push_back(glm::vec3(static_cast<float>(i), 0.0f, 0.0f));
    r.alpha.push_back(1.0f);
  }
  r.offsets.push_back(static_cast<uint32_t>(r.points.size()));
  r.kinds.push_back(kind);
  r.strokes.push_back(0);
  r.opacity.push_back(1.0f);
  r.length_px.push_back(length);
  return r;
}

// `runs` as contours in `style`, drawn in `colour` (with the style's brush when `brushed`)
// over white by the software renderer.
Image drawContours(const StrokeRuns& runs, const ObjectStyle& style, glm::vec4 colour, bool brushed) {
  ScreenLines lines;
  ScreenLinesScratch scratch;
  buildScreenLines(runs, StrokeRuns{}, style, StrokeView{}, {}, lines, scratch);
  Image img(kW, kH);
  std::fill(img.rgba.begin(), img.rgba.end(), 255);
  WorkerPool pool(2);
  drawStrokeTriangles(std::span(lines.vertices).subspan(lines.first[0], lines.count[0]), colour,
                      brushed ? style.lines[LineKind::kContour].stroke.brush.get() : nullptr, img, pool);
  return img;
}

// Ink per column of `runs` drawn in `style` (contours only, in black).
std::vector<double> columnInk(const StrokeRuns& runs, const ObjectStyle& style, Image* brushless = nullptr) {
  const Image img = drawContours(runs, style, glm::vec4(0, 0, 0, 1), true);
  if (brushless) *brushless = img;
  std::vector<double> ink(kW, 0.0);
  for (int x = 0; x < kW; ++x)
    for (int y = 0; y < kH; ++y) ink[x] += 1.0 - img.pixel(x, y)[0] / 255.0;
  return ink;
}

ObjectStyle contourStyle(float width) {
  ObjectStyle s;
  for (auto& k : s.lines.kinds) k.enabled = false;
  s.lines[LineKind::kContour].enabled = true;
  s.lines[LineKind::kContour].color = {0, 0, 0, 1};
  s.lines[LineKind::kContour].width_px = width;
  return s;
}

TEST(StrokeStyles, TaperThinsTheEnds) {
  ObjectStyle style = contourStyle(4.0f);
  style.lines[LineKind::kContour].stroke.taper_in_px = 20.0f;
  style.lines[LineKind::kContour].stroke.taper_out_px = 30.0f;
  style.lines[LineKind::kContour].stroke.taper_min = 0.1f;
  const std::vector<double> ink = columnInk(straightRun(), style);
  EXPECT_NEAR(ink[70], 4.0, 0.1);                 // the middle: full width
  EXPECT_LT(ink[22], 0.35 * 4.0);                 // 2 px from the start
  EXPECT_NEAR(ink[30], 4.0 * (0.1 + 0.9 * 0.5), 0.4);  // halfway up the taper in (smoothstep 0.5)
  EXPECT_LT(ink[118], 0.35 * 4.0);                // 2 px from the end
  EXPECT_GT(ink[105], ink[112]);                  // thinning towards the end
}

TEST(StrokeStyles, DashesMinimumLengthAndStrengthOpacity) {
  ObjectStyle style = contourStyle(2.0f);
  style.lines[LineKind::kContour].stroke.cap = StrokeCap::kButt;
  style.lines[LineKind::kContour].stroke.dash_on = 6.0f;
  style.lines[LineKind::kContour].stroke.dash_off = 4.0f;
  const std::vector<double> ink = columnInk(straightRun(), style);
  int dashes = 0;
  for (int x = 1; x < kW; ++x) dashes += ink[x] > 1.0 && ink[x - 1] <= 1.0;
  EXPECT_EQ(dashes, 10);  // 100 px at a 10 px period
  EXPECT_LT(ink[20 + 8], 0.05);  // inside the first gap [6, 10)
  EXPECT_NEAR(ink[20 + 3], 2.0, 0.05);

  ObjectStyle shortest = contourStyle(2.0f);
  shortest.lines[LineKind::kContour].stroke.min_length_px = 12.0f;
  ScreenLines lines;
  ScreenLinesScratch scratch;
  buildScreenLines(straightRun(LineKind::kContour, 10.0f), StrokeRuns{}, shortest, StrokeView{}, {}, lines, scratch);
  EXPECT_EQ(lines.count[0], 0u);
  buildScreenLines(straightRun(LineKind::kContour, 14.0f), StrokeRuns{}, shortest, StrokeView{}, {}, lines, scratch);
  EXPECT_GT(lines.count[0], 0u);

  // A weak line (strength 0.4): opacity 0.4 with the default strength_opacity 1, full with 0.
  StrokeRuns weak = straightRun();
  std::fill(weak.alpha.begin(), weak.alpha.end(), 0.4f);
  EXPECT_NEAR(columnInk(weak, contourStyle(2.0f))[70], 0.8, 0.05);
  ObjectStyle full = contourStyle(2.0f);
  full.lines[LineKind::kContour].stroke.strength_opacity = 0.0f;
  full.lines[LineKind::kContour].stroke.strength_thickness = 0.5f;  // and 1 - 0.5 * 0.6 = 0.7 of the width
  EXPECT_NEAR(columnInk(weak, full)[70], 1.4, 0.05);
}

TEST(StrokeStyles, BrushInkFollowsTheArcLength) {
  // A brush of one period 10 px: ink in its first half, none in its second.
  auto brush = std::make_shared<Image>(10, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 10; ++x) {
      uint8_t* p = brush->pixel(x, y);
      p[0] = p[1] = p[2] = x < 5 ? 255 : 0;
      p[3] = 255;
    }
  ObjectStyle style = contourStyle(3.0f);
  style.lines[LineKind::kContour].stroke.cap = StrokeCap::kButt;
  style.lines[LineKind::kContour].stroke.brush = brush;
  const std::vector<double> ink = columnInk(straightRun(), style);
  // Column x has arc length x - 20 + 0.5 at its centre: inked where that is in [k·10 + 1, k·10 + 4).
  for (int k = 0; k < 9; ++k) {
    EXPECT_NEAR(ink[20 + 10 * k + 2], 3.0, 0.1) << k;
    EXPECT_LT(ink[20 + 10 * k + 7], 0.1) << k;
  }
}

// Runs from (x0, y) to (x1, y), one point per pixel.
void addRun(StrokeRuns& r, glm::vec2 a, glm::vec2 b, LineKind kind = LineKind::kContour) {
  if (r.offsets.empty()) r.offsets.push_back(0);
  const int n = std::max(1, static_cast<int>(glm::length(b - a)));
  for (int i = 0; i <= n; ++i) {
    const float t = static_cast<float>(i) / static_cast<float>(n);
    r.points.push_back(a + t * (b - a));
    r.positions.push_back(glm::vec3(a + t * (b - a), 0.0f));
    r.alpha.push_back(1.0f);
  }
  r.offsets.push_back(static_cast<uint32_t>(r.points.size()));
  r.kinds.push_back(kind);
  r.strokes.push_back(static_cast<uint32_t>(r.kinds.size() - 1));
  r.opacity.push_back(1.0f);
  r.length_px.push_back(glm::length(b - a));
}

// The darkest red level of `runs` drawn as contours 4 px wide in half-opaque black over
// white (127.5 where strokes blend once, about 64 where two overlap).
int darkestHalfOpaque(const StrokeRuns& runs) {
  ObjectStyle style = contourStyle(4.0f);
  style.lines[LineKind::kContour].color = {0, 0, 0, 0.5f};
  const Image img = drawContours(runs, style, style.lines[LineKind::kContour].color, false);
  int darkest = 255;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) darkest = std::min<int>(darkest, img.pixel(x, y)[0]);
  return darkest;
}

// smoothRuns() smooths each run by its own kind's style: a zig-zag contour (±0.4 px every
// 5 px, as face crossings lie on a coarse mesh) comes out within 0.1 px of straight, with
// its length updated and its ends kept; a suggestive run whose style says 0 stays as it was.
TEST(StrokeStyles, RunsAreSmoothedByTheirKindsStyle) {
  StrokeRuns runs;
  runs.offsets.push_back(0);
  for (LineKind kind : {LineKind::kContour, LineKind::kSuggestive}) {
    float length = 0.0f;
    for (int i = 0; i <= 24; ++i) {
      runs.points.push_back({20.0f + 5.0f * static_cast<float>(i), 40.0f + (i % 2 ? 0.4f : -0.4f)});
      runs.positions.push_back(glm::vec3(static_cast<float>(i), 0.0f, 0.0f));
      runs.alpha.push_back(1.0f);
      if (i > 0) length += glm::length(runs.points.back() - runs.points[runs.points.size() - 2]);
    }
    runs.offsets.push_back(static_cast<uint32_t>(runs.points.size()));
    runs.kinds.push_back(kind);
    runs.strokes.push_back(0);
    runs.opacity.push_back(1.0f);
    runs.length_px.push_back(length);
  }
  const StrokeRuns before = runs;
  ObjectStyle style;
  style.lines[LineKind::kSuggestive].stroke.smoothing_px = 0.0f;
  StrokeCurveScratch scratch;
  smoothRuns(runs, style.lines, scratch);
  EXPECT_EQ(runs.points.front(), before.points.front());
  EXPECT_EQ(runs.points[24], before.points[24]);
  for (int i = 3; i <= 21; ++i) EXPECT_NEAR(runs.points[static_cast<size_t>(i)].y, 40.0f, 0.1f) << i;
  EXPECT_LT(runs.length_px[0], before.length_px[0] - 1.0f);
  EXPECT_NEAR(runs.length_px[0], 120.0f, 0.5f);  // 121.5 with the zig-zag
  for (size_t i = 25; i < runs.points.size(); ++i) EXPECT_EQ(runs.points[i], before.points[i]);
  EXPECT_EQ(runs.length_px[1], before.length_px[1]);
  EXPECT_EQ(runs.positions, before.positions);
}

// A run that doubles back over itself for a few pixels and comes out ahead again (a fold of
// a coarse mesh's zero set: a knot in the drawn line) is straightened: its points go on
// leftwards without a back-step, and the points away from the fold stay. A hairpin (the
// line does not come out ahead), a zig-zag whose way back lies beside the way out (fingers)
// and a back-step shallower than the width (smoothing's business) are left as they were.
TEST(StrokeStyles, AFoldBackOverTheLineIsStraightened) {
  auto path = [](std::initializer_list<glm::vec2> corners) {
    StrokeRuns r;
    r.offsets.push_back(0);
    const std::vector<glm::vec2> c(corners);
    for (size_t k = 0; k + 1 < c.size(); ++k) {
      const int n = std::max(1, static_cast<int>(glm::length(c[k + 1] - c[k])));
      for (int i = k == 0 ? 0 : 1; i <= n; ++i) {
        const glm::vec2 p = c[k] + (c[k + 1] - c[k]) * (static_cast<float>(i) / static_cast<float>(n));
        r.points.push_back(p);
        r.positions.push_back(glm::vec3(p, 0.0f));
        r.alpha.push_back(1.0f);
      }
    }
    r.offsets.push_back(static_cast<uint32_t>(r.points.size()));
    r.kinds.push_back(LineKind::kContour);
    r.strokes.push_back(0);
    r.opacity.push_back(1.0f);
    r.length_px.push_back(0.0f);
    return r;
  };
  ObjectStyle style = contourStyle(2.5f);
  StrokeCurveScratch scratch;
  // Left to x = 60, back 6 px 1 px below the line, then on to the left.
  StrokeRuns fold = path({{100, 40}, {60, 40}, {66, 41}, {20, 41}});
  smoothRuns(fold, style.lines, scratch);
  for (size_t i = 1; i < fold.points.size(); ++i)
    EXPECT_LE(fold.points[i].x, fold.points[i - 1].x + 0.01f) << i;
  EXPECT_EQ(fold.points.front(), glm::vec2(100, 40));
  EXPECT_EQ(fold.points.back(), glm::vec2(20, 41));
  auto backSteps = [](const StrokeRuns& r) {
    float most = 0.0f;
    for (size_t i = 1; i < r.points.size(); ++i) most = std::max(most, r.points[i].x - r.points[i - 1].x);
    return most;
  };
  // A hairpin: back to the right for good, 1 px below.
  StrokeRuns hairpin = path({{100, 40}, {60, 40}, {100, 41}});
  smoothRuns(hairpin, style.lines, scratch);
  EXPECT_GT(backSteps(hairpin), 0.5f);
  // Fingers: back 6 px along a line 5 px below, then on.
  StrokeRuns fingers = path({{100, 40}, {60, 40}, {66, 45}, {20, 45}});
  smoothRuns(fingers, style.lines, scratch);
  EXPECT_GT(backSteps(fingers), 0.5f);
  // Back 2 px only (under the 2.5-px width).
  StrokeRuns shallow = path({{100, 40}, {60, 40}, {62, 41}, {20, 41}});
  smoothRuns(shallow, style.lines, scratch);
  EXPECT_GT(backSteps(shallow), 0.2f);
}

TEST(StrokeStyles, RunsThatMeetAreDrawnAsOneStroke) {
  StrokeRuns runs;
  addRun(runs, {20, 40.5f}, {60, 40.5f});   // 0
  addRun(runs, {100, 60.5f}, {60.3f, 40.7f}); // 1: meets 0's end with its own end (reversed)
  addRun(runs, {100, 60.5f}, {100, 90.5f}, LineKind::kSuggestive);  // 2: another kind, not joined
  addRun(runs, {20, 100.5f}, {50, 100.5f});  // 3: alone
  JoinedRuns j;
  joinRuns(runs, {}, JoinParams{}, j);
  const StrokeRuns& joined = j.runs;
  const std::vector<uint32_t>& first = j.first_run;
  ASSERT_EQ(joined.strokeCount(), 3u);
  EXPECT_EQ(first[0], 0u);
  // Both runs and the step between their ends.
  EXPECT_NEAR(joined.length_px[0],
              runs.length_px[0] + runs.length_px[1] + glm::length(glm::vec2(60.3f, 40.7f) - glm::vec2(60, 40.5f)), 1e-3f);
  // The joined run goes 0 forwards, then 1 backwards, ending at (100, 60.5).
  const glm::vec2 last = joined.points[joined.offsets[1] - 1];
  EXPECT_NEAR(last.x, 100.0f, 1e-4f);
  EXPECT_NEAR(last.y, 60.5f, 1e-4f);
  // Half-opaque: one stroke blends once, so the junction is no darker than the rest (two
  // strokes would overlap their round caps there).
  StrokeRuns two;
  addRun(two, {20, 40.5f}, {60, 40.5f});
  addRun(two, {60.2f, 40.6f}, {100, 40.5f});
  EXPECT_GE(darkestHalfOpaque(two), 126);  // 50% black over white: 127.5, never the 64 of a double blend
}

// Pieces of one line a gap of a pixel or two apart (the visibility test and the outline's
// completion leave such gaps) are bridged into one stroke when the line goes on through the
// gap; ends that turn away from each other, or lie farther apart, are not.
TEST(StrokeStyles, GapsAlongOneLineAreBridged) {
  StrokeRuns runs;
  addRun(runs, {20, 40.5f}, {60, 40.5f});    // 0
  addRun(runs, {62.5f, 40.5f}, {100, 41.5f});  // 1: 2.5 px on along the same line: bridged
  addRun(runs, {20, 80.5f}, {60, 80.5f});    // 2
  addRun(runs, {61.5f, 82.5f}, {61.5f, 120.5f});  // 3: 2.5 px away but turning 90°: apart
  addRun(runs, {20, 140.5f}, {60, 140.5f});  // 4
  addRun(runs, {64.5f, 140.5f}, {100, 140.5f});  // 5: 4.5 px on: too far
  JoinedRuns j;
  joinRuns(runs, {}, JoinParams{}, j);
  ASSERT_EQ(j.runs.strokeCount(), 5u);
  EXPECT_EQ(j.first_run[0], 0u);
  EXPECT_EQ(j.runs.offsets[1] - j.runs.offsets[0], (runs.offsets[2] - runs.offsets[0]));
  EXPECT_NEAR(j.runs.length_px[0], runs.length_px[0] + runs.length_px[1] + 2.5f, 1e-3f);
  // Without bridging every run stays apart but the touching ones.
  JoinParams no_bridge;
  no_bridge.bridge_px = 0.0f;
  joinRuns(runs, {}, no_bridge, j);
  EXPECT_EQ(j.runs.strokeCount(), 6u);
  // With the kind's width known (2.5 px), gaps up to 4 px are bridged, and up to 5.5 px where
  // the line runs straight on and nothing crosses the gap (BridgesOverLongerGaps...): the
  // 4.5-px one is. With 4 px width (5.5 and 7 px), too.
  StrokeRuns gap;
  addRun(gap, {20, 40.5f}, {60, 40.5f});
  addRun(gap, {63.8f, 40.5f}, {100, 40.5f});  // 3.8 px on
  addRun(gap, {20, 140.5f}, {60, 140.5f});
  addRun(gap, {64.5f, 140.5f}, {100, 140.5f});  // 4.5 px on
  joinRuns(gap, {}, JoinParams{}, j);
  EXPECT_EQ(j.runs.strokeCount(), 4u);
  joinRuns(gap, {}, joinParamsFor(contourStyle(2.5f).lines), j);
  EXPECT_EQ(j.runs.strokeCount(), 2u);
  joinRuns(gap, {}, joinParamsFor(contourStyle(4.0f).lines), j);
  EXPECT_EQ(j.runs.strokeCount(), 2u);
  no_bridge = joinParamsFor(contourStyle(4.0f).lines);
  no_bridge.bridge_px = 0.0f;
  joinRuns(gap, {}, no_bridge, j);
  EXPECT_EQ(j.runs.strokeCount(), 4u) << "bridge_px 0 turns bridging off whatever the width";
}

// Gaps of the width + 1.5 to the width + 3 px (4 to 5.5 px for 2.5-px contours; the
// visibility test leaves such gaps in a coarse mesh's outline, breaks of 1.5-3 px under
// round caps) are bridged only where the line runs straight on through them (within 30°)
// and no other run, of any kind, crosses the gap.
TEST(StrokeStyles, BridgesOverLongerGapsOnlyStraightAndUncrossed) {
  StrokeRuns runs;
  addRun(runs, {20, 40.5f}, {60, 40.5f});     // 0
  addRun(runs, {65, 40.5f}, {100, 40.5f});    // 1: 5 px on, straight: bridged
  addRun(runs, {20, 80.5f}, {60, 80.5f});     // 2
  addRun(runs, {64, 83.0f}, {100, 83.0f});    // 3: 4.7 px, 32° off the line: apart
  addRun(runs, {20, 140.5f}, {60, 140.5f});   // 4
  addRun(runs, {65, 140.5f}, {100, 140.5f});  // 5: 5 px on, but run 6 crosses the gap
  addRun(runs, {62.5f, 120.5f}, {62.5f, 160.5f}, LineKind::kSuggestive);  // 6
  addRun(runs, {20, 180.5f}, {60, 180.5f});   // 7
  addRun(runs, {66, 180.5f}, {100, 180.5f});  // 8: 6 px on: too far
  JoinedRuns j;
  joinRuns(runs, {}, joinParamsFor(contourStyle(2.5f).lines), j);
  ASSERT_EQ(j.runs.strokeCount(), 8u);
  EXPECT_EQ(j.link[1], 2) << "run 0's end joins run 1's start";
  for (size_t end = 4; end < 18; ++end) EXPECT_LT(j.link[end], 0) << "end " << end;
  // Without the crossing run, 4 and 5 are bridged.
  StrokeRuns open;
  addRun(open, {20, 140.5f}, {60, 140.5f});
  addRun(open, {65, 140.5f}, {100, 140.5f});
  addRun(open, {62.5f, 120.5f}, {62.5f, 135.5f}, LineKind::kSuggestive);  // ends 5 px above
  joinRuns(open, {}, joinParamsFor(contourStyle(2.5f).lines), j);
  EXPECT_EQ(j.runs.strokeCount(), 2u);
  // along_px 0 (no segment grid): only the 4-px bridge.
  JoinParams no_grid = joinParamsFor(contourStyle(2.5f).lines);
  no_grid.along_px = 0.0f;
  joinRuns(open, {}, no_grid, j);
  EXPECT_EQ(j.runs.strokeCount(), 3u);
}

// A short run lying along a longer one of its kind (within along_px) is left out: drawn, a
// translucent line would be darker there. One 3 px away, or of another kind, is drawn.
TEST(StrokeStyles, RunsLyingAlongALongerOneAreLeftOut) {
  StrokeRuns runs;
  addRun(runs, {20, 40.5f}, {100, 40.5f});  // 0: the line
  addRun(runs, {40, 41.5f}, {55, 41.0f});   // 1: along it, 1 px off: left out
  addRun(runs, {60, 43.5f}, {80, 43.5f});   // 2: 3 px off: drawn
  addRun(runs, {40, 40.5f}, {55, 40.5f}, LineKind::kSuggestive);  // 3: another kind: drawn
  JoinedRuns j;
  joinRuns(runs, {}, JoinParams{}, j);
  ASSERT_EQ(j.runs.strokeCount(), 3u);
  std::vector<uint32_t> firsts(j.first_run.begin(), j.first_run.end());
  std::sort(firsts.begin(), firsts.end());
  EXPECT_EQ(firsts, (std::vector<uint32_t>{0, 2, 3}));
  // Drawn half-opaque, the line is no darker where the short run lay.
  StrokeRuns two;
  addRun(two, {20, 40.5f}, {100, 40.5f});
  addRun(two, {40, 41.5f}, {55, 41.0f});
  EXPECT_GE(darkestHalfOpaque(two), 126);
}


// Within the kind's stroke width a run lying along a longer one only thickens it (a knot
// where the shorter lies): with the width given (joinParamsFor) a run 2 px off a 2.5-px
// line is left out, as one 1 px off always is; one 3 px off is drawn by that rule (it is
// left out as lying beside a line three times its length, burr_px, unless that is off).
TEST(StrokeStyles, RunsWithinTheStrokeWidthOfALongerOneAreLeftOut) {
  StrokeRuns runs;
  addRun(runs, {20, 40.5f}, {100, 40.5f});  // 0: the line
  addRun(runs, {40, 42.5f}, {44, 42.5f});   // 1: 2 px off
  addRun(runs, {60, 43.5f}, {80, 43.5f});   // 2: 3 px off
  JoinedRuns j;
  joinRuns(runs, {}, JoinParams{}, j);
  EXPECT_EQ(j.runs.strokeCount(), 3u) << "along_px alone (1.5) keeps the run 2 px off";
  ObjectStyle style = contourStyle(2.5f);
  JoinParams by_width = joinParamsFor(style.lines);
  EXPECT_EQ(by_width.width_px[static_cast<int>(LineKind::kContour)], 2.5f);
  by_width.burr_px = 0.0f;
  joinRuns(runs, {}, by_width, j);
  ASSERT_EQ(j.runs.strokeCount(), 2u);
  EXPECT_EQ(j.covered, (std::vector<uint8_t>{0, 1, 0}));
  joinRuns(runs, {}, joinParamsFor(style.lines), j);
  EXPECT_EQ(j.covered, (std::vector<uint8_t>{0, 1, 1}));
}

// A line of another kind lying along a contour within the stroke width (a crease that is
// also the silhouette, drawn over the outline in the crease's colour) is left out, whatever
// the lengths: the outline is drawn once, as a contour. A contour along a crease, a crease
// farther off, and a crease where contours are not drawn, are drawn.
TEST(StrokeStyles, OtherKindsAlongAContourAreLeftToIt) {
  StrokeRuns runs;
  addRun(runs, {20, 40.5f}, {60, 40.5f});                       // 0: the contour, in two runs
  addRun(runs, {25, 41.5f}, {95, 41.5f}, LineKind::kCrease);    // 1: 1 px off, longer than each: left out
  addRun(runs, {20, 44.5f}, {60, 44.5f}, LineKind::kCrease);    // 2: 4 px off: drawn
  addRun(runs, {20, 80.5f}, {100, 80.5f}, LineKind::kCrease);   // 3: a crease
  addRun(runs, {30, 81.5f}, {50, 81.5f});                       // 4: a contour along it: drawn
  addRun(runs, {60.5f, 40.5f}, {100, 40.5f});                   // 5: the contour's second run
  ObjectStyle style = contourStyle(2.5f);
  style.lines[LineKind::kCrease].enabled = true;
  style.lines[LineKind::kCrease].width_px = 1.5f;
  JoinParams params = joinParamsFor(style.lines);
  params.burr_px = 0.0f;  // (the burr rule is per kind; off here to test this one alone)
  JoinedRuns j;
  joinRuns(runs, {}, params, j);
  EXPECT_EQ(j.covered, (std::vector<uint8_t>{0, 1, 0, 0, 0, 0}));
  style.lines[LineKind::kContour].enabled = false;  // contours not drawn: the crease stays
  joinRuns(runs, {}, joinParamsFor(style.lines), j);
  EXPECT_EQ(j.covered[1], 0);
}

// A dash standing beside a longer line within the width + 2 px all along is a burr on it and
// is left out (close up on a coarse mesh, 4–10 px of contour 1.5–4.5 px beside the outline),
// as is a longer run beside a line three times its length; one farther off, one beside a
// line less than three times its length, and a dash whose two ends meet other runs' ends (it
// links them) are drawn, as is every run with burr_px 0.
TEST(StrokeStyles, ShortDashesBesideALongerRunAreLeftOut) {
  StrokeRuns runs;
  addRun(runs, {20, 40.5f}, {100, 40.5f});  // 0: the line
  addRun(runs, {40, 44.5f}, {48, 44.5f});   // 1: an 8-px dash 4 px off: a burr
  addRun(runs, {60, 45.5f}, {68, 45.5f});   // 2: 5 px off: drawn
  addRun(runs, {70, 44.5f}, {84, 44.5f});   // 3: 14 px long, 4 px off: left out too
  addRun(runs, {30, 36.5f}, {36, 36.5f});   // 4: 4 px off, linking the ends of 5 and 6
  addRun(runs, {28, 10.0f}, {28, 34.0f});   // 5
  addRun(runs, {38, 34.0f}, {38, 10.0f});   // 6
  addRun(runs, {70, 36.5f}, {100, 36.5f});  // 7: 30 px, 4 px off an 80-px line: drawn
  const JoinParams by_width = joinParamsFor(contourStyle(2.5f).lines);
  JoinedRuns j;
  joinRuns(runs, {}, by_width, j);
  EXPECT_EQ(j.covered, (std::vector<uint8_t>{0, 1, 0, 1, 0, 0, 0, 0}));
  JoinParams off = by_width;
  off.burr_px = 0.0f;
  joinRuns(runs, {}, off, j);
  EXPECT_EQ(j.covered, (std::vector<uint8_t>(8, 0)));
}

// On a coarse mesh the contour can run twice along the outline, a branch 1–4 px inside it for
// tens of pixels (a lens on the cow's back close up). The branch lies beside a line three
// times its length and is left out; so is the 5-px piece that linked the branch's end to the
// line's end, once the branch it linked is gone (the two ends it met, one is left out).
TEST(StrokeStyles, ABranchRunningBesideTheLineIsLeftOutWithWhatLinkedIt) {
  StrokeRuns runs;
  addRun(runs, {20, 40.5f}, {150, 40.5f});   // 0: the line, 130 px
  addRun(runs, {150, 40.5f}, {250, 40.5f});  // 1: its continuation
  addRun(runs, {100, 41.5f}, {140, 44.0f});  // 2: a 40-px branch beside 0, parting to 3.5 px
  addRun(runs, {141, 44.2f}, {146, 43.5f});  // 3: from 2's end to near 0's end
  const JoinParams by_width = joinParamsFor(contourStyle(2.5f).lines);
  JoinedRuns j;
  joinRuns(runs, {}, by_width, j);
  EXPECT_EQ(j.covered, (std::vector<uint8_t>{0, 0, 1, 1}));
  EXPECT_EQ(j.runs.strokeCount(), 1u);  // 0 and 1 joined
  JoinParams off = by_width;
  off.burr_px = 0.0f;
  joinRuns(runs, {}, off, j);
  EXPECT_EQ(j.covered, (std::vector<uint8_t>(4, 0)));
}

// Two pieces of one line that meet end to end but 1.7 px apart across it (the outline's
// completing piece and the contour on the cow's back close up) are joined, the first bending
// over onto the second's line over its last few pixels, not stepping across at one point;
// pieces meeting at a 30° corner, or with step_px 0, are not joined so.
TEST(StrokeStyles, PiecesMeetingSideBySideAreJoinedWithoutAStep) {
  StrokeRuns runs;
  addRun(runs, {20, 40.5f}, {60, 40.5f});
  addRun(runs, {60.2f, 42.2f}, {100, 42.2f});
  const JoinParams by_width = joinParamsFor(contourStyle(2.5f).lines);
  JoinedRuns j;
  joinRuns(runs, {}, by_width, j);
  ASSERT_EQ(j.runs.strokeCount(), 1u);
  // The stroke moves across by 1.7 px over more than 3 px of its length: no segment of it
  // turns by more than 35° (the straight step was 90°), and it starts and ends on the lines.
  const uint32_t n = j.runs.offsets[1];
  EXPECT_EQ(j.runs.points[0], glm::vec2(20, 40.5f));
  EXPECT_EQ(j.runs.points[n - 1], glm::vec2(100, 42.2f));
  for (uint32_t k = 1; k < n; ++k) {
    const glm::vec2 d = j.runs.points[k] - j.runs.points[k - 1];
    if (glm::length(d) > 1e-4f) {
      EXPECT_LT(std::abs(d.y), std::tan(35.0f * 3.14159265f / 180.0f) * d.x + 1e-4f) << k;
    }
  }
  JoinParams off = by_width;
  off.step_px = 0.0f;
  joinRuns(runs, {}, off, j);
  EXPECT_EQ(j.runs.strokeCount(), 2u);
  // A 30° corner with the same offset: not a side step.
  StrokeRuns corner;
  addRun(corner, {20, 40.5f}, {60, 40.5f});
  addRun(corner, {60.2f, 42.2f}, {60.2f + 40.0f * 0.866f, 42.2f + 40.0f * 0.5f});
  joinRuns(corner, {}, by_width, j);
  EXPECT_EQ(j.runs.strokeCount(), 2u);
}

// Two runs of one line that overlap side by side at their ends (the interpolated contour and
// the outline's completing piece, 1.8 px apart for 5 px) become one stroke, the second
// entered past the first's end; ends that overlap farther apart, or run opposite ways, stay
// apart.
TEST(StrokeStyles, RunsOverlappingSideBySideAreJoinedPastTheOverlap) {
  StrokeRuns runs;
  addRun(runs, {20, 40.5f}, {60, 40.5f});      // 0
  addRun(runs, {55, 42.3f}, {100, 42.3f});     // 1: starts 5 px behind 0's end, 1.8 px aside
  addRun(runs, {20, 80.5f}, {60, 80.5f});      // 2
  addRun(runs, {55, 84.5f}, {100, 84.5f});     // 3: 4 px aside: apart
  addRun(runs, {20, 120.5f}, {60, 120.5f});    // 4
  addRun(runs, {100, 122.3f}, {55, 122.3f});   // 5: same place as 1, drawn the other way: joined reversed
  addRun(runs, {20, 160.5f}, {60, 160.5f});    // 6
  addRun(runs, {55, 158.7f}, {0, 158.7f});     // 7: runs back along 6: not a continuation
  ObjectStyle style = contourStyle(2.5f);
  JoinedRuns j;
  joinRuns(runs, {}, joinParamsFor(style.lines), j);
  ASSERT_EQ(j.runs.strokeCount(), 6u);
  // Stroke of runs 0 and 1 (run 0's free start comes first): 0 whole, then 1 from its first
  // point past x = 60, so x only grows along it.
  size_t s01 = j.runs.strokeCount();
  for (size_t s = 0; s < j.runs.strokeCount(); ++s)
    if (j.first_run[s] == 0) s01 = s;
  ASSERT_LT(s01, j.runs.strokeCount());
  const uint32_t b = j.runs.offsets[s01], e = j.runs.offsets[s01 + 1];
  for (uint32_t i = b + 1; i < e; ++i) EXPECT_GT(j.runs.points[i].x, j.runs.points[i - 1].x) << "doubles back at " << i;
  EXPECT_EQ(e - b, (runs.offsets[1] - runs.offsets[0]) + (runs.offsets[2] - runs.offsets[1]) - 6);
  // The first run's end bends over onto the second's line along the overlap: no step of
  // 1.8 px at one point, and the length is the joined polyline's.
  float polyline = 0.0f, max_step = 0.0f;
  for (uint32_t i = b + 1; i < e; ++i) {
    polyline += glm::length(j.runs.points[i] - j.runs.points[i - 1]);
    max_step = std::max(max_step, std::abs(j.runs.points[i].y - j.runs.points[i - 1].y));
  }
  EXPECT_LT(max_step, 0.9f);
  EXPECT_NEAR(j.runs.points[b + 40].y, 42.3f, 0.05f) << "run 0's end lies on run 1's line";
  EXPECT_EQ(j.runs.points[b].y, 40.5f);
  EXPECT_EQ(j.runs.points[b + 35].y, 40.5f) << "bent only along the 5-px overlap";
  EXPECT_NEAR(j.runs.length_px[s01], polyline, 1e-3f);
  EXPECT_GT(polyline, 80.0f);
  EXPECT_LT(polyline, 81.0f);
  // The points left out are run 1's first six (x = 55..60).
  EXPECT_EQ(j.skipped[2], 6u);
  // Run 5 (the same overlap drawn the other way) joins 4 at its end.
  EXPECT_EQ(j.skipped[11], 6u);
  EXPECT_EQ(j.skipped[6] + j.skipped[7], 0u);
  // Without the overlap join, eight strokes.
  JoinParams none = joinParamsFor(style.lines);
  none.overlap_px = 0.0f;
  joinRuns(runs, {}, none, j);
  EXPECT_EQ(j.runs.strokeCount(), 8u);
}

// Each run written alone (the SVG's constant-width paths) draws what the joined stroke draws:
// a bridged gap is drawn by the run of the lower end, an overlap join leaves out the entered
// run's points behind the other's end and steps over to the first kept one, a run lying along
// another is not written.
TEST(StrokeStyles, RunsWrittenAloneDrawWhatTheJoinedStrokeDraws) {
  StrokeRuns runs;
  addRun(runs, {20, 40.5f}, {60, 40.5f});     // 0
  addRun(runs, {63.8f, 40.5f}, {100, 40.5f});  // 1: 3.8 px on: bridged at a 2.5-px width
  addRun(runs, {20, 80.5f}, {60, 80.5f});     // 2
  addRun(runs, {55, 82.3f}, {100, 82.3f});    // 3: overlaps 2's end side by side
  addRun(runs, {30, 81.5f}, {40, 81.5f});     // 4: lies along 2
  JoinedRuns j;
  joinRuns(runs, {}, joinParamsFor(contourStyle(2.5f).lines), j);
  std::vector<glm::vec2> p0, p1, p3, p4;
  appendRunAlone(runs, j, 0, p0);
  appendRunAlone(runs, j, 1, p1);
  appendRunAlone(runs, j, 3, p3);
  appendRunAlone(runs, j, 4, p4);
  ASSERT_EQ(p0.size(), runs.offsets[1] - runs.offsets[0] + 1);
  EXPECT_EQ(p0.back(), glm::vec2(63.8f, 40.5f)) << "run 0 reaches over the gap to run 1";
  ASSERT_EQ(p1.size(), runs.offsets[2] - runs.offsets[1]);
  EXPECT_EQ(p1.front(), glm::vec2(63.8f, 40.5f)) << "the bridge is drawn once";
  ASSERT_EQ(p3.size(), runs.offsets[4] - runs.offsets[3] - 6);
  EXPECT_GT(p3.front().x, 60.0f) << "run 3 starts past run 2's end";
  std::vector<glm::vec2> p2;
  appendRunAlone(runs, j, 2, p2);
  ASSERT_EQ(p2.size(), runs.offsets[3] - runs.offsets[2] + 1);
  EXPECT_EQ(p2.back(), p3.front()) << "run 2 steps over to where run 3 goes on: no gap between them";
  EXPECT_TRUE(p4.empty());
}

// A run through `pts` (its length the polyline's).
void addPolyline(StrokeRuns& r, const std::vector<glm::vec2>& pts, LineKind kind = LineKind::kContour) {
  if (r.offsets.empty()) r.offsets.push_back(0);
  float length = 0.0f;
  for (size_t i = 0; i < pts.size(); ++i) {
    r.points.push_back(pts[i]);
    r.positions.push_back(glm::vec3(pts[i], 0.0f));
    r.alpha.push_back(1.0f);
    if (i > 0) length += glm::length(pts[i] - pts[i - 1]);
  }
  r.offsets.push_back(static_cast<uint32_t>(r.points.size()));
  r.kinds.push_back(kind);
  r.strokes.push_back(static_cast<uint32_t>(r.kinds.size() - 1));
  r.opacity.push_back(1.0f);
  r.length_px.push_back(length);
}

// A straight run from (x0, y) to (x1, y), one point per pixel, then `tail`.
std::vector<glm::vec2> lineThen(float x0, float x1, float y, std::vector<glm::vec2> tail) {
  std::vector<glm::vec2> pts;
  for (float x = x0; x <= x1; x += 1.0f) pts.push_back({x, y});
  pts.insert(pts.end(), tail.begin(), tail.end());
  return pts;
}

// A free end that turns back within a few pixels (a contour's end at a cusp, on a coarse
// mesh) is cut at the turn, in the joined strokes and in the runs written alone; a bend under
// 75°, a hook on a short run, and a turn where the stroke goes on into another run are kept.
TEST(StrokeStyles, HooksAtFreeEndsAreCut) {
  StrokeRuns runs;
  addPolyline(runs, lineThen(20, 60, 40.5f, {{59.5f, 39.0f}, {59.0f, 37.6f}}));  // 0: turns back 108°
  addPolyline(runs, lineThen(20, 60, 60.5f, {{61.0f, 59.5f}, {62.0f, 58.5f}}));  // 1: bends 45°
  addPolyline(runs, lineThen(20, 28, 80.5f, {{27.5f, 79.0f}, {27.0f, 77.6f}}));  // 2: 8 px long
  std::vector<glm::vec2> reversed = lineThen(20, 60, 100.5f, {{59.5f, 99.0f}, {59.0f, 97.6f}});
  std::reverse(reversed.begin(), reversed.end());
  addPolyline(runs, reversed);                                                    // 3: the hook at its start
  addPolyline(runs, lineThen(20, 60, 120.5f, {{59.5f, 119.0f}, {59.0f, 117.6f}}));  // 4: turns into run 5
  addPolyline(runs, {{59.0f, 117.6f}, {58.0f, 114.6f}, {57.0f, 111.6f}, {56.0f, 108.6f}, {55.0f, 105.6f},
                     {54.0f, 102.6f}});
  const ObjectStyle style = contourStyle(2.5f);
  JoinedRuns j;
  joinRuns(runs, {}, joinParamsFor(style.lines), j);
  ASSERT_EQ(j.runs.strokeCount(), 5u);  // 4 and 5 joined
  auto strokeOf = [&](size_t first) {
    for (size_t s = 0; s < j.runs.strokeCount(); ++s)
      if (j.first_run[s] == first) return s;
    return j.runs.strokeCount();
  };
  auto pointsOf = [&](size_t s) {
    return std::vector<glm::vec2>(j.runs.points.begin() + j.runs.offsets[s], j.runs.points.begin() + j.runs.offsets[s + 1]);
  };
  const size_t s0 = strokeOf(0), s1 = strokeOf(1), s2 = strokeOf(2), s3 = strokeOf(3);
  ASSERT_LT(std::max({s0, s1, s2, s3}), j.runs.strokeCount());
  const auto p0 = pointsOf(s0);
  EXPECT_EQ(p0.size(), 41u);
  EXPECT_TRUE(p0.front() == glm::vec2(60.0f, 40.5f) || p0.back() == glm::vec2(60.0f, 40.5f)) << "cut at the turn";
  EXPECT_NEAR(j.runs.length_px[s0], 40.0f, 1e-3f);
  EXPECT_EQ(j.skipped[1], 2u);
  EXPECT_EQ(pointsOf(s1).size(), 43u) << "a 45° bend is kept";
  EXPECT_EQ(pointsOf(s2).size(), 11u) << "a short run keeps its hook";
  const auto p3 = pointsOf(s3);
  EXPECT_EQ(p3.size(), 41u);
  EXPECT_EQ(j.skipped[6], 2u);
  EXPECT_EQ(j.skipped[7], 0u);
  size_t joined_points = 0;
  for (size_t s = 0; s < j.runs.strokeCount(); ++s)
    if (s != s0 && s != s1 && s != s2 && s != s3) joined_points = j.runs.offsets[s + 1] - j.runs.offsets[s];
  EXPECT_EQ(joined_points, 43u + 6u) << "the turn into run 5 is a corner of the stroke, not a hook";
  // Written alone, the runs draw what the joined strokes draw.
  std::vector<glm::vec2> a0, a3;
  appendRunAlone(runs, j, 0, a0);
  appendRunAlone(runs, j, 3, a3);
  EXPECT_EQ(a0.size(), 41u);
  EXPECT_EQ(a0.back(), glm::vec2(60.0f, 40.5f));
  EXPECT_EQ(a3.size(), 41u);
  EXPECT_EQ(a3.front(), glm::vec2(60.0f, 100.5f));
  // hook_px 0: every end as found.
  JoinParams keep = joinParamsFor(style.lines);
  keep.hook_px = 0.0f;
  joinRuns(runs, {}, keep, j);
  EXPECT_EQ(j.runs.points.size(), runs.points.size());
}
}  // namespace
}  // namespace lodline
