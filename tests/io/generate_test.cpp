// Generated surfaces: the terrain used by the depth-falloff experiment (docs/experiments.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "io/generate.h"

namespace lodline {
namespace {

TEST(GenerateTerrain, HeightFieldOverTheGrid) {
  const TriMesh t = makeTerrain(2.0f, 32), g = makeGrid(2.0f, 32);
  ASSERT_EQ(t.vertexCount(), 33u * 33u);
  ASSERT_EQ(t.faces, g.faces);
  float lo = 0.0f, hi = 0.0f;
  for (size_t i = 0; i < t.positions.size(); ++i) {
    EXPECT_EQ(t.positions[i].x, g.positions[i].x);
    EXPECT_EQ(t.positions[i].z, g.positions[i].z);
    lo = std::min(lo, t.positions[i].y);
    hi = std::max(hi, t.positions[i].y);
  }
  // Hills within the documented bound, and real relief (not flat).
  EXPECT_LE(hi, 0.11f * 2.0f);
  EXPECT_GE(lo, -0.11f * 2.0f);
  EXPECT_GT(hi - lo, 0.1f);
  // Every face still faces up (a height field has no overhangs).
  for (const auto& f : t.faces) {
    const glm::vec3 n = glm::cross(t.positions[f[1]] - t.positions[f[0]], t.positions[f[2]] - t.positions[f[0]]);
    EXPECT_GT(n.y, 0.0f);
  }
  // Deterministic.
  EXPECT_EQ(makeTerrain(2.0f, 32).positions, t.positions);
}

}  // namespace
}  // namespace lodline
