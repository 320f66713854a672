// Scenes through the `lodline` program: objects hide each other's lines, per-object detail
// factors, per-object stats that add up to the totals, settings and their precedence, glTF
// input, and one-line errors for bad scene files.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <fstream>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "core/camera.h"
#include "io/generate.h"
#include "io/image.h"
#include "io/load_mesh.h"
#include "test_util.h"

namespace lodline {
namespace {

class SceneCli : public ::testing::Test {
 protected:
  void SetUp() override {
    setenv("XDG_CACHE_HOME", (dir_ / "cache").c_str(), 1);
    ASSERT_TRUE(saveOff(dir_ / "sphere.off", makeIcoSphere(1.0f, 4)).ok());
  }
  std::filesystem::path write(const std::string& name, const nlohmann::json& j) {
    const auto p = dir_ / name;
    std::ofstream(p) << j.dump(1);
    return p;
  }
  int run(const std::string& args, std::string* out = nullptr) { return test::runLodline("render " + args, out); }
  nlohmann::json stats(const std::filesystem::path& p) { return nlohmann::json::parse(std::ifstream(p)); }
  test::TempDir dir_;
};

// Camera of the two-sphere scenes: from +Z, looking at the origin.
nlohmann::json frontCamera() { return {{"eye", {0, 0, 9}}, {"target", {0, 0, 0}}, {"fov", 35}}; }

// Dark pixels (any channel < 128) inside the disc (centre, radius) of `image`.
int darkInDisc(const Image& image, glm::vec2 centre, float radius) {
  int n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      if (glm::length(glm::vec2(x + 0.5f, y + 0.5f) - centre) > radius) continue;
      const uint8_t* p = image.pixel(x, y);
      n += p[0] < 128 || p[1] < 128 || p[2] < 128;
    }
  return n;
}

TEST_F(SceneCli, AnObjectHidesTheLinesOfTheObjectBehindIt) {
  const nlohmann::json front = {{"name", "front"}, {"mesh", "sphere.off"}, {"translate", {0, 0, 2}}};
  const nlohmann::json back = {{"name", "back"}, {"mesh", "sphere.off"}, {"translate", {0.9, 0.3, -1}}};
  const nlohmann::json settings = {{"style", "lines"}, {"lines", "contour"}, {"size", "480x360"}, {"msaa", 1}};
  write("both.json", {{"settings", settings}, {"camera", frontCamera()}, {"objects", {front, back}}});
  write("back.json", {{"settings", settings}, {"camera", frontCamera()}, {"objects", {back}}});
  ASSERT_EQ(run((dir_ / "both.json").string() + " -o " + (dir_ / "both.png").string() + " --stats " +
                (dir_ / "both.stats.json").string() + " --svg " + (dir_ / "both.svg").string()),
            0);
  ASSERT_EQ(run((dir_ / "back.json").string() + " -o " + (dir_ / "back.png").string()), 0);
  auto both = readPng(dir_ / "both.png");
  auto alone = readPng(dir_ / "back.png");
  ASSERT_TRUE(both && alone);
  // The front sphere's disc in the image (its contour is its rim; inside lies nothing of its own).
  Camera cam;
  cam.eye = {0, 0, 9};
  cam.target = {0, 0, 0};
  cam.fov_deg = 35.0f;
  const glm::vec2 c = projectToPixels(cam, {0, 0, 2}, 480, 360);
  const glm::vec2 rim = projectToPixels(cam, {0, 1, 2}, 480, 360);
  const float r = glm::length(rim - c);
  // Without the front sphere, the back sphere's contour crosses that disc...
  EXPECT_GT(darkInDisc(*alone, c, 0.85f * r), 60);
  // ...with it, the front sphere hides it completely.
  EXPECT_EQ(darkInDisc(*both, c, 0.85f * r), 0);
  // The hidden part is missing from the stats and the SVG too.
  const auto s = stats(dir_ / "both.stats.json");
  ASSERT_EQ(s["objects"].size(), 2u);
  EXPECT_LT(s["objects"][1]["lines"]["contour"].get<int>(), s["objects"][1]["lines_extracted"]["contour"].get<int>() * 0.9);
  std::ifstream svg(dir_ / "both.svg");
  const std::string text((std::istreambuf_iterator<char>(svg)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("<g id=\"o-front\">"), std::string::npos);
  EXPECT_NE(text.find("<g id=\"o-back\">"), std::string::npos);
}

TEST_F(SceneCli, PerObjectStatsAddUpAndTheDetailFactorCoarsens) {
  const nlohmann::json a = {{"name", "fine"}, {"mesh", "sphere.off"}, {"translate", {-1.3, 0, 0}}};
  const nlohmann::json b = {{"name", "coarse"}, {"mesh", "sphere.off"}, {"translate", {1.3, 0, 0}}, {"detail_factor", 4}};
  write("pair.json", {{"camera", frontCamera()}, {"settings", {{"size", "640x360"}}}, {"objects", {a, b}}});
  ASSERT_EQ(run((dir_ / "pair.json").string() + " -o " + (dir_ / "pair.png").string() + " --stats " +
                (dir_ / "pair.stats.json").string()),
            0);
  const auto s = stats(dir_ / "pair.stats.json");
  ASSERT_EQ(s["objects"].size(), 2u);
  const auto& fine = s["objects"][0];
  const auto& coarse = s["objects"][1];
  EXPECT_EQ(fine["name"], "fine");
  EXPECT_EQ(coarse["detail_factor"], 4.0);
  // T four times larger: roughly four times fewer faces (the same sphere, the same size on screen).
  const double ratio = fine["lod"]["active_faces"].get<double>() / coarse["lod"]["active_faces"].get<double>();
  EXPECT_GT(ratio, 2.5);
  EXPECT_LT(ratio, 6.0);
  EXPECT_NEAR(coarse["lod"]["target_area"].get<double>(), 64.0, 1e-3);
  for (const char* key : {"faces_drawn", "strokes", "specks", "line_segments"})
    EXPECT_EQ(s[key].get<int64_t>(), fine[key].get<int64_t>() + coarse[key].get<int64_t>()) << key;
  EXPECT_EQ(s["lod"]["active_faces"].get<int64_t>(),
            fine["lod"]["active_faces"].get<int64_t>() + coarse["lod"]["active_faces"].get<int64_t>());
  EXPECT_EQ(s["model"]["faces"].get<int64_t>(), fine["faces"].get<int64_t>() + coarse["faces"].get<int64_t>());
  EXPECT_EQ(s["lines"]["contour"].get<int64_t>(),
            fine["lines"]["contour"].get<int64_t>() + coarse["lines"]["contour"].get<int64_t>());
}

TEST_F(SceneCli, SettingsApplyUnlessTheCommandLineGivesThem) {
  write("s.json", {{"settings", {{"size", "320x240"}, {"target-area", 64}, {"lines", "contour"}}},
                   {"objects", {{{"mesh", "sphere.off"}}}}});
  ASSERT_EQ(run((dir_ / "s.json").string() + " -o " + (dir_ / "a.png").string() + " --stats " + (dir_ / "a.json").string()), 0);
  auto a = readPng(dir_ / "a.png");
  ASSERT_TRUE(a);
  EXPECT_EQ(a->width, 320);
  EXPECT_EQ(stats(dir_ / "a.json")["lod"]["target_area"], 64.0);
  EXPECT_EQ(stats(dir_ / "a.json")["lines_extracted"]["suggestive"], 0);
  ASSERT_EQ(run((dir_ / "s.json").string() + " --size 200x100 --target-area 8 -o " + (dir_ / "b.png").string() +
                " --stats " + (dir_ / "b.json").string()),
            0);
  auto b = readPng(dir_ / "b.png");
  ASSERT_TRUE(b);
  EXPECT_EQ(b->width, 200);
  EXPECT_EQ(stats(dir_ / "b.json")["lod"]["target_area"], 8.0);
}

TEST_F(SceneCli, BadSceneFilesFailWithOneLineAndNoOutput) {
  const std::vector<std::pair<nlohmann::json, std::string>> cases = {
      {{{"objects", {{{"mesh", "nowhere.off"}}}}}, "objects[0].mesh: no such file"},
      {{{"objects", {{{"mesh", "sphere.off"}, {"scale", -2}}}}}, "objects[0].scale: must be > 0"},
      {{{"objects", {{{"mesh", "sphere.off"}, {"shininess", 3}}}}}, "objects[0]: unknown key \"shininess\""},
      {{{"objects", {{{"mesh", "sphere.off"}}}}, {"settings", {{"target-aera", 3}}}}, "settings.target-aera: unknown setting"},
      {{{"objects", {{{"mesh", "sphere.off"}}}}, {"settings", {{"target-area", "big"}}}}, "settings.target-area"},
      {{{"objects", {{{"mesh", "sphere.off"}}}}, {"settings", {{"output", "x.png"}}}}, "settings.output: not a scene setting"},
      {{{"objects", {{{"mesh", "sphere.off"}, {"style", "watercolour"}}}}}, "objects[0]: --style"},
      {{{"objects", {{{"scene", "bad.json"}}}}}, "include cycle"},
  };
  for (const auto& [j, expect] : cases) {
    write("bad.json", j);
    std::string out;
    const auto png = dir_ / "never.png";
    const int rc = run((dir_ / "bad.json").string() + " -o " + png.string(), &out);
    EXPECT_EQ(rc, 1) << out;
    EXPECT_EQ(out.rfind("lodline: " + (dir_ / "bad.json").string(), 0), 0u) << out;
    EXPECT_NE(out.find(expect), std::string::npos) << out;
    EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << out;
    EXPECT_FALSE(std::filesystem::exists(png));
  }
  std::ofstream(dir_ / "broken.json") << "{\"objects\": [ {\"mesh\": \"sphere.off\" ";
  std::string out;
  EXPECT_EQ(run((dir_ / "broken.json").string() + " -o " + (dir_ / "never.png").string(), &out), 1);
  EXPECT_NE(out.find("broken.json: invalid JSON"), std::string::npos) << out;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "never.png"));
}

TEST_F(SceneCli, GltfFilesRenderAsScenes) {
  test::GltfTestNode a = test::gltfCube(), b = test::gltfCube();
  a.name = "near";
  b.name = "far";
  b.translation = {2.5f, 0.5f, -3.0f};
  test::writeGltf(dir_ / "cubes.glb", {a, b});
  ASSERT_EQ(run((dir_ / "cubes.glb").string() + " -o " + (dir_ / "c.png").string() + " --stats " +
                (dir_ / "c.json").string() + " --size 320x240"),
            0);
  const auto s = stats(dir_ / "c.json");
  ASSERT_EQ(s["objects"].size(), 2u);
  EXPECT_EQ(s["objects"][0]["name"], "near");
  EXPECT_EQ(s["objects"][0]["faces"], 12);  // welded: a closed cube
  EXPECT_GT(s["lines"]["crease"].get<int>() + s["lines"]["contour"].get<int>(), 0);
  EXPECT_EQ(s["lines_extracted"]["boundary"], 0);  // split vertices were welded
}

TEST_F(SceneCli, BuildAndBenchTakeScenes) {
  write("two.json", {{"objects", {{{"mesh", "sphere.off"}}, {{"mesh", "sphere.off"}, {"translate", {3, 0, 0}}, {"scale", 0.5}}}}});
  std::string out;
  ASSERT_EQ(test::runLodline("build " + (dir_ / "two.json").string(), &out), 0) << out;
  EXPECT_NE(out.find("sphere#2"), std::string::npos) << out;
  ASSERT_EQ(run((dir_ / "two.json").string() + " -o " + (dir_ / "t.png").string() + " --stats " + (dir_ / "t.json").string()), 0);
  EXPECT_NE(stats(dir_ / "t.json")["lod"]["cache"].get<std::string>().find("loaded"), std::string::npos);
  ASSERT_EQ(test::runLodline("bench walkthrough " + (dir_ / "two.json").string() + " --frames 4 --modes none,pm --size 320x180 --msaa 1 "
                "--cache-dir " + (dir_ / "cache").string(), &out), 0) << out;
  EXPECT_NE(out.find("in 2 objects"), std::string::npos) << out;
  EXPECT_NE(out.find("| pm |"), std::string::npos) << out;
}

// --hidden-lines draws the hidden runs in their own style (dashed grey here) where the
// visible ones are not: inside the front sphere's disc, the back sphere's contour shows as
// grey dashes; the SVG has them as a layer of class "hidden"; the stats count them; an
// object's own hidden_lines key turns them on for it alone.
TEST_F(SceneCli, HiddenLinesInTheirOwnStyle) {
  const nlohmann::json front = {{"name", "front"}, {"mesh", "sphere.off"}, {"translate", {0, 0, 2}}};
  const nlohmann::json back = {{"name", "back"}, {"mesh", "sphere.off"}, {"translate", {0.9, 0.3, -1}}};
  const nlohmann::json settings = {{"style", "lines"}, {"lines", "contour"}, {"size", "480x360"}, {"msaa", 1}};
  write("both.json", {{"settings", settings}, {"camera", frontCamera()}, {"objects", {front, back}}});
  const std::string in = (dir_ / "both.json").string();
  ASSERT_EQ(run(in + " -o " + (dir_ / "plain.png").string() + " --stats " + (dir_ / "plain.json").string()), 0);
  ASSERT_EQ(run(in + " --hidden-lines '#ff0000:1.5:dash=4,3' -o " + (dir_ / "h.png").string() + " --svg " +
                (dir_ / "h.svg").string() + " --stats " + (dir_ / "h.json").string()),
            0);
  auto plain = readPng(dir_ / "plain.png"), hidden = readPng(dir_ / "h.png");
  ASSERT_TRUE(plain && hidden);
  Camera cam;
  cam.eye = {0, 0, 9};
  cam.fov_deg = 35.0f;
  const glm::vec2 c = projectToPixels(cam, {0, 0, 2}, 480, 360);
  const float r = glm::length(projectToPixels(cam, {0, 1, 2}, 480, 360) - c);
  // Inside the front disc: nothing without hidden lines, red dashes with them.
  EXPECT_EQ(darkInDisc(*plain, c, 0.85f * r), 0);
  int red = 0, gaps = 0;
  for (int y = 0; y < 360; ++y)
    for (int x = 0; x < 480; ++x) {
      if (glm::length(glm::vec2(x + 0.5f, y + 0.5f) - c) > 0.85f * r) continue;
      const uint8_t* p = hidden->pixel(x, y);
      red += p[0] > 200 && p[1] < 120 && p[2] < 120;
    }
  EXPECT_GT(red, 60);
  // Dashed: along the hidden arc, drawn and skipped pieces alternate (some pixels of the
  // arc stay white). Count white pixels next to red ones on the arc's rows.
  for (int y = 0; y < 360; ++y)
    for (int x = 1; x < 480; ++x) {
      const uint8_t *p = hidden->pixel(x, y), *q = hidden->pixel(x - 1, y);
      gaps += (p[0] > 200 && p[1] < 120) != (q[0] > 200 && q[1] < 120);
    }
  EXPECT_GT(gaps, 2 * 10);
  // Stats: hidden pixels counted (with or without drawing them), the visible ones unchanged.
  const auto ps = stats(dir_ / "plain.json"), hs = stats(dir_ / "h.json");
  EXPECT_GT(hs["hidden_line_pixels"].get<int>(), 100);
  EXPECT_EQ(hs["hidden_line_pixels"], ps["hidden_line_pixels"]);
  EXPECT_EQ(hs["line_pixels"], ps["line_pixels"]);
  // SVG: a layer of class "hidden", dashed, in the hidden style.
  std::ifstream svg_in(dir_ / "h.svg");
  const std::string svg((std::istreambuf_iterator<char>(svg_in)), std::istreambuf_iterator<char>());
  EXPECT_NE(svg.find("class=\"hidden\""), std::string::npos);
  EXPECT_NE(svg.find("stroke-dasharray=\"4.000 3.000\""), std::string::npos);
  EXPECT_NE(svg.find("#ff0000"), std::string::npos);
  // Per object: only the back sphere's hidden lines drawn in the scene file.
  nlohmann::json back_hidden = back;
  back_hidden["hidden_lines"] = "#ff0000";
  write("one.json", {{"settings", settings}, {"camera", frontCamera()}, {"objects", {front, back_hidden}}});
  ASSERT_EQ(run((dir_ / "one.json").string() + " -o " + (dir_ / "one.png").string()), 0);
  auto one = readPng(dir_ / "one.png");
  ASSERT_TRUE(one);
  int red_one = 0;
  for (size_t i = 0; i < one->rgba.size(); i += 4) red_one += one->rgba[i] > 200 && one->rgba[i + 1] < 120;
  EXPECT_GT(red_one, 60);
  // Bad values are usage errors.
  std::string out;
  EXPECT_EQ(run(in + " --hidden-lines grey:0 -o " + (dir_ / "x.png").string(), &out), 2) << out;
  EXPECT_EQ(run(in + " --hidden-lines grey:1:dash=4 -o " + (dir_ / "x.png").string(), &out), 2) << out;
  EXPECT_EQ(run(in + " --hidden-lines nonsense -o " + (dir_ / "x.png").string(), &out), 2) << out;
}

// Stroke styles: per object in a scene (a preset, and a style file relative to the scene),
// and on the command line; bad names and bad files are refused before anything is written.
TEST_F(SceneCli, StrokeStylesPerObjectAndOnTheCommandLine) {
  std::ofstream(dir_ / "red.json") << R"({"all": {"color": "#ff0000", "width_scale": 2}})";
  nlohmann::json left = {{"mesh", "sphere.off"}, {"translate", {-1.3, 0, 0}}, {"stroke_style", "marker"}};
  nlohmann::json right = {{"mesh", "sphere.off"}, {"translate", {1.3, 0, 0}}, {"stroke_style", "red.json"}};
  const auto in = write("styled.json", {{"settings", {{"style", "lines"}, {"size", "320x160"}}},
                                       {"camera", frontCamera()}, {"objects", {left, right}}});
  std::string out;
  ASSERT_EQ(run(in.string() + " -o " + (dir_ / "styled.png").string(), &out), 0) << out;
  auto img = readPng(dir_ / "styled.png");
  ASSERT_TRUE(img);
  int blue_left = 0, red_right = 0, red_left = 0;
  for (int y = 0; y < img->height; ++y)
    for (int x = 0; x < img->width; ++x) {
      const uint8_t* p = img->pixel(x, y);
      const bool blue = p[2] > p[0] + 20 && p[0] < 160, red = p[0] > 200 && p[1] < 100;
      (x < img->width / 2 ? blue_left : red_right) += x < img->width / 2 ? blue : red;
      if (x < img->width / 2) red_left += red;
    }
  EXPECT_GT(blue_left, 100);  // the marker's slate blue
  EXPECT_GT(red_right, 100);  // the file's red
  EXPECT_EQ(red_left, 0);
  // The command line's style is every object's default.
  const auto sphere = (dir_ / "sphere.off").string();
  ASSERT_EQ(run(sphere + " --style lines --stroke-style pencil -o " + (dir_ / "p.png").string(), &out), 0) << out;
  EXPECT_EQ(run(sphere + " --stroke-style crayon -o " + (dir_ / "x.png").string(), &out), 2);
  EXPECT_NE(out.find("plain, ink, pencil, marker"), std::string::npos) << out;
  std::ofstream(dir_ / "bad.json") << R"({"contour": {"taper_in": -1}})";
  EXPECT_EQ(run(sphere + " --stroke-style " + (dir_ / "bad.json").string() + " -o " + (dir_ / "x.png").string(), &out),
            1);
  EXPECT_NE(out.find("bad.json: contour.taper_in"), std::string::npos) << out;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "x.png"));
}

// Pixels that differ between two images of one size (SIZE_MAX when the sizes differ).
size_t differingPixels(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height) return SIZE_MAX;
  size_t n = 0;
  for (size_t i = 0; i < a.rgba.size(); i += 4) n += std::memcmp(&a.rgba[i], &b.rgba[i], 4) != 0;
  return n;
}

// `bench walkthrough` builds its scene as `render` does: settings, styles and the scene's
// light. Its first frame of each mode is `render`'s picture of the same scene, bit for bit.
TEST_F(SceneCli, BenchWalkthroughDrawsWhatRenderDraws) {
  const nlohmann::json path = {{"keys", {{{"time", 0}, {"eye", {0, 1, 9}}, {"target", {0, 0, 0}}, {"fov", 35}},
                                         {{"time", 1}, {"eye", {1, 1, 9}}, {"target", {0, 0, 0}}, {"fov", 35}}}}};
  write("path.json", path);
  const nlohmann::json objects = {{{"name", "lit"}, {"mesh", "sphere.off"}, {"translate", {-1.2, 0, 0}}},
                                  {{"name", "drawn"}, {"mesh", "sphere.off"}, {"translate", {1.2, 0, 0}}, {"style", "lines"}}};
  const nlohmann::json settings = {{"size", "320x240"}, {"msaa", 1}, {"target-area", 12}};
  nlohmann::json scene = {{"settings", settings}, {"camera", {{"path", "path.json"}}}, {"objects", objects}};
  scene["light"] = {{"direction", {1.0, -0.2, 0.3}}};  // from the right and below: far from the default
  write("lit.json", scene);
  scene.erase("light");
  write("unlit.json", scene);
  std::string out;
  ASSERT_EQ(test::runLodline("bench walkthrough " + (dir_ / "lit.json").string() + " --frames 2 --modes pm,none --snapshot " +
                                 (dir_ / "bench").string(),
                             &out),
            0)
      << out;
  ASSERT_EQ(run((dir_ / "lit.json").string() + " -o " + (dir_ / "render.png").string()), 0);
  ASSERT_EQ(run((dir_ / "lit.json").string() + " --full-detail -o " + (dir_ / "full.png").string()), 0);
  ASSERT_EQ(run((dir_ / "unlit.json").string() + " -o " + (dir_ / "unlit.png").string()), 0);
  auto bench_pm = readPng(dir_ / "bench-pm.png"), bench_none = readPng(dir_ / "bench-none.png");
  auto render = readPng(dir_ / "render.png"), full = readPng(dir_ / "full.png"), unlit = readPng(dir_ / "unlit.png");
  ASSERT_TRUE(bench_pm && bench_none && render && full && unlit);
  EXPECT_EQ(bench_pm->width, 320);
  EXPECT_EQ(differingPixels(*bench_pm, *render), 0u);
  EXPECT_EQ(differingPixels(*bench_none, *full), 0u);
  // The light matters: without it, the toon sphere's tones are elsewhere.
  EXPECT_GT(differingPixels(*render, *unlit), 1000u);
}

// The software backend draws scenes too: every object in its own style, one object hiding
// another's lines, close to the OpenGL picture.
TEST_F(SceneCli, SoftBackendDrawsScenes) {
  const nlohmann::json front = {{"name", "front"}, {"mesh", "sphere.off"}, {"translate", {0, 0, 2}}};
  const nlohmann::json back = {{"name", "back"}, {"mesh", "sphere.off"}, {"translate", {0.9, 0.3, -1}}, {"style", "lines"}};
  const nlohmann::json settings = {{"size", "320x240"}, {"msaa", 1}};
  write("two.json", {{"settings", settings}, {"camera", frontCamera()}, {"objects", {front, back}}});
  const std::string in = (dir_ / "two.json").string();
  ASSERT_EQ(run(in + " -o " + (dir_ / "gl.png").string() + " --stats " + (dir_ / "gl.json").string()), 0);
  ASSERT_EQ(run(in + " --backend soft -o " + (dir_ / "soft.png").string() + " --stats " + (dir_ / "soft.json").string()),
            0);
  auto gl = readPng(dir_ / "gl.png"), soft = readPng(dir_ / "soft.png");
  ASSERT_TRUE(gl && soft);
  // Tone borders and line pixels may move by a pixel; most pixels are equal.
  EXPECT_LT(differingPixels(*gl, *soft), static_cast<size_t>(0.05 * 320 * 240));
  const auto g = stats(dir_ / "gl.json"), s = stats(dir_ / "soft.json");
  EXPECT_EQ(s["context"]["backend"], "soft");
  ASSERT_EQ(s["objects"].size(), 2u);
  EXPECT_EQ(s["objects"][1]["style"], "lines");
  EXPECT_EQ(s["faces_drawn"], g["faces_drawn"]);
  // The front sphere hides most of the back one's contour in both.
  EXPECT_NEAR(s["objects"][1]["line_pixels"].get<double>(), g["objects"][1]["line_pixels"].get<double>(),
              0.05 * g["objects"][1]["line_pixels"].get<double>() + 5);
  EXPECT_LT(s["objects"][1]["lines"]["contour"].get<int>(), s["objects"][1]["lines_extracted"]["contour"].get<int>() * 0.9);
}

}  // namespace
}  // namespace lodline
