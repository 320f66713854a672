// Concurrency (docs/reliability.md): processes building the same model into one cache
// directory at once, while others render from it, never crash and never read a half-written
// cache. Writers write a temporary file and rename it over the cache file (atomic), and a
// reader sizes the file it opened, not the path, so it sees one complete version or the
// other: every render's stats must report the cache loaded or built, never unreadable.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "io/generate.h"
#include "io/load_mesh.h"
#include "pm/pm_file.h"
#include "run_process.h"
#include "test_util.h"

namespace lodline {
namespace {

namespace fs = std::filesystem;

TEST(Concurrency, SimultaneousBuildsAndRendersShareOneCache) {
  test::TempDir dir;
  const std::string model = (dir / "sphere.off").string();
  ASSERT_TRUE(saveOff(model, makeIcoSphere(1.0f, 5)).ok());  // 20k faces: builds take a moment
  const fs::path cache = dir / "cache";
  test::ProcessOptions opt;
  opt.env = {"XDG_CACHE_HOME=" + (dir / "xdg").string()};  // Mesa's shader cache elsewhere
  opt.timeout_s = 300.0;
  int renders = 0;
  for (int round = 0; round < 3; ++round) {
    std::vector<std::unique_ptr<test::Process>> procs;
    std::vector<std::string> stats;
    for (int k = 0; k < 3; ++k) {
      // --force: every build writes the cache file, racing the others.
      procs.push_back(std::make_unique<test::Process>(
          test::lodlineArgs({"build", model, "--force", "--cache-dir", cache.string()}), opt));
      const std::string tag = std::to_string(round * 10 + k);  // append(): GCC 12 -Wrestrict (PR 105329)
      stats.push_back((dir / std::string("s").append(tag).append(".json")).string());
      procs.push_back(std::make_unique<test::Process>(
          test::lodlineArgs({"render", model, "-o", (dir / std::string("o").append(tag).append(".png")).string(), "--size",
                             "96x64", "--msaa", "1", "--stats", stats.back(), "--cache-dir", cache.string()}),
          opt));
    }
    for (auto& p : procs) {
      const test::ProcessResult r = p->wait();
      EXPECT_FALSE(r.timed_out) << r.describe();
      EXPECT_EQ(r.signal, 0) << r.describe() << "\n" << r.err;
      EXPECT_EQ(r.exit_code, 0) << r.err;
    }
    for (const std::string& s : stats) {
      std::ifstream in(s);
      const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      ASSERT_FALSE(text.empty()) << s;
      EXPECT_EQ(text.find("unreadable"), std::string::npos) << "a render read a half-written cache: " << text;
      EXPECT_TRUE(text.find("loaded progressive mesh cache") != std::string::npos ||
                  text.find("rebuilt progressive mesh") != std::string::npos)
          << text;
      ++renders;
    }
  }
  EXPECT_EQ(renders, 9);
  // One progressive-mesh cache file, complete, at most one intersection-line cache (renders
  // write it), and no temporary left.
  std::vector<std::string> files, others;
  for (const auto& e : fs::directory_iterator(cache)) {
    const std::string name = e.path().filename().string();
    (e.path().extension() == ".lpm" ? files : others).push_back(name);
  }
  ASSERT_EQ(files.size(), 1u) << ::testing::PrintToString(files);
  ASSERT_LE(others.size(), 1u) << ::testing::PrintToString(others);
  for (const std::string& o : others) EXPECT_EQ(fs::path(o).extension(), ".lix") << o;
  auto pm = loadPm(cache / files[0]);
  EXPECT_TRUE(pm.ok()) << pm.error().message;
}

}  // namespace
}  // namespace lodline
