#include <gtest/gtest.h>

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

void hline(LineMask& m, int y, int x0, int x1) {
  for (int x = x0; x < x1; ++x) m.on[static_cast<size_t>(y) * m.width + x] = 1;
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
  VisibleStrokes s;
  s.points = {{2.5f, 2.5f}, {12.5f, 2.5f}, {12.5f, 9.5f}};
  s.offsets = {0, 3};
  s.types = {LineType::kContour};
  s.opacity = {1.0f};
  s.length_px = {17.0f};
  LineMask m;
  rasterizeStrokes(s, 20, 20, m);
  size_t on = 0;
  for (uint8_t v : m.on) on += v;
  EXPECT_EQ(on, 11u + 7u);  // 11 px along y = 2, 7 more down x = 12
  EXPECT_TRUE(m.at(7, 2));
  EXPECT_TRUE(m.at(12, 6));
  EXPECT_FALSE(m.at(7, 6));
}

}  // namespace
}  // namespace lodline
