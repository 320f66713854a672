// Output faults (docs/reliability.md): an unwritable directory, an output path that is a
// directory, a full disk (a file-size limit, and a 64 KiB tmpfs where mounting is allowed),
// SIGINT and SIGKILL during `capture` and `build`, and a cache left damaged by a killed
// writer. Each failure is one line naming the path, exit 1, no partial output; a killed
// capture leaves its frames in a playable hidden part file; the cache is never corrupt and
// the next run recovers (and removes what the killed run left).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <sys/stat.h>
#include <unistd.h>

#include "io/generate.h"
#include "io/load_mesh.h"
#include "pm/pm_file.h"
#include "run_process.h"
#include "test_util.h"

namespace lodline {
namespace {

namespace fs = std::filesystem;
using test::ProcessOptions;
using test::ProcessResult;

bool have(const char* program) { return std::system((std::string("command -v ") + program + " >/dev/null 2>&1").c_str()) == 0; }

std::vector<std::string> filesIn(const fs::path& dir) {
  std::vector<std::string> names;
  if (!fs::is_directory(dir)) return names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

int videoFrames(const fs::path& video) {
  std::string out;
  if (test::runCommand("ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames "
                       "-of csv=p=0 " + video.string(), &out) != 0)
    return -1;
  try {
    return std::stoi(out);
  } catch (const std::exception&) {
    return -1;
  }
}

class OutputFaults : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::permissions(dir_.path(), fs::perms::all);
    model_ = (dir_ / "knot.off").string();
    ASSERT_TRUE(saveOff(model_, makeTorusKnot(2, 3, 1.0f, 0.16f, 240, 16, 0.1f)).ok());
    fs::permissions(model_, fs::perms::all);
    cache_ = dir_ / "cache";
    fs::create_directories(cache_);
    fs::permissions(cache_, fs::perms::all);
  }

  // Mesa's shader cache goes to XDG_CACHE_HOME: keep it out of the directories checked.
  std::string xdg() const { return "XDG_CACHE_HOME=" + (dir_ / "xdg").string(); }

  ProcessResult run(const std::vector<std::string>& args, ProcessOptions opt = {}) {
    opt.env.push_back(xdg());
    opt.env.push_back("HOME=" + dir_.path().string());
    if (opt.timeout_s == 120.0) opt.timeout_s = 90.0;
    return test::runProcess(test::lodlineArgs(args), opt);
  }

  // Exit 1 with one line that starts "lodline: " and contains `says`.
  static void expectOneLineError(const ProcessResult& r, const std::string& says) {
    ASSERT_FALSE(r.timed_out) << r.describe();
    ASSERT_EQ(r.signal, 0) << r.describe() << "\n" << r.err;
    EXPECT_EQ(r.exit_code, 1) << r.err;
    const auto lines = test::linesOf(r.err);
    ASSERT_EQ(lines.size(), 1u) << r.err;
    EXPECT_EQ(lines[0].rfind("lodline: ", 0), 0u) << lines[0];
    EXPECT_NE(lines[0].find(says), std::string::npos) << lines[0];
  }

  test::TempDir dir_;
  std::string model_;
  fs::path cache_;
};

TEST_F(OutputFaults, UnwritableDirectory) {
  const fs::path locked = dir_ / "locked";
  fs::create_directory(locked);
  fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                              fs::perms::group_exec | fs::perms::others_read | fs::perms::others_exec);
  // root may write anywhere: run as nobody to meet the directory as a user does.
  std::vector<std::string> as_user;
  if (geteuid() == 0) {
    if (!have("setpriv")) GTEST_SKIP() << "running as root without setpriv";
    as_user = {"setpriv", "--reuid=65534", "--regid=65534", "--clear-groups", "--"};
  }
  const std::vector<std::vector<std::string>> cases = {
      {"render", model_, "-o", (locked / "o.png").string(), "--size", "64x48"},
      {"render", model_, "--svg", (locked / "o.svg").string(), "--size", "64x48"},
      {"render", model_, "-o", (dir_ / "ok.png").string(), "--stats", (locked / "s.json").string()},
      {"capture", model_, "-o", (locked / "o.mp4").string(), "--size", "64x48"},
      {"capture", model_, "-o", (locked / "frames").string() + "/", "--size", "64x48"},
      {"capture", model_, "-o", (dir_ / "seq").string() + "/", "--metrics", (locked / "m.csv").string()},
      {"build", model_, "-o", (locked / "o.lpm").string()},
      {"simplify", model_, "--max-error", "1%", "-o", (locked / "s.off").string()},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c[0] + " " + c[2] + " " + c[3]);
    std::vector<std::string> argv = as_user;
    const auto l = test::lodlineArgs(c);
    argv.insert(argv.end(), l.begin(), l.end());
    argv.insert(argv.end(), {"--cache-dir", cache_.string()});
    if (c[0] == "simplify") argv.resize(argv.size() - 2);
    ProcessOptions opt;
    opt.env = {xdg(), "HOME=" + dir_.path().string()};
    const ProcessResult r = test::runProcess(argv, opt);
    expectOneLineError(r, locked.string());
    EXPECT_TRUE(filesIn(locked).empty());
    EXPECT_FALSE(fs::exists(dir_ / "ok.png"));
    EXPECT_TRUE(filesIn(dir_ / "seq").empty());
  }
}

TEST_F(OutputFaults, OutputPathIsADirectory) {
  for (const char* d : {"d.png", "d.svg", "d.json", "d.lpm", "d.off", "d.csv"}) fs::create_directory(dir_ / d);
  const std::string d = dir_.path().string();
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"render", model_, "-o", d + "/d.png"}, d + "/d.png"},
      {{"render", model_, "-o", d + "/o.png", "--svg", d + "/d.svg"}, d + "/d.svg"},
      {{"render", model_, "-o", d + "/o.png", "--stats", d + "/d.json"}, d + "/d.json"},
      {{"capture", model_, "-o", d + "/seq/", "--metrics", d + "/d.csv"}, d + "/d.csv"},
      {{"build", model_, "-o", d + "/d.lpm"}, d + "/d.lpm"},
      {{"simplify", model_, "--max-error", "1%", "-o", d + "/d.off"}, d + "/d.off"},
  };
  for (const auto& [args, path] : cases) {
    SCOPED_TRACE(path);
    std::vector<std::string> a = args;
    if (a[0] != "simplify") a.insert(a.end(), {"--cache-dir", cache_.string()});
    if (a[0] == "render" || a[0] == "capture") a.insert(a.end(), {"--size", "64x48"});
    const ProcessResult r = run(a);
    expectOneLineError(r, path + ": cannot write");
    EXPECT_FALSE(fs::exists(dir_ / "o.png"));
    EXPECT_TRUE(filesIn(dir_ / "seq").empty());
    EXPECT_TRUE(fs::is_empty(path));
  }
}

// A full disk, by a file-size limit: writes beyond it fail (EFBIG) as they would with
// ENOSPC. Whatever was being written is removed; nothing half-written remains.
TEST_F(OutputFaults, DiskFullByFileSizeLimit) {
  const fs::path out = dir_ / "out";
  fs::create_directory(out);
  ProcessOptions limited;
  limited.file_size_limit = 4096;  // smaller than every output below
  const std::string o = out.string();
  const std::vector<std::vector<std::string>> cases = {
      {"render", model_, "-o", o + "/o.png", "--size", "320x240", "--full-detail"},
      // Hidden lines too: the smooth paths alone come to about 4 KB.
      {"render", model_, "--svg", o + "/o.svg", "--size", "640x480", "--full-detail", "--hidden-lines", "grey"},
      {"build", model_, "-o", o + "/o.lpm"},
      {"simplify", model_, "--max-error", "0.01%", "-o", o + "/s.off"},
      {"capture", model_, "-o", o + "/seq/", "--size", "320x240", "--duration", "0.2", "--fps", "10"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c[0] + " " + c[2] + " " + c[3]);
    std::vector<std::string> a = c;
    if (a[0] != "simplify") a.insert(a.end(), {"--cache-dir", cache_.string()});
    const ProcessResult r = run(a, limited);
    expectOneLineError(r, o);
    for (const std::string& f : filesIn(out)) {
      EXPECT_EQ(f, "seq") << "left behind: " << f;
      EXPECT_TRUE(filesIn(out / "seq").empty());
    }
  }
  if (have("ffmpeg")) {
    const ProcessResult r = run({"capture", model_, "-o", o + "/v.mp4", "--size", "320x240", "--duration", "0.5",
                                 "--fps", "10", "--cache-dir", cache_.string()},
                                limited);
    expectOneLineError(r, o + "/v.mp4");
    EXPECT_FALSE(fs::exists(out / "v.mp4"));
    for (const std::string& f : filesIn(out)) EXPECT_TRUE(f == "seq") << "left behind: " << f;
  }
  // The cache cannot be written: not an error (the model is drawn), and no partial file.
  const fs::path small_cache = dir_ / "small-cache";
  const ProcessResult b = run({"build", model_, "--cache-dir", small_cache.string()}, limited);
  EXPECT_EQ(b.exit_code, 0) << b.err;
  EXPECT_NE(b.out.find("could not write the cache"), std::string::npos) << b.out;
  EXPECT_TRUE(filesIn(small_cache).empty());
}

// A really full file system: a 64 KiB tmpfs in a private mount namespace (needs the right to
// mount, as root in CI; skipped otherwise). The listing of the tmpfs after each command is
// printed from inside the namespace.
TEST_F(OutputFaults, DiskFullOnASmallTmpfs) {
  if (!have("unshare") || test::runCommand("unshare -m sh -c 'mount -t tmpfs -o size=64k tmpfs /mnt'") != 0)
    GTEST_SKIP() << "cannot mount a tmpfs in a private mount namespace here";
  const fs::path mnt = dir_ / "full";
  fs::create_directory(mnt);
  const std::string m = mnt.string(), bin = LODLINE_BINARY, c = cache_.string();
  std::ofstream script(dir_ / "full.sh");
  script << "mount -t tmpfs -o size=64k tmpfs " << m << " || exit 99\n"
         << "export " << xdg() << "\n"
         << "run() {\n  \"$@\" 2>>" << (dir_ / "err.txt").string() << " >/dev/null\n  echo \"rc=$?\"\n"
         << "  for f in $(ls -A " << m << "); do echo \"left: $f\"; done\n  rm -rf " << m << "/* " << m
         << "/.[!.]*\n}\n"
         << "run " << bin << " render " << model_ << " -o " << m << "/o.png --size 4096x3072 --full-detail --cache-dir " << c
         << "\n"
         << "run " << bin << " build " << model_ << " -o " << m << "/o.lpm\n"
         << "run " << bin << " simplify " << model_ << " --max-error 0.01% -o " << m << "/s.off\n";
  if (have("ffmpeg"))
    script << "run " << bin << " capture " << model_ << " -o " << m << "/v.mp4 --size 640x480 --duration 2 --fps 10 --cache-dir "
           << c << "\n";
  script << "run " << bin << " build " << model_ << " --cache-dir " << m << "/cache\n";
  script.close();
  std::string out;
  const int code = test::runCommand("unshare -m sh " + (dir_ / "full.sh").string(), &out);
  ASSERT_EQ(code, 0) << out;
  // Every command but the cache build fails (rc=1) and leaves nothing; the cache build
  // succeeds, with the cache directory but no partial cache file in it.
  size_t failures = 0, successes = 0;
  for (const std::string& line : test::linesOf(out)) {
    if (line == "rc=1") ++failures;
    if (line == "rc=0") ++successes;
    if (line.rfind("left: ", 0) == 0) {
      EXPECT_EQ(line, "left: cache") << out;
    }
  }
  EXPECT_EQ(failures, have("ffmpeg") ? 4u : 3u) << out;
  EXPECT_EQ(successes, 1u) << out;
  // One line per failure, each naming the file on the full file system.
  std::ifstream in(dir_ / "err.txt");
  const std::string err((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto lines = test::linesOf(err);
  EXPECT_EQ(lines.size(), failures) << err;
  for (const std::string& line : lines) EXPECT_EQ(line.rfind("lodline: " + m + "/", 0), 0u) << line;
}

// SIGKILL during capture: nothing can be finished then. The target is not created; the
// frames already encoded are in the hidden part file, which plays (fragmented MP4, completed
// by ffmpeg when the pipe closes); the next capture to the same file removes it and succeeds.
TEST_F(OutputFaults, KilledCaptureLeavesAPlayablePartAndTheNextRunRecovers) {
  if (!have("ffmpeg") || !have("ffprobe")) GTEST_SKIP() << "ffmpeg/ffprobe not installed";
  const fs::path out = dir_ / "out";
  fs::create_directory(out);
  const std::vector<std::string> args = {"capture", model_, "-o", (out / "v.mp4").string(), "--size", "160x96",
                                         "--msaa", "1", "--duration", "1000", "--fps", "30", "--cache-dir", cache_.string()};
  {
    ProcessOptions opt;
    opt.env = {xdg()};
    test::Process p(test::lodlineArgs(args), opt);
    // Wait until frames are being encoded (the part file has grown), then kill.
    fs::path part;
    for (int i = 0; i < 600 && part.empty(); ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      for (const std::string& f : filesIn(out))
        if (f.find(".part") != std::string::npos && fs::file_size(out / f) > 20000) part = out / f;
    }
    ASSERT_FALSE(part.empty()) << "no frames encoded in 60 s";
    p.signal(SIGKILL);
    const ProcessResult r = p.wait();
    EXPECT_EQ(r.signal, SIGKILL);
    EXPECT_FALSE(fs::exists(out / "v.mp4"));
    // ffmpeg (its own process group) sees the pipe close and finishes the file.
    int frames = -1;
    for (int i = 0; i < 100 && frames <= 0; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      frames = videoFrames(part);
    }
    EXPECT_GT(frames, 0) << "the part file does not play";
  }
  // The next run writes the video and removes the killed run's part.
  std::vector<std::string> again = args;
  again[9] = "0.5";  // --duration
  const ProcessResult r = run(again);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(filesIn(out), std::vector<std::string>{"v.mp4"});
  EXPECT_EQ(videoFrames(out / "v.mp4"), 15);
}

// SIGINT during build: the build stops; the cache holds nothing or a complete file, and the
// next run gets a valid progressive mesh.
TEST_F(OutputFaults, InterruptedAndKilledBuildsNeverLeaveACorruptCache) {
  // A model whose build takes a while (about a second here; the signals come within 0.6 s,
  // so most rounds stop it mid-build — a level-6 sphere, 0.14 s since lodline stopped
  // linking OSMesa and LLVM, often finished first).
  const std::string big = (dir_ / "sphere.off").string();
  ASSERT_TRUE(saveOff(big, makeIcoSphere(1.0f, 7)).ok());
  std::mt19937 rng(3);
  int killed = 0;
  for (int round = 0; round < 8; ++round) {
    ProcessOptions opt;
    opt.env = {xdg()};
    test::Process p(test::lodlineArgs({"build", big, "--force", "--cache-dir", cache_.string()}), opt);
    std::this_thread::sleep_for(std::chrono::milliseconds(50 + rng() % 550));
    p.signal(round % 2 == 0 ? SIGKILL : SIGINT);
    const ProcessResult r = p.wait();
    killed += r.signal != 0;
    // Whatever is in the cache under a cache name is complete and valid.
    for (const std::string& f : filesIn(cache_))
      if (f.size() == 20 && f.substr(16) == ".lpm") {
        auto pm = loadPm(cache_ / f);
        EXPECT_TRUE(pm.ok()) << pm.error().message;
      }
  }
  EXPECT_GT(killed, 0);
  // The next run: a valid progressive mesh (loaded or rebuilt), nothing else left behind.
  const ProcessResult r = run({"build", big, "--cache-dir", cache_.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto files = filesIn(cache_);
  ASSERT_EQ(files.size(), 1u) << "cache directory: " << ::testing::PrintToString(files);
  EXPECT_TRUE(loadPm(cache_ / files[0]).ok());
}

// What a writer killed at the worst moment leaves (a temporary file of a dead process, a
// cache file cut short by a crash of the disk or a copy) is cleaned up and rebuilt by the
// next run, which says so in its stats.
TEST_F(OutputFaults, DamagedCacheAndStaleTemporariesAreHealed) {
  ASSERT_EQ(run({"build", model_, "--cache-dir", cache_.string()}).exit_code, 0);
  auto files = filesIn(cache_);
  ASSERT_EQ(files.size(), 1u);
  const fs::path cached = cache_ / files[0];
  const auto size = fs::file_size(cached);
  fs::resize_file(cached, size / 2);
  // A process id that cannot exist (above pid_max) marks the temporary as stale.
  std::ofstream(cache_ / ("." + files[0] + ".tmp999999999-123")) << "partial";
  const fs::path stats = dir_ / "s.json";
  const ProcessResult r = run({"render", model_, "-o", (dir_ / "o.png").string(), "--size", "64x48", "--stats",
                               stats.string(), "--cache-dir", cache_.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(stats);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("cache unreadable"), std::string::npos) << text;
  EXPECT_NE(text.find("truncated"), std::string::npos) << text;
  // The progressive mesh is rebuilt in place, the temporary is gone; the render also cached
  // its intersection lines (a .lix file beside it).
  auto after = filesIn(cache_);
  std::erase_if(after, [](const std::string& f) { return f.size() > 4 && f.substr(f.size() - 4) == ".lix"; });
  EXPECT_EQ(after, files);
  EXPECT_EQ(fs::file_size(cached), size);
  EXPECT_TRUE(loadPm(cached).ok());
}

}  // namespace
}  // namespace lodline
