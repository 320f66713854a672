// Painting by planes (io/mesh_paint.h): the cut keeps the surface and its closedness, the
// material boundary lies on the plane, slabs give two boundaries, existing materials and
// marked edges are kept, and bad regions are refused with the mesh named.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <glm/geometric.hpp>

#include "io/generate.h"
#include "io/mesh_paint.h"

namespace lodline {
namespace {

double area(const TriMesh& m) {
  double a = 0.0;
  for (const auto& f : m.faces)
    a += 0.5 * glm::length(glm::cross(m.positions[f[1]] - m.positions[f[0]], m.positions[f[2]] - m.positions[f[0]]));
  return a;
}

// Undirected edge → the faces using it.
std::map<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>> edgeFaces(const TriMesh& m) {
  std::map<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>> out;
  for (uint32_t f = 0; f < m.faces.size(); ++f)
    for (int i = 0; i < 3; ++i) {
      uint32_t a = m.faces[f][i], b = m.faces[f][(i + 1) % 3];
      out[{std::min(a, b), std::max(a, b)}].push_back(f);
    }
  return out;
}

float longestEdge(const TriMesh& m) {
  float l = 0.0f;
  for (const auto& f : m.faces)
    for (int i = 0; i < 3; ++i) l = std::max(l, glm::distance(m.positions[f[i]], m.positions[f[(i + 1) % 3]]));
  return l;
}

// The vertices of edges between faces of different materials.
std::set<uint32_t> boundaryVertices(const TriMesh& m) {
  std::set<uint32_t> out;
  for (const auto& [e, fs] : edgeFaces(m))
    if (fs.size() == 2 && m.face_materials[fs[0]] != m.face_materials[fs[1]]) {
      out.insert(e.first);
      out.insert(e.second);
    }
  return out;
}

TEST(MeshPaint, HalfSpaceCutsASphereAlongThePlane) {
  TriMesh m = makeIcoSphere(1.0f, 3);
  const double area_before = area(m);
  const float edge = longestEdge(m);
  const PaintRegion r{{0.0f, 2.0f, 0.0f}, 0.6f};  // y >= 0.3 (the normal is normalised)
  auto info = paintMesh(m, std::span(&r, 1), "sphere");
  ASSERT_TRUE(info) << info.error().message;
  EXPECT_GT(info->cut_edges, 20u);
  ASSERT_EQ(m.face_materials.size(), m.faces.size());
  EXPECT_NEAR(area(m), area_before, 1e-5 * area_before);
  // Still closed: every edge has exactly two faces.
  for (const auto& [e, fs] : edgeFaces(m)) ASSERT_EQ(fs.size(), 2u);
  // Each face is wholly on its side; the boundary's vertices are on the plane (within the
  // 5% snap of an edge), and they form one loop round the sphere.
  for (size_t f = 0; f < m.faces.size(); ++f)
    for (uint32_t v : m.faces[f]) {
      if (m.face_materials[f] == 1) {
        EXPECT_GT(m.positions[v].y, 0.3f - 0.05f * edge);
      } else {
        EXPECT_LT(m.positions[v].y, 0.3f + 0.05f * edge);
      }
    }
  const auto boundary = boundaryVertices(m);
  EXPECT_GT(boundary.size(), 20u);
  for (uint32_t v : boundary) EXPECT_NEAR(m.positions[v].y, 0.3f, 0.05f * edge);
  size_t painted = std::count(m.face_materials.begin(), m.face_materials.end(), 1u);
  EXPECT_EQ(painted, info->painted_faces);
  // The cap y ≥ 0.3 holds (1 − 0.3) / 2 = 35% of the sphere's area.
  double cap = 0.0;
  TriMesh caps = m;
  caps.faces.clear();
  for (size_t f = 0; f < m.faces.size(); ++f)
    if (m.face_materials[f] == 1) caps.faces.push_back(m.faces[f]);
  cap = area(caps);
  EXPECT_NEAR(cap / area(m), 0.35, 0.01);
  // No sliver: every new face keeps a sensible share of its longest edge.
  for (const auto& f : m.faces) {
    const glm::vec3 a = m.positions[f[0]], b = m.positions[f[1]], c = m.positions[f[2]];
    const float l = std::max({glm::distance(a, b), glm::distance(b, c), glm::distance(c, a)});
    EXPECT_GT(glm::length(glm::cross(b - a, c - a)) / (l * l), 0.02f);
  }
}

TEST(MeshPaint, SlabPaintsABandWithTwoBoundaries) {
  TriMesh m = makeUvSphere(1.0f, 48, 24);
  const PaintRegion r{{0.0f, 1.0f, 0.0f}, -0.2f, 0.4f};  // −0.2 ≤ y ≤ 0.2
  auto info = paintMesh(m, std::span(&r, 1), "sphere");
  ASSERT_TRUE(info) << info.error().message;
  const auto boundary = boundaryVertices(m);
  size_t low = 0, high = 0;
  for (uint32_t v : boundary) {
    const float y = m.positions[v].y;
    if (std::abs(y + 0.2f) < 0.02f) ++low;
    else if (std::abs(y - 0.2f) < 0.02f) ++high;
    else ADD_FAILURE() << "boundary vertex at y = " << y;
  }
  EXPECT_GE(low, 48u);
  EXPECT_GE(high, 48u);
  for (size_t f = 0; f < m.faces.size(); ++f) {
    glm::vec3 c(0.0f);
    for (uint32_t v : m.faces[f]) c += m.positions[v] / 3.0f;
    EXPECT_EQ(m.face_materials[f], std::abs(c.y) < 0.2f ? 1u : 0u) << "face at y = " << c.y;
  }
}

TEST(MeshPaint, KeepsMaterialsAndMarkedEdgesAndLaterRegionsWin) {
  TriMesh m = makeGrid(2.0f, 8);  // the plane y = 0, x and z in [−1, 1]
  m.face_materials.assign(m.faces.size(), 0);
  for (size_t f = 0; f < m.faces.size(); f += 2) m.face_materials[f] = 1;
  // Mark every edge of the grid's rim on the side z = −1.
  for (const auto& [e, fs] : edgeFaces(m))
    if (std::abs(m.positions[e.first].z + 1.0f) < 1e-5f && std::abs(m.positions[e.second].z + 1.0f) < 1e-5f)
      m.marked_edges.push_back({e.first, e.second});
  const size_t marked_before = m.marked_edges.size();
  ASSERT_GT(marked_before, 0u);
  const PaintRegion regions[] = {{{1.0f, 0.0f, 0.0f}, 0.1f}, {{1.0f, 0.0f, 0.0f}, 0.6f}};  // x ≥ 0.1, then x ≥ 0.6
  auto info = paintMesh(m, regions, "grid");
  ASSERT_TRUE(info) << info.error().message;
  for (size_t f = 0; f < m.faces.size(); ++f) {
    glm::vec3 c(0.0f);
    for (uint32_t v : m.faces[f]) c += m.positions[v] / 3.0f;
    const uint32_t want = c.x > 0.6f ? 3u : c.x > 0.1f ? 2u : m.face_materials[f];
    EXPECT_EQ(m.face_materials[f], want);
    if (c.x < 0.1f) {
      EXPECT_LE(m.face_materials[f], 1u);
    }
  }
  // The cut rim edges stay marked in both halves: the marked length is unchanged.
  EXPECT_EQ(m.marked_edges.size(), marked_before + 2);  // x = 0.1 and x = 0.6 each cut one rim edge
  float marked_length = 0.0f;
  for (const auto& e : m.marked_edges) marked_length += glm::distance(m.positions[e[0]], m.positions[e[1]]);
  EXPECT_NEAR(marked_length, 2.0f, 1e-4f);
}

TEST(MeshPaint, APlaneMissingTheMeshPaintsAllOrNothing) {
  TriMesh m = makeIcoSphere(1.0f, 1);
  const size_t faces = m.faces.size();
  const PaintRegion above{{0.0f, 0.0f, 1.0f}, 5.0f};
  auto info = paintMesh(m, std::span(&above, 1), "sphere");
  ASSERT_TRUE(info);
  EXPECT_EQ(info->painted_faces, 0u);
  EXPECT_EQ(m.faces.size(), faces);
  EXPECT_TRUE(m.face_materials.empty());  // one material is none
}

TEST(MeshPaint, RefusesBadRegionsNamingTheMesh) {
  TriMesh m = makeIcoSphere(1.0f, 1);
  const PaintRegion zero{{0.0f, 0.0f, 0.0f}, 0.0f};
  auto a = paintMesh(m, std::span(&zero, 1), "part.off");
  ASSERT_FALSE(a);
  EXPECT_NE(a.error().message.find("part.off"), std::string::npos);
  EXPECT_NE(a.error().message.find("normal"), std::string::npos);
  const PaintRegion thick{{0.0f, 1.0f, 0.0f}, 0.0f, -1.0f};
  auto b = paintMesh(m, std::span(&thick, 1), "part.off");
  ASSERT_FALSE(b);
  EXPECT_NE(b.error().message.find("thickness"), std::string::npos);
  const PaintRegion inf{{0.0f, 1.0f, 0.0f}, INFINITY};
  EXPECT_FALSE(paintMesh(m, std::span(&inf, 1), "part.off"));
}

}  // namespace
}  // namespace lodline
