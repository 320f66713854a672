// glTF 2.0 input (io/load_gltf.h): node transforms, welding of split vertices, both file
// kinds, and one-line errors for broken files.
#include <gtest/gtest.h>

#include <fstream>

#include <sys/stat.h>

#include <nlohmann/json.hpp>

#include "io/load_gltf.h"
#include "io/scene_file.h"
#include "test_util.h"

namespace lodline {
namespace {

class Gltf : public ::testing::Test {
 protected:
  test::TempDir dir_;
};

TEST_F(Gltf, ReadsNodesWithTheirWorldTransformsAndWeldsSplitVertices) {
  for (const char* name : {"cubes.gltf", "cubes.glb"}) {
    test::GltfTestNode a = test::gltfCube();
    a.name = "parent";
    a.translation = {10, 0, 0};
    test::GltfTestNode b = test::gltfCube();
    b.name = "child";
    b.parent = 0;
    b.translation = {0, 3, 0};
    b.scale = {2, 2, 2};
    b.rotation = {0, 0, 0.70710678f, 0.70710678f};  // 90° about Z
    test::writeGltf(dir_ / name, {a, b});
    auto nodes = loadGltf(dir_ / name);
    ASSERT_TRUE(nodes) << nodes.error().message;
    ASSERT_EQ(nodes->size(), 2u);
    const GltfMeshNode& pa = (*nodes)[0];
    const GltfMeshNode& ch = (*nodes)[1];
    EXPECT_EQ(pa.name, "parent");
    EXPECT_EQ(ch.name, "child");
    // 24 glTF vertices (4 per face) weld into the cube's 8 corners: a closed surface.
    EXPECT_EQ(pa.mesh.vertexCount(), 8u);
    EXPECT_EQ(pa.mesh.faceCount(), 12u);
    // The child's world transform is the parent's times its own: (1, 0, 0) → scaled (2, 0, 0)
    // → rotated (0, 2, 0) → + (0, 3, 0) → + (10, 0, 0).
    const glm::vec3 p = glm::vec3(ch.transform * glm::vec4(1, 0, 0, 1));
    EXPECT_NEAR(p.x, 10.0f, 1e-5f);
    EXPECT_NEAR(p.y, 5.0f, 1e-5f);
    EXPECT_NEAR(p.z, 0.0f, 1e-5f);
  }
}

TEST_F(Gltf, GltfFilesAreScenesAndSceneFilesCanPickANode) {
  test::GltfTestNode a = test::gltfCube(), b = test::gltfCube();
  a.name = "left";
  b.name = "right";
  b.translation = {4, 0, 0};
  test::writeGltf(dir_ / "pair.glb", {a, b});
  auto s = loadScene(dir_ / "pair.glb");
  ASSERT_TRUE(s) << s.error().message;
  ASSERT_EQ(s->objects.size(), 2u);
  EXPECT_EQ(s->objects[1].name, "right");
  EXPECT_EQ(s->objects[1].gltf_node, 1);
  ASSERT_TRUE(s->objects[1].preloaded);
  std::ofstream(dir_ / "pick.json") << R"({"objects": [{"name": "r", "mesh": "pair.glb", "gltf_node": 1, "translate": [0, 1, 0]}]})";
  auto p = loadScene(dir_ / "pick.json");
  ASSERT_TRUE(p) << p.error().message;
  ASSERT_EQ(p->objects.size(), 1u);
  EXPECT_EQ(p->objects[0].name, "r");
  const glm::vec3 c = glm::vec3(p->objects[0].transform * glm::vec4(0, 0, 0, 1));
  EXPECT_NEAR(c.x, 4.0f, 1e-5f);
  EXPECT_NEAR(c.y, 1.0f, 1e-5f);
  std::ofstream(dir_ / "bad.json") << R"({"objects": [{"mesh": "pair.glb", "gltf_node": 7}]})";
  auto bad = loadScene(dir_ / "bad.json");
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("objects[0].gltf_node: node 7 has no triangle mesh"), std::string::npos)
      << bad.error().message;
}

// Rewrites the JSON of a valid .gltf with `edit`, then loads it.
std::string errorAfter(const std::filesystem::path& dir, const std::function<void(nlohmann::json&)>& edit) {
  test::writeGltf(dir / "ok.gltf", {test::gltfCube()});
  nlohmann::json j = nlohmann::json::parse(std::ifstream(dir / "ok.gltf"));
  edit(j);
  std::ofstream(dir / "broken.gltf") << j.dump();
  auto r = loadGltf(dir / "broken.gltf");
  return r ? std::string() : r.error().message;
}

TEST_F(Gltf, BrokenFilesGiveOneLineNamingTheFile) {
  const std::string file = (dir_ / "broken.gltf").string();
  struct Case {
    std::function<void(nlohmann::json&)> edit;
    const char* expect;
  };
  const Case cases[] = {
      {[](nlohmann::json& j) { j["accessors"][0]["count"] = 100000; }, "reads past the end of its buffer"},
      {[](nlohmann::json& j) { j["accessors"][1]["count"] = 1u << 30; }, "reads past the end of its buffer"},
      {[](nlohmann::json& j) { j["bufferViews"][1]["byteOffset"] = 1u << 31; }, "reads past the end"},
      {[](nlohmann::json& j) { j["meshes"][0]["primitives"][0]["attributes"].erase("POSITION"); }, "POSITION"},
      {[](nlohmann::json& j) { j["nodes"][0]["children"] = {0}; }, "node graph is not a tree"},
      {[](nlohmann::json& j) { j["nodes"][0]["mesh"] = 5; }, "mesh 5"},
      {[](nlohmann::json& j) { j["meshes"][0]["primitives"][0]["mode"] = 1; }, "no triangle meshes"},
      {[](nlohmann::json& j) { j["accessors"][0]["componentType"] = 5121; }, "POSITION must be VEC3 of floats"},
      {[](nlohmann::json& j) { j.erase("asset"); }, "cannot read glTF"},
  };
  for (const Case& c : cases) {
    const std::string msg = errorAfter(dir_.path(), c.edit);
    EXPECT_EQ(msg.rfind(file, 0), 0u) << msg;
    EXPECT_NE(msg.find(c.expect), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
  // An index beyond the vertices: patch the index buffer itself.
  test::GltfTestNode n = test::gltfCube();
  n.indices[5] = 999;
  test::writeGltf(dir_ / "index.glb", {n});
  auto r = loadGltf(dir_ / "index.glb");
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("index 999 out of range (24 vertices)"), std::string::npos) << r.error().message;
  std::ofstream(dir_ / "garbage.glb") << "not a glb file at all";
  auto g = loadGltf(dir_ / "garbage.glb");
  ASSERT_FALSE(g);
  EXPECT_NE(g.error().message.find("garbage.glb: cannot read glTF"), std::string::npos) << g.error().message;
  auto missing = loadGltf(dir_ / "none.gltf");
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("no such file"), std::string::npos);
}

// tinygltf reads external buffers itself: a URI naming a FIFO (which would block the read
// forever), a directory or a missing file is refused with one line naming the glTF file.
TEST_F(Gltf, ExternalBuffersMustBeRegularFiles) {
  ASSERT_EQ(::mkfifo((dir_ / "fifo.bin").c_str(), 0600), 0);
  std::filesystem::create_directories(dir_ / "dir.bin");
  const std::string file = (dir_ / "broken.gltf").string();
  for (const char* uri : {"fifo.bin", "dir.bin", "missing.bin"}) {
    const std::string msg = errorAfter(dir_.path(), [&](nlohmann::json& j) { j["buffers"][0]["uri"] = uri; });
    EXPECT_EQ(msg.rfind(file + ": cannot read glTF", 0), 0u) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
  const std::string fifo = errorAfter(dir_.path(), [](nlohmann::json& j) { j["buffers"][0]["uri"] = "fifo.bin"; });
  EXPECT_NE(fifo.find("not a regular file"), std::string::npos) << fifo;
}

}  // namespace
}  // namespace lodline
