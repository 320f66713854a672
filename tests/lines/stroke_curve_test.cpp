// Stroke curves with known answers: a circle's arc is fitted by a few cubics within the
// tolerance of the circle, a corner stays a corner, the zig-zag of face-to-face crossings
// along a straight line is smoothed away, and degenerate polylines give nothing.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "lines/stroke_curve.h"

namespace lodline {
namespace {

constexpr float kPi = 3.14159265358979f;

// Largest distance from points of the fitted chain (sampled densely) to `dist`, a distance
// function of the intended curve.
template <class Dist>
float worstDistance(const std::vector<glm::vec2>& chain, Dist&& dist) {
  float worst = 0.0f;
  for (size_t s = 0; s + 3 < chain.size(); s += 3)
    for (int k = 0; k <= 50; ++k) worst = std::max(worst, dist(bezierPoint(&chain[s], static_cast<float>(k) / 50.0f)));
  return worst;
}

TEST(StrokeCurve, AnArcIsAFewCubicsWithinTheTolerance) {
  // A half circle of radius 100 px sampled every 4 px (as a contour crossing faces would be).
  std::vector<glm::vec2> poly;
  for (int i = 0; i <= 80; ++i) {
    const float a = kPi * static_cast<float>(i) / 80.0f;
    poly.push_back({200.0f + 100.0f * std::cos(a), 200.0f + 100.0f * std::sin(a)});
  }
  std::vector<glm::vec2> out;
  StrokeCurveScratch scratch;
  const size_t n = fitStrokeCurve(poly, StrokeCurveParams{}, out, scratch);
  ASSERT_GE(n, 1u);
  EXPECT_LE(n, 6u);  // 314 px of arc: over 15 px per control point
  EXPECT_EQ(out.size(), 1 + 3 * n);
  EXPECT_EQ(out.front(), poly.front());
  EXPECT_EQ(out.back(), poly.back());
  // The polyline's chords lie up to 0.02 px inside the circle; smoothing and fitting add
  // less than the tolerance.
  EXPECT_LT(worstDistance(out, [](glm::vec2 p) { return std::abs(glm::length(p - glm::vec2(200.0f)) - 100.0f); }),
            0.3f);
}

TEST(StrokeCurve, ACornerIsKept) {
  // An L: 60 px right, then 60 px down; the chain passes through the corner point exactly.
  std::vector<glm::vec2> poly;
  for (int i = 0; i <= 60; i += 3) poly.push_back({10.0f + static_cast<float>(i), 10.0f});
  for (int i = 3; i <= 60; i += 3) poly.push_back({70.0f, 10.0f + static_cast<float>(i)});
  std::vector<glm::vec2> out;
  StrokeCurveScratch scratch;
  const size_t n = fitStrokeCurve(poly, StrokeCurveParams{}, out, scratch);
  ASSERT_GE(n, 2u);
  bool corner = false;
  for (size_t s = 3; s < out.size(); s += 3) corner = corner || glm::length(out[s] - glm::vec2(70.0f, 10.0f)) < 1e-4f;
  EXPECT_TRUE(corner);
  EXPECT_LT(worstDistance(out,
                          [](glm::vec2 p) {
                            return std::min(std::abs(p.y - 10.0f) + std::max(0.0f, p.x - 70.0f),
                                            std::abs(p.x - 70.0f) + std::max(0.0f, 10.0f - p.y));
                          }),
            0.3f);
}

TEST(StrokeCurve, TheZigZagOfFaceCrossingsIsSmoothedAway) {
  // A straight 200-px line whose points alternate 0.6 px either side, 4 px apart.
  std::vector<glm::vec2> poly;
  for (int i = 0; i <= 50; ++i) poly.push_back({4.0f * static_cast<float>(i), 50.0f + (i % 2 ? 0.6f : -0.6f)});
  poly.front().y = poly.back().y = 50.0f;
  std::vector<glm::vec2> out;
  StrokeCurveScratch scratch;
  const size_t n = fitStrokeCurve(poly, StrokeCurveParams{}, out, scratch);
  EXPECT_LE(n, 4u);  // the polyline had 50 segments
  EXPECT_LT(worstDistance(out, [](glm::vec2 p) { return std::abs(p.y - 50.0f); }), 0.5f);
  // Without smoothing, the fit follows the zig-zag.
  StrokeCurveParams raw;
  raw.smoothing_px = 0.0f;
  out.clear();
  EXPECT_GT(fitStrokeCurve(poly, raw, out, scratch), 10u);
}

TEST(StrokeCurve, DegeneratePolylinesGiveNothingAndTwoPointsOneSegment) {
  std::vector<glm::vec2> out;
  StrokeCurveScratch scratch;
  const std::vector<glm::vec2> one = {{1.0f, 1.0f}}, same = {{1.0f, 1.0f}, {1.0f, 1.0f}},
                               nan = {{1.0f, 1.0f}, {std::nanf(""), 2.0f}}, two = {{0.0f, 0.0f}, {9.0f, 0.0f}};
  EXPECT_EQ(fitStrokeCurve(one, {}, out, scratch), 0u);
  EXPECT_EQ(fitStrokeCurve(same, {}, out, scratch), 0u);
  EXPECT_EQ(fitStrokeCurve(nan, {}, out, scratch), 0u);
  EXPECT_TRUE(out.empty());
  EXPECT_EQ(fitStrokeCurve(two, {}, out, scratch), 1u);
  ASSERT_EQ(out.size(), 4u);
  EXPECT_LT(worstDistance(out, [](glm::vec2 p) { return std::abs(p.y); }), 1e-4f);
}

// smoothPolyline() keeps the point count, the ends and the corners, and moves the zig-zag of
// face-to-face crossings (±0.8 px every 5 px along a line) onto the line; with smoothing 0
// it moves nothing.
TEST(StrokeCurve, SmoothPolylineTakesOutTheZigZagAndKeepsEndsAndCorners) {
  std::vector<glm::vec2> poly;
  for (int i = 0; i <= 20; ++i) poly.push_back({10.0f + 5.0f * static_cast<float>(i), 50.0f + (i % 2 ? 0.8f : -0.8f)});
  for (int i = 1; i <= 20; ++i) poly.push_back({110.0f + (i % 2 ? 0.8f : -0.8f), 50.0f + 5.0f * static_cast<float>(i)});
  const std::vector<glm::vec2> before = poly;
  StrokeCurveScratch scratch;
  StrokeCurveParams off;
  off.smoothing_px = 0.0f;
  smoothPolyline(poly, off, scratch);
  EXPECT_EQ(poly, before);
  // Unlimited: the points go onto the smoothed curve.
  StrokeCurveParams free_params;
  free_params.max_shift_px = 0.0f;
  smoothPolyline(poly, free_params, scratch);
  ASSERT_EQ(poly.size(), before.size());
  EXPECT_EQ(poly.front(), before.front());
  EXPECT_EQ(poly.back(), before.back());
  EXPECT_EQ(poly[20], before[20]);  // the corner
  // Away from the ends and the corner (three σ), every point lies within 0.2 px of its line;
  // before, 0.8 (a Gaussian of σ = 3 px keeps exp(−2π²σ²/10²) = 17% of a 10-px period).
  float worst = 0.0f;
  for (int i = 2; i <= 18; ++i) worst = std::max(worst, std::abs(poly[static_cast<size_t>(i)].y - 50.0f));
  for (int i = 22; i <= 38; ++i) worst = std::max(worst, std::abs(poly[static_cast<size_t>(i)].x - 110.0f));
  EXPECT_LT(worst, 0.2f);
  // By default no point moves more than half a pixel: the same zig-zag keeps 0.3 px.
  std::vector<glm::vec2> limited = before;
  smoothPolyline(limited, StrokeCurveParams{}, scratch);
  float moved = 0.0f, left = 0.0f;
  for (size_t i = 0; i < limited.size(); ++i) moved = std::max(moved, glm::length(limited[i] - before[i]));
  for (int i = 2; i <= 18; ++i) left = std::max(left, std::abs(limited[static_cast<size_t>(i)].y - 50.0f));
  EXPECT_LE(moved, 0.5f + 1e-5f);
  EXPECT_NEAR(left, 0.3f, 0.01f);
  // A polyline with a point that is not finite is left alone.
  std::vector<glm::vec2> bad = before;
  bad[5].x = std::nanf("");
  smoothPolyline(bad, StrokeCurveParams{}, scratch);
  EXPECT_EQ(bad[6], before[6]);
}

}  // namespace
}  // namespace lodline
