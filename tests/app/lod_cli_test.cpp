// Detail control through the CLI: progressive-mesh cache, converged stills, stats.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>
#include <sys/wait.h>

#include "io/generate.h"
#include "io/image.h"
#include "io/load_mesh.h"
#include "test_util.h"

namespace lodline {
namespace {

int run(const std::string& args, std::string* output = nullptr) { return test::runLodline(args, output); }

nlohmann::json readJson(const std::filesystem::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

class LodCli : public ::testing::Test {
 protected:
  void SetUp() override {
    model_ = (dir_ / "knot.off").string();
    ASSERT_TRUE(saveOff(model_, makeTorusKnot(2, 3, 1.0f, 0.16f, 480, 32, 0.15f)).ok());
    cache_ = (dir_ / "cache").string();
  }
  std::string render(const std::string& args) {
    return "render " + model_ + " --size 480x270 --cache-dir " + cache_ + " " + args;
  }
  test::TempDir dir_;
  std::string model_, cache_;
};

TEST_F(LodCli, ConvergedStillKeepsTrianglesInTheBand) {
  const auto stats = dir_ / "s.json";
  std::string out;
  ASSERT_EQ(run(render("-o " + (dir_ / "a.png").string() + " --stats " + stats.string()), &out), 0) << out;
  const auto j = readJson(stats);
  ASSERT_TRUE(j.contains("lod"));
  EXPECT_GE(j["lod"]["band_fraction"].get<double>(), 0.9);
  EXPECT_EQ(j["lod"]["target_area"].get<double>(), 16.0);
  EXPECT_EQ(j["lod"]["splits"].get<int>(), 0);  // converged
  EXPECT_EQ(j["lod"]["collapses"].get<int>(), 0);
  EXPECT_EQ(j["lod"]["folded_faces"].get<int>(), 0);  // a still is refined, not folded
  EXPECT_EQ(j["faces_drawn"], j["lod"]["active_faces"]);
  EXPECT_LT(j["faces_drawn"].get<int>(), j["model"]["faces"].get<int>());
  EXPECT_GT(j["line_segments"].get<int>(), 100);
  EXPECT_NE(j["lod"]["cache"].get<std::string>().find("rebuilt"), std::string::npos);
}

TEST_F(LodCli, CacheIsReusedAndCorruptCacheRebuilt) {
  const auto stats = dir_ / "s.json";
  ASSERT_EQ(run(render("-o " + (dir_ / "a.png").string())), 0);
  ASSERT_EQ(run(render("-o " + (dir_ / "b.png").string() + " --stats " + stats.string())), 0);
  EXPECT_EQ(readJson(stats)["lod"]["cache"].get<std::string>().rfind("loaded", 0), 0u)
      << readJson(stats)["lod"]["cache"];
  // Same input, same converged image.
  EXPECT_EQ(readPng(dir_ / "a.png")->rgba, readPng(dir_ / "b.png")->rgba);
  // Truncate every cache file (the progressive mesh's and the intersection lines'): the next
  // render rebuilds them and still draws the same picture.
  size_t files = 0;
  for (auto& e : std::filesystem::directory_iterator(cache_)) {
    std::filesystem::resize_file(e.path(), std::filesystem::file_size(e.path()) / 2);
    ++files;
  }
  ASSERT_EQ(files, 2u);
  std::string out;
  ASSERT_EQ(run(render("-o " + (dir_ / "c.png").string() + " --stats " + stats.string()), &out), 0) << out;
  EXPECT_NE(readJson(stats)["lod"]["cache"].get<std::string>().find("rebuilt"), std::string::npos);
  EXPECT_EQ(readPng(dir_ / "a.png")->rgba, readPng(dir_ / "c.png")->rgba);
}

TEST_F(LodCli, DistantViewsDrawFewerTriangles) {
  const auto near = dir_ / "n.json", far = dir_ / "f.json", full = dir_ / "full.json";
  ASSERT_EQ(run(render("-o " + (dir_ / "n.png").string() + " --view 30,20,2 --stats " + near.string())), 0);
  ASSERT_EQ(run(render("-o " + (dir_ / "f.png").string() + " --view 30,20,16 --stats " + far.string())), 0);
  ASSERT_EQ(run(render("-o " + (dir_ / "x.png").string() + " --view 30,20,16 --full-detail --stats " + full.string())), 0);
  const int n = readJson(near)["faces_drawn"], f = readJson(far)["faces_drawn"], x = readJson(full)["faces_drawn"];
  EXPECT_FALSE(readJson(full).contains("lod"));
  EXPECT_EQ(x, readJson(full)["model"]["faces"].get<int>());
  // 8x farther covers 1/64 of the image area: far fewer triangles (the base mesh bounds it below).
  EXPECT_LT(f * 8, n);
  EXPECT_LT(f * 8, x);
}

TEST_F(LodCli, CoarserTargetAreaDrawsFewerTriangles) {
  const auto a = dir_ / "a.json", b = dir_ / "b.json";
  ASSERT_EQ(run(render("-o " + (dir_ / "a.png").string() + " --target-area 8 --stats " + a.string())), 0);
  ASSERT_EQ(run(render("-o " + (dir_ / "b.png").string() + " --target-area 64 --stats " + b.string())), 0);
  const double ratio = readJson(a)["faces_drawn"].get<double>() / readJson(b)["faces_drawn"].get<double>();
  EXPECT_GT(ratio, 4.0);  // 8x the area per triangle: about 8x fewer (bounded by base and full)
}

TEST_F(LodCli, DetailMapCoarsensWhereItIsWhite) {
  Image map(2, 1);
  for (int c = 0; c < 3; ++c) {
    map.pixel(0, 0)[c] = 255;  // left half coarse
    map.pixel(1, 0)[c] = 32;   // right half fine
  }
  map.pixel(0, 0)[3] = map.pixel(1, 0)[3] = 255;
  ASSERT_TRUE(writePng(dir_ / "map.png", map).ok());
  const auto with = dir_ / "m.json", without = dir_ / "w.json";
  std::string out;
  ASSERT_EQ(run(render("-o " + (dir_ / "m.png").string() + " --detail-map " + (dir_ / "map.png").string() +
                       " --stats " + with.string()), &out), 0) << out;
  ASSERT_EQ(run(render("-o " + (dir_ / "w.png").string() + " --stats " + without.string())), 0);
  EXPECT_NE(readJson(with)["faces_drawn"], readJson(without)["faces_drawn"]);
}

// A still converges whatever the frames' adaptation budget: the same picture with one.
TEST_F(LodCli, StillIgnoresTheAdaptBudget) {
  std::string out;
  ASSERT_EQ(run(render("-o " + (dir_ / "a.png").string()), &out), 0) << out;
  ASSERT_EQ(run(render("-o " + (dir_ / "b.png").string() + " --adapt-budget 0.001"), &out), 0) << out;
  auto a = readPng(dir_ / "a.png"), b = readPng(dir_ / "b.png");
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_TRUE(a->rgba == b->rgba);
}

TEST_F(LodCli, BuildCommandAndErrors) {
  std::string out;
  ASSERT_EQ(run("build " + model_ + " -o " + (dir_ / "k.lpm").string(), &out), 0) << out;
  EXPECT_TRUE(std::filesystem::exists(dir_ / "k.lpm"));
  EXPECT_NE(out.find("vertex splits"), std::string::npos) << out;
  ASSERT_EQ(run("build " + model_ + " --cache-dir " + cache_, &out), 0) << out;
  ASSERT_EQ(run("build " + model_ + " --cache-dir " + cache_, &out), 0) << out;
  EXPECT_NE(out.find("loaded"), std::string::npos) << out;
  EXPECT_EQ(run("build /nonexistent.off", &out), 1);
  EXPECT_EQ(run(render("-o " + (dir_ / "e.png").string() + " --target-area 0")), 2);
  EXPECT_EQ(run(render("-o " + (dir_ / "e.png").string() + " --geomorphs maybe")), 2);
  EXPECT_EQ(run(render("-o " + (dir_ / "e.png").string() + " --adapt-budget -1"), &out), 2);
  EXPECT_NE(out.find("--adapt-budget"), std::string::npos) << out;
  EXPECT_EQ(run(render("-o " + (dir_ / "e.png").string() + " --min-suggestive-length -0.5"), &out), 2);
  EXPECT_NE(out.find("--min-suggestive-length"), std::string::npos) << out;
  EXPECT_EQ(run(render("-o " + (dir_ / "e.png").string() + " --detail-map " + (dir_ / "none.png").string()), &out), 1);
  EXPECT_NE(out.find("none.png"), std::string::npos) << out;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "e.png"));
}

}  // namespace
}  // namespace lodline
