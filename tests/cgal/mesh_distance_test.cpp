// Pan, Zhou, Shi's approximation error E_s and the Hausdorff distance through CGAL's AABB tree
// (src/cgal/mesh_distance.h) on meshes with known distances, and the error-bounded
// simplification (pm/progressive_mesh.h simplifyWithinBound) on bunny00.off.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "cgal/mesh_distance.h"
#include "io/generate.h"
#include "io/load_mesh.h"
#include "pm/progressive_mesh.h"
#include "test_util.h"

namespace lodline {
namespace {

TEST(MeshDistance, IdenticalMeshesHaveZeroError) {
  const TriMesh m = makeTorus(1.0f, 0.3f, 48, 16);
  auto d = measureMeshDistance(m, m);
  ASSERT_TRUE(d.ok()) << d.error().message;
  EXPECT_LT(d->e_s, 1e-6);
  EXPECT_LT(d->hausdorff, 1e-6);
}

TEST(MeshDistance, ShiftedParallelPlaneIsAtTheShift) {
  // Two identical grids, the second lifted by h along its normal: every vertex of either lies
  // exactly h above/below the other plane (its foot point is inside the other grid).
  const TriMesh a = makeGrid(2.0f, 20);
  for (float h : {0.001f, 0.05f, 0.3f}) {
    TriMesh b = a;
    for (auto& p : b.positions) p.y += h;
    auto d = measureMeshDistance(a, b);
    ASSERT_TRUE(d.ok()) << d.error().message;
    EXPECT_NEAR(d->e_s, h, 1e-6 + 1e-5 * h);
    EXPECT_NEAR(d->hausdorff, h, 1e-6 + 1e-5 * h);
    EXPECT_NEAR(d->mean_o_to_s, h, 1e-6 + 1e-5 * h);
    EXPECT_NEAR(d->mean_s_to_o, h, 1e-6 + 1e-5 * h);
    EXPECT_NEAR(d->diagonal, std::sqrt(8.0), 1e-5);
    EXPECT_NEAR(d->relativeEs(), h / std::sqrt(8.0), 1e-6);
  }
}

/// Largest sagitta of an icosphere of radius 1: 1 − the smallest distance from the centre to
/// a face plane.
double maxSagitta(const TriMesh& m) {
  double s = 0.0;
  for (const auto& f : m.faces) {
    const glm::dvec3 a(m.positions[f[0]]), b(m.positions[f[1]]), c(m.positions[f[2]]);
    const glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a));
    s = std::max(s, 1.0 - std::abs(glm::dot(n, a)));
  }
  return s;
}

TEST(MeshDistance, InscribedIcosphereIsWithinTheSagitta) {
  // The "sphere" is a fine icosphere (vertices on the unit sphere); the inscribed polyhedra
  // are coarser icospheres with their vertices on the same sphere.
  const TriMesh sphere = makeIcoSphere(1.0f, 5);
  const double fine = maxSagitta(sphere);
  auto tree = SurfaceDistance::create(sphere, "sphere");
  ASSERT_TRUE(tree.ok());
  double prev = 1e9;
  for (int level : {1, 2, 3}) {
    const TriMesh poly = makeIcoSphere(1.0f, level);
    const double sag = maxSagitta(poly);
    auto d = measureMeshDistance(sphere, *tree, poly);
    ASSERT_TRUE(d.ok());
    SCOPED_TRACE(level);
    EXPECT_GT(d->e_s, 0.0);
    EXPECT_LE(d->e_s, sag);
    EXPECT_LE(d->hausdorff, sag + fine);
    EXPECT_GE(d->hausdorff, 0.5 * sag);  // face centres sit about a sagitta inside
    EXPECT_LE(d->mean_s_to_o, fine);     // the polyhedron's vertices lie on the sphere
    EXPECT_LT(d->e_s, prev);             // finer polyhedra are closer
    prev = d->e_s;
    // Single point queries agree with the batch.
    EXPECT_NEAR(tree->distance({0.0f, 0.0f, 0.0f}), 1.0, fine + 1e-6);
  }
}

TEST(MeshDistance, MeshWithoutTrianglesIsAnError) {
  TriMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  m.faces = {{0, 1, 2}};  // collinear: degenerate
  auto t = SurfaceDistance::create(m, "flat.off");
  ASSERT_FALSE(t.ok());
  EXPECT_NE(t.error().message.find("flat.off"), std::string::npos);
}

TEST(BoundedSimplification, LevelMeshesSpanInputToBase) {
  const TriMesh m = makeTorus(1.0f, 0.3f, 48, 16);
  auto pm = buildProgressiveMesh(m);
  ASSERT_TRUE(pm.ok());
  const TriMesh l0 = pmLevelMesh(*pm, 0);
  EXPECT_EQ(l0.faceCount(), m.faceCount());
  EXPECT_EQ(l0.vertexCount(), m.vertexCount());
  const TriMesh base = pmLevelMesh(*pm, static_cast<uint32_t>(pm->splits.size()));
  EXPECT_EQ(base.faceCount(), pm->base_faces.size());
  EXPECT_EQ(base.vertexCount(), pm->roots.size());
  const TriMesh mid = pmLevelMesh(*pm, 100);
  EXPECT_EQ(mid.faceCount(), m.faceCount() - 200);
  EXPECT_TRUE(validateMesh(mid, "level 100").ok());
}

TEST(BoundedSimplification, MeasuredErrorNeverExceedsTheBoundOnBunny) {
  const auto path = test::dataMesh("bunny00.off");
  if (path.empty()) GTEST_SKIP() << "data/meshes/bunny00.off not extracted";
  auto mesh = loadMesh(path);
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  auto pm = buildProgressiveMesh(*mesh);
  ASSERT_TRUE(pm.ok());
  auto tree = SurfaceDistance::create(*mesh, "bunny00.off");
  ASSERT_TRUE(tree.ok());
  const double diag = computeBounds(mesh->positions).diagonal();
  auto error = [&](const TriMesh& c) {
    auto d = measureMeshDistance(*mesh, *tree, c);
    return d ? d->e_s / diag : -1.0;
  };
  size_t prev_faces = mesh->faceCount() + 1;
  for (double bound : {0.00002, 0.0001, 0.0002, 0.0005, 0.001}) {
    SCOPED_TRACE(bound);
    const BoundedSimplification s = simplifyWithinBound(*pm, bound, error);
    // Measure again from scratch (both trees rebuilt): still within the bound.
    auto d = measureMeshDistance(*mesh, s.mesh);
    ASSERT_TRUE(d.ok());
    EXPECT_LE(d->relativeEs(), bound);
    EXPECT_NEAR(d->relativeEs(), s.error, 1e-12);
    EXPECT_GT(d->relativeEs(), 0.5 * bound);  // the search goes close to the bound
    EXPECT_LT(s.mesh.faceCount(), prev_faces);
    EXPECT_TRUE(validateMesh(s.mesh, "simplified").ok());
    prev_faces = s.mesh.faceCount();
  }
}

}  // namespace
}  // namespace lodline
