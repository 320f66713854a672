// Scene files (io/scene_file.h): what a valid file gives, and one clear error naming the file
// and the key for each kind of bad file.
#include <gtest/gtest.h>

#include <fstream>
#include <set>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "io/generate.h"
#include "io/load_mesh.h"
#include "io/scene_file.h"
#include "test_util.h"

namespace lodline {
namespace {

class SceneFile : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(saveOff(dir_ / "sphere.off", makeIcoSphere(1.0f, 2)).ok());
    write("inner.json", R"({"objects": [{"mesh": "sphere.off"}]})");
    std::filesystem::create_directories(dir_ / "sub");
    ASSERT_TRUE(saveOff(dir_ / "sub" / "box.off", makeIcoSphere(0.5f, 1)).ok());
  }
  std::filesystem::path write(const std::string& name, const std::string& text) {
    const auto p = dir_ / name;
    std::ofstream(p) << text;
    return p;
  }
  // The error message of loading `text` (empty if it loads).
  std::string error(const std::string& text, const std::string& name = "scene.json") {
    auto s = loadScene(write(name, text));
    return s ? std::string() : s.error().message;
  }
  test::TempDir dir_;
};

glm::vec3 apply(const glm::mat4& m, glm::vec3 p) { return glm::vec3(m * glm::vec4(p, 1.0f)); }

TEST_F(SceneFile, ReadsObjectsTransformsStylesCameraAndLight) {
  auto s = loadScene(write("scene.json", R"({
    "lodline": 1,
    "settings": {"target-area": 32, "style": "lines", "line-style": ["contour=#ff0000"]},
    "camera": {"view": [30, 20, 4], "fov": 40},
    "light": {"direction": [0, 1, 1]},
    "objects": [
      {"mesh": "sphere.off", "translate": [1, 2, 3], "rotate": [0, 90, 0], "scale": 2, "detail_factor": 3,
       "style": "toon", "line_style": ["suggestive=#00ff00:1"], "chamfer": "off"},
      {"name": "small", "mesh": "sub/box.off", "quaternion": [0, 0, 0.7071068, 0.7071068], "scale": [1, 2, 3]},
      {"mesh": "sphere.off"}
    ]})"));
  ASSERT_TRUE(s) << s.error().message;
  ASSERT_EQ(s->objects.size(), 3u);
  const SceneObject& a = s->objects[0];
  EXPECT_EQ(a.name, "sphere");
  EXPECT_EQ(a.mesh, dir_ / "sphere.off");
  EXPECT_FLOAT_EQ(a.detail_factor, 3.0f);
  // Scale 2, then 90° about Y (x → −z), then translate.
  const glm::vec3 p = apply(a.transform, {1, 0, 0});
  EXPECT_NEAR(p.x, 1.0f, 1e-5f);
  EXPECT_NEAR(p.y, 2.0f, 1e-5f);
  EXPECT_NEAR(p.z, 1.0f, 1e-5f);
  EXPECT_EQ(a.style["style"], "toon");
  EXPECT_EQ(a.style["line-style"][0], "suggestive=#00ff00:1");
  EXPECT_EQ(a.style["chamfer"], "off");
  const SceneObject& b = s->objects[1];
  EXPECT_EQ(b.name, "small");
  EXPECT_EQ(b.mesh, dir_ / "sub" / "box.off");
  // Non-uniform scale, then 90° about Z: (1, 0, 0) → (1, 0, 0) scaled → (0, 1, 0).
  const glm::vec3 q = apply(b.transform, {1, 0, 0});
  EXPECT_NEAR(q.x, 0.0f, 1e-5f);
  EXPECT_NEAR(q.y, 1.0f, 1e-5f);
  const glm::vec3 r = apply(b.transform, {0, 1, 0});
  EXPECT_NEAR(r.x, -2.0f, 1e-5f);
  // Duplicate names are made unique.
  EXPECT_EQ(s->objects[2].name, "sphere#2");
  EXPECT_EQ(s->settings["target-area"], 32);
  ASSERT_TRUE(s->camera);
  EXPECT_EQ(*s->camera->view, "30,20,4");
  EXPECT_FLOAT_EQ(*s->camera->fov_deg, 40.0f);
  ASSERT_TRUE(s->light_dir_eye);
  EXPECT_FLOAT_EQ(s->light_dir_eye->y, 1.0f);
}

TEST_F(SceneFile, NamesAreMadeUnique) {
  auto s = loadScene(write("names.json", R"({"objects": [{"mesh": "sphere.off", "name": "a"}, {"mesh": "sphere.off", "name": "a"},
      {"mesh": "sphere.off", "name": "a#2"}, {"mesh": "sphere.off", "name": "a"}]})"));
  ASSERT_TRUE(s) << s.error().message;
  std::set<std::string> names;
  for (const auto& o : s->objects) names.insert(o.name);
  EXPECT_EQ(names.size(), 4u);
  EXPECT_EQ(s->objects[0].name, "a");
  EXPECT_EQ(s->objects[2].name, "a#2");
}

TEST_F(SceneFile, IncludesComposeTransformsFactorsAndStyles) {
  write("inner.json", R"({"objects": [{"mesh": "sphere.off", "translate": [1, 0, 0], "detail_factor": 2}]})");
  auto s = loadScene(write("outer.json", R"({"objects": [
      {"scene": "inner.json", "translate": [0, 5, 0], "scale": 3, "detail_factor": 1.5, "style": "lines"}]})"));
  ASSERT_TRUE(s) << s.error().message;
  ASSERT_EQ(s->objects.size(), 1u);
  const glm::vec3 p = apply(s->objects[0].transform, {0, 0, 0});
  EXPECT_NEAR(p.x, 3.0f, 1e-5f);  // outer scale applies to the inner translation
  EXPECT_NEAR(p.y, 5.0f, 1e-5f);
  EXPECT_FLOAT_EQ(s->objects[0].detail_factor, 3.0f);
  EXPECT_EQ(s->objects[0].style["style"], "lines");
}

TEST_F(SceneFile, MatrixRoundTripsExactly) {
  const glm::mat4 m = composeTransform({0.1f, -2.3f, 7.0f}, eulerRotation({12.5f, -33.0f, 71.0f}), {0.3f, 1.7f, 2.2f});
  nlohmann::json j = {{"objects", {{{"mesh", "sphere.off"}, {"matrix", matrixJson(m)}}}}};
  auto s = loadScene(write("m.json", j.dump()));
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_TRUE(s->objects[0].transform == m);  // bit for bit: a saved view renders the same mesh
}

TEST_F(SceneFile, MeshFilesAreScenesOfOneObject) {
  auto s = loadScene(dir_ / "sphere.off");
  ASSERT_TRUE(s);
  ASSERT_EQ(s->objects.size(), 1u);
  EXPECT_EQ(s->objects[0].name, "sphere");
  EXPECT_TRUE(s->objects[0].transform == glm::mat4(1.0f));
  EXPECT_TRUE(isSceneFile("a.JSON"));
  EXPECT_TRUE(isSceneFile("a.glb"));
  EXPECT_FALSE(isSceneFile("a.off"));
}

TEST_F(SceneFile, PaintGivesAMeshMaterialsBeforeItIsPlaced) {
  // The plane is in the mesh's own coordinates: y >= 0.5 of the unit sphere, then moved up 10.
  auto s = loadScene(write("scene.json", R"({"objects": [
      {"mesh": "sphere.off", "translate": [0, 10, 0], "paint": [{"plane": [0, 1, 0, 0.5]}]},
      {"mesh": "sphere.off"}]})"));
  ASSERT_TRUE(s) << s.error().message;
  ASSERT_EQ(s->objects[0].paint.size(), 1u);
  auto painted = loadObjectMesh(s->objects[0]);
  ASSERT_TRUE(painted) << painted.error().message;
  ASSERT_EQ(painted->face_materials.size(), painted->faces.size());
  for (size_t f = 0; f < painted->faces.size(); ++f) {
    glm::vec3 c(0.0f);
    for (uint32_t v : painted->faces[f]) c += painted->positions[v] / 3.0f;
    EXPECT_EQ(painted->face_materials[f], c.y > 10.5f ? 1u : 0u);
  }
  auto plain = loadObjectMesh(s->objects[1]);
  ASSERT_TRUE(plain);
  EXPECT_TRUE(plain->face_materials.empty());
}

TEST_F(SceneFile, BadFilesNameTheFileAndTheKey) {
  struct Case {
    const char* text;
    const char* expect;  // part of the message after the file name
  };
  const Case cases[] = {
      {R"({"objects": [{"mesh": "missing.off"}]})", "objects[0].mesh: no such file"},
      {R"({"objects": [{"mesh": "sphere.off",}]})", "invalid JSON"},
      {R"({"objects": [{"mesh": "sphere.off", "scale": -1}]})", "objects[0].scale: must be > 0"},
      {R"({"objects": [{"mesh": "sphere.off", "scale": [1, 0, 1]}]})", "objects[0].scale: must be > 0"},
      {R"({"objects": [{"mesh": "sphere.off", "colour": "red"}]})", "objects[0]: unknown key \"colour\""},
      {R"({"objects": [{"mesh": "sphere.off"}], "camrea": {}})", "unknown key \"camrea\""},
      {R"({"objects": []})", "objects: expected a non-empty array"},
      {R"([1, 2])", "expected a JSON object"},
      {R"({"objects": [{"mesh": "sphere.off", "scene": "x.json"}]})", "needs exactly one of"},
      {R"({"objects": [{"mesh": "sphere.off", "rotate": [0, 0, 0], "quaternion": [0, 0, 0, 1]}]})", "not both"},
      {R"({"objects": [{"mesh": "sphere.off", "quaternion": [0, 0, 0, 0]}]})", "quaternion: must not be zero"},
      {R"({"objects": [{"mesh": "sphere.off", "translate": [0, "a", 0]}]})", "objects[0].translate: expected"},
      {R"({"objects": [{"mesh": "sphere.off", "detail_factor": 0}]})", "detail_factor: must be > 0"},
      {R"({"objects": [{"mesh": "sphere.off", "gltf_node": 0}]})", "gltf_node: only for .gltf"},
      {R"({"objects": [{"mesh": "sphere.off", "style": {"x": 1}}]})", "objects[0].style: expected"},
      {R"({"objects": [{"mesh": "sphere.off"}], "camera": {"eye": [0, 0, 1]}})", "camera: needs both"},
      {R"({"objects": [{"mesh": "sphere.off"}], "camera": {"view": "1,2,3", "path": "orbit"}})", "camera: give one of"},
      {R"({"objects": [{"mesh": "sphere.off"}], "camera": {"fov": 500}})", "camera.fov: must be in"},
      {R"({"objects": [{"mesh": "sphere.off"}], "settings": [1]})", "settings: expected an object"},
      {R"({"objects": [{"mesh": "sphere.off"}], "settings": {"size": {"w": 1}}})", "settings.size: expected"},
      {R"({"objects": [{"mesh": "sphere.off"}], "light": {"direction": [0, 0, 0]}})", "light.direction: must not be zero"},
      {R"({"lodline": 2, "objects": [{"mesh": "sphere.off"}]})", "unsupported scene format version"},
      {R"({"objects": [{"mesh": "sphere.off", "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, 0, 0, 0, 0, 1]}]})",
       "matrix: must not be singular or mirror"},
      {R"({"objects": [{"mesh": "sub"}]})", "sub' is not a regular file"},
      // A number past double's range: nlohmann throws out_of_range, not parse_error.
      {R"({"objects": [{"mesh": "sphere.off", "scale": 1e999}]})", "invalid JSON: number overflow"},
      {"{\"objects\": [{\"mesh\": \"sphere.off\", \"sc\\u0001ale\": 1}]}", "unknown key \"sc?ale\""},
      {R"({"objects": [{"mesh": "sphere.off", "paint": []}]})", "objects[0].paint: expected an array of 1 to 64"},
      {R"({"objects": [{"mesh": "sphere.off", "paint": [{"plane": [0, 1, 0]}]}]})", "paint[0].plane: expected [a, b, c, d]"},
      {R"({"objects": [{"mesh": "sphere.off", "paint": [{"plane": [0, 0, 0, 1]}]}]})", "paint[0].plane: the normal"},
      {R"({"objects": [{"mesh": "sphere.off", "paint": [{"plane": [0, 1, 0, 0], "thickness": 0}]}]})",
       "paint[0].thickness: must be > 0"},
      {R"({"objects": [{"mesh": "sphere.off", "paint": [{"plane": [0, 1, 0, 0], "colour": 1}]}]})",
       "paint[0]: unknown key \"colour\""},
      {R"({"objects": [{"scene": "inner.json", "paint": [{"plane": [0, 1, 0, 0]}]}]})", "paint: only for meshes"},
  };
  for (const Case& c : cases) {
    const std::string msg = error(c.text);
    EXPECT_EQ(msg.rfind((dir_ / "scene.json").string() + ": ", 0), 0u) << c.text << " -> " << msg;
    EXPECT_NE(msg.find(c.expect), std::string::npos) << c.text << " -> " << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}

TEST_F(SceneFile, IncludeCyclesAreErrors) {
  write("a.json", R"({"objects": [{"scene": "b.json"}]})");
  write("b.json", R"({"objects": [{"mesh": "sphere.off"}, {"scene": "a.json"}]})");
  auto s = loadScene(dir_ / "a.json");
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().message.find("include cycle: a.json -> b.json -> a.json"), std::string::npos) << s.error().message;
  write("self.json", R"({"objects": [{"scene": "self.json"}]})");
  auto t = loadScene(dir_ / "self.json");
  ASSERT_FALSE(t);
  EXPECT_NE(t.error().message.find("include cycle"), std::string::npos);
}

TEST_F(SceneFile, MissingOrUnreadableSceneFiles) {
  auto s = loadScene(dir_ / "nope.json");
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().message.find("nope.json: no such file"), std::string::npos);
  std::filesystem::create_directories(dir_ / "dir.json");
  auto d = loadScene(dir_ / "dir.json");
  ASSERT_FALSE(d);
  EXPECT_NE(d.error().message.find("is a directory, not a scene file"), std::string::npos);
}

TEST_F(SceneFile, TransformMeshKeepsOutwardFacesUnderMirroring) {
  TriMesh m = makeIcoSphere(1.0f, 1);
  auto volume = [](const TriMesh& t) {
    double v = 0.0;
    for (const auto& f : t.faces)
      v += glm::dot(t.positions[f[0]], glm::cross(t.positions[f[1]], t.positions[f[2]])) / 6.0;
    return v;
  };
  const double before = volume(m);
  ASSERT_GT(before, 0.0);
  transformMesh(m, glm::scale(glm::mat4(1.0f), glm::vec3(-2.0f, 1.0f, 1.0f)));
  EXPECT_NEAR(volume(m), 2.0 * before, 1e-3 * before);  // still positive: winding flipped
}

}  // namespace
}  // namespace lodline
