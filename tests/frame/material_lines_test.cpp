// Material lines (lines/lines.h extractMaterialLines): materials read from OBJ `usemtl` and
// glTF primitives, carried through loading, kept exact by the progressive mesh (their
// vertices are never collapsed) and drawn at every level of detail.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <numbers>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "frame/lod_drawing.h"
#include "io/generate.h"
#include "io/load_gltf.h"
#include "io/load_mesh.h"
#include "lines/lines.h"
#include "pm/progressive_mesh.h"
#include "shape/adjacency.h"
#include "test_util.h"

namespace lodline {
namespace {

// A torus in alternating bands around the ring: `bands` meridian circles between them.
TriMesh bandedTorus(int bands) {
  TriMesh m = makeTorus(1.0f, 0.35f, 96, 32);
  m.face_materials.resize(m.faces.size());
  for (size_t f = 0; f < m.faces.size(); ++f) {
    glm::vec3 c(0.0f);
    for (uint32_t v : m.faces[f]) c += m.positions[v] / 3.0f;
    const float a = std::atan2(c.z, c.x) + std::numbers::pi_v<float>;
    m.face_materials[f] = static_cast<uint32_t>(a / (2.0f * std::numbers::pi_v<float>) * bands) % 2;
  }
  return m;
}

size_t materialSegments(const TriMesh& m) {
  MeshAdjacency adj;
  buildAdjacency(m, adj);
  LineSet out;
  extractMaterialLines(m, adj, out);
  EXPECT_EQ(out.segmentCount(), out.counts[static_cast<int>(LineKind::kMaterial)]);
  return out.segmentCount();
}

TEST(MaterialLines, ObjUsemtlGivesFaceMaterials) {
  test::TempDir dir;
  std::ofstream(dir / "two.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\n"
                                    "usemtl red\nf 1 2 3 4\nusemtl blue\nf 2 5 6 3\n";
  auto m = loadMesh(dir / "two.obj");
  ASSERT_TRUE(m) << m.error().message;
  ASSERT_EQ(m->faces.size(), 4u);
  ASSERT_EQ(m->face_materials.size(), 4u);
  EXPECT_EQ(m->face_materials[0], m->face_materials[1]);  // the quad's two triangles
  EXPECT_NE(m->face_materials[1], m->face_materials[2]);
  EXPECT_EQ(materialSegments(*m), 1u);  // the edge (2, 3) between the quads
  // One material (or none) gives no per-face materials.
  std::ofstream(dir / "one.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl red\nf 1 2 3\n";
  auto one = loadMesh(dir / "one.obj");
  ASSERT_TRUE(one) << one.error().message;
  EXPECT_TRUE(one->face_materials.empty());
}

TEST(MaterialLines, GltfPrimitivesGiveFaceMaterials) {
  test::TempDir dir;
  test::writeGltf(dir / "cube.gltf", {test::gltfCube()});
  // Split the cube's one primitive into two with materials 0 and 1 (first and last 18 indices).
  nlohmann::json j = nlohmann::json::parse(std::ifstream(dir / "cube.gltf"));
  auto& prim = j["meshes"][0]["primitives"][0];
  const int acc = prim["indices"];
  nlohmann::json second = j["accessors"][acc];
  const int count = j["accessors"][acc]["count"];
  const int type = j["accessors"][acc]["componentType"];
  const int size = type == 5121 ? 1 : type == 5123 ? 2 : 4;
  j["accessors"][acc]["count"] = count / 2;
  second["count"] = count / 2;
  second["byteOffset"] = second.value("byteOffset", 0) + (count / 2) * size;
  second.erase("max");
  second.erase("min");
  j["accessors"].push_back(second);
  nlohmann::json prim2 = prim;
  prim2["indices"] = static_cast<int>(j["accessors"].size()) - 1;
  prim["material"] = 0;
  prim2["material"] = 1;
  j["meshes"][0]["primitives"].push_back(prim2);
  j["materials"] = nlohmann::json::array({{{"name", "a"}}, {{"name", "b"}}});
  std::ofstream(dir / "two.gltf") << j.dump();
  auto nodes = loadGltf(dir / "two.gltf");
  ASSERT_TRUE(nodes) << nodes.error().message;
  const TriMesh& m = (*nodes)[0].mesh;
  ASSERT_EQ(m.faces.size(), 12u);
  ASSERT_EQ(m.face_materials.size(), 12u);
  EXPECT_EQ(std::count(m.face_materials.begin(), m.face_materials.end(), m.face_materials[0]), 6);
  EXPECT_GT(materialSegments(m), 0u);
}

TEST(MaterialLines, ProgressiveMeshKeepsThemExactAtEveryLevel) {
  const TriMesh full = bandedTorus(8);
  const size_t full_count = materialSegments(full);
  EXPECT_EQ(full_count, 8u * 32u);  // 8 meridian circles of 32 edges
  auto pm = buildProgressiveMesh(full);
  ASSERT_TRUE(pm.ok()) << pm.error().message;
  // Its content hash differs from the same mesh without materials (a different build).
  TriMesh plain = full;
  plain.face_materials.clear();
  EXPECT_NE(meshContentHash(full), meshContentHash(plain));
  // The base mesh, coarsest of all, still has every boundary edge.
  TriMesh base = pm->baseMesh();
  ASSERT_EQ(base.faces.size(), pm->base_faces.size());
  base.face_materials.clear();
  for (uint32_t f : pm->base_faces) base.face_materials.push_back(full.face_materials[f]);
  EXPECT_LT(base.faces.size(), full.faces.size() / 2);
  EXPECT_EQ(materialSegments(base), full_count);
  // Drawn under detail control, far away: the same lines.
  LodDrawing lod(full, std::make_shared<const ProgressiveMesh>(std::move(pm.value())));
  std::array<bool, kLineKindCount> enabled{};
  enabled[static_cast<int>(LineKind::kMaterial)] = true;
  DetailParams detail;
  detail.target_area = 64.0f;
  const Camera cam = orbitCamera(lod.bounds(), {30.0f, 30.0f, 6.0f}, 35.0f, 16.0f / 9.0f);
  ASSERT_TRUE(lod.converge(cam, 320, 180, detail, 1.0f / 30.0f, 300, enabled).ok());
  ASSERT_TRUE(lod.frame(cam, 320, 180, detail, 1.0f / 30.0f, enabled).ok());
  EXPECT_LT(lod.drawing().mesh().faces.size(), full.faces.size());
  EXPECT_EQ(lod.drawing().segments().counts[static_cast<int>(LineKind::kMaterial)], full_count);
}

}  // namespace
}  // namespace lodline
