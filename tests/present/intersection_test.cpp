// Intersection lines (cgal/intersections.h, chained by frame/scene_builder.h): two
// overlapping spheres cross in a circle of the analytic radius; separate ones do not cross;
// a mesh's own neighbours are not crossings.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "cgal/intersections.h"
#include "frame/scene_builder.h"
#include "io/generate.h"

namespace lodline {
namespace {

TriMesh sphereAt(glm::vec3 c, int level = 5) {
  TriMesh m = makeIcoSphere(1.0f, level);
  for (auto& p : m.positions) p += c;
  return m;
}

TEST(Intersections, TwoOverlappingSpheresCrossInACircleOfTheRightRadius) {
  const TriMesh a = sphereAt({-0.5f, 0.0f, 0.0f}), b = sphereAt({0.5f, 0.0f, 0.0f});
  const std::vector<const TriMesh*> meshes{&a, &b};
  const auto segments = findIntersectionSegments(meshes);
  ASSERT_EQ(segments.size(), 2u);
  EXPECT_TRUE(segments[1].empty());  // a pair's crossing belongs to the first object
  ASSERT_GT(segments[0].size(), 100u);
  // Unit spheres 1 apart cross in the plane x = 0, in a circle of radius sqrt(1 - 0.25).
  const double expected = std::sqrt(0.75);
  double worst = 0.0;
  for (const glm::vec3& p : segments[0]) {
    EXPECT_NEAR(p.x, 0.0f, 2e-3f);
    worst = std::max(worst, std::abs(std::hypot(p.y, p.z) - expected) / expected);
  }
  EXPECT_LT(worst, 0.01) << "radius off by " << 100.0 * worst << "%";
  // Chained: one closed loop as long as the circle.
  StrokeSet strokes;
  chainIntersections(segments[0], 1e-6f, strokes);
  ASSERT_EQ(strokes.strokeCount(), 1u);
  EXPECT_EQ(strokes.closed[0], 1);
  EXPECT_EQ(strokes.kinds[0], LineKind::kIntersection);
  double length = 0.0;
  for (uint32_t i = strokes.offsets[0]; i + 1 < strokes.offsets[1]; ++i)
    length += glm::length(strokes.points[i + 1] - strokes.points[i]);
  EXPECT_NEAR(length, 2.0 * std::numbers::pi * expected, 0.01 * 2.0 * std::numbers::pi * expected);
}

TEST(Intersections, SeparateSpheresAndAClosedMeshDoNotCross) {
  const TriMesh a = sphereAt({-1.5f, 0.0f, 0.0f}, 4), b = sphereAt({1.5f, 0.0f, 0.0f}, 4);
  const std::vector<const TriMesh*> meshes{&a, &b};
  const auto segments = findIntersectionSegments(meshes);
  ASSERT_EQ(segments.size(), 2u);
  EXPECT_TRUE(segments[0].empty());
  EXPECT_TRUE(segments[1].empty());
  // A mesh whose faces are duplicated (same corners) or touch its neighbours along shared
  // edges has no crossing either.
  TriMesh twice = makeTorus(1.0f, 0.35f, 48, 24);
  const size_t n = twice.faces.size();
  for (size_t f = 0; f < n; f += 7) twice.faces.push_back(twice.faces[f]);
  const std::vector<const TriMesh*> one{&twice};
  EXPECT_TRUE(findIntersectionSegments(one)[0].empty());
}

TEST(Intersections, APartCrossingItsOwnMeshIsFound) {
  // Two overlapping spheres in one mesh: a self-intersection.
  TriMesh both = sphereAt({-0.5f, 0.0f, 0.0f}, 4);
  const TriMesh other = sphereAt({0.5f, 0.0f, 0.0f}, 4);
  const uint32_t base = static_cast<uint32_t>(both.positions.size());
  both.positions.insert(both.positions.end(), other.positions.begin(), other.positions.end());
  for (const auto& f : other.faces) both.faces.push_back({f[0] + base, f[1] + base, f[2] + base});
  const std::vector<const TriMesh*> one{&both};
  const auto segments = findIntersectionSegments(one);
  ASSERT_GT(segments[0].size(), 50u);
  for (const glm::vec3& p : segments[0]) EXPECT_NEAR(p.x, 0.0f, 5e-3f);
}

}  // namespace
}  // namespace lodline
