// Progressive mesh file and cache: round trip, and every kind of damaged or stale cache is
// detected (an error from loadPm, a rebuild from loadOrBuildPm), never a crash.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <random>

#include "io/load_mesh.h"
#include "pm/pm_file.h"
#include "pm/pm_test_meshes.h"
#include "pm/progressive_mesh.h"
#include "test_util.h"

namespace lodline {
namespace {

std::string readAll(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
void writeAll(const std::filesystem::path& p, const std::string& s) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out.write(s.data(), static_cast<std::streamsize>(s.size()));
}

void expectSame(const ProgressiveMesh& a, const ProgressiveMesh& b) {
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.faces, b.faces);
  EXPECT_EQ(a.vertex_flags, b.vertex_flags);
  ASSERT_EQ(a.splits.size(), b.splits.size());
  if (!a.splits.empty()) {  // data() of an empty vector may be null: no memcmp then
    EXPECT_EQ(0, std::memcmp(a.splits.data(), b.splits.data(), a.splits.size() * sizeof(VertexSplit)));
  }
  EXPECT_EQ(a.base_faces, b.base_faces);
  EXPECT_EQ(a.base_corners, b.base_corners);
  EXPECT_EQ(a.base_neighbors, b.base_neighbors);
  EXPECT_EQ(a.content_hash, b.content_hash);
  EXPECT_EQ(a.params_hash, b.params_hash);
  EXPECT_EQ(a.parent, b.parent);
  EXPECT_EQ(a.origin, b.origin);
  EXPECT_EQ(a.roots, b.roots);
}

class PmFile : public ::testing::Test {
 protected:
  void SetUp() override {
    mesh_ = makeTorus(1.0f, 0.3f, 40, 20);
    auto pm = buildProgressiveMesh(mesh_);
    ASSERT_TRUE(pm.ok());
    pm_ = std::move(pm).value();
    path_ = dir_ / "model.lpm";
    ASSERT_TRUE(savePm(path_, pm_).ok());
    bytes_ = readAll(path_);
  }
  TriMesh mesh_;
  ProgressiveMesh pm_;
  test::TempDir dir_;
  std::filesystem::path path_;
  std::string bytes_;
};

TEST_F(PmFile, RoundTrip) {
  auto loaded = loadPm(path_);
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  expectSame(pm_, *loaded);
  // Compact: well under 100 bytes per face.
  EXPECT_LT(bytes_.size(), 100 * mesh_.faceCount());
  // No temporary file left behind.
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir_.path())) ++files, (void)e;
  EXPECT_EQ(files, 1);
}

TEST_F(PmFile, MissingFileIsAnError) {
  auto r = loadPm(dir_ / "nope.lpm");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("nope.lpm"), std::string::npos);
}

TEST_F(PmFile, WrongMagicVersionTruncationChecksum) {
  auto expectError = [&](const std::string& bytes, const std::string& what) {
    writeAll(path_, bytes);
    auto r = loadPm(path_);
    ASSERT_FALSE(r.ok()) << what;
    EXPECT_NE(r.error().message.find(what), std::string::npos) << r.error().message;
    EXPECT_NE(r.error().message.find("model.lpm"), std::string::npos) << r.error().message;
  };
  std::string b = bytes_;
  b[0] = 'X';
  expectError(b, "magic");
  b = bytes_;
  b[8] = 99;  // version
  expectError(b, "version");
  expectError(bytes_.substr(0, 30), "truncated");
  expectError(bytes_.substr(0, bytes_.size() - 7), "truncated");
  expectError(bytes_ + "junk", "trailing");
  b = bytes_;
  b[b.size() / 2] ^= 0x10;  // one flipped bit in the payload
  expectError(b, "checksum");
  b = bytes_;
  b[12] ^= 1;  // vertex count in the header: sizes no longer match
  expectError(b, "corrupt header");
  expectError("", "truncated");
}

TEST_F(PmFile, RandomCorruptionNeverCrashes) {
  std::mt19937 rng(11);
  for (int i = 0; i < 200; ++i) {
    std::string b = bytes_;
    const int flips = 1 + static_cast<int>(rng() % 8);
    for (int k = 0; k < flips; ++k) b[rng() % b.size()] = static_cast<char>(rng());
    if (i % 3 == 0) b.resize(rng() % b.size());
    writeAll(path_, b);
    auto r = loadPm(path_);
    if (b != bytes_) {
      EXPECT_FALSE(r.ok());
    }
  }
}

TEST_F(PmFile, IndicesOutOfRangeAreRejectedEvenWithAValidChecksum) {
  // A structurally bad file that passes the checksum (as a buggy or hostile writer could make).
  ProgressiveMesh bad = pm_;
  bad.splits[3].fl = bad.faceCount() + 5;
  ASSERT_TRUE(savePm(path_, bad).ok());
  auto r = loadPm(path_);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("split 3"), std::string::npos) << r.error().message;
  bad = pm_;
  bad.base_corners[0][1] = bad.nodeCount() + 1;
  ASSERT_TRUE(savePm(path_, bad).ok());
  EXPECT_FALSE(loadPm(path_).ok());
  bad = pm_;
  bad.splits[5].vt = bad.splits[5].vu;
  ASSERT_TRUE(savePm(path_, bad).ok());
  EXPECT_FALSE(loadPm(path_).ok());
  bad = pm_;
  bad.faces[2][0] = 1u << 30;
  ASSERT_TRUE(savePm(path_, bad).ok());
  EXPECT_FALSE(loadPm(path_).ok());
}

// Found by fuzzing (tests/fuzz/fuzz_pm_cache.cpp): a file that passes the checksum and every
// index check but whose records do not describe a valid refinement crashed the selective
// refinement (AdaptiveMesh::exportCompact read a face corner without a slot). loadPm replays
// the hierarchy and refuses such files; loadOrBuildPm then rebuilds the cache.
TEST_F(PmFile, ValidChecksumButInconsistentHierarchyIsRefusedAndHealed) {
  ASSERT_GT(pm_.splits.size(), 10u);
  std::vector<std::pair<std::string, ProgressiveMesh>> damaged;
  auto add = [&](const std::string& what, auto&& change) {
    ProgressiveMesh p = pm_;
    change(p);
    damaged.emplace_back(what, std::move(p));
  };
  add("neighbour faces swapped", [](ProgressiveMesh& p) { std::swap(p.splits[4].fn[0], p.splits[4].fn[1]); });
  add("children swapped", [](ProgressiveMesh& p) { std::swap(p.splits[7].vt, p.splits[7].vu); });
  add("created faces swapped", [](ProgressiveMesh& p) { std::swap(p.splits[2].fl, p.splits[2].fr); });
  add("faces of two splits exchanged", [](ProgressiveMesh& p) { std::swap(p.splits[3].fl, p.splits[9].fl); });
  add("base neighbour wrong", [](ProgressiveMesh& p) { std::swap(p.base_neighbors[0][0], p.base_neighbors[0][1]); });
  add("base corners rotated against neighbours", [](ProgressiveMesh& p) {
    auto& c = p.base_corners[1];
    std::rotate(c.begin(), c.begin() + 1, c.end());
  });
  add("input face changed", [](ProgressiveMesh& p) { std::swap(p.faces[5][0], p.faces[5][1]); });
  const uint64_t hash = meshContentHash(mesh_);
  const auto cache = dir_ / "cache";
  for (auto& [what, bad] : damaged) {
    SCOPED_TRACE(what);
    bad.content_hash = hash;
    ASSERT_TRUE(savePm(path_, bad).ok());  // written with a valid checksum
    auto r = loadPm(path_);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("model.lpm"), std::string::npos) << r.error().message;
    // In the cache: detected, rebuilt and rewritten.
    std::filesystem::create_directories(cache);
    ASSERT_TRUE(savePm(pmCachePath(cache, hash), bad).ok());
    std::string note;
    auto healed = loadOrBuildPm(mesh_, hash, cache, {}, {}, &note);
    ASSERT_TRUE(healed.ok());
    EXPECT_NE(note.find("unreadable"), std::string::npos) << note;
    EXPECT_TRUE(loadPm(pmCachePath(cache, hash)).ok());
  }
}

// A cache file whose header names this model but whose arrays are another model's (e.g. the
// header copied over) is stale, not used.
TEST_F(PmFile, CacheWithAnotherModelsArraysIsStale) {
  TriMesh moved = mesh_;
  moved.positions[3].y += 0.25f;
  auto other = buildProgressiveMesh(moved);
  ASSERT_TRUE(other.ok());
  const uint64_t hash = meshContentHash(mesh_);
  other->content_hash = hash;  // the header claims this model
  const auto cache = dir_ / "cache";
  std::filesystem::create_directories(cache);
  ASSERT_TRUE(savePm(pmCachePath(cache, hash), *other).ok());
  std::string note;
  auto r = loadOrBuildPm(mesh_, hash, cache, {}, {}, &note);
  ASSERT_TRUE(r.ok());
  EXPECT_NE(note.find("stale"), std::string::npos) << note;
  EXPECT_EQ(r->positions, mesh_.positions);
}

// Found by fuzzing: empty arrays were copied with memcpy from a null pointer (undefined
// behaviour, reported by UBSan). A mesh too small to simplify has no split at all.
TEST(PmFileSmall, NoSplitsRoundTrip) {
  TriMesh tri;
  tri.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  tri.faces = {{0, 1, 2}};
  auto pm = buildProgressiveMesh(tri);
  ASSERT_TRUE(pm.ok());
  EXPECT_TRUE(pm->splits.empty());
  test::TempDir dir;
  ASSERT_TRUE(savePm(dir / "t.lpm", *pm).ok());
  auto back = loadPm(dir / "t.lpm");
  ASSERT_TRUE(back.ok()) << back.error().message;
  expectSame(*pm, *back);
}

// The replay accepts every genuine progressive mesh: those of all CGAL demo meshes lodline
// reads (up to 200 KiB) survive save and load.
TEST(PmFileSmall, GenuineCachesOfTheCgalDemoMeshesLoad) {
  const auto meshes = test::dataMesh("");
  if (!std::filesystem::exists(meshes / "armadillo.off")) GTEST_SKIP() << "data/meshes missing (run scripts/setup.sh)";
  test::TempDir dir;
  int loaded = 0;
  for (const auto& e : std::filesystem::directory_iterator(meshes)) {
    if (e.path().extension() != ".off" || e.file_size() > 200 * 1024) continue;
    auto mesh = loadMesh(e.path());
    if (!mesh) continue;
    auto pm = buildProgressiveMesh(*mesh);
    ASSERT_TRUE(pm.ok()) << e.path();
    ASSERT_TRUE(savePm(dir / "m.lpm", *pm).ok());
    auto back = loadPm(dir / "m.lpm");
    EXPECT_TRUE(back.ok()) << e.path() << ": " << back.error().message;
    ++loaded;
  }
  EXPECT_GT(loaded, 100);
}

TEST_F(PmFile, SaveToMissingDirectoryIsAnError) {
  auto st = savePm(dir_ / "no" / "such" / "dir" / "x.lpm", pm_);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.error().message.find("x.lpm"), std::string::npos) << st.error().message;
}

TEST_F(PmFile, CacheBuildsLoadsAndRebuildsWhenStaleOrCorrupt) {
  const auto cache = dir_ / "cache";
  const uint64_t hash = meshContentHash(mesh_);
  std::string note;
  int progress_calls = 0;
  auto first = loadOrBuildPm(mesh_, hash, cache, {}, [&](float) { ++progress_calls; }, &note);
  ASSERT_TRUE(first.ok());
  EXPECT_NE(note.find("rebuilt"), std::string::npos) << note;
  EXPECT_GT(progress_calls, 0);
  const auto file = pmCachePath(cache, hash);
  ASSERT_TRUE(std::filesystem::exists(file));

  progress_calls = 0;
  auto second = loadOrBuildPm(mesh_, hash, cache, {}, [&](float) { ++progress_calls; }, &note);
  ASSERT_TRUE(second.ok());
  EXPECT_NE(note.find("loaded"), std::string::npos) << note;
  EXPECT_EQ(progress_calls, 0);
  expectSame(*first, *second);

  // Corrupt: detected, rebuilt, rewritten.
  std::string b = readAll(file);
  b[b.size() - 3] ^= 0x55;
  writeAll(file, b);
  auto third = loadOrBuildPm(mesh_, hash, cache, {}, {}, &note);
  ASSERT_TRUE(third.ok());
  EXPECT_NE(note.find("checksum"), std::string::npos) << note;
  expectSame(*first, *third);
  EXPECT_TRUE(loadPm(file).ok());

  // Truncated.
  writeAll(file, readAll(file).substr(0, 100));
  auto fourth = loadOrBuildPm(mesh_, hash, cache, {}, {}, &note);
  ASSERT_TRUE(fourth.ok());
  EXPECT_NE(note.find("truncated"), std::string::npos) << note;

  // Stale: other build parameters (same file name, different params hash).
  PmBuildParams other;
  other.max_valence = 16;
  auto fifth = loadOrBuildPm(mesh_, hash, cache, other, {}, &note);
  ASSERT_TRUE(fifth.ok());
  EXPECT_NE(note.find("stale"), std::string::npos) << note;
  EXPECT_EQ(fifth->params_hash, buildParamsHash(other));

  // Stale: a different model stored under this key.
  TriMesh moved = mesh_;
  moved.positions[0].x += 0.01f;
  auto other_pm = buildProgressiveMesh(moved);
  ASSERT_TRUE(other_pm.ok());
  ASSERT_TRUE(savePm(file, *other_pm).ok());
  auto sixth = loadOrBuildPm(mesh_, hash, cache, {}, {}, &note);
  ASSERT_TRUE(sixth.ok());
  EXPECT_NE(note.find("stale"), std::string::npos) << note;
  expectSame(*first, *sixth);
}

TEST_F(PmFile, UnwritableCacheStillReturnsTheMesh) {
  const auto blocker = dir_ / "file_not_dir";
  writeAll(blocker, "x");
  std::string note;
  auto r = loadOrBuildPm(mesh_, 42, blocker / "cache", {}, {}, &note);
  ASSERT_TRUE(r.ok());
  EXPECT_NE(note.find("could not write"), std::string::npos) << note;
}

}  // namespace
}  // namespace lodline
