#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

#include "core/mesh.h"
#include "core/mesh_order.h"
#include "io/generate.h"
#include "test_util.h"

namespace lodline {
namespace {

// Face f as its corners' positions, turned to start at its smallest corner (the cyclic
// order, so the orientation, is kept).
using Corners = std::array<std::tuple<float, float, float>, 3>;
Corners cornersOf(const TriMesh& m, size_t f) {
  Corners c;
  for (int i = 0; i < 3; ++i) {
    const glm::vec3& p = m.positions[m.faces[f][i]];
    c[i] = {p.x, p.y, p.z};
  }
  std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
  return c;
}

// Every face's corners with its material, sorted: the same for any numbering of one surface.
std::vector<std::pair<Corners, uint32_t>> facesWithMaterials(const TriMesh& m) {
  std::vector<std::pair<Corners, uint32_t>> out;
  for (size_t f = 0; f < m.faces.size(); ++f) out.push_back({cornersOf(m, f), m.face_materials[f]});
  std::sort(out.begin(), out.end());
  return out;
}

TEST(MeshOrder, SameSurfaceNearerCorners) {
  TriMesh m = makeTorusKnot(2, 3, 1.0f, 0.3f, 256, 24, 0.1f);
  // A material per face (by position) and a few marked edges, to follow the renumbering.
  m.face_materials.resize(m.faces.size());
  for (size_t f = 0; f < m.faces.size(); ++f) m.face_materials[f] = m.positions[m.faces[f][0]].x > 0.0f ? 1 : 0;
  for (size_t f = 0; f < m.faces.size(); f += 97) m.marked_edges.push_back({m.faces[f][0], m.faces[f][1]});
  const TriMesh stored = test::shuffledMesh(m, 7);
  TriMesh ordered = stored;
  ASSERT_TRUE(orderForLocality(ordered));

  ASSERT_EQ(ordered.positions.size(), stored.positions.size());
  ASSERT_EQ(ordered.faces.size(), stored.faces.size());
  // The same oriented triangles, each with its material.
  EXPECT_EQ(facesWithMaterials(ordered), facesWithMaterials(stored));
  ASSERT_EQ(ordered.marked_edges.size(), stored.marked_edges.size());
  for (size_t k = 0; k < stored.marked_edges.size(); ++k)
    for (int i = 0; i < 2; ++i)
      EXPECT_EQ(ordered.positions[ordered.marked_edges[k][i]], stored.positions[stored.marked_edges[k][i]]);

  // Faces by their lowest corner; corners far nearer each other than in the shuffled file.
  for (size_t f = 1; f < ordered.faces.size(); ++f) {
    const auto lo = [&](size_t g) { return *std::min_element(ordered.faces[g].begin(), ordered.faces[g].end()); };
    ASSERT_LE(lo(f - 1), lo(f));
  }
  const uint32_t before = medianCornerSpread(stored), after = medianCornerSpread(ordered);
  std::printf("median corner spread: shuffled %u, ordered %u (%zu vertices)\n", before, after,
              ordered.positions.size());
  EXPECT_LT(after, before / 20);
  // Ordered again: nothing to gain, nothing changes.
  TriMesh again = ordered;
  EXPECT_FALSE(orderForLocality(again));
  EXPECT_EQ(again.faces, ordered.faces);
}

TEST(MeshOrder, LocalEmptyAndInvalidMeshesKeepTheirOrder) {
  TriMesh empty;
  EXPECT_FALSE(orderForLocality(empty));
  EXPECT_EQ(medianCornerSpread(empty), 0u);
  // All vertices at one point: the order is the stored one.
  TriMesh flat;
  flat.positions.assign(4, glm::vec3(1.0f));
  flat.faces = {{0, 1, 2}, {0, 2, 3}};
  EXPECT_FALSE(orderForLocality(flat));
  EXPECT_EQ(flat.faces[0], (std::array<uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(flat.faces[1], (std::array<uint32_t, 3>{0, 2, 3}));
  // Scattered, but every vertex at one point: all Morton codes equal, the stable sort keeps the
  // stored order, nothing to gain.
  TriMesh collapsed = test::shuffledMesh(makeIcoSphere(1.0f, 4), 9);
  for (auto& p : collapsed.positions) p = glm::vec3(0.5f);
  ASSERT_GT(medianCornerSpread(collapsed), 256u);
  TriMesh collapsed_copy = collapsed;
  std::vector<uint32_t> map{1, 2, 3};
  EXPECT_FALSE(orderForLocality(collapsed_copy, &map));
  EXPECT_EQ(collapsed_copy.faces, collapsed.faces);
  EXPECT_TRUE(map.empty());
  // A non-finite position: left for validateMesh to report.
  TriMesh nan_mesh = test::shuffledMesh(makeIcoSphere(1.0f, 4), 4);
  nan_mesh.positions[17].y = std::nanf("");
  TriMesh nan_copy = nan_mesh;
  EXPECT_FALSE(orderForLocality(nan_copy));
  EXPECT_EQ(nan_copy.faces, nan_mesh.faces);
  // Stored in a local order already (a generated tube, ring by ring): kept.
  const TriMesh knot = makeTorusKnot(2, 3, 1.0f, 0.3f, 256, 24, 0.1f);
  TriMesh knot_copy = knot;
  EXPECT_LE(medianCornerSpread(knot), 256u);
  EXPECT_FALSE(orderForLocality(knot_copy));
  EXPECT_EQ(knot_copy.faces, knot.faces);
  // An index out of range: left for validateMesh to report, nothing reordered.
  TriMesh bad = test::shuffledMesh(makeIcoSphere(1.0f, 3), 3);
  const TriMesh bad_before = bad;
  bad.faces.back()[1] = static_cast<uint32_t>(bad.positions.size());
  TriMesh copy = bad;
  EXPECT_FALSE(orderForLocality(copy));
  EXPECT_EQ(copy.faces, bad.faces);
  EXPECT_EQ(copy.positions, bad_before.positions);
}

}  // namespace
}  // namespace lodline
