#include <gtest/gtest.h>

#include <cstring>
#include <fstream>

#include <sys/stat.h>

#include "io/atomic_file.h"
#include "io/generate.h"
#include "io/image.h"
#include "io/load_mesh.h"
#include "test_util.h"

namespace lodline {
namespace {

using test::TempDir;

void writeText(const std::filesystem::path& p, const std::string& text) {
  std::ofstream(p, std::ios::binary) << text;
}

template <class T>
void put(std::string& s, T v) {
  s.append(reinterpret_cast<const char*>(&v), sizeof(T));
}

// A unit square as two triangles (OFF/PLY/STL) or one quad (OBJ).
constexpr const char* kSquareOff = "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";

TEST(LoadMesh, Off) {
  TempDir dir;
  writeText(dir / "sq.off", kSquareOff);
  auto m = loadMesh(dir / "sq.off");
  ASSERT_TRUE(m.ok()) << m.error().message;
  EXPECT_EQ(m->vertexCount(), 4u);
  EXPECT_EQ(m->faceCount(), 2u);
}

TEST(LoadMesh, ObjQuadIsTriangulated) {
  TempDir dir;
  writeText(dir / "sq.obj", "# square\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  auto m = loadMesh(dir / "sq.obj");
  ASSERT_TRUE(m.ok()) << m.error().message;
  EXPECT_EQ(m->vertexCount(), 4u);
  EXPECT_EQ(m->faceCount(), 2u);
  // Fan triangulation keeps the quad's orientation (+Z).
  std::vector<glm::vec3> n;
  computeFaceNormals(*m, n);
  for (const auto& fn : n) EXPECT_GT(fn.z, 0.99f);
}

TEST(LoadMesh, ObjLinesMarkSharpEdges) {
  TempDir dir;
  writeText(dir / "m.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\nl 1 2 3\nl -1 -4\n");
  auto m = loadMesh(dir / "m.obj");
  ASSERT_TRUE(m.ok()) << m.error().message;
  ASSERT_EQ(m->marked_edges.size(), 3u);
  EXPECT_EQ(m->marked_edges[0], (EdgeKey{0, 1}));
  EXPECT_EQ(m->marked_edges[1], (EdgeKey{1, 2}));
  EXPECT_EQ(m->marked_edges[2], (EdgeKey{3, 0}));
  writeText(dir / "bad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\nl 1 9\n");
  auto bad = loadMesh(dir / "bad.obj");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("line 5"), std::string::npos) << bad.error().message;
}

TEST(LoadMesh, PlyAscii) {
  TempDir dir;
  writeText(dir / "sq.ply",
            "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
            "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
            "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n");
  auto m = loadMesh(dir / "sq.ply");
  ASSERT_TRUE(m.ok()) << m.error().message;
  EXPECT_EQ(m->faceCount(), 2u);
}

TEST(LoadMesh, PlyBinary) {
  TempDir dir;
  std::string s =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n";
  const float v[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  for (auto& p : v)
    for (float c : p) put(s, c);
  for (auto f : {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{0, 2, 3}}) {
    put<uint8_t>(s, 3);
    for (int i : f) put(s, i);
  }
  writeText(dir / "sq.ply", s);
  auto m = loadMesh(dir / "sq.ply");
  ASSERT_TRUE(m.ok()) << m.error().message;
  EXPECT_EQ(m->vertexCount(), 4u);
  EXPECT_EQ(m->faceCount(), 2u);
}

TEST(LoadMesh, StlAsciiMergesVertices) {
  TempDir dir;
  writeText(dir / "sq.stl",
            "solid sq\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\n"
            "endloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 1 0\n"
            "vertex 0 1 0\nendloop\nendfacet\nendsolid sq\n");
  auto m = loadMesh(dir / "sq.stl");
  ASSERT_TRUE(m.ok()) << m.error().message;
  EXPECT_EQ(m->faceCount(), 2u);
  EXPECT_EQ(m->vertexCount(), 4u);
}

TEST(LoadMesh, StlBinary) {
  TempDir dir;
  std::string s(80, ' ');
  put<uint32_t>(s, 2);
  const float tris[2][3][3] = {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}, {{0, 0, 0}, {1, 1, 0}, {0, 1, 0}}};
  for (auto& t : tris) {
    for (float c : {0.0f, 0.0f, 1.0f}) put(s, c);
    for (auto& p : t)
      for (float c : p) put(s, c);
    put<uint16_t>(s, 0);
  }
  writeText(dir / "sq.stl", s);
  auto m = loadMesh(dir / "sq.stl");
  ASSERT_TRUE(m.ok()) << m.error().message;
  EXPECT_EQ(m->faceCount(), 2u);
  EXPECT_EQ(m->vertexCount(), 4u);
}

TEST(LoadMesh, CgalArmadillo) {
  const auto p = test::dataMesh("armadillo.off");
  if (p.empty()) GTEST_SKIP() << "data/meshes/armadillo.off missing (run scripts/setup.sh)";
  auto m = loadMesh(p);
  ASSERT_TRUE(m.ok()) << m.error().message;
  EXPECT_GT(m->faceCount(), 10000u);
}

// ---- bad input: one clear error naming the file, never a crash ----

void expectError(const std::filesystem::path& p, const std::string& fragment) {
  auto m = loadMesh(p);
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.error().message.find(p.string()), std::string::npos) << m.error().message;
  EXPECT_NE(m.error().message.find(fragment), std::string::npos) << m.error().message;
  EXPECT_EQ(m.error().message.find('\n'), std::string::npos) << "one line: " << m.error().message;
  EXPECT_EQ(m.error().exitCode(), 1);
}

TEST(LoadMeshBadInput, MissingFile) { expectError("/nonexistent/x.off", "no such file"); }

TEST(LoadMeshBadInput, Directory) {
  TempDir dir;
  std::filesystem::create_directory(dir / "d.off");
  expectError(dir / "d.off", "directory");
}

TEST(LoadMeshBadInput, WrongExtension) {
  TempDir dir;
  writeText(dir / "sq.xyz", kSquareOff);
  expectError(dir / "sq.xyz", "unsupported file type");
}

TEST(LoadMeshBadInput, EmptyFile) {
  TempDir dir;
  writeText(dir / "e.off", "");
  expectError(dir / "e.off", "empty");
}

TEST(LoadMeshBadInput, TruncatedOff) {
  TempDir dir;
  writeText(dir / "t.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n");
  expectError(dir / "t.off", "truncated");
}

TEST(LoadMeshBadInput, HostileHeaderCounts) {
  TempDir dir;
  writeText(dir / "h.off", "OFF\n2000000000 2000000000 0\n0 0 0\n");
  expectError(dir / "h.off", "truncated");
}

TEST(LoadMeshBadInput, NanCoordinate) {
  TempDir dir;
  writeText(dir / "n.off", "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n");
  auto m = loadMesh(dir / "n.off");
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.error().message.find("n.off"), std::string::npos);
}

TEST(LoadMeshBadInput, InfCoordinateObj) {
  TempDir dir;
  // OpenMesh's OBJ reader drops the unparsable vertex line, so the face's index is then out
  // of range; either way the load fails with the file named.
  writeText(dir / "i.obj", "v 0 0 0\nv inf 0 0\nv 0 1 0\nf 1 2 3\n");
  expectError(dir / "i.obj", "i.obj");
}

TEST(LoadMeshBadInput, IndexOutOfRange) {
  TempDir dir;
  writeText(dir / "r.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7      \n");
  expectError(dir / "r.off", "out of range");
}

TEST(LoadMeshBadInput, ZeroFaces) {
  TempDir dir;
  writeText(dir / "z.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n");
  expectError(dir / "z.off", "no faces");
}

TEST(LoadMeshBadInput, GarbageBytes) {
  TempDir dir;
  std::string junk(4096, '\0');
  for (size_t i = 0; i < junk.size(); ++i) junk[i] = static_cast<char>((i * 7919) % 251);
  writeText(dir / "g.ply", junk);
  auto m = loadMesh(dir / "g.ply");
  EXPECT_FALSE(m.ok());
}

TEST(SaveOff, RoundTripAndAtomic) {
  TempDir dir;
  const TriMesh t = makeTorus(1.0f, 0.3f, 12, 8);
  ASSERT_TRUE(saveOff(dir / "t.off", t).ok());
  auto m = loadMesh(dir / "t.off");
  ASSERT_TRUE(m.ok()) << m.error().message;
  EXPECT_EQ(m->faceCount(), t.faceCount());
  EXPECT_EQ(m->vertexCount(), t.vertexCount());
  // No temporary files are left behind.
  size_t files = 0;
  for ([[maybe_unused]] auto& e : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 1u);
}

TEST(AtomicFile, FailedWriteLeavesNothing) {
  TempDir dir;
  Status s = writeFileAtomically(dir / "x.txt", [](std::ostream& out) -> Status {
    out << "partial";
    return Error::runtime("simulated failure");
  });
  EXPECT_FALSE(s.ok());
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

TEST(AtomicFile, UnwritableDirectory) {
  Status s = checkWritable("/nonexistent-dir/out.png");
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("/nonexistent-dir/out.png"), std::string::npos);
}

TEST(Png, RoundTrip) {
  TempDir dir;
  Image img(7, 5);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 7; ++x) {
      uint8_t* p = img.pixel(x, y);
      p[0] = static_cast<uint8_t>(x * 30);
      p[1] = static_cast<uint8_t>(y * 50);
      p[2] = 7;
      p[3] = 255;
    }
  ASSERT_TRUE(writePng(dir / "a.png", img).ok());
  auto back = readPng(dir / "a.png");
  ASSERT_TRUE(back.ok()) << back.error().message;
  EXPECT_EQ(back->width, 7);
  EXPECT_EQ(back->height, 5);
  EXPECT_EQ(back->rgba, img.rgba);
}

// A PNG whose header claims 20000 x 20000 pixels (1.6 GB as RGBA; the file is 76 bytes):
// refused from the header, before any pixel memory (the limit was 32768 x 32768, and the
// RGBA buffer was allocated and zeroed before the data turned out missing). Detail maps have
// a tighter limit.

TEST(Png, HugeDimensionsAreRefusedFromTheHeader) {
  TempDir dir;
  writeText(dir / "huge.png", test::pngHeaderOnly(20000, 20000));
  auto r = readPng(dir / "huge.png");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("huge.png: PNG of 20000x20000 pixels is too large"), std::string::npos)
      << r.error().message;
  writeText(dir / "map.png", test::pngHeaderOnly(5000, 4000));
  auto m = readPng(dir / "map.png", kMaxDetailMapPixels);
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.error().message.find("too large"), std::string::npos) << m.error().message;
  // Within the limit the header passes, and the missing pixel data is the error.
  writeText(dir / "small.png", test::pngHeaderOnly(64, 64));
  auto s = readPng(dir / "small.png", kMaxDetailMapPixels);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("small.png: cannot read PNG"), std::string::npos) << s.error().message;
}

TEST(Png, NotRegularFiles) {
  TempDir dir;
  ASSERT_EQ(mkfifo((dir / "f.png").c_str(), 0600), 0);  // libpng's fopen would block on it
  auto f = readPng(dir / "f.png");
  ASSERT_FALSE(f.ok());
  EXPECT_NE(f.error().message.find("not a regular file"), std::string::npos) << f.error().message;
  std::filesystem::create_directory(dir / "d.png");
  auto d = readPng(dir / "d.png");
  ASSERT_FALSE(d.ok());
  EXPECT_NE(d.error().message.find("is a directory"), std::string::npos) << d.error().message;
}

TEST(Png, NotAPng) {
  TempDir dir;
  writeText(dir / "b.png", "definitely not a png");
  auto r = readPng(dir / "b.png");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("b.png"), std::string::npos);
}

}  // namespace
}  // namespace lodline
