// Option faults (docs/reliability.md): every value a user could mistype — sizes of 0 or
// 100000x100000, NaN or negative T, inverted t_c/t_s, bad frame ranges, fps 0, detail maps
// that are not PNGs or are 20000x20000 — is refused with exit 2 (usage) or 1 (a bad file
// named by an option), exactly one line on stderr naming the option or the file, and
// nothing left in the output directory.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include <sys/stat.h>

#include "io/generate.h"
#include "io/image.h"
#include "io/load_mesh.h"
#include "run_process.h"
#include "test_util.h"

namespace lodline {
namespace {

namespace fs = std::filesystem;

struct Fault {
  std::string command;               ///< render, capture, build, simplify, view
  std::vector<std::string> options;  ///< the faulty options
  int exit_code;                     ///< 2 usage, 1 bad file
  std::string says;                  ///< part of the error line (the option or the file)
};


class OptionFaults : public ::testing::Test {
 protected:
  void SetUp() override {
    model_ = (dir_ / "knot.off").string();
    ASSERT_TRUE(saveOff(model_, makeTorusKnot(2, 3, 1.0f, 0.16f, 120, 12, 0.1f)).ok());
    std::ofstream(dir_ / "text.png") << "not a png at all";
    std::ofstream(dir_ / "huge.png", std::ios::binary) << test::pngHeaderOnly(20000, 20000);
    std::ofstream(dir_ / "wide.png", std::ios::binary) << test::pngHeaderOnly(8192, 4096);
    ASSERT_EQ(mkfifo((dir_ / "fifo.png").c_str(), 0600), 0);
    fs::create_directory(dir_ / "dir.png");
    fs::create_directory(dir_ / "out");
  }

  // Runs `command model options... <outputs>` and checks the contract.
  void expectRefused(const Fault& f) {
    SCOPED_TRACE(f.command + " " + [&] {
      std::string s;
      for (const auto& o : f.options) s += o + " ";
      return s;
    }());
    const fs::path out = dir_ / "out";
    std::vector<std::string> args = {f.command, model_};
    args.insert(args.end(), f.options.begin(), f.options.end());
    const bool sized = std::find(f.options.begin(), f.options.end(), "--size") != f.options.end();
    if (f.command == "render") args.insert(args.end(), {"-o", (out / "o.png").string()});
    if (!sized && (f.command == "render" || f.command == "capture")) args.insert(args.end(), {"--size", "64x48"});
    if (f.command == "capture") args.insert(args.end(), {"-o", (out / "o.mp4").string()});
    if (f.command == "simplify") args.insert(args.end(), {"-o", (out / "s.off").string()});
    args.insert(args.end(), {"--cache-dir", (dir_ / "cache").string()});
    if (f.command == "simplify") args.resize(args.size() - 2);  // simplify keeps no cache
    test::ProcessOptions opt;
    opt.timeout_s = 60.0;
    opt.env = {"XDG_CACHE_HOME=" + (dir_ / "cache").string()};
    const test::ProcessResult r = test::runProcess(test::lodlineArgs(args), opt);
    ASSERT_FALSE(r.timed_out) << r.describe();
    ASSERT_EQ(r.signal, 0) << r.describe() << "\n" << r.err;
    EXPECT_EQ(r.exit_code, f.exit_code) << r.err;
    const auto lines = test::linesOf(r.err);
    ASSERT_EQ(lines.size(), 1u) << r.err;
    EXPECT_EQ(lines[0].rfind("lodline: ", 0), 0u) << lines[0];
    EXPECT_NE(lines[0].find(f.says), std::string::npos) << lines[0];
    EXPECT_TRUE(fs::is_empty(out)) << "output left behind";
    ++checked_;
    if (std::getenv("LODLINE_TEST_VERBOSE")) {  // one line per run, for docs/reliability.md
      std::string opts;
      for (const auto& o : f.options) opts += (opts.empty() ? "" : " ") + o;
      std::cout << f.command << " | " << opts << " | " << r.describe() << " | " << lines[0].substr(0, 140) << "\n";
    }
  }

  test::TempDir dir_;
  std::string model_;
  int checked_ = 0;
};

TEST_F(OptionFaults, SizesOutOfRange) {
  for (const char* size : {"0x0", "0x100", "100x0", "100000x100000", "-64x48", "64x", "x48", "64x48x2", "nanxnan"})
    for (const char* cmd : {"render", "capture"}) expectRefused({cmd, {"--size", size}, 2, "--size"});
  EXPECT_EQ(checked_, 18);
}

TEST_F(OptionFaults, TargetAreaAndThresholds) {
  for (const char* t : {"nan", "-16", "0", "inf", "1e30"})
    expectRefused({"render", {"--target-area", t}, 2, "--target-area"});
  // Inverted or too close: the paper needs 2 t_c < t_s.
  expectRefused({"render", {"--t-collapse", "1.42", "--t-split", "0.7"}, 2, "--t-collapse/--t-split"});
  expectRefused({"render", {"--t-collapse", "0.8", "--t-split", "1.5"}, 2, "--t-collapse/--t-split"});
  expectRefused({"render", {"--t-collapse", "nan"}, 2, "--t-collapse/--t-split"});
  expectRefused({"render", {"--t-collapse", "-0.7"}, 2, "--t-collapse/--t-split"});
  expectRefused({"capture", {"--t-split", "nan"}, 2, "--t-collapse/--t-split"});
  for (const char* k : {"nan", "0", "-1"}) expectRefused({"render", {"--lod", "cluster", "--pixel-error", k}, 2, "--pixel-error"});
  expectRefused({"render", {"--morph-time", "0"}, 2, "--morph-time"});
  expectRefused({"render", {"--smoothing-alpha", "1"}, 2, "--smoothing-alpha"});
  expectRefused({"render", {"--depth-falloff", "nan"}, 2, "--depth-falloff"});
  expectRefused({"render", {"--foveation", "-1"}, 2, "--foveation"});
  expectRefused({"render", {"--focus", "1,2,3"}, 2, "--focus"});
  expectRefused({"render", {"--object-factor", "0"}, 2, "--object-factor"});
  expectRefused({"render", {"--fov", "nan"}, 2, "--fov"});
  expectRefused({"render", {"--fov", "180"}, 2, "--fov"});
  expectRefused({"render", {"--view", "nan,0,3"}, 2, "--view"});
  expectRefused({"render", {"--view", "0,0,-1"}, 2, "--view"});
  expectRefused({"render", {"--msaa", "0"}, 2, "--msaa"});
  expectRefused({"render", {"--line-width", "nan"}, 2, "--line-width"});
  expectRefused({"render", {"--chamfer-radius", "-1"}, 2, "--chamfer-radius"});
}

TEST_F(OptionFaults, FrameRangesFpsAndDuration) {
  for (const char* frames : {"5:2", "3:3", "0", "-1", "abc", "1:", ":4", "1:2:3", "99999999999999999999"})
    expectRefused({"capture", {"--frames", frames}, 2, "--frames"});
  for (const char* fps : {"0", "-30", "nan", "inf", "1e9", "thirty"}) expectRefused({"capture", {"--fps", fps}, 2, "--fps"});
  for (const char* duration : {"0", "-1", "nan", "inf", "1e300"})
    expectRefused({"capture", {"--duration", duration}, 2, "duration"});
}

TEST_F(OptionFaults, DetailMaps) {
  const std::string d = dir_.path().string();
  for (const char* cmd : {"render", "capture"}) {
    expectRefused({cmd, {"--detail-map", d + "/text.png"}, 1, d + "/text.png: cannot read PNG"});
    // 20000x20000: refused from the header (it used to cost 1.6 GB before failing).
    expectRefused({cmd, {"--detail-map", d + "/huge.png"}, 1, d + "/huge.png: PNG of 20000x20000 pixels is too large"});
    expectRefused({cmd, {"--detail-map", d + "/wide.png"}, 1, "too large"});
    expectRefused({cmd, {"--detail-map", d + "/missing.png"}, 1, d + "/missing.png: no such file"});
    expectRefused({cmd, {"--detail-map", d + "/fifo.png"}, 1, "not a regular file"});
    expectRefused({cmd, {"--detail-map", d + "/dir.png"}, 1, "is a directory"});
  }
  expectRefused({"render", {"--detail-map-scale", "nan"}, 2, "--detail-map-scale"});
}

TEST_F(OptionFaults, SimplifyBounds) {
  for (const char* e : {"-1%", "nan", "200%", "abc", ""}) expectRefused({"simplify", {"--max-error", e}, 2, "--max-error"});
}

}  // namespace
}  // namespace lodline
