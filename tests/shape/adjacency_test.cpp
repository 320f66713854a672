// updateAdjacency(): in-place updates around changed face slots must describe exactly what a
// rebuild would (same rings in the same order, same edges with the same faces), for any
// kind of edit — including the invalid faces and non-manifold edges a rebuild tolerates.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "io/generate.h"
#include "shape/adjacency.h"

namespace lodline {
namespace {

// Face slots whose triple differs between `old_faces` and mesh.faces (incl. added/removed).
std::vector<uint32_t> changedSlots(const std::vector<std::array<uint32_t, 3>>& old_faces,
                                   const TriMesh& mesh) {
  std::vector<uint32_t> changed;
  const size_t common = std::min(old_faces.size(), mesh.faces.size());
  for (size_t f = 0; f < common; ++f)
    if (old_faces[f] != mesh.faces[f]) changed.push_back(static_cast<uint32_t>(f));
  for (size_t f = common; f < std::max(old_faces.size(), mesh.faces.size()); ++f)
    changed.push_back(static_cast<uint32_t>(f));
  return changed;
}

// Random edits of the kinds a view-dependent mesh makes (slots rewritten in place, faces
// appended, swap-removed and popped, vertices added), on a small dense vertex set where
// edges are shared by many faces, and on a torus.
TEST(Adjacency, InPlaceUpdatesMatchARebuild) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 2; ++trial) {
    TriMesh m;
    if (trial == 0) {
      m.positions.assign(12, glm::vec3(0.0f));
      auto pick = [&] { return static_cast<uint32_t>(rng() % 12); };
      for (int f = 0; f < 60; ++f) m.faces.push_back({pick(), pick(), pick()});
    } else {
      m = makeTorus(1.0f, 0.3f, 24, 12);
    }
    MeshAdjacency adj;
    buildAdjacency(m, adj);
    int in_place = 0;
    for (int round = 0; round < 400; ++round) {
      const auto old_faces = m.faces;
      const int edits = 1 + static_cast<int>(rng() % 3);
      for (int k = 0; k < edits; ++k) {
        const uint32_t nv = static_cast<uint32_t>(m.positions.size());
        auto vertex = [&] { return (rng() % 50 == 0) ? nv + 3 : static_cast<uint32_t>(rng() % nv); };
        const uint32_t f = static_cast<uint32_t>(rng() % m.faces.size());
        switch (rng() % 6) {
          case 0:  // rewrite a slot (may become invalid: repeated or out-of-range index)
            m.faces[f] = {vertex(), vertex(), vertex()};
            break;
          case 1:  // flip its orientation
            std::swap(m.faces[f][1], m.faces[f][2]);
            break;
          case 2:  // append a face sharing an edge with slot f (non-manifold edges arise)
            m.faces.push_back({m.faces[f][1], m.faces[f][0], vertex()});
            break;
          case 3:  // swap-remove slot f
            if (m.faces.size() > 8) {
              m.faces[f] = m.faces.back();
              m.faces.pop_back();
            }
            break;
          case 4:  // a new vertex on slot f's first corner's place
            m.positions.emplace_back(0.0f);
            m.faces[f][0] = nv;
            break;
          default:  // pop the last face
            if (m.faces.size() > 8) m.faces.pop_back();
            break;
        }
      }
      const auto changed = changedSlots(old_faces, m);
      if (updateAdjacency(m, old_faces, changed, adj)) {
        ++in_place;
      } else {
        buildAdjacency(m, adj);
      }
      ASSERT_EQ(checkAdjacency(m, adj), "") << "trial " << trial << ", round " << round;
    }
    EXPECT_GT(in_place, 300) << trial;  // the in-place path did the work
  }
}

// A vertex whose ring outgrows its slack moves to the end of the storage; the rings stay
// right, and a rebuild is chosen once the storage holds twice what it needs.
TEST(Adjacency, GrowingRingsMoveAndStorageIsBounded) {
  TriMesh m = makeTorus(1.0f, 0.3f, 16, 8);
  MeshAdjacency adj;
  buildAdjacency(m, adj);
  const size_t storage = adj.vertex_faces.size();
  const uint32_t nv = static_cast<uint32_t>(m.vertexCount());
  for (uint32_t k = 0; k < 12; ++k) {
    const auto old_faces = m.faces;
    m.faces.push_back({0, 1 + k, 2 + k});
    ASSERT_TRUE(updateAdjacency(m, old_faces, changedSlots(old_faces, m), adj));
    ASSERT_EQ(checkAdjacency(m, adj), "") << k;
  }
  EXPECT_GT(adj.vertex_faces.size(), storage);
  EXPECT_EQ(adj.facesOf(0).size(), 6u + 12u);
  // Many changes at once: refused, adjacency untouched.
  const auto before = m.faces;
  TriMesh edited = m;
  for (size_t f = 0; f < edited.faces.size(); f += 4) std::swap(edited.faces[f][1], edited.faces[f][2]);
  EXPECT_FALSE(updateAdjacency(edited, before, changedSlots(before, edited), adj));
  EXPECT_EQ(checkAdjacency(m, adj), "");
  (void)nv;
}

// findEdge works from the rings (no per-vertex edge table), in both directions.
TEST(Adjacency, FindEdgeAfterUpdates) {
  TriMesh m = makeTorus(1.0f, 0.3f, 12, 6);
  MeshAdjacency adj;
  buildAdjacency(m, adj);
  const auto old_faces = m.faces;
  m.faces.pop_back();
  m.faces.pop_back();
  ASSERT_TRUE(updateAdjacency(m, old_faces, changedSlots(old_faces, m), adj));
  for (size_t e = 0; e < adj.edgeCount(); ++e) {
    if (adj.edge_face_count[e] == 0) continue;
    EXPECT_EQ(adj.findEdge(adj.edges[e][0], adj.edges[e][1]), e);
    EXPECT_EQ(adj.findEdge(adj.edges[e][1], adj.edges[e][0]), e);
  }
  EXPECT_EQ(adj.findEdge(0, 0), kNoIndex);
  EXPECT_EQ(adj.findEdge(0, 100000), kNoIndex);
}

// Back-face culling is allowed only for closed surfaces seen from outside.
TEST(Adjacency, ClosedOutwardSurfaces) {
  auto closed = [](const TriMesh& m) {
    MeshAdjacency adj;
    buildAdjacency(m, adj);
    return isClosedOutward(m, adj);
  };
  const TriMesh sphere = makeIcoSphere(1.0f, 2);
  EXPECT_TRUE(closed(sphere));
  EXPECT_TRUE(closed(makeTorusKnot(2, 3, 1.0f, 0.16f, 120, 12, 0.18f)));
  // Far from the origin: the volume is taken about a vertex of the mesh.
  TriMesh far = sphere;
  for (glm::vec3& p : far.positions) p += glm::vec3(1e4f, -2e4f, 5e3f);
  EXPECT_TRUE(closed(far));
  TriMesh inside_out = sphere;
  for (auto& f : inside_out.faces) std::swap(f[1], f[2]);
  EXPECT_FALSE(closed(inside_out));
  // One face turned: the orientation is inconsistent across its edges.
  TriMesh flipped = sphere;
  std::swap(flipped.faces[7][1], flipped.faces[7][2]);
  EXPECT_FALSE(closed(flipped));
  // A hole.
  TriMesh open = sphere;
  open.faces.pop_back();
  EXPECT_FALSE(closed(open));
  EXPECT_FALSE(closed(makeGrid(2.0f, 8)));
  // Two pieces: both outward is fine; one inside out (its volume negative) is not, even when
  // the total volume is positive.
  TriMesh two = sphere, small = makeIcoSphere(0.5f, 1);
  const uint32_t base = static_cast<uint32_t>(two.positions.size());
  for (glm::vec3 p : small.positions) two.positions.push_back(p + glm::vec3(3.0f, 0.0f, 0.0f));
  for (auto f : small.faces) two.faces.push_back({f[0] + base, f[1] + base, f[2] + base});
  EXPECT_TRUE(closed(two));
  for (size_t k = sphere.faces.size(); k < two.faces.size(); ++k) std::swap(two.faces[k][1], two.faces[k][2]);
  EXPECT_FALSE(closed(two));
}

}  // namespace
}  // namespace lodline
