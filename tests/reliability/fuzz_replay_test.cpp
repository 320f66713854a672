// Every input in tests/fuzz/regressions/TARGET/ (past fuzz findings and hand-made hostile
// files) replayed through the fuzz target TARGET, built here without libFuzzer, so the
// ordinary and the ASan test builds keep them fixed. A target aborts on a finding (crash,
// broken error contract), which fails this test binary.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include "harness.h"

namespace lodline {
namespace {

std::string readAll(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(FuzzReplay, EveryRegressionDirectoryHasATarget) {
  std::set<std::string> names;
  for (const auto& [name, fn] : fuzz::registeredTargets()) names.insert(name);
  for (const char* expected : {"mesh_off", "mesh_obj", "mesh_ply_ascii", "mesh_ply_binary", "mesh_stl_ascii",
                               "mesh_stl_binary", "pm_cache", "camera_path", "detail_map_png", "intersection_cache"})
    EXPECT_TRUE(names.count(expected)) << expected;
  for (const auto& dir : std::filesystem::directory_iterator(LODLINE_FUZZ_REGRESSIONS))
    EXPECT_TRUE(names.count(dir.path().filename().string())) << "no fuzz target for " << dir.path();
}

TEST(FuzzReplay, RegressionInputs) {
  size_t replayed = 0;
  for (const auto& [name, fn] : fuzz::registeredTargets()) {
    const std::filesystem::path dir = std::filesystem::path(LODLINE_FUZZ_REGRESSIONS) / name;
    if (!std::filesystem::is_directory(dir)) continue;
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(dir)) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    for (const auto& file : files) {
      SCOPED_TRACE(name + ": " + file.filename().string());
      const std::string bytes = readAll(file);
      fn(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
      ++replayed;
    }
  }
  EXPECT_GE(replayed, 15u);
}

}  // namespace
}  // namespace lodline
