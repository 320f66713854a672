#include <gtest/gtest.h>

#include <cmath>

#include <glm/trigonometric.hpp>

#include "export/visibility.h"

namespace lodline {
namespace {

// Camera at the origin looking down -Z; window depth of a surface at eye depth z.
Camera testCamera() {
  Camera cam;
  cam.eye = {0, 0, 0};
  cam.target = {0, 0, -1};
  cam.fov_deg = 60.0f;
  cam.near_plane = 1.0f;
  cam.far_plane = 20.0f;
  return cam;
}

float windowDepth(const Camera& cam, float z) {
  const glm::vec4 c = cam.projection(1.0f) * glm::vec4(0, 0, -z, 1);
  return 0.5f * c.z / c.w + 0.5f;
}

DepthImage flat(int w, int h, float value) {
  DepthImage d;
  d.width = w;
  d.height = h;
  d.depth.assign(static_cast<size_t>(w) * h, value);
  return d;
}

TEST(Visibility, BackgroundShowsEverythingInsideTheImage) {
  const Camera cam = testCamera();
  const DepthImage d = flat(64, 64, 1.0f);
  EXPECT_TRUE(isPointVisible(cam, d, {0, 0, -5}));
  EXPECT_TRUE(isPointVisible(cam, d, {1, 1, -5}));
  EXPECT_FALSE(isPointVisible(cam, d, {50, 0, -5}));  // outside the frustum
  EXPECT_FALSE(isPointVisible(cam, d, {0, 0, 5}));    // behind the eye
}

TEST(Visibility, SurfaceHidesWhatIsBehindIt) {
  const Camera cam = testCamera();
  const DepthImage d = flat(64, 64, windowDepth(cam, 5.0f));
  EXPECT_TRUE(isPointVisible(cam, d, {0, 0, -3}));
  EXPECT_TRUE(isPointVisible(cam, d, {0, 0, -5.005f}));  // on the surface, within tolerance
  EXPECT_FALSE(isPointVisible(cam, d, {0, 0, -5.1f}));
  EXPECT_FALSE(isPointVisible(cam, d, {0, 0, -12}));
}

TEST(Visibility, StrokesSplitIntoVisibleRuns) {
  const Camera cam = testCamera();
  // Left half of the image: a wall at depth 5; right half: background.
  DepthImage d = flat(100, 100, 1.0f);
  const float wall = windowDepth(cam, 5.0f);
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 50; ++x) d.depth[static_cast<size_t>(y) * 100 + x] = wall;
  // A horizontal stroke at depth 8 across the image: hidden on the left, visible on the
  // right (sampled every 0.25 units, as an extracted line is: a surface nearer than one
  // segment's length counts as the line's own neighbourhood); a second one at depth 3,
  // visible everywhere.
  StrokeSet s;
  for (int i = 0; i <= 24; ++i) {
    s.points.push_back({-3.0f + 0.25f * static_cast<float>(i), 0, -8});
    s.alpha.push_back(1);
  }
  s.points.insert(s.points.end(), {{-1, 0.5f, -3}, {1, 0.5f, -3}});
  s.alpha.insert(s.alpha.end(), {0.5f, 0.5f});
  s.offsets = {0, 25, 27};
  s.kinds = {LineKind::kContour, LineKind::kSuggestive};
  s.closed = {0, 0};
  StrokeRuns out;
  visibleStrokes(s, cam, d, {}, out);
  ASSERT_EQ(out.strokeCount(), 2u);
  EXPECT_EQ(out.kinds[0], LineKind::kContour);
  // The visible part of the first stroke starts near the wall's edge (x = 50 px).
  const glm::vec2 first = out.points[out.offsets[0]];
  EXPECT_NEAR(first.x, 50.0f, 2.0f);
  EXPECT_GT(out.length_px[0], 30.0f);
  EXPECT_LT(out.length_px[0], 50.0f);
  EXPECT_EQ(out.kinds[1], LineKind::kSuggestive);
  EXPECT_NEAR(out.opacity[1], 0.5f, 1e-5f);
  // Projected length of the near stroke: 2 units at depth 3 with f = 50/tan(30°) px.
  EXPECT_NEAR(out.length_px[1], 2.0f / 3.0f * 50.0f / std::tan(glm::radians(30.0f)), 1.5f);
}

TEST(Visibility, ASurfaceWithinOneSegmentIsTheLinesOwnNeighbourhood) {
  const Camera cam = testCamera();
  const DepthImage d = flat(100, 100, windowDepth(cam, 5.0f));
  // Strokes 0.2 units behind a wall at depth 5: with segments 0.5 long the wall is within
  // one segment (the line's own faces turning away); with segments 0.1 long it occludes.
  auto stroke = [](float step) {
    StrokeSet s;
    for (float x = -1.0f; x <= 1.0f + 1e-4f; x += step) {
      s.points.push_back({x, 0, -5.2f});
      s.alpha.push_back(1);
    }
    s.offsets = {0, static_cast<uint32_t>(s.points.size())};
    s.kinds = {LineKind::kContour};
    s.closed = {0};
    return s;
  };
  StrokeRuns coarse, fine;
  visibleStrokes(stroke(0.5f), cam, d, {}, coarse);
  visibleStrokes(stroke(0.1f), cam, d, {}, fine);
  EXPECT_EQ(coarse.strokeCount(), 1u);
  EXPECT_EQ(fine.strokeCount(), 0u);
  VisibilityParams strict;
  strict.segment_tolerance = 0.0f;
  StrokeRuns none;
  visibleStrokes(stroke(0.5f), cam, d, strict, none);
  EXPECT_EQ(none.strokeCount(), 0u);
}

// A hidden line that passes within a pixel of an outline sees the background in its 3×3
// neighbourhood there. Its short visible bits between hidden stretches were drawn as dots of
// ink along the outline (the far contour of the bunny's ear); they are hidden now, while a
// longer visible stretch, and a short one at the stroke's end, stay.
TEST(Visibility, ShortVisibleBitsBetweenHiddenStretchesAreHidden) {
  const Camera cam = testCamera();
  DepthImage d = flat(100, 100, 1.0f);  // a wall at depth 5 left of x = 50 px, background right
  const float wall = windowDepth(cam, 5.0f);
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 50; ++x) d.depth[static_cast<size_t>(y) * 100 + x] = wall;
  // A suggestive line (no slack) at depth 8 running down the wall's edge, at x = 46.5 px
  // (hidden: its neighbourhood is wall) and now and then at 49.5 px (background beside it).
  const float z = 8.0f, px_per_unit = 50.0f / std::tan(glm::radians(30.0f)) / z;
  auto at = [&](float px, float py) { return glm::vec3((px - 50.0f) / px_per_unit, (50.0f - py) / px_per_unit, -z); };
  StrokeSet s;
  for (int py = 10; py <= 90; ++py) {
    const bool blip = py == 20 || py == 21 || py == 30 || py == 31 || py == 40 || py == 41;  // 1 px long
    const bool stretch = py >= 55 && py <= 65;                                             // 10 px long
    const bool end = py >= 89;                                                             // at the end
    s.points.push_back(at(blip || stretch || end ? 49.5f : 46.5f, static_cast<float>(py)));
    s.alpha.push_back(1);
  }
  s.offsets = {0, static_cast<uint32_t>(s.points.size())};
  s.kinds = {LineKind::kSuggestive};
  s.closed = {0};
  VisibilityParams off;
  off.min_visible_between_hidden_px = 0.0f;
  StrokeRuns before, after;
  visibleStrokes(s, cam, d, off, before);
  visibleStrokes(s, cam, d, {}, after);
  EXPECT_EQ(before.strokeCount(), 5u);  // three dots, the stretch and the end
  ASSERT_EQ(after.strokeCount(), 2u);
  EXPECT_NEAR(after.length_px[0], 10.0f, 1.0f);
  EXPECT_NEAR(after.points[after.offsets[0]].y, 55.0f, 1.0f);
  EXPECT_NEAR(after.points[after.offsets[1]].y, 89.0f, 1.0f);
  // What is hidden goes to the hidden runs: the dots join the hidden stretches around them.
  StrokeRuns vis, hid;
  splitStrokes(s, cam, d, {}, &vis, &hid);
  EXPECT_EQ(hid.strokeCount(), 2u);  // before the stretch and between it and the end
}

// A long segment among short ones (a CAD part's sliver) gets the slack of the mesh's typical
// edge, not half its own length: behind a wall 0.2 units in front of it, a 2-unit segment is
// visible with no cap and hidden with a cap of 0.2 (slack 0.1).
TEST(Visibility, TheSlackOfALongSegmentIsCappedByTheMeshsTypicalEdge) {
  const Camera cam = testCamera();
  const DepthImage d = flat(100, 100, windowDepth(cam, 5.0f));
  StrokeSet s;
  s.points = {{-1.0f, 0, -5.2f}, {1.0f, 0, -5.2f}};
  s.alpha = {1, 1};
  s.offsets = {0, 2};
  s.kinds = {LineKind::kContour};
  s.closed = {0};
  StrokeRuns uncapped, capped;
  visibleStrokes(s, cam, d, {}, uncapped);
  EXPECT_EQ(uncapped.strokeCount(), 1u);
  VisibilityParams p;
  p.segment_tolerance_cap = 0.2f;
  visibleStrokes(s, cam, d, p, capped);
  EXPECT_EQ(capped.strokeCount(), 0u);
}

TEST(Visibility, CountsMidpointsPerType) {
  const Camera cam = testCamera();
  const DepthImage d = flat(64, 64, windowDepth(cam, 5.0f));
  LineSet lines;
  lines.points = {{0, 0, -3}, {0.1f, 0, -3}, {0, 0, -9}, {0.1f, 0, -9}, {0, 0.1f, -4}, {0, 0.2f, -4}};
  lines.kinds = {LineKind::kContour, LineKind::kContour, LineKind::kCrease};
  const auto counts = countVisibleSegments(lines, cam, d);
  EXPECT_EQ(counts[0], 1u);
  EXPECT_EQ(counts[2], 1u);
  EXPECT_EQ(counts[1], 0u);
}

}  // namespace
}  // namespace lodline
