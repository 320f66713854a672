// The bounded mesh readers (io/mesh_reader.h) through loadMesh: every format variant they
// accept, every hostile construction refused with one line naming the file and where, and
// agreement with OpenMesh's readers (the readers they replaced) on the CGAL demo meshes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <random>

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <sys/stat.h>

#include "io/generate.h"
#include "io/load_mesh.h"
#include "io/mesh_reader.h"
#include "test_util.h"

namespace lodline {
namespace {

using test::TempDir;

void writeBytes(const std::filesystem::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

template <class T>
void put(std::string& s, T v) {
  s.append(reinterpret_cast<const char*>(&v), sizeof(T));
}

template <class T>
void putBig(std::string& s, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  for (size_t i = sizeof(T); i-- > 0;) s.push_back(b[i]);
}

Result<TriMesh> load(const TempDir& dir, const std::string& name, const std::string& bytes) {
  writeBytes(dir / name, bytes);
  return loadMesh(dir / name);
}

// Refused: one line naming the file and containing `fragment`.
void expectRefused(const TempDir& dir, const std::string& name, const std::string& bytes, const std::string& fragment) {
  auto m = load(dir, name, bytes);
  ASSERT_FALSE(m.ok()) << name << " was accepted";
  const std::string& msg = m.error().message;
  EXPECT_NE(msg.find((dir / name).string()), std::string::npos) << msg;
  EXPECT_NE(msg.find(fragment), std::string::npos) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  for (unsigned char c : msg) EXPECT_TRUE(c >= 0x20 && c < 0x7f) << "unprintable byte " << int(c) << " in: " << msg;
}

// ---- accepted variants ----

TEST(MeshReader, OffCommentsColoursAndVariants) {
  TempDir dir;
  // Comments before and between the counts, vertex colours and face colours on a plain OFF.
  auto m = load(dir, "c.off",
                "# made by hand\nOFF\n# counts next\n4 2 0\n0 0 0 255 0 0\n1 0 0\n1 1 0\n0 1 0 # last\n"
                "3 0 1 2 0.7 0 0\n3 0 2 3\n");
  ASSERT_TRUE(m.ok()) << m.error().message;
  EXPECT_EQ(m->vertexCount(), 4u);
  EXPECT_EQ(m->faceCount(), 2u);
  for (const char* magic : {"COFF", "NOFF", "CNOFF", "STOFF"}) {
    auto v = load(dir, "v.off", std::string(magic) + "\n3 1 0\n0 0 0 1 2 3\n1 0 0 1 2 3\n0 1 0 1 2 3\n3 0 1 2\n");
    ASSERT_TRUE(v.ok()) << magic << ": " << v.error().message;
    EXPECT_EQ(v->positions[1], glm::vec3(1, 0, 0)) << magic;
  }
  expectRefused(dir, "n.off", "nOFF\n3\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "not supported");
  expectRefused(dir, "4.off", "4OFF\n3 1 0\n0 0 0 1\n1 0 0 1\n0 1 0 1\n3 0 1 2\n", "not supported");
}

TEST(MeshReader, OffBinary) {
  TempDir dir;
  std::string s = "OFF BINARY\n";
  for (uint32_t c : {5u, 2u, 0u}) put(s, c);
  for (float c : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 1.f, 1.f, 0.f, 0.f, 1.f, 0.f, -1.f, 0.5f, 0.f}) put(s, c);
  for (uint32_t c : {3u, 0u, 1u, 2u, 4u, 0u, 2u, 3u, 4u}) put(s, c);  // a triangle and a quad
  auto m = load(dir, "b.off", s);
  ASSERT_TRUE(m.ok()) << m.error().message;
  EXPECT_EQ(m->vertexCount(), 5u);
  EXPECT_EQ(m->faceCount(), 3u);  // the quad is fanned into two
}

TEST(MeshReader, ObjReferencesAndIgnoredStatements) {
  TempDir dir;
  // mtllib names a FIFO: opening it would block forever; it must not be opened at all.
  ASSERT_EQ(mkfifo((dir / "m.mtl").c_str(), 0600), 0);
  auto m = load(dir, "r.obj",
                "mtllib m.mtl\no thing\nv 0 0 0\nv 1 0 0 1.0\nv 1 1 0 0.5 0.5 0.5\nv 0 1 0\nvt 0 0\nvn 0 0 1\n"
                "g part\nusemtl red\ns off\nf 1/1/1 2/1/1 3//1\nf -4 -2 -1\n");
  ASSERT_TRUE(m.ok()) << m.error().message;
  EXPECT_EQ(m->vertexCount(), 4u);
  ASSERT_EQ(m->faceCount(), 2u);
  EXPECT_EQ(m->faces[1], (std::array<uint32_t, 3>{0, 2, 3}));
}

TEST(MeshReader, PlyBigEndianExtraElementsAndAnyOrder) {
  TempDir dir;
  // Faces before vertices, an extra element with a list, double coordinates, a uint count.
  std::string s =
      "ply\nformat binary_big_endian 1.0\ncomment x\nelement face 1\nproperty list uint int vertex_indices\n"
      "property uchar flags\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
      "property float confidence\nelement edge 1\nproperty list uchar int pair\nend_header\n";
  putBig<uint32_t>(s, 3);
  for (int32_t i : {0, 1, 2}) putBig(s, i);
  s.push_back(7);  // flags
  for (int v = 0; v < 3; ++v) {  // x, y, z, confidence
    for (int c = 0; c < 3; ++c) putBig(s, (v == 1 && c == 0) || (v == 2 && c == 1) ? 2.0 : 0.0);
    putBig(s, 0.5f);
  }
  s.push_back(2);
  putBig<int32_t>(s, 0);
  putBig<int32_t>(s, 1);
  auto m = load(dir, "be.ply", s);
  ASSERT_TRUE(m.ok()) << m.error().message;
  EXPECT_EQ(m->vertexCount(), 3u);
  EXPECT_EQ(m->faceCount(), 1u);
  EXPECT_EQ(m->positions[2], glm::vec3(0, 2, 0));
}

TEST(MeshReader, StlAsciiSeveralSolidsAndSignedZero) {
  TempDir dir;
  auto m = load(dir, "s.stl",
                "solid facet\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nendloop\n"
                "endfacet\nendsolid facet\nsolid b\nfacet normal 0 0 1\nouter loop\nvertex -0 0 0\n"
                "vertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid b\n");
  ASSERT_TRUE(m.ok()) << m.error().message;
  EXPECT_EQ(m->faceCount(), 2u);
  EXPECT_EQ(m->vertexCount(), 4u);  // -0 is the same corner as 0
}

TEST(MeshReader, LargePolygonIsFanned) {
  TempDir dir;
  std::string s = "OFF\n1000 1 0\n";
  for (int i = 0; i < 1000; ++i)
    s.append(std::to_string(std::cos(2 * M_PI * i / 1000)))
        .append(" ")
        .append(std::to_string(std::sin(2 * M_PI * i / 1000)))
        .append(" 0\n");
  s += "1000";
  for (int i = 0; i < 1000; ++i) s.append(" ").append(std::to_string(i));
  auto m = load(dir, "disc.off", s + "\n");
  ASSERT_TRUE(m.ok()) << m.error().message;
  EXPECT_EQ(m->faceCount(), 998u);
}

TEST(MeshReader, NonManifoldFacesGetTheirOwnVertices) {
  TempDir dir;
  // Three triangles on the edge (0, 1): the third cannot join the half-edge mesh.
  auto m = load(dir, "nm.off", "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n");
  ASSERT_TRUE(m.ok()) << m.error().message;
  EXPECT_EQ(m->faceCount(), 3u);
  EXPECT_EQ(m->vertexCount(), 8u);
  EXPECT_TRUE(validateMesh(*m, "nm").ok());
}

// ---- hostile input ----

TEST(MeshReaderHostile, CountsClaimingTwoToThe31ElementsAreRefusedBeforeAllocating) {
  TempDir dir;
  expectRefused(dir, "a.off", "OFF\n2147483648 1 0\n0 0 0\n", "truncated");
  expectRefused(dir, "f.off", "OFF\n3 2147483648 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "truncated");
  expectRefused(dir, "k.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2147483648 0 1 2\n", "more than the rest");
  std::string b = "OFF BINARY\n";
  for (uint32_t c : {0x80000000u, 0x80000000u, 0u}) put(b, c);
  expectRefused(dir, "b.off", b, "truncated");
  const std::string ply_v = "ply\nformat ascii 1.0\nelement vertex 2147483648\nproperty float x\nproperty float y\n"
                            "property float z\nend_header\n0 0 0\n";
  expectRefused(dir, "v.ply", ply_v, "truncated");
  std::string ply_l = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                      "property float z\nelement face 1\nproperty list uint int vertex_indices\nend_header\n";
  for (float c : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) put(ply_l, c);
  put<uint32_t>(ply_l, 0x80000000u);
  expectRefused(dir, "l.ply", ply_l, "more than the rest");
  expectRefused(dir, "e.ply", "ply\nformat ascii 1.0\nelement vertex 99999999999\nend_header\n", "too many");
  std::string stl(80, ' ');
  put<uint32_t>(stl, 0x80000000u);
  stl.append(50, '\0');
  expectRefused(dir, "c.stl", stl, "announces 2147483648 triangles");
}

TEST(MeshReaderHostile, EmptyHeaderOnlyAndTruncated) {
  TempDir dir;
  for (const char* name : {"e.off", "e.obj", "e.ply", "e.stl"}) expectRefused(dir, name, "", "empty file");
  expectRefused(dir, "h.off", "OFF\n", "malformed OFF header");
  expectRefused(dir, "h.ply", "ply\nformat ascii 1.0\n", "no end_header");  // OpenMesh looped forever here
  expectRefused(dir, "h2.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n", "lacks");
  expectRefused(dir, "h.stl", "solid x\n", "no vertices");
  expectRefused(dir, "h.obj", "# nothing\n", "no vertices");
  expectRefused(dir, "t.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2", "truncated");
  std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                    "property float z\nend_header\n";
  for (float c : {0.f, 0.f, 0.f, 1.f, 0.f}) put(ply, c);
  expectRefused(dir, "t.ply", ply, "truncated");
  std::string stl(80, ' ');
  put<uint32_t>(stl, 2);
  stl.append(70, '\0');  // one and a half facets
  expectRefused(dir, "t.stl", stl, "not an STL file");
  expectRefused(dir, "t.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n", "facet not ended");
}

TEST(MeshReaderHostile, BadNumbersAndIndices) {
  TempDir dir;
  expectRefused(dir, "nan.off", "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n", "non-finite");
  expectRefused(dir, "inf.obj", "v 0 0 0\nv inf 0 0\nv 0 1 0\nf 1 2 3\n", "non-finite");
  // A binary STL whose coordinates are all NaN: its corners weld into one vertex, yet the
  // problem to name is the coordinates, not "every face repeats a vertex".
  std::string nan_stl(80, ' ');
  put<uint32_t>(nan_stl, 2);
  for (int f = 0; f < 2; ++f) {
    for (int k = 0; k < 12; ++k) put(nan_stl, std::nanf(""));
    put<uint16_t>(nan_stl, 0);
  }
  expectRefused(dir, "nan.stl", nan_stl, "non-finite");
  expectRefused(dir, "big.off", "OFF\n3 1 0\n1e38 0 0\n-1e38 0 0\n0 1e38 0\n3 0 1 2\n", "too large");
  expectRefused(dir, "huge.off", "OFF\n3 1 0\n1e39 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "non-finite");
  expectRefused(dir, "point.off", "OFF\n3 1 0\n1 1 1\n1 1 1\n1 1 1\n3 0 1 2\n", "no extent");
  expectRefused(dir, "word.off", "OFF\n3 1 0\n0 0 zero\n1 0 0\n0 1 0\n3 0 1 2\n", "line 3: vertex 0: coordinate 'zero'");
  expectRefused(dir, "neg.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", "line 6: face 0 references vertex -1");
  expectRefused(dir, "range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99\n", "line 4: face vertex 99 out of range");
  expectRefused(dir, "zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "line 4: vertex reference '0'");
  // OpenMesh's OBJ reader aborted the program on a face without an index.
  expectRefused(dir, "slash.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf /1 /2 /3\n", "line 4: vertex reference '/1'");
  expectRefused(dir, "range.ply",
                "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n",
                "face 0 references vertex 5, out of range");
  // Control characters from the file never reach the message.
  expectRefused(dir, "ctl.ply", "ply\nformat ascii 1.0\nelement \x1b[31mvertex 3\nend_header\n", "no vertex element");
  expectRefused(dir, "ctl.off", "OFF\n3 1 0\n0 0 \x1b[2J\n1 0 0\n0 1 0\n3 0 1 2\n", "'?[2J'");
}

TEST(MeshReaderHostile, DegenerateFaces) {
  TempDir dir;
  for (const char* face : {"0", "1 0", "2 0 1"})
    expectRefused(dir, "d.off", std::string("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n") + face + "\n", "at least 3 needed");
  expectRefused(dir, "d.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", "face has 2 vertices");
  expectRefused(dir, "r.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 0 1\n", "every face repeats a vertex");
  expectRefused(dir, "iso.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n", "no faces");
  // Zero-area and duplicated faces are meshes lodline draws.
  auto m = load(dir, "z.off", "OFF\n4 3 0\n0 0 0\n1 0 0\n2 0 0\n0 1 0\n3 0 1 2\n3 0 1 3\n3 0 1 3\n");
  ASSERT_TRUE(m.ok()) << m.error().message;
  EXPECT_EQ(m->faceCount(), 3u);
}

TEST(MeshReaderHostile, NotRegularFiles) {
  TempDir dir;
  std::filesystem::create_directory(dir / "d.obj");
  auto d = loadMesh(dir / "d.obj");
  ASSERT_FALSE(d.ok());
  EXPECT_NE(d.error().message.find("is a directory"), std::string::npos) << d.error().message;
  ASSERT_EQ(mkfifo((dir / "f.off").c_str(), 0600), 0);  // opening it to read would block
  auto f = loadMesh(dir / "f.off");
  ASSERT_FALSE(f.ok());
  EXPECT_NE(f.error().message.find("not a regular file"), std::string::npos) << f.error().message;
  auto dev = loadMesh("/dev/zero");
  ASSERT_FALSE(dev.ok());
  EXPECT_NE(dev.error().message.find("not a regular file"), std::string::npos) << dev.error().message;
}

TEST(MeshReaderHostile, RandomBytesForEveryExtension) {
  TempDir dir;
  std::mt19937 rng(5);
  for (const char* ext : {".off", ".obj", ".ply", ".stl"})
    for (int i = 0; i < 50; ++i) {
      std::string bytes(1 + rng() % 4096, '\0');
      for (char& c : bytes) c = static_cast<char>(rng());
      if (i % 5 == 0) bytes.insert(0, std::string(ext) == ".off" ? "OFF\n" : std::string(ext) == ".ply" ? "ply\n" : "");
      const std::string name = std::string("r").append(std::to_string(i)).append(ext);
      auto m = load(dir, name, bytes);
      ASSERT_FALSE(m.ok()) << name;
      EXPECT_NE(m.error().message.find(name), std::string::npos) << m.error().message;
      EXPECT_EQ(m.error().message.find('\n'), std::string::npos) << m.error().message;
    }
}

// ---- agreement with OpenMesh's readers on trusted files ----

struct OmTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3f;
};
using OmMesh = OpenMesh::PolyMesh_ArrayKernelT<OmTraits>;

TriMesh fromOpenMesh(OmMesh& om) {
  TriMesh m;
  for (auto vh : om.vertices()) m.positions.emplace_back(om.point(vh)[0], om.point(vh)[1], om.point(vh)[2]);
  for (auto fh : om.faces()) {
    std::vector<uint32_t> poly;
    for (auto vh : om.fv_range(fh)) poly.push_back(static_cast<uint32_t>(vh.idx()));
    for (size_t k = 1; k + 1 < poly.size(); ++k) m.faces.push_back({poly[0], poly[k], poly[k + 1]});
  }
  return m;
}

// Every CGAL demo mesh OpenMesh reads (up to 300 KiB), and OpenMesh's own OBJ, ASCII and
// binary PLY and binary OFF versions of it, give the same vertices and faces in the same
// order through loadMesh. (loadMesh also reads OFF files OpenMesh cannot: comments after
// the header, face colours in a plain OFF.)
TEST(MeshReader, AgreesWithOpenMeshOnTheCgalDemoMeshes) {
  const auto dir_path = test::dataMesh("");
  if (!std::filesystem::is_directory(dir_path) || !std::filesystem::exists(dir_path / "armadillo.off"))
    GTEST_SKIP() << "data/meshes missing (run scripts/setup.sh)";
  TempDir tmp;
  int compared = 0;
  // OpenMesh's reader and writer chatter on std::cerr and std::clog.
  std::cerr.setstate(std::ios::failbit);
  std::clog.setstate(std::ios::failbit);
  for (const auto& e : std::filesystem::directory_iterator(dir_path)) {
    if (e.path().extension() != ".off" || e.file_size() > 300 * 1024) continue;
    OmMesh src;
    OpenMesh::IO::Options none;
    if (!OpenMesh::IO::read_mesh(src, e.path().string(), none) || src.n_faces() == 0) continue;
    struct Variant {
      const char* file;
      OpenMesh::IO::Options::Flag flag;
    };
    for (Variant v : {Variant{"x.off", OpenMesh::IO::Options::Default}, Variant{"x.obj", OpenMesh::IO::Options::Default},
                      Variant{"x.ply", OpenMesh::IO::Options::Default}, Variant{"xb.ply", OpenMesh::IO::Options::Binary},
                      Variant{"xb.off", OpenMesh::IO::Options::Binary}}) {
      const std::string path = (tmp / v.file).string();
      OpenMesh::IO::Options wo(v.flag), ro(v.flag);
      ASSERT_TRUE(OpenMesh::IO::write_mesh(src, path, wo)) << path;
      OmMesh om;
      ASSERT_TRUE(OpenMesh::IO::read_mesh(om, path, ro)) << path;
      const TriMesh want = fromOpenMesh(om);
      auto got = loadMesh(path);
      ASSERT_TRUE(got.ok()) << e.path() << " as " << v.file << ": " << got.error().message;
      EXPECT_TRUE(got->positions == want.positions && got->faces == want.faces) << e.path() << " as " << v.file;
      ++compared;
    }
  }
  std::cerr.clear();
  std::clog.clear();
  std::cout << "compared " << compared << " files (" << compared / 5 << " meshes x 5 formats)\n";
  EXPECT_GT(compared, 400);
}

}  // namespace
}  // namespace lodline
