// The `lodline` program as a user meets it: help, option errors, exit codes, outputs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>
#include <sys/wait.h>

#include "io/generate.h"
#include "io/image.h"
#include "io/load_mesh.h"
#include "test_util.h"

namespace lodline {
namespace {

struct CliRun {
  int code = -1;
  std::string output;  // stdout + stderr
};

CliRun lodline(const std::string& args) {
  CliRun r;
  r.code = test::runLodline(args, &r.output);
  return r;
}

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    // Progressive-mesh caches go to the test's directory, not the user's ~/.cache.
    setenv("XDG_CACHE_HOME", (dir_ / "cache").c_str(), 1);
    sphere_ = (dir_ / "sphere.off").string();
    ASSERT_TRUE(saveOff(sphere_, makeIcoSphere(1.0f, 3)).ok());
  }
  test::TempDir dir_;
  std::string sphere_;
};

TEST_F(Cli, HelpListsCommands) {
  CliRun r = lodline("--help");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.output.find("render"), std::string::npos);
  EXPECT_NE(r.output.find("view"), std::string::npos);
  CliRun rr = lodline("render --help");
  EXPECT_EQ(rr.code, 0);
  for (const char* opt : {"--size", "--view", "--fov", "--style", "--line-width", "--background",
                          "--stats", "--context", "--lines"})
    EXPECT_NE(rr.output.find(opt), std::string::npos) << opt;
  EXPECT_EQ(lodline("view --help").code, 0);
}

TEST_F(Cli, UsageErrorsExitWith2) {
  EXPECT_EQ(lodline("").code, 2);
  EXPECT_EQ(lodline("frobnicate").code, 2);
  EXPECT_EQ(lodline("render " + sphere_).code, 2);  // no -o
  const std::string out = (dir_ / "o.png").string();
  for (const char* bad : {"--size 12", "--size 100x0", "--view 1,2", "--fov 0", "--style watercolour",
                          "--background #12", "--lines contour,blobs", "--context vulkan",
                          "--no-such-option"}) {
    CliRun r = lodline("render " + sphere_ + " -o " + out + " " + bad);
    EXPECT_EQ(r.code, 2) << bad << ": " << r.output;
    EXPECT_FALSE(std::filesystem::exists(out)) << bad;
  }
  EXPECT_EQ(lodline("render " + sphere_ + " -o " + (dir_ / "o.jpg").string()).code, 2);
}

TEST_F(Cli, RuntimeErrorsExitWith1AndNameTheFile) {
  const std::string out = (dir_ / "o.png").string();
  CliRun missing = lodline("render /nonexistent/model.off -o " + out);
  EXPECT_EQ(missing.code, 1);
  EXPECT_NE(missing.output.find("/nonexistent/model.off"), std::string::npos) << missing.output;
  EXPECT_FALSE(std::filesystem::exists(out));

  std::ofstream(dir_ / "bad.off") << "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 9\n";
  CliRun bad = lodline("render " + (dir_ / "bad.off").string() + " -o " + out);
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.output.find("bad.off"), std::string::npos);
  EXPECT_NE(bad.output.find("out of range"), std::string::npos) << bad.output;
  EXPECT_FALSE(std::filesystem::exists(out));

  CliRun unwritable = lodline("render " + sphere_ + " -o /nonexistent-dir/o.png");
  EXPECT_EQ(unwritable.code, 1);
  EXPECT_NE(unwritable.output.find("/nonexistent-dir/o.png"), std::string::npos);
}

TEST_F(Cli, RenderWritesPngAndStats) {
  const std::string out = (dir_ / "s.png").string(), stats = (dir_ / "s.json").string();
  CliRun r = lodline("render " + sphere_ + " -o " + out + " --size 320x200 --full-detail --stats " + stats);
  ASSERT_EQ(r.code, 0) << r.output;
  auto img = readPng(out);
  ASSERT_TRUE(img.ok()) << img.error().message;
  EXPECT_EQ(img->width, 320);
  EXPECT_EQ(img->height, 200);
  std::ifstream in(stats);
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["model"]["faces"], 1280);
  EXPECT_EQ(j["model"]["vertices"], 642);
  EXPECT_EQ(j["image"]["width"], 320);
  EXPECT_EQ(j["faces_drawn"], 1280);
  EXPECT_GT(j["line_segments"].get<int>(), 10);
  for (const char* k : {"load", "setup", "render", "readback", "total"})
    EXPECT_GE(j["ms"][k].get<double>(), 0.0) << k;
  // Only the two outputs are in the directory (plus the model): no temporary files.
  std::vector<std::string> files;
  for (auto& e : std::filesystem::directory_iterator(dir_.path()))
    if (e.path().filename() != "cache") files.push_back(e.path().filename());  // Mesa's shader cache
  std::sort(files.begin(), files.end());
  EXPECT_EQ(files, (std::vector<std::string>{"s.json", "s.png", "sphere.off"}));
  EXPECT_FALSE(j.contains("lod"));
}

// Fraction of the dark pixels of `a` that have a dark pixel of `b` within `r` pixels.
double coveredFraction(const Image& a, const Image& b, int r) {
  // "Inked": clearly darker than the white page (thin antialiased lines stay light grey).
  auto dark = [](const Image& im, int x, int y) { return im.pixel(x, y)[0] < 200; };
  size_t total = 0, covered = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      if (!dark(a, x, y)) continue;
      ++total;
      bool found = false;
      for (int yy = std::max(0, y - r); yy <= std::min(b.height - 1, y + r) && !found; ++yy)
        for (int xx = std::max(0, x - r); xx <= std::min(b.width - 1, x + r) && !found; ++xx)
          found = dark(b, xx, yy);
      covered += found;
    }
  return total ? static_cast<double>(covered) / static_cast<double>(total) : 0.0;
}

// The SVG holds exactly the visible strokes the PNG draws (one visibility for both):
// rasterised by a real SVG renderer (librsvg's rsvg-convert) it matches the OpenGL render of
// the same lines, line pixels within 1 px of each other.
void checkSvgAgainstGl(const std::filesystem::path& dir, const std::string& model, const std::string& view) {
  if (std::system("command -v rsvg-convert >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "rsvg-convert not installed (scripts/setup.sh installs librsvg2-bin)";
  const std::string png = (dir / "gl.png").string(), svg = (dir / "v.svg").string(),
                    raster = (dir / "svg.png").string();
  CliRun r = lodline("render " + model + " -o " + png + " --svg " + svg + " --size 400x300 --style lines " +
                     "--msaa 1 " + view);
  ASSERT_EQ(r.code, 0) << r.output;
  ASSERT_EQ(std::system(("rsvg-convert " + svg + " -o " + raster).c_str()), 0);
  auto gl = readPng(png);
  auto sv = readPng(raster);
  ASSERT_TRUE(gl.ok() && sv.ok());
  ASSERT_EQ(sv->width, 400);
  ASSERT_EQ(sv->height, 300);
  // Compositing the RGBA SVG raster over white is unnecessary: the page has a white rect.
  const double svg_in_png = coveredFraction(*sv, *gl, 1), png_in_svg = coveredFraction(*gl, *sv, 1);
  std::printf("%s: SVG line pixels near PNG lines %.4f, PNG near SVG %.4f\n", model.c_str(), svg_in_png, png_in_svg);
  EXPECT_GT(svg_in_png, 0.98) << "SVG lines without a GL line nearby";
  EXPECT_GT(png_in_svg, 0.98) << "GL lines missing from the SVG";
}

TEST_F(Cli, SvgMatchesGlRenderSphereScene) {
  checkSvgAgainstGl(dir_.path(), sphere_, "--view 30,20,3");
}

TEST_F(Cli, SvgMatchesGlRenderArmadillo) {
  const auto p = test::dataMesh("armadillo.off");
  if (p.empty()) GTEST_SKIP() << "data/meshes/armadillo.off missing (run scripts/setup.sh)";
  checkSvgAgainstGl(dir_.path(), p.string(), "--view 200,10,2.9");
}

TEST_F(Cli, SvgMatchesGlRenderCowCloseUp) {  // a coarse mesh: the completed outline too
  const auto p = test::dataMesh("cow.off");
  if (p.empty()) GTEST_SKIP() << "data/meshes/cow.off missing (run scripts/setup.sh)";
  checkSvgAgainstGl(dir_.path(), p.string(), "--view 60,20,1.6");
}

TEST_F(Cli, ViewWithoutDisplayIsAClearError) {
  CliRun r = lodline("view " + sphere_ + " --full-detail");  // tests run with DISPLAY unset
  if (std::getenv("DISPLAY")) GTEST_SKIP() << "a display is available";
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_TRUE(r.output.find("window") != std::string::npos || r.output.find("viewer") != std::string::npos)
      << r.output;
}

TEST_F(Cli, PerKindLineStyle) {
  const std::string out = (dir_ / "red.png").string();
  CliRun r = lodline("render " + sphere_ + " -o " + out + " --size 160x120 --style lines --full-detail " +
                     "--line-style contour=#ff0000:3");
  ASSERT_EQ(r.code, 0) << r.output;
  auto img = readPng(out);
  ASSERT_TRUE(img.ok());
  int red = 0, black = 0;
  for (int y = 0; y < img->height; ++y)
    for (int x = 0; x < img->width; ++x) {
      const uint8_t* p = img->pixel(x, y);
      red += p[0] > 200 && p[1] < 80 && p[2] < 80;
      black += p[0] < 60 && p[1] < 60 && p[2] < 60;
    }
  EXPECT_GT(red, 100);
  EXPECT_EQ(black, 0);  // the contour is the only line kind on a sphere
  EXPECT_EQ(lodline("render " + sphere_ + " -o " + out + " --line-style blob=#fff").code, 2);
  EXPECT_EQ(lodline("render " + sphere_ + " -o " + out + " --line-style contour=#fff:0").code, 2);
  const CliRun bad = lodline("render " + sphere_ + " -o " + out + " --suggestive-at-creases sometimes");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.output.find("--suggestive-at-creases"), std::string::npos) << bad.output;
  EXPECT_EQ(lodline("render " + sphere_ + " -o " + out + " --suggestive-at-creases on").code, 0);
  const CliRun bad_fit = lodline("render " + sphere_ + " -o " + out + " --lines ridge --ridge-estimator guess");
  EXPECT_EQ(bad_fit.code, 2);
  EXPECT_NE(bad_fit.output.find("--ridge-estimator"), std::string::npos) << bad_fit.output;
  EXPECT_EQ(lodline("render " + sphere_ + " -o " + out + " --lines contour,ridge,valley --ridge-estimator fit").code, 0);
}

TEST_F(Cli, ContextChoiceOsMesa) {
  const std::string out = (dir_ / "m.png").string(), stats = (dir_ / "m.json").string();
  CliRun r = lodline("render " + sphere_ + " -o " + out + " --size 64x64 --context osmesa --stats " + stats);
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(stats);
  EXPECT_EQ(nlohmann::json::parse(in)["context"]["backend"], "osmesa");
}

TEST_F(Cli, GenerateWritesLoadableMesh) {
  const std::string out = (dir_ / "knot.off").string();
  CliRun r = lodline("generate knot -o " + out + " --resolution 120");
  ASSERT_EQ(r.code, 0) << r.output;
  auto m = loadMesh(out);
  ASSERT_TRUE(m.ok()) << m.error().message;
  EXPECT_GT(m->faceCount(), 1000u);
  EXPECT_EQ(lodline("generate teapot -o " + out).code, 2);
  EXPECT_EQ(lodline("generate sphere --resolution 30 -o " + out).code, 2);
}

// --backend soft: the software rasteriser (docs/softraster.md) needs no OpenGL at all. With
// libglvnd pointed at no EGL vendor, GL rendering fails but the soft backend still works.
TEST_F(Cli, SoftBackendRendersWithoutOpenGl) {
  const std::string out = (dir_ / "soft.png").string(), stats = (dir_ / "soft.json").string();
  const std::string no_egl = "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json ";
  auto run = [&](const std::string& args) {
    CliRun r;
    FILE* pipe = popen((no_egl + LODLINE_BINARY + " " + args + " 2>&1").c_str(), "r");
    if (!pipe) return r;
    char buf[4096];
    size_t n;
    while ((n = fread(buf, 1, sizeof(buf), pipe)) > 0) r.output.append(buf, n);
    const int status = pclose(pipe);
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    return r;
  };
  EXPECT_EQ(run("render " + sphere_ + " -o " + out + " --context egl").code, 1);
  CliRun r = run("render " + sphere_ + " -o " + out + " --size 320x200 --backend soft --stats " + stats);
  ASSERT_EQ(r.code, 0) << r.output;
  auto img = readPng(out);
  ASSERT_TRUE(img.ok()) << img.error().message;
  EXPECT_EQ(img->width, 320);
  EXPECT_EQ(img->height, 200);
  // Toon-shaded sphere in the middle, white page in the corner.
  EXPECT_LT(img->pixel(160, 100)[2], 250);
  EXPECT_EQ(img->pixel(0, 0)[0], 255);
  std::ifstream in(stats);
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["context"]["backend"], "soft");
  EXPECT_GT(j["faces_drawn"].get<int>(), 100);
  EXPECT_GT(j["line_segments"].get<int>(), 10);
  EXPECT_EQ(lodline("render " + sphere_ + " -o " + out + " --backend vulkan").code, 2);
  EXPECT_NE(lodline("render --help").output.find("--backend"), std::string::npos);
}

// --backend soft draws the lines and toon styles; what it cannot draw (the shaded style,
// chamfer highlights) is refused with a one-line usage error, never drawn as something else.
TEST_F(Cli, SoftBackendRefusesWhatItCannotDraw) {
  const std::string out = (dir_ / "soft.png").string();
  for (const std::string opts : {"--style shaded", "--chamfer on"}) {
    CliRun r = lodline("render " + sphere_ + " -o " + out + " --backend soft " + opts);
    EXPECT_EQ(r.code, 2) << opts << ": " << r.output;
    EXPECT_NE(r.output.find("--backend soft"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("OpenGL (use --backend gl)"), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << "one line: " << r.output;
    EXPECT_FALSE(std::filesystem::exists(out));
  }
  EXPECT_EQ(lodline("render " + sphere_ + " -o " + out + " --backend soft --style lines").code, 0);
  EXPECT_EQ(lodline("render " + sphere_ + " -o " + out + " --backend soft --style toon").code, 0);
}

// The SVG written with --backend soft (visibility from the software depth buffer) matches
// the OpenGL render of the same lines (GL depth test).
void checkSoftSvgAgainstGl(const std::filesystem::path& dir, const std::string& model, const std::string& view) {
  if (std::system("command -v rsvg-convert >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "rsvg-convert not installed (scripts/setup.sh installs librsvg2-bin)";
  const std::string png = (dir / "gl.png").string(), svg = (dir / "soft.svg").string(),
                    raster = (dir / "soft-svg.png").string();
  const std::string common = " --size 400x300 --style lines --msaa 1 " + view;
  CliRun g = lodline("render " + model + " -o " + png + common);
  ASSERT_EQ(g.code, 0) << g.output;
  CliRun r = lodline("render " + model + " --svg " + svg + " --backend soft" + common);
  ASSERT_EQ(r.code, 0) << r.output;
  ASSERT_EQ(std::system(("rsvg-convert " + svg + " -o " + raster).c_str()), 0);
  auto gl = readPng(png);
  auto sv = readPng(raster);
  ASSERT_TRUE(gl.ok() && sv.ok());
  EXPECT_GT(coveredFraction(*sv, *gl, 2), 0.95) << "soft-SVG lines without a GL line nearby";
  EXPECT_GT(coveredFraction(*gl, *sv, 2), 0.95) << "GL lines missing from the soft SVG";
}

TEST_F(Cli, SoftSvgMatchesGlRenderSphereScene) {
  checkSoftSvgAgainstGl(dir_.path(), sphere_, "--view 30,20,3");
}

TEST_F(Cli, SoftSvgMatchesGlRenderArmadillo) {
  const auto p = test::dataMesh("armadillo.off");
  if (p.empty()) GTEST_SKIP() << "data/meshes/armadillo.off missing (run scripts/setup.sh)";
  checkSoftSvgAgainstGl(dir_.path(), p.string(), "--view 200,10,2.9");
}

}  // namespace
}  // namespace lodline
