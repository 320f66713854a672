// Progressive mesh build: hierarchy structure, base mesh, non-manifold input, errors.
#include <gtest/gtest.h>

#include <set>

#include "pm/pm_test_meshes.h"
#include "pm/progressive_mesh.h"
#include "test_util.h"

namespace lodline {
namespace {

/// The root ancestor of every leaf, by walking parents.
std::vector<uint32_t> rootOfLeaves(const ProgressiveMesh& pm) {
  std::vector<uint32_t> root(pm.vertexCount());
  for (uint32_t v = 0; v < pm.vertexCount(); ++v) {
    uint32_t r = v;
    while (pm.parent[r] != kPmNone) r = pm.parent[r];
    root[v] = r;
  }
  return root;
}

/// Base faces are the input faces seen through the root ancestors; the other faces collapse.
void expectConsistentHierarchy(const TriMesh& mesh, const ProgressiveMesh& pm) {
  ASSERT_EQ(pm.faceCount(), mesh.faceCount());
  const auto root = rootOfLeaves(pm);
  std::vector<uint8_t> is_base(pm.faceCount(), 0);
  for (size_t k = 0; k < pm.base_faces.size(); ++k) {
    const uint32_t f = pm.base_faces[k];
    is_base[f] = 1;
    for (int i = 0; i < 3; ++i) EXPECT_EQ(pm.base_corners[k][i], root[mesh.faces[f][i]]);
  }
  for (uint32_t f = 0; f < pm.faceCount(); ++f) {
    if (is_base[f]) continue;
    const auto& c = mesh.faces[f];
    EXPECT_TRUE(root[c[0]] == root[c[1]] || root[c[1]] == root[c[2]] || root[c[0]] == root[c[2]])
        << "face " << f;
  }
  // The parent of a split keeps the position of its vt child (half-edge collapse).
  for (uint32_t s = pm.vertexCount(); s < pm.nodeCount(); ++s)
    EXPECT_EQ(pm.origin[s], pm.origin[pm.split(s).vt]);
}

TEST(PmBuild, IcoSphereSimplifiesToSmallBase) {
  const TriMesh mesh = makeIcoSphere(1.0f, 4);  // 5120 faces
  auto pm = buildProgressiveMesh(mesh);
  ASSERT_TRUE(pm.ok()) << pm.error().message;
  EXPECT_LT(pm->base_faces.size(), 100u);
  EXPECT_EQ(pm->base_faces.size() + 2 * pm->splits.size(), mesh.faceCount());
  expectConsistentHierarchy(mesh, *pm);
  EXPECT_EQ(pm->content_hash, meshContentHash(mesh));
}

TEST(PmBuild, BaseMeshIsClosedManifold) {
  const TriMesh mesh = makeTorus(1.0f, 0.3f, 48, 24);
  auto pm = buildProgressiveMesh(mesh);
  ASSERT_TRUE(pm.ok()) << pm.error().message;
  expectConsistentHierarchy(mesh, *pm);
  const TriMesh base = pm->baseMesh();
  // Every directed edge appears once and its twin once.
  std::set<std::pair<uint32_t, uint32_t>> edges;
  for (const auto& f : base.faces)
    for (int i = 0; i < 3; ++i) EXPECT_TRUE(edges.insert({f[i], f[(i + 1) % 3]}).second);
  for (const auto& e : edges) EXPECT_TRUE(edges.count({e.second, e.first}));
  // Torus: Euler characteristic 0.
  EXPECT_EQ(static_cast<long>(base.vertexCount()) - static_cast<long>(edges.size() / 2) +
                static_cast<long>(base.faceCount()),
            0);
}

TEST(PmBuild, BoundaryVerticesArePreserved) {
  const TriMesh mesh = makeGrid(2.0f, 20);
  auto pm = buildProgressiveMesh(mesh);
  ASSERT_TRUE(pm.ok()) << pm.error().message;
  expectConsistentHierarchy(mesh, *pm);
  const auto root = rootOfLeaves(*pm);
  for (uint32_t v = 0; v < mesh.vertexCount(); ++v)
    if (pm->vertex_flags[v] & kPmBoundary) {
      EXPECT_EQ(root[v], v) << "boundary vertex collapsed";
    }
  EXPECT_GT(pm->splits.size(), 200u);
}

TEST(PmBuild, NonManifoldInputIsHandled) {
  // Two icospheres sharing one vertex (a bow-tie vertex) plus a fin: three faces on one edge.
  TriMesh a = makeIcoSphere(1.0f, 2);
  TriMesh mesh = a;
  const uint32_t off = static_cast<uint32_t>(mesh.positions.size());
  for (auto p : a.positions) mesh.positions.push_back(p + glm::vec3(2.0f, 0.0f, 0.0f));
  for (auto f : a.faces) {
    for (auto& v : f) v = (v == 0 ? 0u : v + off);  // vertex 0 is shared
    mesh.faces.push_back(f);
  }
  mesh.positions.push_back({0.0f, 3.0f, 0.0f});
  const uint32_t fin = static_cast<uint32_t>(mesh.positions.size()) - 1;
  mesh.faces.push_back({mesh.faces[5][0], mesh.faces[5][1], fin});  // third face on an edge
  mesh.faces.push_back({7, 7, 8});                                   // degenerate face
  mesh.positions.push_back({9.0f, 9.0f, 9.0f});                      // isolated vertex
  auto pm = buildProgressiveMesh(mesh);
  ASSERT_TRUE(pm.ok()) << pm.error().message;
  expectConsistentHierarchy(mesh, *pm);
  EXPECT_TRUE(pm->vertex_flags[0] & kPmFrozen);
  EXPECT_TRUE(pm->vertex_flags[fin] & (kPmFrozen | kPmBoundary));
  EXPECT_TRUE(pm->vertex_flags[7] & kPmFrozen);
  EXPECT_TRUE(pm->vertex_flags[mesh.positions.size() - 1] & kPmFrozen);
  EXPECT_GT(pm->splits.size(), 100u);
}

TEST(PmBuild, BadInputIsAnError) {
  TriMesh empty;
  empty.positions.push_back({0, 0, 0});
  EXPECT_FALSE(buildProgressiveMesh(empty).ok());
  TriMesh bad = makeIcoSphere(1.0f, 1);
  bad.faces[3][1] = 1000;
  auto r = buildProgressiveMesh(bad);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("1000"), std::string::npos) << r.error().message;
  TriMesh nan = makeIcoSphere(1.0f, 1);
  nan.positions[2].y = std::nanf("");
  EXPECT_FALSE(buildProgressiveMesh(nan).ok());
}

TEST(PmBuild, ProgressIsReportedAndHashesDiffer) {
  TriMesh mesh = makeIcoSphere(1.0f, 3);
  float last = -1.0f;
  int calls = 0;
  auto pm = buildProgressiveMesh(mesh, {}, [&](float f) {
    EXPECT_GE(f, last);
    last = f;
    ++calls;
  });
  ASSERT_TRUE(pm.ok());
  EXPECT_GT(calls, 10);
  EXPECT_FLOAT_EQ(last, 1.0f);
  const uint64_t h = meshContentHash(mesh);
  mesh.positions[0].x += 1e-3f;
  EXPECT_NE(h, meshContentHash(mesh));
  PmBuildParams p;
  p.max_valence = 20;
  EXPECT_NE(buildParamsHash(p), buildParamsHash(PmBuildParams{}));
}

TEST(PmBuild, NoFaceTurnsAwayFromItsInputNormal) {
  TriMesh mesh = makeIcoSphere(1.0f, 4);
  test::perturbRadially(mesh, 0.01f);
  auto pm = buildProgressiveMesh(mesh);
  ASSERT_TRUE(pm.ok());
  std::vector<glm::vec3> n0;
  computeFaceNormals(mesh, n0);
  for (size_t k = 0; k < pm->base_faces.size(); ++k) {
    const auto& c = pm->base_corners[k];
    const glm::vec3 n = glm::cross(pm->nodePosition(c[1]) - pm->nodePosition(c[0]),
                                   pm->nodePosition(c[2]) - pm->nodePosition(c[0]));
    EXPECT_GT(glm::dot(n, n0[pm->base_faces[k]]), 0.0f);
  }
}

TEST(PmBuild, CgalMeshes) {
  for (const char* name : {"bunny00.off", "armadillo.off"}) {
    const auto path = test::dataMesh(name);
    if (path.empty()) GTEST_SKIP() << name << " not found (run scripts/setup.sh)";
    TriMesh mesh;
    ASSERT_TRUE(test::readOff(path, mesh)) << name;
    auto pm = buildProgressiveMesh(mesh);
    ASSERT_TRUE(pm.ok()) << pm.error().message;
    expectConsistentHierarchy(mesh, *pm);
    EXPECT_LT(pm->base_faces.size(), mesh.faceCount() / 20) << name;
  }
}

}  // namespace
}  // namespace lodline
