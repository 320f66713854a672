// Coherent stroke parameterisation (present/stroke_parameterization.h) with known answers:
// a camera rolling about its view axis around a sphere keeps the contour in place on screen
// while the surface slides along it, so a texture that stays on the surface must move along
// the contour by the roll; carried from frame to frame it does (drift under 0.5 px per
// frame), and starting at each run's first point it does not (drift = the slide).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include <glm/geometric.hpp>

#include "present/stroke_parameterization.h"

namespace lodline {
namespace {

constexpr int kSize = 400;
constexpr float kRoll = 1.0f * std::numbers::pi_v<float> / 180.0f;  // per frame

Camera rolled(float theta) {
  Camera c;
  c.eye = {0.0f, 0.0f, 5.0f};
  c.target = {0.0f, 0.0f, 0.0f};
  c.up = {-std::sin(theta), std::cos(theta), 0.0f};
  c.fov_deg = 35.0f;
  c.near_plane = 0.1f;
  c.far_plane = 20.0f;
  return c;
}

// The visible contour of the unit sphere seen from (0, 0, 5): the circle z = 0.2, as `pieces`
// runs covering screen angles [a0, a1) each, sampled about a pixel apart (`reversed`: each
// run chained the other way). The camera is rolled by theta: the surface point at screen
// angle a is at world angle a + theta.
StrokeRuns contour(float theta, std::vector<std::pair<float, float>> pieces, bool reversed = false) {
  StrokeRuns r;
  const Camera cam = rolled(theta);
  const float rho = std::sqrt(1.0f - 0.04f);
  r.offsets.push_back(0);
  for (auto [a0, a1] : pieces) {
    const int n = static_cast<int>((a1 - a0) * 130.0f);  // ~1 px apart at a radius of ~130 px
    for (int k = 0; k <= n; ++k) {
      const int j = reversed ? n - k : k;
      const float a = a0 + (a1 - a0) * static_cast<float>(j) / static_cast<float>(n);
      const glm::vec3 p(rho * std::cos(a + theta), rho * std::sin(a + theta), 0.2f);
      r.points.push_back(projectToPixels(cam, p, kSize, kSize));
      r.positions.push_back(p);
      r.alpha.push_back(1.0f);
    }
    r.offsets.push_back(static_cast<uint32_t>(r.points.size()));
    r.kinds.push_back(LineKind::kContour);
    r.strokes.push_back(0);
    r.opacity.push_back(1.0f);
    r.length_px.push_back(0.0f);
  }
  return r;
}

double meanDrift(bool coherent) {
  StrokeParameterizer p;
  double sum = 0.0;
  size_t persisting = 0;
  for (int k = 0; k <= 12; ++k) {
    // Frames 6 and 7: the arc splits in two, then is chained the other way round.
    std::vector<std::pair<float, float>> pieces{{0.3f, 5.0f}};
    if (k == 6) pieces = {{0.3f, 2.5f}, {2.6f, 5.0f}};
    StrokeRuns runs = contour(kRoll * static_cast<float>(k), pieces, k == 7);
    p.update(runs, rolled(kRoll * static_cast<float>(k)), kSize, kSize, coherent);
    EXPECT_EQ(p.parameters().size(), runs.points.size());
    if (k == 0) {
      EXPECT_EQ(p.persisting(), 0u);
      continue;
    }
    EXPECT_GT(p.persisting(), runs.points.size() / 2) << k;
    sum += p.driftSum();
    persisting += p.persisting();
  }
  return sum / static_cast<double>(persisting);
}

TEST(StrokeParameterization, TextureStaysOnARollingSphere) {
  const double on = meanDrift(true), off = meanDrift(false);
  std::printf("texture drift per frame: coherent %.3f px, from each run start %.3f px\n", on, off);
  // The surface slides along the contour by radius × roll ≈ 129 px × 1° ≈ 2.3 px per frame.
  EXPECT_GT(off, 1.8);
  EXPECT_LT(on, 0.5);
  EXPECT_LT(on * 5.0, off);
}

TEST(StrokeParameterization, FirstFrameAndUnmatchedRunsStartAtTheirFirstPoint) {
  StrokeParameterizer p;
  StrokeRuns runs = contour(0.0f, {{0.3f, 2.0f}});
  p.update(runs, rolled(0.0f), kSize, kSize, true);
  ASSERT_EQ(p.parameters().size(), runs.points.size());
  float arc = 0.0f;  // u = the arc length from the run's first point
  for (size_t i = 0; i < runs.points.size(); ++i) {
    if (i > 0) arc += glm::length(runs.points[i] - runs.points[i - 1]);
    EXPECT_NEAR(p.parameters()[i], arc, 1e-3f);
  }
  // A run on the far side of the circle, where nothing was before: afresh.
  StrokeRuns far = contour(0.0f, {{3.5f, 5.0f}});
  p.update(far, rolled(0.0f), kSize, kSize, true);
  EXPECT_EQ(p.persisting(), 0u);
  EXPECT_EQ(p.parameters()[0], 0.0f);
  // After a reset nothing persists.
  p.reset();
  p.update(runs, rolled(0.0f), kSize, kSize, true);
  EXPECT_EQ(p.persisting(), 0u);
}

// A previous sample that lands on a run in the image but not on its surface (another sheet
// of the surface behind the same pixels) does not persist: it neither votes nor counts in
// the drift.
TEST(StrokeParameterization, SamplesOfAnotherSurfaceDoNotPersist) {
  StrokeParameterizer p;
  StrokeRuns first = contour(0.0f, {{0.3f, 2.0f}});
  p.update(first, rolled(0.0f), kSize, kSize, true);
  // The same arc in the image, but each point pushed 0.5 units along its view ray: the same
  // pixels, surface points ~40 px' worth away.
  const Camera cam = rolled(0.0f);
  StrokeRuns behind = first;
  for (glm::vec3& q : behind.positions) q += 0.5f * glm::normalize(q - cam.eye);
  p.update(behind, cam, kSize, kSize, true);
  EXPECT_EQ(p.persisting(), 0u);
  // Without the surface test they would all persist.
  StrokeParameterizer loose;
  StrokeParameterizationParams params;
  params.surface_px = 0.0f;
  loose.update(first, cam, kSize, kSize, true, params);
  loose.update(behind, cam, kSize, kSize, true, params);
  EXPECT_GT(loose.persisting(), behind.points.size() / 2);
}

// A closed loop is chained from an arbitrary point each frame; it is rotated to start where
// it started before, so its seam stays on the surface and the samples beside it keep their
// texture (a loop that starts elsewhere would move the seam across them).
TEST(StrokeParameterization, ClosedLoopsKeepTheirSeamOnTheSurface) {
  constexpr float kTwoPi = 2.0f * std::numbers::pi_v<float>;
  for (bool coherent : {true, false}) {
    StrokeParameterizer p;
    StrokeRuns a = contour(0.0f, {{0.3f, 0.3f + kTwoPi}});
    ASSERT_LT(glm::length(a.points.front() - a.points.back()), 0.5f);  // closed
    p.update(a, rolled(0.0f), kSize, kSize, coherent);
    const glm::vec3 seam = a.positions.front();
    // Next frame: rolled by 1°, chained from screen angle 2.0.
    StrokeRuns b = contour(kRoll, {{2.0f, 2.0f + kTwoPi}});
    p.update(b, rolled(kRoll), kSize, kSize, coherent);
    ASSERT_GT(p.persisting(), a.points.size() / 2);
    const double drift = p.driftSum() / static_cast<double>(p.persisting());
    if (coherent) {
      EXPECT_LT(glm::length(b.positions.front() - seam), 0.02f);  // starts where it started
      EXPECT_LT(glm::length(b.points.front() - b.points.back()), 0.5f);  // and is still closed
      EXPECT_LT(drift, 0.5);
    } else {
      EXPECT_GT(drift, 1.8);  // u = s from the new start: the texture slides
    }
  }
}

}  // namespace
}  // namespace lodline
