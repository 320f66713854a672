// View-dependent vertex clustering (Pan, Zhou, Shi; src/lod/vertex_clustering.h): weights,
// the clustering radius, valid output faces, culling that keeps boundary triangles whole,
// and the grid against a brute-force reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "io/generate.h"
#include "io/load_mesh.h"
#include "lod/vertex_clustering.h"
#include "test_util.h"

namespace lodline {
namespace {

constexpr int kW = 1280, kH = 720;

Camera lookAt(glm::vec3 eye, glm::vec3 target, const Bounds& b) {
  Camera c;
  c.eye = eye;
  c.target = target;
  if (std::abs(glm::dot(glm::normalize(target - eye), c.up)) > 0.99f) c.up = {0.0f, 0.0f, -1.0f};
  fitClipPlanes(c, b);
  return c;
}

/// Checks the output faces: indices in range, three distinct corners, non-zero area, no two
/// faces with the same corner set.
void expectValidFaces(const VertexClustering& vc) {
  const auto& pos = vc.mesh().positions;
  std::set<std::array<uint32_t, 3>> seen;
  for (const auto& f : vc.faces()) {
    for (uint32_t v : f) ASSERT_LT(v, pos.size());
    ASSERT_TRUE(f[0] != f[1] && f[1] != f[2] && f[2] != f[0]);
    const glm::vec3 cr = glm::cross(pos[f[1]] - pos[f[0]], pos[f[2]] - pos[f[0]]);
    EXPECT_GT(glm::length(cr), 0.0f);
    auto key = f;
    std::sort(key.begin(), key.end());
    EXPECT_TRUE(seen.insert(key).second) << "duplicate face";
  }
}

/// Every visible vertex maps to a representative that maps to itself, lies within that
/// representative's radius, and the radius is sqrt(K) pixels at the representative's depth.
void expectRadiusRespected(const VertexClustering& vc, const Camera& cam, float k) {
  const auto rep = vc.representatives();
  const auto r = vc.radii();
  const auto& pos = vc.mesh().positions;
  for (uint32_t v = 0; v < rep.size(); ++v) {
    if (rep[v] == kClusterCulled) continue;
    const uint32_t c = rep[v];
    ASSERT_LT(c, rep.size());
    ASSERT_EQ(rep[c], c);
    EXPECT_LE(glm::distance(pos[v], pos[c]), r[c] * (1.0f + 1e-5f));
  }
  // R in pixels: a segment of length R at the vertex's depth, perpendicular to the view
  // axis, projects to sqrt(K) pixels.
  const glm::vec3 right = glm::normalize(glm::cross(cam.forward(), cam.up));
  int checked = 0;
  for (uint32_t v = 0; v < rep.size() && checked < 50; ++v) {
    if (rep[v] != v) continue;
    const glm::vec2 a = projectToPixels(cam, pos[v], kW, kH);
    const glm::vec2 b = projectToPixels(cam, pos[v] + r[v] * right, kW, kH);
    // Off-axis points see a slightly different scale (perspective), within a few percent.
    EXPECT_NEAR(glm::distance(a, b), std::sqrt(k), 0.05f * std::sqrt(k));
    ++checked;
  }
  EXPECT_GT(checked, 0);
}

TEST(VertexClustering, WeightsAreFlatZeroCurvedPositiveBoundaryMaximal) {
  const TriMesh grid = makeGrid(2.0f, 10);
  VertexClustering vc(grid);
  for (uint32_t v = 0; v < grid.vertexCount(); ++v) {
    if (vc.boundaryVertices()[v]) EXPECT_NEAR(vc.weights()[v], 3.14159f, 1e-4f);
    else EXPECT_NEAR(vc.weights()[v], 0.0f, 1e-3f);
  }
  // Boundary vertices come first in the order.
  EXPECT_TRUE(vc.boundaryVertices()[vc.order()[0]]);
  EXPECT_FALSE(vc.boundaryVertices()[vc.order().back()]);
  for (size_t i = 1; i < vc.order().size(); ++i)
    EXPECT_GE(vc.weights()[vc.order()[i - 1]], vc.weights()[vc.order()[i]]);
  // An icosahedron: every vertex has the same positive weight (mean angle to its faces).
  const TriMesh ico = makeIcoSphere(1.0f, 0);
  VertexClustering vs(ico);
  for (float w : vs.weights()) {
    EXPECT_GT(w, 0.1f);
    EXPECT_NEAR(w, vs.weights()[0], 1e-3f);
  }
}

TEST(VertexClustering, RadiusAndValidFacesOnATorusKnot) {
  const TriMesh knot = makeTorusKnot(2, 3, 1.0f, 0.16f, 480, 32, 0.15f);
  const Bounds b = computeBounds(knot.positions);
  VertexClustering vc(knot);
  uint32_t prev_faces = 0xffffffffu;
  for (float k : {0.25f, 1.0f, 4.0f, 16.0f, 64.0f}) {
    const Camera cam = orbitCamera(b, {30.0f, 20.0f, 0.0f}, 35.0f, float(kW) / kH);
    ClusterParams p;
    p.pixel_error = k;
    vc.cluster(cam, kW, kH, p);
    SCOPED_TRACE(k);
    expectValidFaces(vc);
    expectRadiusRespected(vc, cam, k);
    EXPECT_LE(vc.stats().faces, prev_faces);  // coarser with larger K
    prev_faces = vc.stats().faces;
  }
  EXPECT_LT(prev_faces, knot.faceCount() / 2);
}

TEST(VertexClustering, FarViewsMergeMoreThanNearViews) {
  const TriMesh knot = makeTorusKnot(2, 3, 1.0f, 0.16f, 480, 32, 0.15f);
  const Bounds b = computeBounds(knot.positions);
  VertexClustering vc(knot);
  vc.cluster(orbitCamera(b, {30.0f, 20.0f, 0.0f}, 35.0f, float(kW) / kH), kW, kH, {});
  const uint32_t near = vc.stats().representatives;
  vc.cluster(orbitCamera(b, {30.0f, 20.0f, 100.0f}, 35.0f, float(kW) / kH), kW, kH, {});
  EXPECT_LT(vc.stats().representatives, near / 4);
  expectValidFaces(vc);
}

TEST(VertexClustering, CullingKeepsBoundaryCrossingTrianglesWhole) {
  // A grid seen from above, zoomed so the frustum cuts it: triangles with one vertex inside
  // and two outside appear with their outside corners untouched; triangles wholly outside on
  // one side are dropped.
  const TriMesh grid = makeGrid(2.0f, 60);
  const Bounds b = computeBounds(grid.positions);
  VertexClustering vc(grid);
  Camera cam = lookAt({0.3f, 0.8f, 0.2f}, {0.3f, 0.0f, 0.2f}, b);
  ClusterParams p;
  p.pixel_error = 16.0f;
  vc.cluster(cam, kW, kH, p);
  expectValidFaces(vc);
  const auto rep = vc.representatives();
  EXPECT_GT(vc.stats().culled_vertices, 0u);
  EXPECT_GT(vc.stats().culled_faces, 0u);
  std::set<std::array<uint32_t, 3>> out;
  for (auto f : vc.faces()) {
    std::sort(f.begin(), f.end());
    out.insert(f);
  }
  int crossing = 0;
  for (const auto& f : grid.faces) {
    int culled = 0;
    for (uint32_t v : f) culled += rep[v] == kClusterCulled;
    if (culled != 2) continue;
    std::array<uint32_t, 3> m;
    for (int i = 0; i < 3; ++i) m[i] = rep[f[i]] == kClusterCulled ? f[i] : rep[f[i]];
    std::sort(m.begin(), m.end());
    EXPECT_TRUE(out.count(m)) << "boundary triangle dropped";
    ++crossing;
  }
  EXPECT_GT(crossing, 10);
  // Boundary vertices of the mesh are never absorbed.
  for (uint32_t v = 0; v < rep.size(); ++v)
    if (vc.boundaryVertices()[v] && rep[v] != kClusterCulled) {
      EXPECT_EQ(rep[v], v);
    }
  // Seen from below the grid faces away: everything is culled.
  vc.cluster(lookAt({0.0f, -2.0f, 0.1f}, {0.0f, 0.0f, 0.0f}, b), kW, kH, p);
  EXPECT_EQ(vc.stats().faces, 0u);
}

TEST(VertexClustering, GridMatchesBruteForce) {
  const TriMesh ico = makeIcoSphere(1.0f, 4);
  const Bounds b = computeBounds(ico.positions);
  VertexClustering vc(ico);
  for (float dist : {1.5f, 4.0f, 12.0f}) {
    const Camera cam = orbitCamera(b, {10.0f, 30.0f, dist}, 35.0f, float(kW) / kH);
    ClusterParams p;
    p.pixel_error = 9.0f;
    p.foveation = 1.0f;
    p.focus_px = {200.0f, 300.0f};
    vc.cluster(cam, kW, kH, p);
    const auto rep = vc.representatives();
    const auto r = vc.radii();
    std::vector<uint32_t> ref(rep.size());
    for (uint32_t v = 0; v < rep.size(); ++v) ref[v] = rep[v] == kClusterCulled ? kClusterCulled : 0xfffffffeu;
    for (uint32_t v : vc.order()) {
      if (ref[v] != 0xfffffffeu) continue;
      ref[v] = v;
      for (uint32_t w = 0; w < ref.size(); ++w)
        if (ref[w] == 0xfffffffeu && glm::distance(ico.positions[v], ico.positions[w]) <= r[v] * (1.0f - 1e-6f))
          ref[w] = v;
    }
    int differ = 0;
    for (uint32_t v = 0; v < rep.size(); ++v) differ += rep[v] != ref[v];
    // Only ties at exactly the radius (float rounding of the two distance forms) may differ.
    EXPECT_LE(differ, 2) << "dist " << dist;
  }
}

TEST(VertexClustering, FoveationCoarsensAwayFromTheFocus) {
  const TriMesh grid = makeGrid(2.0f, 120);
  const Bounds b = computeBounds(grid.positions);
  VertexClustering vc(grid);
  const Camera cam = lookAt({0.0f, 2.5f, 0.01f}, {0.0f, 0.0f, 0.0f}, b);
  ClusterParams p;
  p.pixel_error = 36.0f;  // 6 px: just below the grid spacing at the centre
  vc.cluster(cam, kW, kH, p);
  const uint32_t plain = vc.stats().faces;
  p.foveation = 1.0f;
  p.focus_px = {0.0f, 0.0f};
  vc.cluster(cam, kW, kH, p);
  EXPECT_LT(vc.stats().faces, plain);
  expectValidFaces(vc);
}

TEST(VertexClustering, BunnyFacesValidAcrossViews) {
  const auto path = test::dataMesh("bunny00.off");
  if (path.empty()) GTEST_SKIP() << "data/meshes/bunny00.off not extracted";
  auto mesh = loadMesh(path);
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  const Bounds b = computeBounds(mesh->positions);
  VertexClustering vc(*mesh);
  for (float az : {0.0f, 120.0f, 240.0f}) {
    const Camera cam = orbitCamera(b, {az, 15.0f, 0.0f}, 35.0f, float(kW) / kH);
    vc.cluster(cam, kW, kH, {});
    SCOPED_TRACE(az);
    expectValidFaces(vc);
    expectRadiusRespected(vc, cam, 1.0f);
    EXPECT_GT(vc.stats().faces, 1000u);
    EXPECT_LT(vc.stats().faces, mesh->faceCount());
  }
}

}  // namespace
}  // namespace lodline
