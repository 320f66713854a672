// Hybrid static + dynamic simplification through the CLI (Pan, Zhou, Shi; docs/design.md §2.4):
// `simplify`, `compare`, `build --pre-simplify`, `render --lod cluster` and
// `bench walkthrough`.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>

#include <nlohmann/json.hpp>

#include "io/generate.h"
#include "io/load_mesh.h"
#include "test_util.h"

namespace lodline {
namespace {

int run(const std::string& args, std::string* output = nullptr) { return test::runLodline(args, output); }

class SimplifyCli : public ::testing::Test {
 protected:
  void SetUp() override {
    model_ = (dir_ / "knot.off").string();
    ASSERT_TRUE(saveOff(model_, makeTorusKnot(2, 3, 1.0f, 0.16f, 480, 32, 0.15f)).ok());
  }
  /// True (and the test skips) when the binary was built without CGAL.
  bool noCgal(const std::string& output) { return output.find("without CGAL") != std::string::npos; }
  test::TempDir dir_;
  std::string model_;
};

/// The number before "% of the diagonal" on the line starting with `label`.
double percentAfter(const std::string& text, const std::string& label) {
  const std::regex re(label + " [0-9.e+-]+ \\(([0-9.e+-]+)% of the diagonal");
  std::smatch m;
  if (!std::regex_search(text, m, re)) return -1.0;
  return std::stod(m[1]);
}

TEST_F(SimplifyCli, SimplifyStaysWithinTheBoundAndCompareAgrees) {
  for (const char* bound : {"0.01%", "0.05"}) {
    const auto out = dir_ / "s.off";
    std::string text;
    const int rc = run("simplify " + model_ + " --max-error " + bound + " -o " + out.string(), &text);
    if (noCgal(text)) GTEST_SKIP() << text;
    ASSERT_EQ(rc, 0) << text;
    auto s = loadMesh(out);
    ASSERT_TRUE(s.ok());
    EXPECT_LT(s->faceCount(), 30720u);
    ASSERT_EQ(run("compare " + model_ + " " + out.string(), &text), 0) << text;
    const double e = percentAfter(text, "E_s");
    EXPECT_GE(e, 0.0) << text;
    EXPECT_LE(e, std::stod(std::string(bound).substr(0, 4)) * (1.0 + 1e-6)) << text;
    EXPECT_NE(text.find("Hausdorff"), std::string::npos);
  }
}

TEST_F(SimplifyCli, BadInputsAreReportedWithoutOutput) {
  const auto out = dir_ / "s.off";
  std::string text;
  EXPECT_EQ(run("simplify " + model_ + " --max-error abc -o " + out.string(), &text), 2);
  EXPECT_NE(text.find("--max-error"), std::string::npos) << text;
  EXPECT_EQ(run("simplify " + (dir_ / "missing.off").string() + " --max-error 0.1% -o " + out.string(), &text), 1);
  EXPECT_NE(text.find("missing.off"), std::string::npos) << text;
  EXPECT_FALSE(std::filesystem::exists(out));
  {
    std::ofstream bad(dir_ / "bad.off");
    bad << "OFF\n3 1 0\n0 0 0\n1 0 0\n";
  }
  EXPECT_EQ(run("compare " + model_ + " " + (dir_ / "bad.off").string(), &text), 1);
  EXPECT_NE(text.find("bad.off"), std::string::npos) << text;
  EXPECT_EQ(run("build " + model_ + " --pre-simplify 0.02%", &text), 2);
  EXPECT_NE(text.find("--mesh-out"), std::string::npos) << text;
}

TEST_F(SimplifyCli, BuildPreSimplifiedFeedsTheRenderCache) {
  const auto pre = dir_ / "pre.off";
  const auto cache = dir_ / "cache";
  std::string text;
  const int rc = run("build " + model_ + " --pre-simplify 0.02% --mesh-out " + pre.string() + " --cache-dir " +
                         cache.string(), &text);
  if (noCgal(text)) GTEST_SKIP() << text;
  ASSERT_EQ(rc, 0) << text;
  const auto stats = dir_ / "s.json";
  ASSERT_EQ(run("render " + pre.string() + " --size 320x180 -o " + (dir_ / "a.png").string() + " --cache-dir " +
                cache.string() + " --stats " + stats.string(), &text), 0) << text;
  std::ifstream in(stats);
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j["lod"]["cache"].get<std::string>().rfind("loaded", 0), 0u) << j["lod"]["cache"];
}

TEST_F(SimplifyCli, RenderWithClustering) {
  const auto stats = dir_ / "c.json";
  std::string text;
  ASSERT_EQ(run("render " + model_ + " --size 480x270 --lod cluster --pixel-error 4 -o " + (dir_ / "c.png").string() +
                " --stats " + stats.string(), &text), 0) << text;
  std::ifstream in(stats);
  const auto j = nlohmann::json::parse(in);
  EXPECT_LT(j["faces_drawn"].get<int>(), j["model"]["faces"].get<int>());
  EXPECT_GT(j["line_segments"].get<int>(), 50);
  EXPECT_EQ(run("render " + model_ + " --lod bogus -o " + (dir_ / "x.png").string(), &text), 2);
  EXPECT_NE(text.find("--lod"), std::string::npos);
  EXPECT_EQ(run("render " + model_ + " --lod cluster --full-detail -o " + (dir_ / "x.png").string(), &text), 2);
  EXPECT_EQ(run("render " + model_ + " --lod cluster --pixel-error 0 -o " + (dir_ / "x.png").string(), &text), 2);
  // --lod none is --full-detail: every face drawn.
  ASSERT_EQ(run("render " + model_ + " --size 480x270 --lod none -o " + (dir_ / "n.png").string() + " --stats " +
                stats.string(), &text), 0) << text;
  std::ifstream in2(stats);
  const auto n = nlohmann::json::parse(in2);
  EXPECT_EQ(n["faces_drawn"].get<int>(), n["model"]["faces"].get<int>());
}

TEST_F(SimplifyCli, WalkthroughBenchPrintsAllModes) {
  std::string text;
  const int rc = run("bench walkthrough " + model_ + " --path orbit --frames 3 --size 320x180 --msaa 1 --cache-dir " +
                         (dir_ / "cache").string(), &text);
  if (noCgal(text)) GTEST_SKIP() << text;
  ASSERT_EQ(rc, 0) << text;
  for (const char* row : {"| none |", "| cluster |", "| hybrid |", "| pm |"})
    EXPECT_NE(text.find(row), std::string::npos) << row << "\n" << text;
  EXPECT_NE(text.find("triangles drawn"), std::string::npos);
  EXPECT_EQ(run("bench walkthrough " + model_ + " --path nowhere.json --frames 3", &text), 1);
  EXPECT_NE(text.find("nowhere.json"), std::string::npos) << text;
}

}  // namespace
}  // namespace lodline
