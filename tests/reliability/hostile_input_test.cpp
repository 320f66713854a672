// Hostile input through every command that reads a model (docs/reliability.md). Each hostile
// file is run through each command as its own process, and:
//  - a malformed file (empty, header only, NaN/Inf/huge coordinates, bad indices, faces of
//    0-2 vertices, counts claiming 2^31 elements, truncated, random bytes, no faces, not a
//    regular file, unreadable) is refused: exit 1, exactly one line on stderr,
//    "lodline: FILE: problem", and nothing left in the output directory;
//  - the same for scene files and glTF (bad JSON, missing or broken meshes they name, a
//    cycle of includes, a glTF buffer that is a FIFO, accessors past their buffers) through
//    the commands that take scenes;
//  - a valid but degenerate mesh (a 1000-vertex face, non-manifold edges, duplicate and
//    zero-area faces, thousands of components) is drawn: exit 0, nothing on stderr, the
//    command's outputs and nothing else;
//  - either way no crash, no hang, and peak memory within a bound (without sanitizers the
//    address space is also capped at 2 GiB for refused files, so an attempt to allocate what
//    a count claims fails the test rather than passing unnoticed).
// Under the sanitizers refused files go through `render` only (see the loop below).
//
// Adding a command is one entry in commands() below.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <sys/stat.h>
#include <unistd.h>

#include "io/generate.h"
#include "io/load_mesh.h"
#include "run_process.h"
#include "test_util.h"

namespace lodline {
namespace {

namespace fs = std::filesystem;

// ---- the commands ----

struct Paths {
  std::string model;     ///< the hostile file
  fs::path out;          ///< empty directory for the command's outputs
  fs::path cache;        ///< progressive-mesh cache directory
  std::string other;     ///< a valid model (for commands that take two)
};

struct CommandSpec {
  std::string name;
  /// Arguments after `lodline`.
  std::function<std::vector<std::string>(const Paths&)> args;
  /// What it leaves in `out` when it succeeds (file names; '*' matches any run of characters).
  std::vector<std::string> outputs;
  /// Whether it prints nothing on stderr when it succeeds (bench reports progress there).
  bool quiet = true;
  /// Whether it takes scene files (.json, .gltf, .glb) where it takes a mesh.
  bool scenes = true;
};

const std::vector<CommandSpec>& commands() {
  static const std::vector<CommandSpec> table = {
      {"render",
       [](const Paths& p) {
         return std::vector<std::string>{"render", p.model, "-o", (p.out / "o.png").string(), "--svg",
                                         (p.out / "o.svg").string(), "--stats", (p.out / "o.json").string(),
                                         "--size", "64x48", "--msaa", "1", "--cache-dir", p.cache.string()};
       },
       {"o.png", "o.svg", "o.json"}},
      {"capture",
       [](const Paths& p) {
         return std::vector<std::string>{"capture", p.model, "--size", "64x48", "--msaa", "1", "--duration", "0.2",
                                         "--fps", "10", "-o", (p.out / "o.mp4").string(), "--metrics",
                                         (p.out / "m.csv").string(), "--cache-dir", p.cache.string()};
       },
       {"o.mp4", "m.csv"}},
      {"build",  // into the cache: `out` is the cache directory
       [](const Paths& p) { return std::vector<std::string>{"build", p.model, "--cache-dir", p.out.string()}; },
       {"*.lpm"}},
      {"build-o",
       [](const Paths& p) { return std::vector<std::string>{"build", p.model, "-o", (p.out / "o.lpm").string()}; },
       {"o.lpm"}, true, false},
      {"simplify",
       [](const Paths& p) {
         return std::vector<std::string>{"simplify", p.model, "--max-error", "1%", "-o", (p.out / "s.off").string()};
       },
       {"s.off"}, true, false},
      {"compare", [](const Paths& p) { return std::vector<std::string>{"compare", p.model, p.other}; }, {}, true, false},
      {"bench",
       [](const Paths& p) {
         return std::vector<std::string>{"bench", "walkthrough", p.model, "--frames", "2", "--modes", "none,cluster,pm",
                                         "--size", "64x48", "--msaa", "1", "--cache-dir", p.cache.string()};
       },
       {},
       false},
      {"compare-second", [](const Paths& p) { return std::vector<std::string>{"compare", p.other, p.model}; }, {}, true,
       false},
      {"sweep",  // reads every model before it writes anything
       [](const Paths& p) {
         return std::vector<std::string>{"sweep", p.model, "--vary", "target-area=8,16", "-o", (p.out / "sweep").string(),
                                         "--", "--size", "64x48", "--msaa", "1", "--cache-dir", p.cache.string()};
       },
       {"sweep"}},
  };
  return table;
}

// `name` matches `pattern` where '*' stands for any run of characters.
bool matches(const std::string& name, const std::string& pattern) {
  const size_t star = pattern.find('*');
  if (star == std::string::npos) return name == pattern;
  const std::string head = pattern.substr(0, star), tail = pattern.substr(star + 1);
  return name.size() >= head.size() + tail.size() && name.compare(0, head.size(), head) == 0 &&
         name.compare(name.size() - tail.size(), tail.size(), tail) == 0;
}

// ---- the files ----

enum class Expect { kRefused, kDrawn };

struct HostileFile {
  std::string name;  ///< for messages
  std::string file;  ///< file name; the extension picks the reader
  std::function<void(const fs::path&)> make;
  Expect expect = Expect::kRefused;
  std::string problem;   ///< part of the error line (refused)
  bool unreadable = false;
};

bool isScene(const HostileFile& h) {
  const std::string ext = fs::path(h.file).extension().string();
  return ext == ".json" || ext == ".gltf" || ext == ".glb";
}

void write(const fs::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}
std::function<void(const fs::path&)> text(std::string bytes) {
  return [bytes](const fs::path& p) { write(p, bytes); };
}
template <class T>
void put(std::string& s, T v) {
  s.append(reinterpret_cast<const char*>(&v), sizeof(T));
}
std::string randomBytes(uint32_t seed, size_t n) {
  std::mt19937 rng(seed);
  std::string s(n, '\0');
  for (char& c : s) c = static_cast<char>(rng());
  return s;
}

// Writes `sibling` (a mesh a scene names) next to the scene, then the scene.
std::function<void(const fs::path&)> withSibling(std::string name, std::string sibling, std::string scene) {
  return [=](const fs::path& p) {
    write(p.parent_path() / name, sibling);
    write(p, scene);
  };
}
// A one-cube .gltf whose JSON `edit` changes (it may also make files next to it).
std::function<void(const fs::path&)> gltfEdited(std::function<void(nlohmann::json&, const fs::path&)> edit) {
  return [edit](const fs::path& p) {
    test::writeGltf(p, {test::gltfCube()});
    nlohmann::json j = nlohmann::json::parse(std::ifstream(p));
    edit(j, p.parent_path());
    write(p, j.dump());
  };
}

std::vector<HostileFile> hostileFiles() {
  const std::string torus = test::offText(makeTorus(1.0f, 0.3f, 16, 8));
  const std::string tri = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n";
  std::string ply_bin_head =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uint int vertex_indices\nend_header\n";
  std::string ply_huge_list = ply_bin_head;
  for (float c : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) put(ply_huge_list, c);
  put<uint32_t>(ply_huge_list, 0x80000000u);
  std::string ply_nan = ply_bin_head;
  for (float c : {0.f, 0.f, 0.f, std::nanf(""), 0.f, 0.f, 0.f, 1.f, 0.f}) put(ply_nan, c);
  put<uint32_t>(ply_nan, 3);
  for (int32_t i : {0, 1, 2}) put(ply_nan, i);
  std::string off_bin = "OFF BINARY\n";
  for (uint32_t c : {0x80000000u, 1u, 0u}) put(off_bin, c);
  std::string stl_huge(80, ' ');
  put<uint32_t>(stl_huge, 0x80000000u);
  stl_huge.append(50, '\0');
  std::string stl_cut(80, ' ');
  put<uint32_t>(stl_cut, 12);
  stl_cut.append(300, '\0');
  // A disc with one 1000-vertex face.
  std::string disc = "OFF\n1000 1 0\n";
  for (int i = 0; i < 1000; ++i)
    disc.append(std::to_string(std::cos(2 * M_PI * i / 1000))).append(" ")
        .append(std::to_string(std::sin(2 * M_PI * i / 1000))).append(" 0\n");
  disc += "1000";
  for (int i = 0; i < 1000; ++i) disc.append(" ").append(std::to_string(i));
  disc += "\n";
  // Thousands of components: 3000 separate triangles on a grid.
  std::string soup = "OFF\n9000 3000 0\n";
  for (int i = 0; i < 3000; ++i) {
    const float x = static_cast<float>(i % 60), y = static_cast<float>(i / 60);
    soup.append(std::to_string(x)).append(" ").append(std::to_string(y)).append(" 0\n");
    soup.append(std::to_string(x + 0.8f)).append(" ").append(std::to_string(y)).append(" 0.1\n");
    soup.append(std::to_string(x)).append(" ").append(std::to_string(y + 0.8f)).append(" 0.2\n");
  }
  for (int i = 0; i < 3000; ++i)
    soup.append("3 ").append(std::to_string(3 * i)).append(" ").append(std::to_string(3 * i + 1)).append(" ")
        .append(std::to_string(3 * i + 2)).append("\n");
  // The torus with three faces on one of its edges, duplicated faces and zero-area faces.
  TriMesh t = makeTorus(1.0f, 0.3f, 16, 8);
  TriMesh nm = t;
  nm.positions.push_back({0.0f, 2.0f, 0.0f});
  nm.faces.push_back({t.faces[0][0], t.faces[0][1], static_cast<uint32_t>(nm.positions.size() - 1)});
  TriMesh dup = t;
  for (size_t f = 0; f < 20; ++f) dup.faces.push_back(t.faces[f]);
  TriMesh flat = t;
  const uint32_t base = static_cast<uint32_t>(flat.positions.size());
  flat.positions.push_back({3, 0, 0});
  flat.positions.push_back({4, 0, 0});
  flat.positions.push_back({5, 0, 0});  // collinear
  flat.faces.push_back({base, base + 1, base + 2});
  flat.faces.push_back({t.faces[3][0], t.faces[3][1], t.faces[3][1] == 0 ? 1u : 0u});

  std::vector<HostileFile> files = {
      {"empty OFF", "e.off", text(""), Expect::kRefused, "empty file"},
      {"empty OBJ", "e.obj", text(""), Expect::kRefused, "empty file"},
      {"empty PLY", "e.ply", text(""), Expect::kRefused, "empty file"},
      {"empty STL", "e.stl", text(""), Expect::kRefused, "empty file"},
      {"OFF header only", "h.off", text("OFF\n"), Expect::kRefused, "malformed OFF header"},
      {"PLY header only", "h.ply", text("ply\nformat ascii 1.0\n"), Expect::kRefused, "no end_header"},
      {"STL header only", "h.stl", text("solid x\nendsolid x\n"), Expect::kRefused, "no vertices"},
      {"OBJ comment only", "h.obj", text("# nothing\n"), Expect::kRefused, "no vertices"},
      {"NaN coordinate", "nan.off", text("OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n"), Expect::kRefused, "non-finite"},
      {"Inf coordinate", "inf.obj", text("v 0 0 0\nv 1 inf 0\nv 0 1 0\nf 1 2 3\n"), Expect::kRefused, "non-finite"},
      {"NaN in binary PLY", "nan.ply", text(ply_nan), Expect::kRefused, "non-finite"},
      {"1e38 coordinates", "big.off", text("OFF\n3 1 0\n1e38 0 0\n-1e38 0 0\n0 1e38 0\n3 0 1 2\n"),
       Expect::kRefused, "too large"},
      {"negative index", "neg.off", text(tri + "3 0 -1 2\n"), Expect::kRefused, "references vertex -1"},
      {"index out of range", "range.obj", text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"), Expect::kRefused,
       "out of range"},
      {"face of 0 vertices", "f0.off", text(tri + "0\n"), Expect::kRefused, "has 0 vertices"},
      {"face of 1 vertex", "f1.off", text(tri + "1 0\n"), Expect::kRefused, "has 1 vertices"},
      {"face of 2 vertices", "f2.off", text(tri + "2 0 1\n"), Expect::kRefused, "has 2 vertices"},
      {"2^31 vertices (OFF)", "cv.off", text("OFF\n2147483648 1 0\n0 0 0\n"), Expect::kRefused, "truncated"},
      {"2^31 faces (OFF)", "cf.off", text("OFF\n3 2147483648 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
       Expect::kRefused, "truncated"},
      {"2^31 face vertices (OFF)", "ck.off", text(tri + "2147483648 0 1 2\n"), Expect::kRefused, "more than the rest"},
      {"2^31 vertices (binary OFF)", "cb.off", text(off_bin), Expect::kRefused, "truncated"},
      {"2^31 vertices (PLY)", "cv.ply",
       text("ply\nformat ascii 1.0\nelement vertex 2147483648\nproperty float x\nproperty float y\n"
            "property float z\nend_header\n0 0 0\n"),
       Expect::kRefused, "truncated"},
      {"2^31 list items (PLY)", "cl.ply", text(ply_huge_list), Expect::kRefused, "more than the rest"},
      {"2^31 triangles (STL)", "ct.stl", text(stl_huge), Expect::kRefused, "2147483648 triangles"},
      {"truncated OFF", "t.off", text(torus.substr(0, torus.size() / 2)), Expect::kRefused, "truncated"},
      {"truncated binary STL", "t.stl", text(stl_cut), Expect::kRefused, "not an STL file"},
      {"truncated OBJ", "t.obj", text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2"), Expect::kRefused, "face has 2 vertices"},
      {"random bytes OFF", "r.off", text(randomBytes(1, 3000)), Expect::kRefused, ""},
      {"random bytes OBJ", "r.obj", text(randomBytes(2, 3000)), Expect::kRefused, ""},
      {"random bytes PLY", "r.ply", text(randomBytes(3, 3000)), Expect::kRefused, ""},
      {"random bytes STL", "r.stl", text(randomBytes(4, 3000)), Expect::kRefused, ""},
      {"isolated vertices only", "iso.off", text("OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n"), Expect::kRefused, "no faces"},
      {"every face repeats a vertex", "rep.off", text(tri + "3 0 0 1\n"), Expect::kRefused, "repeats a vertex"},
      {"unsupported extension", "m.xyz", text(torus), Expect::kRefused, "unsupported file type"},
      {"directory", "dir.off", [](const fs::path& p) { fs::create_directory(p); }, Expect::kRefused, "is a directory"},
      {"FIFO", "fifo.off", [](const fs::path& p) { mkfifo(p.c_str(), 0666); }, Expect::kRefused,
       "not a regular file"},
      {"unreadable file", "locked.off", text(torus), Expect::kRefused, "Permission denied", true},
      // Scene files (docs/scenes.md) and glTF: their own errors name the scene file, and a
      // broken mesh a scene names is reported with the scene entry that names it.
      {"empty scene", "e.json", text(""), Expect::kRefused, "invalid JSON"},
      {"random bytes scene", "r.json", text(randomBytes(5, 3000)), Expect::kRefused, "invalid JSON"},
      {"scene without objects", "none.json", text(R"({"objects": []})"), Expect::kRefused, "non-empty array"},
      {"scene naming a missing mesh", "miss.json", text(R"({"objects": [{"mesh": "nowhere.off"}]})"),
       Expect::kRefused, "no such file"},
      {"scene with a negative scale", "neg.json", withSibling("m.off", torus, R"({"objects": [{"mesh": "m.off", "scale": -1}]})"),
       Expect::kRefused, "objects[0].scale: must be > 0"},
      {"scene with a control character in a key", "key.json", text("{\"objects\": [], \"a\\u0007\\n\": 1}"),
       Expect::kRefused, "unknown key \"a??\""},
      {"scene including itself", "self.json", text(R"({"objects": [{"scene": "self.json"}]})"), Expect::kRefused,
       "include cycle"},
      {"scene naming a NaN mesh", "nanmesh.json",
       withSibling("nan.off", "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n", R"({"objects": [{"mesh": "nan.off"}]})"),
       Expect::kRefused, "objects[0].mesh: "},
      {"scene scaled past 1e18", "huge.json",
       withSibling("m.off", torus, R"({"objects": [{"mesh": "m.off", "scale": [1, 1e30, 1e30]}]})"), Expect::kRefused,
       "too large"},
      {"empty glTF", "e.gltf", text(""), Expect::kRefused, "cannot read glTF"},
      {"random bytes glTF", "r.gltf", text(randomBytes(6, 3000)), Expect::kRefused, "cannot read glTF"},
      {"random bytes GLB", "r.glb", text("glTF" + randomBytes(7, 3000)), Expect::kRefused, "cannot read glTF"},
      {"glTF buffer that is a FIFO", "fifo.gltf", gltfEdited([](nlohmann::json& j, const fs::path& dir) {
         mkfifo((dir / "buffer.bin").c_str(), 0666);
         j["buffers"][0]["uri"] = "buffer.bin";
       }), Expect::kRefused, "not a regular file"},
      {"glTF accessor past its buffer", "count.gltf",
       gltfEdited([](nlohmann::json& j, const fs::path&) { j["accessors"][1]["count"] = 1u << 30; }), Expect::kRefused,
       "reads past the end"},
      {"glTF node that is its own child", "cycle.gltf",
       gltfEdited([](nlohmann::json& j, const fs::path&) { j["nodes"][0]["children"] = {0}; }), Expect::kRefused,
       "not a tree"},
      {"face of 1000 vertices", "disc.off", text(disc), Expect::kDrawn},
      {"non-manifold edge", "nm.off", text(test::offText(nm)), Expect::kDrawn},
      {"duplicate faces", "dup.off", text(test::offText(dup)), Expect::kDrawn},
      {"zero-area faces", "flat.off", text(test::offText(flat)), Expect::kDrawn},
      {"thousands of components", "soup.off", text(soup), Expect::kDrawn},
      {"scene of two coincident objects", "twice.json",
       withSibling("m.off", torus, R"({"objects": [{"mesh": "m.off"}, {"mesh": "m.off", "name": "m"}]})"), Expect::kDrawn},
      {"glTF of one cube", "cube.glb", [](const fs::path& p) { test::writeGltf(p, {test::gltfCube()}); }, Expect::kDrawn},
  };
  return files;
}

// Peak resident memory allowed per run, KiB: a hostile file may cost no more than a valid
// model of its size. Sanitizer builds carry shadow memory and quarantine.
long memoryBoundKb(Expect expect) {
  const long base = expect == Expect::kRefused ? 200 * 1024 : 600 * 1024;
  return test::sanitizerBuild() ? 4 * base : base;
}

bool canDropPrivileges() { return geteuid() != 0 || std::system("command -v setpriv >/dev/null 2>&1") == 0; }

class HostileInput : public ::testing::TestWithParam<std::string> {};

TEST_P(HostileInput, EveryFileIsRefusedCleanlyOrDrawn) {
  const CommandSpec* cmd = nullptr;
  for (const CommandSpec& c : commands())
    if (c.name == GetParam()) cmd = &c;
  ASSERT_NE(cmd, nullptr);
  const bool root = geteuid() == 0;
  if (cmd->name == "capture" && std::system("command -v ffmpeg >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "ffmpeg not installed";
  int tried = 0;
  for (const HostileFile& h : hostileFiles()) {
    // A refused file stops in loadMesh, the same code for every command, so the sanitizer
    // build (slower to start) runs refused files through render only; the other build runs
    // every file through every command, and every build runs the drawn ones everywhere.
    if (test::sanitizerBuild() && h.expect == Expect::kRefused && cmd->name != "render") continue;
    if (isScene(h) && !cmd->scenes) continue;
    SCOPED_TRACE(cmd->name + " on " + h.name);
    test::TempDir dir;
    fs::permissions(dir.path(), fs::perms::all);  // reachable when the command runs as nobody
    const fs::path model = dir / h.file;
    h.make(model);
    Paths p{model.string(), dir / "out", dir / "cache", (dir / "other.off").string()};
    fs::create_directories(p.out);
    fs::create_directories(p.cache);
    fs::permissions(p.out, fs::perms::all);
    fs::permissions(p.cache, fs::perms::all);
    ASSERT_TRUE(saveOff(p.other, makeIcoSphere(1.0f, 2)).ok());
    std::vector<std::string> argv = test::lodlineArgs(cmd->args(p));
    if (h.unreadable) {
      fs::permissions(model, fs::perms::none);
      // root reads any file: run the command as nobody to see what a user would see.
      if (root) {
        if (!canDropPrivileges()) {
          std::cout << "[ SKIPPED  ] " << h.name << ": running as root without setpriv\n";
          continue;
        }
        argv.insert(argv.begin(), {"setpriv", "--reuid=65534", "--regid=65534", "--clear-groups", "--"});
      }
    }
    test::ProcessOptions opt;
    opt.env = {"XDG_CACHE_HOME=" + p.cache.string(), "HOME=" + dir.path().string()};
    if (h.expect == Expect::kRefused) opt.address_space_limit = 2ull << 30;
    opt.timeout_s = 60.0;
    const test::ProcessResult r = test::runProcess(argv, opt);
    ++tried;
    if (std::getenv("LODLINE_TEST_VERBOSE"))  // one line per run, for docs/reliability.md
      std::cout << cmd->name << " | " << h.name << " | " << r.describe() << " | " << r.peak_rss_kb << " KiB | "
                << (r.err.empty() ? std::string("-") : test::linesOf(r.err).front().substr(0, 160)) << "\n";
    if (r.timed_out || r.signal != 0) {
      ADD_FAILURE() << (r.timed_out ? "hung: " : "crashed: ") << r.describe() << "\n" << r.err;
      continue;
    }
    EXPECT_LE(r.peak_rss_kb, memoryBoundKb(h.expect)) << "peak RSS " << r.peak_rss_kb << " KiB";
    std::vector<std::string> left;
    for (const auto& e : fs::directory_iterator(p.out)) left.push_back(e.path().filename().string());
    if (h.expect == Expect::kRefused) {
      EXPECT_EQ(r.exit_code, 1) << r.err;
      const auto lines = test::linesOf(r.err);
      if (lines.size() != 1) {
        ADD_FAILURE() << lines.size() << " lines on stderr, expected one:\n" << r.err.substr(0, 2000);
        continue;
      }
      EXPECT_EQ(lines[0].rfind("lodline: ", 0), 0u) << lines[0];
      EXPECT_NE(lines[0].find(model.string()), std::string::npos) << lines[0];
      EXPECT_NE(lines[0].find(h.problem), std::string::npos) << lines[0];
      EXPECT_TRUE(left.empty()) << "left behind: " << left.front();
    } else {
      EXPECT_EQ(r.exit_code, 0) << r.err;
      if (cmd->quiet) {
        EXPECT_EQ(r.err, "");
      }
      EXPECT_EQ(left.size(), cmd->outputs.size());
      for (const std::string& f : left) {
        bool expected = false;
        for (const std::string& pattern : cmd->outputs) expected |= matches(f, pattern);
        EXPECT_TRUE(expected) << "unexpected file left: " << f;
      }
    }
  }
  EXPECT_GE(tried, test::sanitizerBuild() && cmd->name != "render" ? 5 : 40);
}

std::vector<std::string> commandNames() {
  std::vector<std::string> names;
  for (const CommandSpec& c : commands()) names.push_back(c.name);
  return names;
}

INSTANTIATE_TEST_SUITE_P(Commands, HostileInput, ::testing::ValuesIn(commandNames()),
                         [](const ::testing::TestParamInfo<std::string>& param) {
                           std::string n = param.param;
                           for (char& c : n)
                             if (c == '-') c = '_';
                           return n;
                         });

}  // namespace
}  // namespace lodline
