// The exterior outline is complete on a coarse mesh close up (docs/visibility.md), full
// detail and under detail control, measured as `render --stats` reports it; the
// interpolated contour alone is not, which is what the completion is for.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include <nlohmann/json.hpp>

#include "test_util.h"

namespace lodline {
namespace {

nlohmann::json outline(const test::TempDir& dir, const std::string& model, const std::string& opts) {
  const auto stats = dir / "s.json";
  std::string out;
  EXPECT_EQ(test::runLodline("render " + model + " --style lines --size 960x540 -o " + (dir / "o.png").string() +
                                 " --stats " + stats.string() + " " + opts,
                             &out),
            0)
      << out;
  return nlohmann::json::parse(std::ifstream(stats))["outline"];
}

TEST(OutlineCli, TheCowsOutlineIsCompleteCloseUp) {
  const auto cow = test::dataMesh("cow.off");
  if (cow.empty()) GTEST_SKIP() << "data/meshes/cow.off missing (run scripts/setup.sh)";
  test::TempDir dir;
  setenv("XDG_CACHE_HOME", (dir / "cache").c_str(), 1);
  for (const std::string view : {"60,20,1.6", "60,20,2.2", "35,20,0"})
    for (const std::string mode : {"--full-detail", "--target-area 16"}) {
      const auto o = outline(dir, cow.string(), "--view " + view + " " + mode);
      EXPECT_GE(o["coverage"].get<double>(), 0.99) << view << " " << mode;
      EXPECT_EQ(o["gaps"].get<int>(), 0) << view << " " << mode;
      EXPECT_GT(o["pixels"].get<int>(), 500) << view << " " << mode;
    }
  // The contour alone leaves gaps there.
  const auto contour = outline(dir, cow.string(), "--view 60,20,1.6 --full-detail --outline contour");
  EXPECT_LT(contour["coverage"].get<double>(), 0.97);
  EXPECT_GT(contour["gaps"].get<int>(), 2);
  EXPECT_GT(contour["largest_gap_px"].get<int>(), 20);
}

}  // namespace
}  // namespace lodline
