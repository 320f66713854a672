// Outline coverage with known answers: a disc's outline against a ring of line pixels, with
// and without a gap.
#include <gtest/gtest.h>

#include <cmath>

#include "export/outline_coverage.h"

namespace lodline {
namespace {

// A `w`×`h` depth image covered (depth 0.5) inside the disc of radius `r` at the centre.
DepthImage disc(int w, int h, float r) {
  DepthImage d;
  d.width = w;
  d.height = h;
  d.depth.assign(static_cast<size_t>(w) * h, 1.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (std::hypot(x + 0.5f - w / 2.0f, y + 0.5f - h / 2.0f) < r) d.depth[static_cast<size_t>(y) * w + x] = 0.5f;
  return d;
}

// Line pixels on the circle of radius `r`, except where the angle is in [gap0, gap1).
LineMask ring(int w, int h, float r, float gap0 = 0.0f, float gap1 = 0.0f) {
  LineMask m;
  m.width = w;
  m.height = h;
  m.on.assign(static_cast<size_t>(w) * h, 0);
  for (int i = 0; i < 4000; ++i) {
    const float a = 6.2831853f * static_cast<float>(i) / 4000.0f;
    if (a >= gap0 && a < gap1) continue;
    const int x = static_cast<int>(std::floor(w / 2.0f + r * std::cos(a)));
    const int y = static_cast<int>(std::floor(h / 2.0f + r * std::sin(a)));
    if (x >= 0 && y >= 0 && x < w && y < h) m.on[static_cast<size_t>(y) * w + x] = 1;
  }
  return m;
}

TEST(OutlineCoverage, ALineOnTheOutlineCoversItAll) {
  const DepthImage d = disc(200, 160, 50.0f);
  const OutlineCoverage c = measureOutlineCoverage(d, ring(200, 160, 49.0f));
  EXPECT_GT(c.outline_px, 250u);  // about 2π·50
  EXPECT_EQ(c.covered_px, c.outline_px);
  EXPECT_EQ(c.gaps, 0u);
  EXPECT_DOUBLE_EQ(c.coverage(), 1.0);
}

TEST(OutlineCoverage, AGapIsCountedAndALineTooFarInsideDoesNotCover) {
  const DepthImage d = disc(200, 160, 50.0f);
  // A quarter of the circle missing: one gap of about a quarter of the outline.
  const OutlineCoverage c = measureOutlineCoverage(d, ring(200, 160, 49.0f, 0.0f, 1.5708f));
  EXPECT_EQ(c.gaps, 1u);
  EXPECT_NEAR(c.coverage(), 0.75, 0.03);
  EXPECT_GT(c.largest_gap_px, 60u);
  // A ring 4 px inside the outline covers nothing (the radius is 2 px).
  const OutlineCoverage inside = measureOutlineCoverage(d, ring(200, 160, 45.0f));
  EXPECT_EQ(inside.covered_px, 0u);
  EXPECT_EQ(inside.gaps, 1u);
  // No lines at all, no outline at all.
  EXPECT_EQ(measureOutlineCoverage(d, ring(200, 160, 0.0f, 0.0f, 7.0f)).covered_px, 0u);
  EXPECT_DOUBLE_EQ(measureOutlineCoverage(disc(200, 160, 0.0f), ring(200, 160, 49.0f)).coverage(), 1.0);
}

}  // namespace
}  // namespace lodline
