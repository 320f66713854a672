#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "core/camera.h"
#include "export/coherence.h"

namespace lodline {
namespace {

LineMask empty(int w, int h) {
  LineMask m;
  m.width = w;
  m.height = h;
  m.on.assign(static_cast<size_t>(w) * h, 0);
  return m;
}

// A line of opacity `a` (of 255) along row y.
void hline(LineMask& m, int y, int x0, int x1, uint8_t a = 255) {
  for (int x = x0; x < x1; ++x) m.on[static_cast<size_t>(y) * m.width + x] = a;
}

TEST(Coherence, IdenticalMasksHaveNoChurn) {
  LineMask a = empty(40, 30);
  hline(a, 10, 5, 35);
  const MaskChange c = compareMasks(a, a);
  EXPECT_EQ(c.line_pixels, 30u);
  EXPECT_EQ(c.appeared, 0u);
  EXPECT_EQ(c.vanished, 0u);
  EXPECT_EQ(c.churn(), 0.0);
}

TEST(Coherence, OnePixelShiftIsToleratedTwoIsNot) {
  LineMask a = empty(40, 30), b = empty(40, 30), c = empty(40, 30);
  hline(a, 10, 5, 35);
  hline(b, 11, 5, 35);
  hline(c, 12, 5, 35);
  EXPECT_EQ(compareMasks(a, b).churn(), 0.0);
  const MaskChange far = compareMasks(a, c);
  EXPECT_EQ(far.appeared, 30u);
  EXPECT_EQ(far.vanished, 30u);
  EXPECT_DOUBLE_EQ(far.churn(), 2.0);
}

TEST(Coherence, KnownAppearAndVanish) {
  LineMask prev = empty(50, 50), cur = empty(50, 50);
  hline(prev, 5, 0, 20);   // stays
  hline(cur, 5, 0, 20);
  hline(prev, 30, 0, 10);  // vanishes: 10 px
  hline(cur, 45, 10, 40);  // appears: 30 px
  const MaskChange c = compareMasks(prev, cur);
  EXPECT_EQ(c.line_pixels, 50u);
  EXPECT_EQ(c.appeared, 30u);
  EXPECT_EQ(c.vanished, 10u);
  EXPECT_DOUBLE_EQ(c.churn(), 40.0 / 50.0);
}

TEST(Coherence, RasterizeStrokesIsContinuous) {
  StrokeRuns s;
  s.points = {{2.5f, 2.5f}, {12.5f, 2.5f}, {12.5f, 9.5f}};
  s.offsets = {0, 3};
  s.kinds = {LineKind::kContour};
  s.opacity = {1.0f};
  s.length_px = {17.0f};
  LineMask m;
  rasterizeStrokes(s, 20, 20, m);
  EXPECT_EQ(m.count(), 11u + 7u);  // 11 px along y = 2, 7 more down x = 12
  EXPECT_DOUBLE_EQ(m.weight(), 18.0);  // no alpha given: opaque
  EXPECT_TRUE(m.at(7, 2));
  EXPECT_TRUE(m.at(12, 6));
  EXPECT_FALSE(m.at(7, 6));
}

}  // namespace
}  // namespace lodline

// ---- motion-compensated comparison, on a ray-cast sphere (exact surfaces, no GL) ----

namespace lodline {
namespace {

constexpr int kW = 200, kH = 160;

Camera lookAt(glm::vec3 eye, glm::vec3 target) {
  Camera c;
  c.eye = eye;
  c.target = target;
  c.fov_deg = 35.0f;
  c.near_plane = 0.5f;
  c.far_plane = 50.0f;
  return c;
}

// The visible surface of a sphere (object 1) seen by `cam`, by ray casting each pixel centre.
SurfaceImage raycastSphere(const Camera& cam, glm::vec3 centre, float radius) {
  SurfaceImage s;
  s.width = kW;
  s.height = kH;
  s.texels.assign(static_cast<size_t>(kW) * kH, glm::vec4(0.0f));
  const glm::vec3 f = cam.forward(), r = glm::normalize(glm::cross(f, cam.up)), u = glm::cross(r, f);
  const float t = std::tan(glm::radians(cam.fov_deg) * 0.5f), aspect = static_cast<float>(kW) / kH;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const float nx = (2.0f * (x + 0.5f) / kW - 1.0f) * t * aspect, ny = (1.0f - 2.0f * (y + 0.5f) / kH) * t;
      const glm::vec3 d = glm::normalize(f + nx * r + ny * u);
      const glm::vec3 oc = cam.eye - centre;
      const float b = glm::dot(oc, d), c = glm::dot(oc, oc) - radius * radius, disc = b * b - c;
      if (disc < 0.0f) continue;
      const float hit = -b - std::sqrt(disc);
      s.texels[static_cast<size_t>(y) * kW + x] = glm::vec4(cam.eye + hit * d, 1.0f);
    }
  return s;
}

// Its contour as drawn: the covered pixels with a background 4-neighbour.
LineMask rim(const SurfaceImage& s) {
  LineMask m = empty(kW, kH);
  for (int y = 1; y < kH - 1; ++y)
    for (int x = 1; x < kW - 1; ++x)
      if (s.at(x, y).w > 0.0f && (s.at(x - 1, y).w == 0.0f || s.at(x + 1, y).w == 0.0f || s.at(x, y - 1).w == 0.0f ||
                                  s.at(x, y + 1).w == 0.0f))
        m.on[static_cast<size_t>(y) * kW + x] = 255;
  return m;
}

TEST(CompensatedCoherence, ARigidOrbitOfASpheresContourDoesNotChurn) {
  // In front of the orbit's centre: orbiting 1.5° (a slow orbit's step) about the origin moves
  // its image by ~4 px. (Much larger steps move the surface points under the silhouette's
  // pixels — up to ~10° around the sphere from the true rim — visibly off the new rim.)
  const glm::vec3 centre(0.3f, 0.2f, 3.0f);
  const Camera a = lookAt({0, 0, 8}, {0, 0, 0});
  const float ang = glm::radians(1.5f);
  const Camera b = lookAt({8 * std::sin(ang), 0, 8 * std::cos(ang)}, {0, 0, 0});
  const SurfaceImage sa = raycastSphere(a, centre, 1.0f), sb = raycastSphere(b, centre, 1.0f);
  const LineMask ma = rim(sa), mb = rim(sb);
  const MaskChange raw = compareMasks(ma, mb);
  const CompensatedChange comp = compareMasksCompensated(ma, sa, a, mb, sb, b);
  EXPECT_GT(raw.churn(), 1.0);  // most pixels appear and vanish
  EXPECT_LT(comp.churn(), 0.02);
  EXPECT_LT(comp.dropped, comp.line_pixels / 10);
}

TEST(CompensatedCoherence, ALineRemovedInOneFrameCountsOnce) {
  const Camera cam = lookAt({0, 0, 8}, {0, 0, 0});
  const SurfaceImage s = raycastSphere(cam, {0, 0, 0}, 1.5f);
  LineMask with = rim(s), without = rim(s);
  hline(with, kH / 2, kW / 2 - 20, kW / 2 + 20);  // a 40-px line across the sphere's face
  PopMap pops;
  CompensationParams cp;
  cp.pops = &pops;
  auto marked = [](const std::vector<uint8_t>& plane) {
    return std::count_if(plane.begin(), plane.end(), [](uint8_t v) { return v != 0; });
  };
  const CompensatedChange gone = compareMasksCompensated(with, s, cam, without, s, cam, cp);
  EXPECT_EQ(gone.vanished, 40u);
  EXPECT_EQ(gone.appeared, 0u);
  // The pop map marks the 40 vanished pixels where they were (the camera did not move), at
  // their full opacity, and nothing as appeared.
  ASSERT_EQ(pops.width, kW);
  EXPECT_EQ(marked(pops.vanished), 40);
  EXPECT_EQ(marked(pops.appeared), 0);
  EXPECT_EQ(pops.vanished[static_cast<size_t>(kH / 2) * kW + kW / 2], 255);
  const CompensatedChange back = compareMasksCompensated(without, s, cam, with, s, cam, cp);
  EXPECT_EQ(back.appeared, 40u);
  EXPECT_EQ(back.vanished, 0u);
  EXPECT_EQ(marked(pops.appeared), 40);  // reset by the call: nothing left of the first
  EXPECT_EQ(marked(pops.vanished), 0);
  // Drawn over a white frame: the popped pixels green, the rest white.
  Image white(kW, kH);
  std::fill(white.rgba.begin(), white.rgba.end(), uint8_t{255});
  const Image shown = popImage(white, pops);
  const uint8_t* at = shown.pixel(kW / 2, kH / 2);
  EXPECT_LT(at[0], 10);
  EXPECT_GT(at[1], 150);
  EXPECT_EQ(shown.pixel(2, 2)[0], 255);
  // Moving with the camera, the removal still counts exactly the line's pixels.
  const Camera moved = lookAt({0.3f, 0.1f, 8}, {0.3f, 0.1f, 0});
  const SurfaceImage s2 = raycastSphere(moved, {0, 0, 0}, 1.5f);
  LineMask moved_with = rim(s2);
  // The same surface points as `with`'s line, seen by the moved camera.
  for (int x = kW / 2 - 20; x < kW / 2 + 20; ++x) {
    const glm::vec3 p(s.at(x, kH / 2));
    const glm::vec2 px = projectToPixels(moved, p, kW, kH);
    moved_with.on[static_cast<size_t>(std::floor(px.y)) * kW + static_cast<size_t>(std::floor(px.x))] = 255;
  }
  const CompensatedChange kept = compareMasksCompensated(with, s, cam, moved_with, s2, moved);
  EXPECT_EQ(kept.appeared + kept.vanished, 0u);
  const CompensatedChange lost = compareMasksCompensated(with, s, cam, rim(s2), s2, moved);
  EXPECT_EQ(lost.vanished, 40u);
  EXPECT_EQ(lost.appeared, 0u);
  EXPECT_GT(compareMasks(with, rim(s2)).churn(), lost.churn());  // raw also counts the rim's motion
}

// The meter keeps the previous frame: the first frame compares with nothing, the next ones
// with the frame before, and the caller gets buffers back to refill.
// Popped pixels are attributed to the zones where the mesh changed: a line removed next to a
// split counts near it, with its own line pixels; one removed far from every change does not.
TEST(CompensatedCoherence, PoppedPixelsAreAttributedToTheZonesOfChanges) {
  const Camera cam = lookAt({0, 0, 8}, {0, 0, 0});
  const SurfaceImage s = raycastSphere(cam, {0, 0, 0}, 1.5f);
  LineMask with = rim(s), without = rim(s);
  hline(with, kH / 2, kW / 2 - 20, kW / 2 + 20);  // 40 px, from x = kW/2 - 20 to kW/2 + 19
  ChangeZones zones;
  zones.reset(kW, kH);
  zones.mark({kW / 2 - 10.5f, kH / 2 + 0.5f}, 6, ChangeZones::kNearOps);   // covers 13 of its pixels
  zones.mark({kW / 2 + 30.5f, kH / 2 + 0.5f}, 6, ChangeZones::kNearMorph);  // beyond its end
  CompensationParams cp;
  cp.zones = &zones;
  const CompensatedChange gone = compareMasksCompensated(with, s, cam, without, s, cam, cp);
  EXPECT_EQ(gone.vanished, 40u);
  EXPECT_EQ(gone.popped_near_ops, 13u);
  EXPECT_EQ(gone.popped_near_morphs, 0u);
  const CompensatedChange back = compareMasksCompensated(without, s, cam, with, s, cam, cp);
  EXPECT_EQ(back.appeared, 40u);
  EXPECT_EQ(back.popped_near_ops, 13u);
  EXPECT_EQ(back.lines_near_ops, 13u);  // the current frame's line pixels in the zone
  // Zones of another size are ignored.
  ChangeZones small;
  small.reset(kW / 2, kH / 2);
  cp.zones = &small;
  const CompensatedChange none = compareMasksCompensated(with, s, cam, without, s, cam, cp);
  EXPECT_EQ(none.vanished, 40u);
  EXPECT_EQ(none.popped_near_ops + none.popped_near_morphs + none.lines_near_ops, 0u);
}

TEST(CompensatedCoherence, TheMeterComparesEachFrameWithThePreviousOne) {
  const Camera cam = lookAt({0, 0, 8}, {0, 0, 0});
  const SurfaceImage s = raycastSphere(cam, {0, 0, 0}, 1.5f);
  CoherenceMeter meter;
  LineMask mask = rim(s);
  SurfaceImage surface = s;
  const uint64_t rim_pixels = mask.count();
  FrameCoherence f = meter.measure(mask, surface, cam);
  EXPECT_FALSE(f.compared);
  EXPECT_EQ(f.compensated.line_pixels, rim_pixels);
  EXPECT_EQ(f.compensated.appeared + f.compensated.vanished, 0u);
  EXPECT_TRUE(meter.hasPrevious());
  // Second frame: the rim plus a 40-px line; 40 pixels appeared.
  mask = rim(s);
  hline(mask, kH / 2, kW / 2 - 20, kW / 2 + 20);
  surface = s;
  f = meter.measure(mask, surface, cam);
  EXPECT_TRUE(f.compared);
  EXPECT_EQ(f.compensated.appeared, 40u);
  EXPECT_EQ(f.raw.appeared, 40u);
  EXPECT_EQ(f.compensated.vanished, 0u);
  // Third frame: the line is gone again, compared with the second frame (not the first).
  mask = rim(s);
  surface = s;
  f = meter.measure(mask, surface, cam);
  EXPECT_EQ(f.compensated.vanished, 40u);
  EXPECT_EQ(f.compensated.appeared, 0u);
  // After reset() the next frame is a first frame again.
  meter.reset();
  mask = rim(s);
  hline(mask, 5, 5, 45);
  surface = s;
  f = meter.measure(mask, surface, cam);
  EXPECT_FALSE(f.compared);
  EXPECT_EQ(f.compensated.appeared, 0u);
}

TEST(CompensatedCoherence, AStaticCameraGivesTheRawMeasure) {
  const Camera cam = lookAt({0, 0, 8}, {0.2f, -0.1f, 0});
  const SurfaceImage s = raycastSphere(cam, {0, 0, 0}, 1.5f);
  LineMask a = rim(s), b = rim(s);
  hline(a, 60, 80, 120);
  hline(b, 62, 90, 130);   // shifted by 2 px and 10 px: partly matched, partly not
  hline(b, 100, 70, 75);   // a new piece
  const MaskChange raw = compareMasks(a, b);
  const CompensatedChange comp = compareMasksCompensated(a, s, cam, b, s, cam);
  EXPECT_EQ(comp.appeared, raw.appeared);
  EXPECT_EQ(comp.vanished, raw.vanished);
  EXPECT_EQ(comp.dropped, 0u);
  EXPECT_GT(raw.appeared, 0u);
  EXPECT_DOUBLE_EQ(comp.churn(), raw.churn());
}

// The churn counts opacity: a line fading in at 20% adds 0.2 per pixel where nothing was, a
// line that fades from full to half adds 0.5 as vanished, and one that keeps its opacity adds
// nothing; the binary measure counts the first whole and the others not at all.
TEST(CompensatedCoherence, ChurnIsWeightedByOpacity) {
  const Camera cam = lookAt({0, 0, 8}, {0, 0, 0});
  const SurfaceImage s = raycastSphere(cam, {0, 0, 0}, 1.5f);
  LineMask a = empty(kW, kH), b = empty(kW, kH);
  hline(a, kH / 2, kW / 2 - 20, kW / 2 + 20);        // 40 px, opaque, kept
  hline(b, kH / 2, kW / 2 - 20, kW / 2 + 20);
  hline(a, kH / 2 + 10, kW / 2 - 10, kW / 2 + 10);   // 20 px fading from 255 to 128
  hline(b, kH / 2 + 10, kW / 2 - 10, kW / 2 + 10, 128);
  hline(b, kH / 2 - 10, kW / 2 - 25, kW / 2 + 25, 51);  // 50 px appearing at 20%
  const CompensatedChange c = compareMasksCompensated(a, s, cam, b, s, cam);
  EXPECT_EQ(c.appeared, 50u);
  EXPECT_EQ(c.vanished, 0u);
  EXPECT_NEAR(c.appeared_weight, 50 * 0.2, 1e-9);
  EXPECT_NEAR(c.vanished_weight, 20 * 127 / 255.0, 1e-9);
  EXPECT_NEAR(c.line_weight, 40 + 20 * 128 / 255.0 + 50 * 0.2, 1e-9);
  EXPECT_NEAR(c.churn(), (10.0 + 20 * 127 / 255.0) / c.line_weight, 1e-12);
  EXPECT_NEAR(c.churnBinary(), 50.0 / 110.0, 1e-12);
  // Strokes carry their opacity into the mask (StrokeRuns::alpha, interpolated).
  StrokeRuns runs;
  runs.points = {{2.5f, 2.5f}, {12.5f, 2.5f}};
  runs.alpha = {0.2f, 1.0f};
  runs.offsets = {0, 2};
  runs.kinds = {LineKind::kSuggestive};
  LineMask m;
  rasterizeStrokes(runs, 20, 20, m);
  EXPECT_NEAR(m.opacity(2, 2), 0.2f, 0.01f);
  EXPECT_NEAR(m.opacity(7, 2), 0.6f, 0.06f);
  EXPECT_EQ(m.opacity(12, 2), 1.0f);
}

TEST(CompensatedCoherence, PointsHiddenOrOffScreenInTheOtherFrameAreDropped) {
  const Camera cam = lookAt({0, 0, 8}, {0, 0, 0});
  const SurfaceImage s = raycastSphere(cam, {0, 0, 0}, 1.5f);
  LineMask a = rim(s);
  // Half a turn about the sphere: what was in front is now behind it.
  const Camera back = lookAt({0, 0, -8}, {0, 0, 0});
  const SurfaceImage sb = raycastSphere(back, {0, 0, 0}, 1.5f);
  LineMask face = empty(kW, kH);
  hline(face, kH / 2, kW / 2 - 10, kW / 2 + 10);  // on the front of the sphere
  const CompensatedChange c = compareMasksCompensated(face, s, cam, rim(sb), sb, back);
  EXPECT_EQ(c.vanished, 0u);  // not vanished: hidden behind the sphere now
  EXPECT_GE(c.dropped, 20u);
}

}  // namespace
}  // namespace lodline
