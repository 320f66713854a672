// The level-set kinds on analytic surfaces (docs/lines.md): isophotes of a sphere are the
// circles n·l = c, topographic lines of a sphere equally spaced circles, parabolic lines of a
// torus its top and bottom circles — each within a tolerance that shrinks as the mesh is
// refined. The errors printed are the table in docs/lines.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <vector>

#include <glm/geometric.hpp>

#include "io/generate.h"
#include "lines/level_lines.h"
#include "lines/lines.h"
#include "lines/view_quantities.h"
#include "shape/shape_cache.h"

namespace lodline {
namespace {

// Segments of one level kind on `m` (feature size 1, so thresholds are absolute).
LineSet levelLines(const TriMesh& m, LineKind kind, const LevelSpec& spec_in) {
  ShapeCache shape;
  shape.compute(m);
  LevelSpec spec = spec_in;
  spec.isophotes = kind == LineKind::kIsophote;
  spec.topo = kind == LineKind::kTopo;
  spec.parabolic = kind == LineKind::kParabolic;
  ViewQuantities q;
  computeLevelQuantities(shape.fields(m), spec, q);
  LineParams p;
  p.contours = p.suggestive = p.creases = p.marked_edges = p.boundaries = false;
  p.isophotes = spec.isophotes;
  p.topo = spec.topo;
  p.parabolic = spec.parabolic;
  LineScratch scratch;
  LineSet out;
  extractLines(m, shape.adjacency(), shape.faceNormals(), q, p, 1.0f, scratch, out);
  return out;
}

// Distance of x from the nearest multiple of `step`, and that multiple's index.
double offLevel(double x, double step, long* level = nullptr) {
  const double k = std::round(x / step);
  if (level) *level = std::lround(k);
  return std::abs(x - k * step);
}

TEST(LevelLines, WaveIsZeroAtIntegersAndLinearBetween) {
  for (int k = -3; k <= 3; ++k) {
    EXPECT_NEAR(levelWave(static_cast<float>(k)), 0.0f, 1e-6f);
    EXPECT_NEAR(std::abs(levelWave(k + 0.5f)), 0.5f, 1e-6f);
    // Slope ±1 on either side, opposite signs: every integer is a sign change.
    EXPECT_NEAR(std::abs(levelWave(k + 0.1f) - levelWave(k - 0.1f)), 0.2f, 1e-5f);
    EXPECT_LT(levelWave(k + 0.1f) * levelWave(k - 0.1f), 0.0f);
  }
}

TEST(LevelLines, LightInModelSpaceFollowsTheCamera) {
  Camera cam;
  cam.eye = {0, 0, 5};
  cam.target = {0, 0, 0};
  cam.up = {0, 1, 0};
  // Eye space +z is towards the viewer: the light behind the camera shines along −forward.
  EXPECT_NEAR(glm::length(lightInModelSpace(cam, {0, 0, 1}) - glm::vec3(0, 0, 1)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::length(lightInModelSpace(cam, {1, 0, 0}) - glm::vec3(1, 0, 0)), 0.0f, 1e-6f);
  cam.eye = {5, 0, 0};  // looking down −x: eye +x is world −z
  EXPECT_NEAR(glm::length(lightInModelSpace(cam, {1, 0, 0}) - glm::vec3(0, 0, -1)), 0.0f, 1e-6f);
}

TEST(LevelLines, SphereIsophotesAreCirclesOfConstantNdotL) {
  LevelSpec spec;
  spec.light = glm::normalize(glm::vec3(1, 2, 2));
  spec.isophote_spacing = 0.25f;
  double previous = 1e9;
  for (int level : {3, 4, 5, 6}) {
    const TriMesh m = makeIcoSphere(1.0f, level);
    const LineSet s = levelLines(m, LineKind::kIsophote, spec);
    ASSERT_GT(s.segmentCount(), 0u);
    double worst = 0.0;
    std::set<long> levels;
    for (const glm::vec3& p : s.points) {
      long k = 0;
      const double c = glm::dot(glm::normalize(p), spec.light);
      worst = std::max(worst, offLevel(c, spec.isophote_spacing, &k));
      levels.insert(k);
      EXPECT_GE(k, 0) << "a level below the terminator";
    }
    // n·l = 0, 0.25, 0.5, 0.75: four circles (n·l = 1 is a point).
    EXPECT_EQ(levels, (std::set<long>{0, 1, 2, 3})) << "level " << level;
    std::printf("isophotes, icosphere level %d (%zu faces): max |n.l - c| = %.2e\n", level, m.faceCount(), worst);
    EXPECT_LT(worst, previous) << "the error shrinks as the sphere is refined";
    previous = worst;
  }
  EXPECT_LT(previous, 2e-3);
}

TEST(LevelLines, SphereTopographicLinesAreEquallySpacedCircles) {
  LevelSpec spec;
  spec.topo_origin = glm::vec3(0.0f);
  spec.topo_axis = {0, 1, 0};
  spec.topo_spacing = 0.15f;
  double previous = 1e9;
  for (int level : {3, 4, 5, 6}) {
    const TriMesh m = makeIcoSphere(1.0f, level);
    const LineSet s = levelLines(m, LineKind::kTopo, spec);
    double worst = 0.0;
    std::set<long> levels;
    for (const glm::vec3& p : s.points) {
      long k = 0;
      worst = std::max(worst, offLevel(p.y, spec.topo_spacing, &k));
      levels.insert(k);
    }
    // |k·0.15| < 1: k = −6..6, thirteen circles.
    EXPECT_EQ(levels.size(), 13u) << "level " << level;
    EXPECT_EQ(*levels.begin(), -6);
    EXPECT_EQ(*levels.rbegin(), 6);
    // Each circle lies on the sphere: radius sqrt(1 − h²) up to the chord's sag.
    std::printf("topo, icosphere level %d: max |h - k s| = %.2e\n", level, worst);
    EXPECT_LE(worst, previous + 1e-7);
    previous = worst;
  }
  // Heights are linear on an edge: exact up to rounding.
  EXPECT_LT(previous, 1e-5);
}

TEST(LevelLines, TorusParabolicLinesAreItsTopAndBottomCircles) {
  const float R = 1.0f, r = 0.3f;
  LevelSpec spec;
  spec.feature_size = 1.0f;
  spec.parabolic_threshold = 1.0f;  // the tube's curvature 1/r = 3.3 passes, K = 0 nowhere else
  double previous = 1e9;
  for (int n : {48, 96, 192, 384}) {
    const TriMesh m = makeTorus(R, r, n, n / 2);
    // The axis: the box's thin dimension.
    glm::vec3 lo(1e9f), hi(-1e9f);
    for (const glm::vec3& p : m.positions) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    const glm::vec3 ext = hi - lo;
    const int a = ext.x < ext.y && ext.x < ext.z ? 0 : ext.y < ext.z ? 1 : 2;
    const LineSet s = levelLines(m, LineKind::kParabolic, spec);
    ASSERT_GT(s.segmentCount(), 0u);
    double worst_h = 0.0, worst_rho = 0.0;
    size_t top = 0, bottom = 0;
    for (const glm::vec3& p : s.points) {
      const double h = p[a];
      glm::vec3 q = p;
      q[a] = 0.0f;
      worst_h = std::max(worst_h, std::abs(std::abs(h) - r));
      worst_rho = std::max(worst_rho, std::abs(double(glm::length(q)) - R));
      (h > 0 ? top : bottom)++;
    }
    EXPECT_GT(top, 0u);
    EXPECT_GT(bottom, 0u);
    const double worst = std::max(worst_h, worst_rho);
    std::printf("parabolic, torus %dx%d: max height error %.2e, radius error %.2e\n", n, n / 2, worst_h, worst_rho);
    EXPECT_LT(worst, previous) << "the error shrinks as the torus is refined";
    previous = worst;
  }
  EXPECT_LT(previous, 5e-3);
}

}  // namespace
}  // namespace lodline
