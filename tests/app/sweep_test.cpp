// `lodline sweep`: plans (cross product, --zip), up-front checks of keys and values, real
// sweeps through the built binary (outputs, resuming, --force, failures, --jobs, Ctrl-C).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "io/generate.h"
#include "io/image.h"
#include "io/load_mesh.h"
#include "test_util.h"

extern char** environ;

namespace lodline {
namespace {

namespace fs = std::filesystem;

struct CliRun {
  int code = -1;
  std::string output;  // stdout + stderr
};

std::string readAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

// results.csv as rows of fields (no quoted commas in these tests except where checked).
std::vector<std::map<std::string, std::string>> readCsv(const fs::path& p) {
  const auto rows = lines(readAll(p));
  std::vector<std::map<std::string, std::string>> out;
  if (rows.empty()) return out;
  auto split = [](const std::string& s) {
    std::vector<std::string> f;
    std::string cur;
    bool quoted = false;
    for (char c : s) {
      if (c == '"') quoted = !quoted;
      else if (c == ',' && !quoted) f.push_back(std::exchange(cur, {}));
      else cur += c;
    }
    f.push_back(cur);
    return f;
  };
  const auto header = split(rows[0]);
  for (size_t r = 1; r < rows.size(); ++r) {
    const auto f = split(rows[r]);
    std::map<std::string, std::string> row;
    for (size_t i = 0; i < header.size() && i < f.size(); ++i) row[header[i]] = f[i];
    out.push_back(row);
  }
  return out;
}

std::vector<std::string> filesIn(const fs::path& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

// No temporary files of atomic writes (".NAME.tmpPID-...") and no PNG without its JSON.
void expectNoLeftovers(const fs::path& runs) {
  for (const auto& f : filesIn(runs)) {
    EXPECT_NE(f[0], '.') << "temporary file left: " << f;
    if (f.ends_with(".png")) {
      EXPECT_TRUE(fs::exists(runs / (f.substr(0, f.size() - 4) + ".json"))) << "PNG without JSON: " << f;
    }
  }
}

class Sweep : public ::testing::Test {
 protected:
  void SetUp() override {
    setenv("XDG_CACHE_HOME", (dir_ / "cache").c_str(), 1);
    model_ = (dir_ / "knot.off").string();
    ASSERT_TRUE(saveOff(model_, makeTorusKnot(2, 3, 1.0f, 0.2f, 160, 12, 0.1f)).ok());
  }
  // `lodline sweep MODEL ARGS` with small, quick renders.
  CliRun sweep(const std::string& args, const std::string& model = {}) {
    CliRun r;
    r.code = test::runLodline("sweep " + (model.empty() ? model_ : model) + " --set size=96x64 --set msaa=1 " + args,
                              &r.output);
    return r;
  }
  test::TempDir dir_;
  std::string model_;
};

TEST_F(Sweep, HelpDescribesTheCommand) {
  CliRun r;
  r.code = test::runLodline("sweep --help", &r.output);
  EXPECT_EQ(r.code, 0);
  for (const char* opt : {"--vary", "--zip", "--set", "--jobs", "--force", "--chart", "--dry-run", "view.dist"})
    EXPECT_NE(r.output.find(opt), std::string::npos) << opt;
  CliRun all;
  all.code = test::runLodline("--help", &all.output);
  EXPECT_NE(all.output.find("sweep"), std::string::npos);
}

TEST_F(Sweep, CrossProductPlanFirstAxisSlowest) {
  const auto out = dir_ / "plan";
  CliRun r = sweep("--vary target-area=4,8,16 --vary view.dist=3,6 -o " + out.string() + " --dry-run");
  ASSERT_EQ(r.code, 0) << r.output;
  const auto l = lines(r.output);
  ASSERT_EQ(l.size(), 7u) << r.output;
  const char* names[] = {"target-area-4_view.dist-3",  "target-area-4_view.dist-6",  "target-area-8_view.dist-3",
                         "target-area-8_view.dist-6",  "target-area-16_view.dist-3", "target-area-16_view.dist-6"};
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(l[i].rfind(std::string(names[i]) + "  pending  lodline render ", 0), 0u) << l[i];
    // Fixed options first, then the varied ones; view.dist replaces the distance of the
    // default 3/4 view (35, 20).
    EXPECT_NE(l[i].find("--size=96x64 --msaa=1"), std::string::npos) << l[i];
    const std::string t = std::string("--target-area=") + (i < 2 ? "4" : i < 4 ? "8" : "16");
    EXPECT_NE(l[i].find(t), std::string::npos) << l[i];
    EXPECT_NE(l[i].find(std::string("--view=35,20,") + (i % 2 ? "6" : "3")), std::string::npos) << l[i];
  }
  EXPECT_EQ(l[6], "sweep: 6 runs: 6 to render, 0 complete");
  EXPECT_FALSE(fs::exists(out)) << "a dry run writes nothing";
}

TEST_F(Sweep, ZipPlanPairsTheLists) {
  const auto out = (dir_ / "zip").string();
  CliRun r = sweep("--zip --vary target-area=4,8,16 --vary view.az=0,90,180 --set view=10,30,5 -o " + out +
                   " --dry-run");
  ASSERT_EQ(r.code, 0) << r.output;
  const auto l = lines(r.output);
  ASSERT_EQ(l.size(), 4u) << r.output;
  EXPECT_NE(l[0].find("--target-area=4 --view=0,30,5"), std::string::npos) << l[0];
  EXPECT_NE(l[1].find("--target-area=8 --view=90,30,5"), std::string::npos) << l[1];
  EXPECT_NE(l[2].find("--target-area=16 --view=180,30,5"), std::string::npos) << l[2];
  EXPECT_EQ(l[3], "sweep: 3 runs: 3 to render, 0 complete");
  // Unequal lengths cannot be paired.
  CliRun bad = sweep("--zip --vary target-area=4,8 --vary view.az=0,90,180 -o " + out);
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.output.find("same length"), std::string::npos) << bad.output;
}

TEST_F(Sweep, ModelsCanBeAnAxis) {
  const std::string sphere = (dir_ / "sphere.off").string();
  ASSERT_TRUE(saveOff(sphere, makeIcoSphere(1.0f, 4)).ok());
  const fs::path out = dir_ / "models";
  CliRun r;
  r.code = test::runLodline("sweep --vary model=" + model_ + "," + sphere +
                                " --vary target-area=8,32 --set size=96x64 --set msaa=1 -o " + out.string(),
                            &r.output);
  ASSERT_EQ(r.code, 0) << r.output;
  const auto rows = readCsv(out / "results.csv");
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0].at("model"), model_);
  EXPECT_EQ(rows[2].at("model"), sphere);
  EXPECT_EQ(rows[0].at("run").rfind("model-knot-", 0), 0u) << rows[0].at("run");
  EXPECT_EQ(rows[2].at("faces"), "5120");  // the level-4 icosphere
  EXPECT_NE(rows[0].at("faces"), rows[2].at("faces"));
  EXPECT_TRUE(fs::exists(out / "sheet.png"));
  // MODEL and --vary model exclude each other; one of them is needed.
  CliRun both;
  both.code = test::runLodline("sweep " + model_ + " --vary model=" + sphere + " -o " + out.string(), &both.output);
  EXPECT_EQ(both.code, 2) << both.output;
  CliRun none;
  none.code = test::runLodline("sweep --vary target-area=8 -o " + out.string(), &none.output);
  EXPECT_EQ(none.code, 2) << none.output;
  EXPECT_NE(none.output.find("MODEL"), std::string::npos) << none.output;
}

TEST_F(Sweep, RenderOptionsGivenDirectlyReachEveryRun) {
  // `sweep MODEL --size 320x240 ...` was refused ("not expected: --size"); render's drawing
  // options are the sweep's too, and reach every run as if they followed --.
  CliRun r = sweep("--vary target-area=8,16 --fov 40 --style lines --geomorphs off -o " + (dir_ / "direct").string() +
                   " --dry-run");
  ASSERT_EQ(r.code, 0) << r.output;
  const auto l = lines(r.output);
  ASSERT_EQ(l.size(), 3u);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_NE(l[i].find("--fov=40"), std::string::npos) << l[i];
    EXPECT_NE(l[i].find("--style=lines"), std::string::npos) << l[i];
    EXPECT_NE(l[i].find("--geomorphs=off"), std::string::npos) << l[i];
  }
  // Varied and given directly: refused, as after --.
  CliRun both = sweep("--vary fov=30,50 --fov 40 -o " + (dir_ / "both").string() + " --dry-run");
  EXPECT_EQ(both.code, 2) << both.output;
  EXPECT_NE(both.output.find("also varied"), std::string::npos) << both.output;
}

TEST_F(Sweep, RenderOptionsAfterDoubleDashAndFramingDistance) {
  // Options after -- reach every run; with only the azimuth varied, the distance is the one
  // render's default view frames the model with (35° fov, 96x64: ~3.6 radii).
  CliRun r = sweep("--vary view.az=0,90 -o " + (dir_ / "dd").string() + " --dry-run -- --style lines --fov 35");
  ASSERT_EQ(r.code, 0) << r.output;
  const auto l = lines(r.output);
  ASSERT_EQ(l.size(), 3u);
  EXPECT_NE(l[0].find("--style lines --fov 35 --view=0,20,3.59"), std::string::npos) << l[0];
  // Paths become safe, stable names (the file stem plus a hash of the exact value); an empty
  // value passes no option (render's default, here: no detail map).
  Image map(4, 4);
  std::fill(map.rgba.begin(), map.rgba.end(), uint8_t{255});
  ASSERT_TRUE(writePng(dir_ / "map.png", map).ok());
  CliRun p = sweep("--vary detail-map=," + (dir_ / "map.png").string() + " -o " + (dir_ / "dm").string() + " --dry-run");
  ASSERT_EQ(p.code, 0) << p.output;
  const auto pl = lines(p.output);
  ASSERT_EQ(pl.size(), 3u);
  EXPECT_EQ(pl[0].rfind("detail-map-  pending", 0), 0u) << pl[0];
  EXPECT_EQ(pl[0].find("--detail-map"), std::string::npos) << pl[0];
  const std::string name = pl[1].substr(0, pl[1].find(' '));
  EXPECT_EQ(name.rfind("detail-map-map-", 0), 0u) << name;
  EXPECT_EQ(name.size(), std::string("detail-map-map-").size() + 8) << name;
  EXPECT_NE(pl[1].find("--detail-map=" + (dir_ / "map.png").string()), std::string::npos) << pl[1];
}

TEST_F(Sweep, BadKeysAndValuesFailBeforeAnythingRenders) {
  const std::string out = (dir_ / "bad").string();
  struct Case {
    std::string args, expect;
  };
  const std::vector<Case> cases = {
      {"--vary target-aera=4,8", "--vary target-aera"},
      {"--vary target-area=4,-8", "--vary target-area=-8"},
      {"--vary target-area=4,abc", "--vary target-area=abc"},
      {"--vary style=lines,watercolour", "--vary style=watercolour"},
      {"--vary view.dist=3,far", "--vary view.dist=far"},
      {"--vary view.el=10,95", "--vary view.el=95"},
      {"--vary output=a.png", "--vary output"},
      {"--vary target-area=4,4", "given twice"},
      {"--vary target-area=4 --vary target-area=8", "given twice"},
      {"--vary 'view=0,20,3;90,20,3' --vary view.az=0,90", "--vary view"},
      {"--vary target-area=4 --set target-area=8", "--set target-area"},
      {"--vary target-area=4 --set no-such=1", "--set no-such"},
      {"--vary target-area=4 --set style=watercolour", "--style"},
      {"--vary target-area=4 -- --target-area 8", "--target-area"},
      {"--vary target-area=4 -- --no-such-option", "--no-such-option"},
      {"--vary target-area=4 -- -o x.png", "-o"},
      {"--vary t-collapse=0.7,0.8", "--vary t-collapse=0.8"},
      {"--vary target-area=4 --chart nonsense", "--chart nonsense"},
      {"--vary target-area=4 --caption nonsense", "--caption nonsense"},
      {"--vary target-area", "--vary"},
      {"", "--vary"},
      {"--vary target-area=4 --jobs 0", "--jobs"},
  };
  for (const auto& c : cases) {
    CliRun r = sweep("-o " + out + " " + c.args);
    EXPECT_EQ(r.code, 2) << c.args << ": " << r.output;
    EXPECT_NE(r.output.find(c.expect), std::string::npos) << c.args << ": " << r.output;
    EXPECT_EQ(lines(r.output).size(), 1u) << "one line: " << r.output;
    EXPECT_FALSE(fs::exists(out)) << c.args;
  }
  // A missing detail map is found before any rendering too (runtime error: a missing file).
  CliRun map = sweep("--vary detail-map=/nonexistent/map.png -o " + out);
  EXPECT_EQ(map.code, 1) << map.output;
  EXPECT_NE(map.output.find("/nonexistent/map.png"), std::string::npos) << map.output;
  CliRun model = sweep("--vary target-area=4 -o " + out, "/nonexistent/model.off");
  EXPECT_EQ(model.code, 1) << model.output;
  EXPECT_NE(model.output.find("/nonexistent/model.off"), std::string::npos) << model.output;
  CliRun font = sweep("--vary target-area=4 --font /nonexistent/font.ttf -o " + out);
  EXPECT_EQ(font.code, 1) << font.output;
  EXPECT_NE(font.output.find("fonts-dejavu-core"), std::string::npos) << font.output;
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(Sweep, WritesRunsCsvAndSheetThenSkipsWhatIsDone) {
  const fs::path out = dir_ / "s";
  const std::string vary = "--vary target-area=4,32 --vary view.dist=3,6 --chart active_faces -o " + out.string();
  CliRun first = sweep(vary);
  ASSERT_EQ(first.code, 0) << first.output;
  EXPECT_NE(first.output.find("4 rendered, 0 skipped"), std::string::npos) << first.output;
  const std::vector<std::string> names = {"target-area-4_view.dist-3", "target-area-4_view.dist-6",
                                          "target-area-32_view.dist-3", "target-area-32_view.dist-6"};
  std::map<std::string, fs::file_time_type> mtimes;
  for (const auto& n : names) {
    for (const char* ext : {".png", ".json"}) {
      ASSERT_TRUE(fs::exists(out / "runs" / (n + ext))) << n << ext;
      mtimes[n + ext] = fs::last_write_time(out / "runs" / (n + ext));
    }
    auto img = readPng(out / "runs" / (n + ".png"));
    ASSERT_TRUE(img.ok());
    EXPECT_EQ(img->width, 96);
  }
  expectNoLeftovers(out / "runs");
  EXPECT_EQ(filesIn(out), (std::vector<std::string>{"chart_active_faces.svg", "results.csv", "runs", "sheet.png",
                                                     "sweep.json"}));
  const auto rows = readCsv(out / "results.csv");
  ASSERT_EQ(rows.size(), 4u);
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(rows[i].at("run"), names[i]);
    EXPECT_EQ(rows[i].at("status"), "ok");
    EXPECT_EQ(rows[i].at("target-area"), i < 2 ? "4" : "32");
    EXPECT_EQ(rows[i].at("view.dist"), i % 2 ? "6" : "3");
    for (const char* col : {"faces", "active_faces", "visible_faces", "band_fraction", "band_or_limit_fraction",
                            "strokes", "specks", "line_pixels", "ms_adapt", "ms_render", "ms_total"})
      EXPECT_FALSE(rows[i].at(col).empty()) << col;
    EXPECT_GE(std::stod(rows[i].at("band_or_limit_fraction")), std::stod(rows[i].at("band_fraction")));
    EXPECT_GT(std::stoi(rows[i].at("line_pixels")), 50);
    EXPECT_EQ(std::stod(rows[i].at("target_area")), i < 2 ? 4.0 : 32.0);
  }
  // Coarser with larger T and with distance.
  EXPECT_GT(std::stoi(rows[0].at("active_faces")), std::stoi(rows[2].at("active_faces")));
  EXPECT_GT(std::stoi(rows[0].at("active_faces")), std::stoi(rows[1].at("active_faces")));
  // The sheet: a 2x2 grid of 96-px cells plus labels.
  auto sheet = readPng(out / "sheet.png");
  ASSERT_TRUE(sheet.ok());
  EXPECT_GT(sheet->width, 2 * 96);
  EXPECT_GT(sheet->height, 2 * 64);
  const std::string svg = readAll(out / "chart_active_faces.svg");
  size_t points = 0;
  for (size_t p = svg.find("<circle class=\"point\""); p != std::string::npos; p = svg.find("<circle class=\"point\"", p + 1))
    ++points;
  EXPECT_EQ(points, 4u);
  const std::string csv = readAll(out / "results.csv");

  // Rerun: every run is complete, nothing is rendered, the summaries are the same.
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  CliRun again = sweep(vary);
  ASSERT_EQ(again.code, 0) << again.output;
  EXPECT_NE(again.output.find("0 rendered, 4 skipped"), std::string::npos) << again.output;
  for (const auto& [file, t] : mtimes) EXPECT_EQ(fs::last_write_time(out / "runs" / file), t) << file;
  EXPECT_EQ(readAll(out / "results.csv"), csv);

  // A longer list renders only the new runs.
  CliRun more = sweep("--vary target-area=4,32,64 --vary view.dist=3,6 -o " + out.string());
  ASSERT_EQ(more.code, 0) << more.output;
  EXPECT_NE(more.output.find("2 rendered, 4 skipped"), std::string::npos) << more.output;
  EXPECT_EQ(readCsv(out / "results.csv").size(), 6u);

  // --force renders everything again.
  CliRun force = sweep(vary + " --force");
  ASSERT_EQ(force.code, 0) << force.output;
  EXPECT_NE(force.output.find("4 rendered, 0 skipped"), std::string::npos) << force.output;
  for (const auto& [file, t] : mtimes) EXPECT_NE(fs::last_write_time(out / "runs" / file), t) << file;

  // Other fixed options into the same directory would mix two sweeps: refused.
  CliRun other = sweep("--vary target-area=4,32 --vary view.dist=3,6 --set style=lines -o " + out.string());
  EXPECT_EQ(other.code, 2) << other.output;
  EXPECT_NE(other.output.find("sweep.json"), std::string::npos) << other.output;
  // Also when the fixed part is a view component (folded into each run's --view).
  CliRun view = sweep("--vary target-area=4,32 --vary view.dist=3,6 --set view.el=40 -o " + out.string());
  EXPECT_EQ(view.code, 2) << view.output;
  // A manifest that is not one is not overwritten silently.
  std::ofstream(out / "sweep.json") << "{\"model\": 3}";
  CliRun bad = sweep(vary);
  EXPECT_EQ(bad.code, 2) << bad.output;
  EXPECT_NE(bad.output.find("not a sweep manifest"), std::string::npos) << bad.output;
}

TEST_F(Sweep, HeldOutMeshFourTargetsByThreeDistances) {
  const auto mesh = test::dataMesh("elk.off");
  if (mesh.empty()) GTEST_SKIP() << "data/meshes/elk.off missing (run scripts/setup.sh)";
  const fs::path out = dir_ / "elk";
  const std::string args = "--vary target-area=4,8,16,32 --vary view.dist=2.5,5,10 -o " + out.string();
  CliRun r = sweep(args, mesh.string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("sweep: 12 runs: 12 rendered, 0 skipped"), std::string::npos) << r.output;
  size_t pngs = 0, jsons = 0;
  for (const auto& f : filesIn(out / "runs")) {
    pngs += f.ends_with(".png");
    jsons += f.ends_with(".json");
  }
  EXPECT_EQ(pngs, 12u);
  EXPECT_EQ(jsons, 12u);
  const auto rows = readCsv(out / "results.csv");
  ASSERT_EQ(rows.size(), 12u);
  for (const auto& row : rows) EXPECT_EQ(row.at("status"), "ok") << row.at("run");
  // Active faces fall as T grows, at every distance, down to the base mesh (the fewest any
  // run draws: at 96x64 and 10 radii the elk is a few pixels), which only the farthest reaches.
  auto faces = [&](int t, int d) { return std::stoi(rows[t * 3 + d].at("active_faces")); };
  int base = faces(0, 0);
  for (int i = 0; i < 12; ++i) base = std::min(base, faces(i / 3, i % 3));
  for (int d = 0; d < 3; ++d)
    for (int t = 1; t < 4; ++t) {
      if (faces(t - 1, d) == base) EXPECT_EQ(faces(t, d), base) << rows[t * 3 + d].at("run");
      else EXPECT_LT(faces(t, d), faces(t - 1, d)) << rows[t * 3 + d].at("run");
    }
  for (int t = 0; t < 4; ++t) EXPECT_GT(faces(t, 1), base) << rows[t * 3 + 1].at("run");
  auto sheet = readPng(out / "sheet.png");
  ASSERT_TRUE(sheet.ok());
  EXPECT_GT(sheet->width, 3 * 96);
  EXPECT_GT(sheet->height, 4 * 64);
  expectNoLeftovers(out / "runs");

  CliRun again = sweep(args, mesh.string());
  ASSERT_EQ(again.code, 0) << again.output;
  EXPECT_NE(again.output.find("sweep: 12 runs: 0 rendered, 12 skipped"), std::string::npos) << again.output;
}

TEST_F(Sweep, FailedRunIsRecordedAndTheOthersGoOn) {
  const fs::path out = dir_ / "f";
  // A directory where one run's PNG goes: that render fails (its output is unwritable).
  fs::create_directories(out / "runs" / "target-area-8_view.dist-3.png" / "blocker");
  const std::string args = "--vary target-area=4,8 --vary view.dist=3,6 -o " + out.string();
  CliRun r = sweep(args);
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("lodline: sweep: run target-area-8_view.dist-3 failed: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("is a directory"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("3 rendered, 0 skipped (complete from before), 1 failed"), std::string::npos) << r.output;
  const auto rows = readCsv(out / "results.csv");
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[2].at("status"), "failed");
  EXPECT_NE(rows[2].at("error").find("is a directory"), std::string::npos) << rows[2].at("error");
  EXPECT_TRUE(rows[2].at("active_faces").empty());
  for (int i : {0, 1, 3}) EXPECT_EQ(rows[i].at("status"), "ok");
  EXPECT_TRUE(fs::exists(out / "sheet.png"));
  EXPECT_FALSE(fs::exists(out / "runs" / "target-area-8_view.dist-3.json"));
  // Next time the failed run is tried again (and only it).
  fs::remove_all(out / "runs" / "target-area-8_view.dist-3.png");
  CliRun again = sweep(args);
  EXPECT_EQ(again.code, 0) << again.output;
  EXPECT_NE(again.output.find("1 rendered, 3 skipped"), std::string::npos) << again.output;
}

TEST_F(Sweep, ParallelJobsGiveTheSameImages) {
  const fs::path a = dir_ / "j1", b = dir_ / "j2";
  const std::string vary = "--vary target-area=8,32 --vary view.az=0,120 --vary lod=pm,none";
  CliRun one = sweep(vary + " -o " + a.string());
  ASSERT_EQ(one.code, 0) << one.output;
  CliRun two = sweep(vary + " --jobs 3 --chart active_faces -o " + b.string());
  ASSERT_EQ(two.code, 0) << two.output;
  EXPECT_NE(two.output.find("8 rendered"), std::string::npos) << two.output;
  const auto files = filesIn(a / "runs");
  ASSERT_EQ(files.size(), 16u);
  EXPECT_EQ(filesIn(b / "runs"), files);
  for (const auto& f : files)
    if (f.ends_with(".png")) {
      EXPECT_TRUE(readAll(a / "runs" / f) == readAll(b / "runs" / f)) << f;
    }
  // A third axis makes one sheet per value.
  EXPECT_TRUE(fs::exists(b / "sheet_lod-pm.png"));
  EXPECT_TRUE(fs::exists(b / "sheet_lod-none.png"));
  EXPECT_FALSE(fs::exists(b / "sheet.png"));
  // The chart: active faces against T, one line per (view.az, lod) pair.
  const std::string svg = readAll(b / "chart_active_faces.svg");
  size_t points = 0, lines = 0;
  for (size_t p = svg.find("<circle class=\"point\""); p != std::string::npos; p = svg.find("<circle class=\"point\"", p + 1))
    ++points;
  for (size_t p = svg.find("<g class=\"series\""); p != std::string::npos; p = svg.find("<g class=\"series\"", p + 1))
    ++lines;
  EXPECT_EQ(points, 8u);
  EXPECT_EQ(lines, 4u);
  EXPECT_NE(svg.find("view.az = 120, lod = none"), std::string::npos);
}

// A sweep rendered elsewhere: --emit-commands prints one command per pending run, GNU
// parallel runs them two at a time (from another directory), and --collect builds the same
// results.csv (timing columns aside) and sheet as the sweep run by lodline itself.
TEST_F(Sweep, EmitCommandsThroughParallelThenCollectEqualsTheSweep) {
  if (test::runCommand("command -v parallel") != 0) GTEST_SKIP() << "GNU parallel is not installed (apt install parallel)";
  const fs::path self = dir_ / "self", shard = dir_ / "shard";
  const std::string vary = "--vary target-area=8,16,32,64 --vary view.az=0,60,120 --vary lod=pm,none";  // 24 runs
  CliRun one = sweep(vary + " -o " + self.string());
  ASSERT_EQ(one.code, 0) << one.output;
  CliRun emitted = sweep(vary + " --emit-commands -o " + shard.string());
  ASSERT_EQ(emitted.code, 0) << emitted.output;
  const auto commands = lines(emitted.output);
  ASSERT_EQ(commands.size(), 24u) << emitted.output;
  for (const auto& c : commands) EXPECT_EQ(c.rfind("cd ", 0), 0u) << c;
  std::ofstream(dir_ / "commands.txt") << emitted.output;
  // Collecting before anything rendered says what is missing.
  CliRun early = sweep(vary + " --collect -o " + shard.string());
  EXPECT_EQ(early.code, 1) << early.output;
  EXPECT_NE(early.output.find("24 run(s) have no PNG and JSON"), std::string::npos) << early.output;
  // Two runs as tasks of a Slurm job array (scripts/slurm_array.sh runs line TASK + 1)...
  std::string out;
  for (int task : {0, 1})
    ASSERT_EQ(test::runCommand("SLURM_ARRAY_TASK_ID=" + std::to_string(task) + " " + LODLINE_SOURCE_DIR +
                                   "/scripts/slurm_array.sh " + (dir_ / "commands.txt").string(),
                               &out),
              0)
        << out;
  // ...then the 22 still pending through GNU parallel, two at a time.
  CliRun rest = sweep(vary + " --emit-commands -o " + shard.string());
  ASSERT_EQ(rest.code, 0) << rest.output;
  ASSERT_EQ(lines(rest.output).size(), 22u) << rest.output;
  std::ofstream(dir_ / "rest.txt") << rest.output;
  ASSERT_EQ(test::runCommand("cd / && parallel --will-cite -j2 --halt now,fail=1 < " + (dir_ / "rest.txt").string(), &out), 0)
      << out;
  // Everything is done: nothing left to emit.
  CliRun none = sweep(vary + " --emit-commands -o " + shard.string());
  ASSERT_EQ(none.code, 0) << none.output;
  EXPECT_TRUE(lines(none.output).empty()) << none.output;
  CliRun collected = sweep(vary + " --collect -o " + shard.string());
  ASSERT_EQ(collected.code, 0) << collected.output;
  auto a = readCsv(self / "results.csv"), b = readCsv(shard / "results.csv");
  ASSERT_EQ(a.size(), 24u);
  ASSERT_EQ(b.size(), a.size());
  for (size_t i = 0; i < a.size(); ++i) {
    for (auto* row : {&a[i], &b[i]})
      for (auto it = row->begin(); it != row->end();) it = it->first.rfind("ms_", 0) == 0 ? row->erase(it) : std::next(it);
    EXPECT_EQ(a[i], b[i]) << "row " << i;
  }
  EXPECT_TRUE(fs::exists(shard / "sheet_lod-pm.png"));
  EXPECT_EQ(readAll(self / "sheet_lod-pm.png"), readAll(shard / "sheet_lod-pm.png"));
  // The modes exclude each other.
  EXPECT_EQ(sweep(vary + " --collect --emit-commands -o " + shard.string()).code, 2);
}

TEST_F(Sweep, InterruptStopsTheRendersAndKeepsTheRunsDone) {
  const fs::path out = dir_ / "i";
  setenv("EGL_PLATFORM", "surfaceless", 1);
  const std::vector<std::string> args = {LODLINE_BINARY, "sweep", model_, "--set", "size=320x240", "--vary",
                                         "target-area=2,3,4,6,8,12,16,24,32,48,64,96", "--jobs", "2", "-o",
                                         out.string()};
  std::vector<char*> argv;
  for (const auto& s : args) argv.push_back(const_cast<char*>(s.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, (dir_ / "out.txt").c_str(), O_WRONLY | O_CREAT, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  pid_t pid = -1;
  ASSERT_EQ(posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  // Once the first run is done, Ctrl-C.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!fs::exists(out / "runs" / "target-area-2.json") && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  kill(pid, SIGINT);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  const std::string output = readAll(dir_ / "out.txt");
  ASSERT_TRUE(WIFEXITED(status)) << output;
  EXPECT_EQ(WEXITSTATUS(status), 130) << output;
  EXPECT_NE(output.find("interrupted"), std::string::npos) << output;
  // The CSV lists exactly the complete runs; nothing half-written anywhere.
  expectNoLeftovers(out / "runs");
  expectNoLeftovers(dir_ / "cache" / "lodline");
  size_t complete = 0;
  for (const auto& f : filesIn(out / "runs")) complete += f.ends_with(".json");
  EXPECT_GE(complete, 1u);
  EXPECT_LT(complete, 12u) << "interrupted before the end";
  EXPECT_EQ(readCsv(out / "results.csv").size(), complete);
  EXPECT_TRUE(fs::exists(out / "sheet.png"));
  // The same command finishes the sweep.
  CliRun rest;
  rest.code = test::runLodline("sweep " + model_ + " --set size=320x240 --vary target-area=2,3,4,6,8,12,16,24,32,48,64,96 "
                               "-o " + out.string(), &rest.output);
  EXPECT_EQ(rest.code, 0) << rest.output;
  EXPECT_NE(rest.output.find(std::to_string(12 - complete) + " rendered, " + std::to_string(complete) + " skipped"),
            std::string::npos)
      << rest.output;
}

}  // namespace
}  // namespace lodline
