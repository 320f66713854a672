// `lodline capture`: determinism, frame ranges, video frame counts, interruption, metrics.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include <sys/wait.h>

#include "io/generate.h"
#include "io/image.h"
#include "io/load_mesh.h"
#include "test_util.h"

namespace lodline {
namespace {

int shell(const std::string& cmd, std::string* output = nullptr) { return test::runCommand(cmd, output); }

std::string readAll(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

class Capture : public ::testing::Test {
 protected:
  void SetUp() override {
    setenv("XDG_CACHE_HOME", (dir_ / "cache").c_str(), 1);
    // A knot, not a torus: an orbit about the axis of a torus gives identical frames.
    model_ = (dir_ / "knot.off").string();
    ASSERT_TRUE(saveOff(model_, makeTorusKnot(2, 3, 1.0f, 0.16f, 240, 16, 0.1f)).ok());
  }
  std::string capture(const std::string& args) {
    return std::string(LODLINE_BINARY) + " capture " + model_ + " --size 160x96 --msaa 1 " + args;
  }
  test::TempDir dir_;
  std::string model_;
};

// Without metrics the frames are pipelined (frame k + 1's stages run while frame k is
// drawn); with them, drawn in turn. Both give the same frames.
TEST_F(Capture, FramesAreDeterministicAndRangesAgree) {
  const auto a = dir_ / "a", b = dir_ / "b", c = dir_ / "c", d = dir_ / "d";
  std::string out;
  ASSERT_EQ(shell(capture("--duration 1 --fps 8 -o " + a.string() + "/"), &out), 0) << out;
  ASSERT_EQ(shell(capture("--duration 1 --fps 8 -o " + b.string() + "/"), &out), 0) << out;
  ASSERT_EQ(shell(capture("--duration 1 --fps 8 --frames 5:8 -o " + c.string() + "/"), &out), 0) << out;
  ASSERT_EQ(shell(capture("--duration 1 --fps 8 --metrics " + (dir_ / "m.csv").string() + " -o " + d.string() + "/"),
                  &out),
            0)
      << out;
  for (int k = 0; k < 8; ++k) {
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%05d.png", k);
    ASSERT_TRUE(std::filesystem::exists(a / name)) << name;
    EXPECT_TRUE(readAll(a / name) == readAll(b / name)) << "same frame bytes twice: " << name;
    EXPECT_TRUE(readAll(a / name) == readAll(d / name)) << "pipelined vs drawn in turn: " << name;
    if (k >= 5) EXPECT_TRUE(readAll(a / name) == readAll(c / name)) << "full vs ranged: " << name;
    else EXPECT_FALSE(std::filesystem::exists(c / name)) << name;
  }
  EXPECT_FALSE(std::filesystem::exists(a / "frame_00008.png"));
  // The camera moves: consecutive frames differ.
  EXPECT_FALSE(readAll(a / "frame_00000.png") == readAll(a / "frame_00001.png"));
}

// Four `--frames A:B` shards joined with `lodline join` equal the capture made in one
// process: the same PNG frames, the same metrics rows (the timing column aside), and an MP4
// of all the frames without re-encoding.
TEST_F(Capture, FourShardsJoinedEqualTheOneProcessCapture) {
  const auto whole = dir_ / "whole", joined = dir_ / "joined";
  const std::string path = "--path orbit --duration 2 --fps 8 ";  // 16 frames
  std::string out;
  ASSERT_EQ(shell(capture(path + "-o " + whole.string() + "/ --metrics " + (dir_ / "whole.csv").string()), &out), 0)
      << out;
  const std::vector<std::string> ranges = {"0:3", "3:8", "8:9", "9:16"};
  std::string pngs, csvs, mp4s;
  for (size_t i = 0; i < ranges.size(); ++i) {
    const auto part = dir_ / ("part" + std::to_string(i));
    const std::string csv = part.string() + ".csv", mp4 = part.string() + ".mp4";
    ASSERT_EQ(shell(capture(path + "--frames " + ranges[i] + " -o " + part.string() + "/ --metrics " + csv), &out), 0)
        << out;
    pngs += " " + part.string();
    csvs += " " + csv;
    if (shell("command -v ffmpeg") == 0) {
      ASSERT_EQ(shell(capture(path + "--frames " + ranges[i] + " -o " + mp4), &out), 0) << out;
      mp4s += " " + mp4;
    }
  }
  // Shards in any order on the command line: frames are placed by number.
  ASSERT_EQ(test::runLodline("join" + pngs + " -o " + joined.string() + "/", &out), 0) << out;
  ASSERT_EQ(test::runLodline("join" + csvs + " -o " + (dir_ / "joined.csv").string(), &out), 0) << out;
  for (int k = 0; k < 16; ++k) {
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%05d.png", k);
    EXPECT_TRUE(readAll(whole / name) == readAll(joined / name)) << name;
  }
  EXPECT_FALSE(std::filesystem::exists(joined / "frame_00016.png"));
  // Metrics: equal row by row except ms_total.
  auto rows = [](const std::filesystem::path& p) {
    std::vector<std::vector<std::string>> table;
    std::ifstream in(p);
    for (std::string line; std::getline(in, line);) {
      std::vector<std::string> f;
      std::stringstream ss(line);
      for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
      table.push_back(f);
    }
    return table;
  };
  auto a = rows(dir_ / "whole.csv"), b = rows(dir_ / "joined.csv");
  ASSERT_EQ(a.size(), 17u);
  ASSERT_EQ(b.size(), a.size());
  const auto ms = std::find(a[0].begin(), a[0].end(), "ms_total") - a[0].begin();
  for (size_t r = 0; r < a.size(); ++r) {
    ASSERT_EQ(a[r].size(), b[r].size());
    for (size_t c = 0; c < a[r].size(); ++c) {
      if (r == 0 || static_cast<std::ptrdiff_t>(c) != ms) {
        EXPECT_EQ(a[r][c], b[r][c]) << "row " << r << " column " << a[0][c];
      }
    }
  }
  // A missing shard is a gap, a repeated one an overlap: both refused, nothing written.
  EXPECT_EQ(test::runLodline("join " + (dir_ / "part0").string() + " " + (dir_ / "part2").string() + " -o " +
                                 (dir_ / "gap").string() + "/",
                             &out),
            1);
  EXPECT_NE(out.find("frames 3..7 are in no part"), std::string::npos) << out;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "gap"));
  EXPECT_EQ(test::runLodline("join " + (dir_ / "part0.csv").string() + " " + (dir_ / "part0.csv").string() + " -o " +
                                 (dir_ / "twice.csv").string(),
                             &out),
            1);
  EXPECT_NE(out.find("frame 0 is also in"), std::string::npos) << out;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "twice.csv"));
  if (mp4s.empty() || shell("command -v ffprobe") != 0) return;
  const auto video = dir_ / "joined.mp4";
  ASSERT_EQ(test::runLodline("join" + mp4s + " -o " + video.string(), &out), 0) << out;
  ASSERT_EQ(shell("ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames "
                  "-of csv=p=0 " + video.string(), &out), 0);
  EXPECT_EQ(std::stoi(out), 16);
}

TEST_F(Capture, VideoHasTheRequestedFrameCount) {
  if (shell("command -v ffprobe") != 0) GTEST_SKIP() << "ffprobe not installed";
  const auto video = dir_ / "v.mp4";
  std::string out;
  ASSERT_EQ(shell(capture("--path zoom-out --duration 2 --fps 10 --frames 13 -o " + video.string()), &out), 0) << out;
  ASSERT_EQ(shell("ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames "
                  "-of csv=p=0 " + video.string(), &out), 0);
  EXPECT_EQ(std::stoi(out), 13);
  // Nothing but the model, the cache (ours and Mesa's shader cache) and the video in the
  // directory: the temporary file was renamed.
  size_t files = 0;
  for ([[maybe_unused]] auto& e : std::filesystem::directory_iterator(dir_.path())) ++files;
  EXPECT_EQ(files, 3u);
}

TEST_F(Capture, InterruptedCaptureLeavesAPlayableVideo) {
  if (shell("command -v ffprobe") != 0) GTEST_SKIP() << "ffprobe not installed";
  const auto video = dir_ / "i.mp4";
  std::string out;
  // 30000 frames take far longer than the 3 s before SIGINT.
  const int code = shell("sh -c '" + capture("--duration 1000 --fps 30 -o " + video.string()) +
                             " & pid=$!; sleep 3; kill -INT $pid; wait $pid'", &out);
  EXPECT_EQ(code, 130) << out;
  EXPECT_NE(out.find("interrupted"), std::string::npos) << out;
  ASSERT_TRUE(std::filesystem::exists(video)) << out;
  ASSERT_EQ(shell("ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames "
                  "-of csv=p=0 " + video.string(), &out), 0) << out;
  EXPECT_GT(std::stoi(out), 0);
  EXPECT_LT(std::stoi(out), 30000);
}

TEST_F(Capture, MetricsCsvHasHeaderAndOneRowPerFrame) {
  const auto csv = dir_ / "m.csv";
  std::string out;
  ASSERT_EQ(shell(capture("--duration 1 --fps 6 -o " + (dir_ / "seq").string() + "/ --metrics " + csv.string()), &out), 0)
      << out;
  EXPECT_NE(out.find("churn mean"), std::string::npos) << out;
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line,
            "frame,line_pixels,appeared,vanished,churn,dropped,appeared_raw,vanished_raw,churn_raw,strokes,specks,"
            "active_faces,splits,collapses,ms_total,texture_drift,churn_binary,band_fraction,popped_near_ops,"
            "popped_near_morphs,lines_near_ops,lines_near_morphs");
  int rows = 0;
  while (std::getline(in, line)) {
    ++rows;
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), 21) << line;
    std::vector<std::string> fields;
    std::stringstream ls(line);
    for (std::string v; std::getline(ls, v, ',');) fields.push_back(v);
    ASSERT_EQ(fields.size(), 22u) << line;
    const double band = std::stod(fields[17]);
    EXPECT_TRUE(band > 0.0 && band <= 1.0) << line;
    // The popped pixels near changes are some of the popped ones, the line pixels near
    // changes some of the line pixels.
    const double appeared = std::stod(fields[2]), vanished = std::stod(fields[3]), lines = std::stod(fields[1]);
    EXPECT_LE(std::stod(fields[18]), appeared + vanished) << line;
    EXPECT_LE(std::stod(fields[19]), appeared + vanished) << line;
    EXPECT_LE(std::stod(fields[20]), lines) << line;
    EXPECT_LE(std::stod(fields[21]), lines) << line;
  }
  EXPECT_EQ(rows, 6);
}

// Per-frame columns of a metrics CSV by name.
std::map<std::string, std::vector<double>> readCsv(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  std::stringstream hs(line);
  for (std::string n; std::getline(hs, n, ',');) names.push_back(n);
  std::map<std::string, std::vector<double>> cols;
  while (std::getline(in, line)) {
    std::stringstream ls(line);
    std::string v;
    for (size_t i = 0; i < names.size() && std::getline(ls, v, ','); ++i) cols[names[i]].push_back(std::stod(v));
  }
  return cols;
}

double meanAfterFirst(const std::vector<double>& v) {
  double s = 0.0;
  for (size_t i = 1; i < v.size(); ++i) s += v[i];
  return v.size() > 1 ? s / static_cast<double>(v.size() - 1) : 0.0;
}

// Built-in paths start from --view: from ten bounding radii the knot draws far fewer line
// pixels than from three, on every path that starts there.
TEST_F(Capture, BuiltInPathsStartFromTheView) {
  for (const char* path : {"orbit", "zoom-out", "dolly"}) {
    SCOPED_TRACE(path);
    std::map<std::string, double> first_pixels;
    for (const char* dist : {"3", "10"}) {
      const auto csv = dir_ / (std::string(path) + dist + ".csv");
      std::string out;
      ASSERT_EQ(shell(capture(std::string("--path ") + path + " --view 35,20," + dist +
                              " --duration 1 --fps 4 --frames 0:1 --full-detail -o " +
                              (dir_ / (std::string(path) + dist)).string() + "/ --metrics " + csv.string()),
                      &out),
                0)
          << out;
      first_pixels[dist] = readCsv(csv)["line_pixels"].at(0);
    }
    EXPECT_GT(first_pixels["3"], 2.0 * first_pixels["10"]);
  }
}

// capture --pop-frames DIR/: one PNG per compared frame (none for the first), the frame's size,
// with green pixels where lines appeared and red where they vanished, present exactly where
// the metrics count popped pixels.
TEST_F(Capture, PopFramesShowWhereLinesPopped) {
  const auto pops = dir_ / "pops", csv = dir_ / "m.csv";
  std::string out;
  ASSERT_EQ(shell(capture("--path orbit --duration 2 --fps 30 --frames 6 -o " + (dir_ / "png").string() +
                          "/ --metrics " + csv.string() + " --pop-frames " + pops.string() + "/"),
                  &out),
            0)
      << out;
  EXPECT_FALSE(std::filesystem::exists(pops / "pop_00000.png"));
  const auto cols = readCsv(csv);
  double popped_total = 0.0;
  int tinted_total = 0;
  for (int k = 1; k < 6; ++k) {
    const auto f = pops / ("pop_0000" + std::to_string(k) + ".png");
    auto img = readPng(f);
    ASSERT_TRUE(img.ok()) << f;
    auto frame = readPng(dir_ / "png" / ("frame_0000" + std::to_string(k) + ".png"));
    ASSERT_TRUE(frame.ok());
    EXPECT_EQ(img->width, frame->width);
    EXPECT_EQ(img->height, frame->height);
    int tinted = 0;  // red or green, not grey
    for (int y = 0; y < img->height; ++y)
      for (int x = 0; x < img->width; ++x) {
        const uint8_t* c = img->pixel(x, y);
        tinted += std::abs(int{c[0]} - int{c[1]}) > 24;
      }
    const double popped = cols.at("appeared").at(k) + cols.at("vanished").at(k);
    if (popped == 0.0) {
      EXPECT_EQ(tinted, 0) << "frame " << k;
    }
    popped_total += popped;
    tinted_total += tinted;
  }
  // The default drawing has strong lines: most popped pixels show (faint ones may not).
  EXPECT_GT(popped_total, 0.0);
  EXPECT_GT(tinted_total, 0);
  EXPECT_LE(tinted_total, 2.0 * popped_total + 50.0);
}

// capture --svg DIR/: one SVG per frame, each stroke with an id; most of a frame's stroke
// length keeps the ids of the frame before (a slow orbit), ids are unique within a frame, and
// frame k's SVG is the same whichever range renders it.
TEST_F(Capture, SvgPerFrameWithStableStrokeIds) {
  auto ids = [](const std::filesystem::path& f) {
    std::ifstream in(f);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::vector<std::string> out;
    for (size_t at = text.find(" id=\"s"); at != std::string::npos; at = text.find(" id=\"s", at + 1))
      out.push_back(text.substr(at + 6, text.find('"', at + 6) - at - 6));
    return out;
  };
  const auto svg = dir_ / "svg", svg2 = dir_ / "svg2";
  std::string out;
  ASSERT_EQ(shell(capture("--path orbit --duration 8 --fps 30 --frames 4 -o " + (dir_ / "png").string() + "/ --svg " +
                          svg.string() + "/"),
                  &out),
            0)
      << out;
  std::vector<std::vector<std::string>> frames;
  for (int k = 0; k < 4; ++k) {
    const auto f = svg / ("frame_0000" + std::to_string(k) + ".svg");
    ASSERT_TRUE(std::filesystem::exists(f)) << f;
    frames.push_back(ids(f));
    auto sorted = frames.back();
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(std::unique(sorted.begin(), sorted.end()), sorted.end()) << "duplicate ids in frame " << k;
    EXPECT_GT(frames.back().size(), 3u);
  }
  for (int k = 1; k < 4; ++k) {
    size_t kept = 0;
    for (const auto& id : frames[k]) kept += std::count(frames[k - 1].begin(), frames[k - 1].end(), id);
    EXPECT_GE(2 * kept, frames[k].size()) << "frame " << k;
  }
  // Frames 2..3 alone: the same files.
  ASSERT_EQ(shell(capture("--path orbit --duration 8 --fps 30 --frames 2:4 -o " + (dir_ / "png2").string() +
                          "/ --svg " + svg2.string() + "/"),
                  &out),
            0)
      << out;
  EXPECT_EQ(ids(svg2 / "frame_00003.svg"), frames[3]);
  EXPECT_FALSE(std::filesystem::exists(svg2 / "frame_00001.svg"));
}

// A sphere away from the orbit's centre: its contour sweeps across the image (the raw measure
// counts nearly every line pixel every frame), yet it never pops (the compensated one does not).
TEST_F(Capture, CompensatedChurnSeparatesCameraMotionFromPopping) {
  ASSERT_TRUE(saveOff(dir_ / "ball.off", makeIcoSphere(1.0f, 4)).ok());
  ASSERT_TRUE(saveOff(dir_ / "pivot.off", makeIcoSphere(0.05f, 1)).ok());
  std::ofstream(dir_ / "scene.json") << R"({"settings": {"lines": "contour", "size": "320x240", "msaa": 1,
      "full-detail": true}, "objects": [{"mesh": "ball.off", "translate": [2.2, 0, 0]}, {"mesh": "pivot.off"}]})";
  const auto csv = dir_ / "orbit.csv";
  std::string out;
  ASSERT_EQ(shell(std::string(LODLINE_BINARY) + " capture " + (dir_ / "scene.json").string() +
                      " --path orbit --duration 4 --fps 15 -o " + (dir_ / "o").string() + "/ --metrics " + csv.string(),
                  &out),
            0)
      << out;
  const auto cols = readCsv(csv);
  ASSERT_EQ(cols.at("churn").size(), 60u);
  const double raw = meanAfterFirst(cols.at("churn_raw")), compensated = meanAfterFirst(cols.at("churn"));
  EXPECT_GT(raw, 0.5);
  EXPECT_LT(compensated, 0.05);
  EXPECT_LT(compensated * 10.0, raw);
}

TEST_F(Capture, MissingFfmpegIsAClearError) {
  std::string out;
  const int code = shell("PATH=/nonexistent " + capture("-o " + (dir_ / "x.mp4").string()), &out);
  EXPECT_EQ(code, 1);
  EXPECT_NE(out.find("ffmpeg not found"), std::string::npos) << out;
  EXPECT_NE(out.find("PNG"), std::string::npos) << out;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "x.mp4"));
}

TEST_F(Capture, BadOptions) {
  for (const std::string& args : {"--frames 5:2 -o " + (dir_ / "s").string() + "/",
                                 "--path spiral -o " + (dir_ / "s").string() + "/",
                                 "-o " + (dir_ / "v.avi").string(), "--fps 0 -o " + (dir_ / "s").string() + "/"}) {
    std::string out;
    EXPECT_EQ(shell(capture(args), &out), 2) << args << ": " << out;
  }
  std::ofstream(dir_ / "bad.json") << "{\"keys\": 3}";
  std::string out;
  EXPECT_EQ(shell(capture("--path " + (dir_ / "bad.json").string() + " -o " + (dir_ / "s").string() + "/"), &out), 1);
  EXPECT_NE(out.find("bad.json"), std::string::npos) << out;
}

}  // namespace
}  // namespace lodline
