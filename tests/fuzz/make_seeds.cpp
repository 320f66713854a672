// lodline_fuzz_seeds OUT_DIR [MESH_DIR]: writes the seed corpus of each fuzz target into
// OUT_DIR/<target>/ — small generated meshes in every format the readers take, the small
// CGAL demo meshes of MESH_DIR (data/meshes, files up to 8 KiB) converted to every format,
// progressive-mesh caches, camera paths, PNGs of every colour type, scene files and glTF
// files (.gltf with embedded buffers and .glb) of one and several nodes. Inputs of the
// prefixed targets (fuzz_mesh_ply_*, fuzz_mesh_stl_ascii) are written without the prefix
// the target adds. Run by scripts/fuzz.sh.
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <png.h>

#include "core/camera.h"
#include "frame/camera_path.h"
#include "io/generate.h"
#include "io/image.h"
#include "io/load_mesh.h"
#include "io/intersection_cache.h"
#include "pm/pm_file.h"
#include "pm/progressive_mesh.h"
#include "test_util.h"

namespace fs = std::filesystem;
using namespace lodline;

namespace {

fs::path g_out;
int g_written = 0;

void put(const std::string& target, const std::string& name, const std::string& bytes) {
  const fs::path dir = g_out / target;
  fs::create_directories(dir);
  std::ofstream(dir / name, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  ++g_written;
}

template <class T>
void bin(std::string& s, T v) {
  s.append(reinterpret_cast<const char*>(&v), sizeof(T));
}

// Binary OFF as OpenMesh writes it (and mesh_reader.h reads it): little-endian 32-bit counts,
// floats and indices, no colour count after a face.
std::string offBinary(const TriMesh& m) {
  std::string s = "OFF BINARY\n";
  bin(s, static_cast<uint32_t>(m.positions.size()));
  bin(s, static_cast<uint32_t>(m.faces.size()));
  bin(s, uint32_t{0});
  for (const auto& p : m.positions)
    for (float c : {p.x, p.y, p.z}) bin(s, c);
  for (const auto& f : m.faces) {
    bin(s, uint32_t{3});
    for (uint32_t v : f) bin(s, v);
  }
  return s;
}

std::string obj(const TriMesh& m, bool with_lines) {
  std::ostringstream o;
  o << "# seed\n";
  for (const auto& p : m.positions) o << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
  for (const auto& f : m.faces) o << "f " << f[0] + 1 << ' ' << f[1] + 1 << ' ' << f[2] + 1 << '\n';
  if (with_lines && m.faces.size() > 1) o << "l 1 2 3\nl -1 -2\n";
  return o.str();
}

// PLY body after "ply\nformat ... 1.0\n" (the prefix the PLY targets add).
std::string plyBody(const TriMesh& m, bool binary) {
  std::ostringstream h;
  h << "comment seed\nelement vertex " << m.positions.size()
    << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << m.faces.size()
    << "\nproperty list uchar int vertex_indices\nend_header\n";
  std::string s = h.str();
  if (binary) {
    for (const auto& p : m.positions)
      for (float c : {p.x, p.y, p.z}) bin(s, c);
    for (const auto& f : m.faces) {
      bin<uint8_t>(s, 3);
      for (uint32_t v : f) bin(s, static_cast<int32_t>(v));
    }
  } else {
    std::ostringstream o;
    for (const auto& p : m.positions) o << p.x << ' ' << p.y << ' ' << p.z << '\n';
    for (const auto& f : m.faces) o << "3 " << f[0] << ' ' << f[1] << ' ' << f[2] << '\n';
    s += o.str();
  }
  return s;
}

// ASCII STL after "solid " (the prefix fuzz_mesh_stl_ascii adds).
std::string stlAsciiBody(const TriMesh& m) {
  std::ostringstream o;
  o << "seed\n";
  for (const auto& f : m.faces) {
    o << "facet normal 0 0 1\nouter loop\n";
    for (uint32_t v : f) o << "vertex " << m.positions[v].x << ' ' << m.positions[v].y << ' ' << m.positions[v].z << '\n';
    o << "endloop\nendfacet\n";
  }
  o << "endsolid seed\n";
  return o.str();
}

std::string stlBinary(const TriMesh& m) {
  std::string s(80, ' ');
  bin(s, static_cast<uint32_t>(m.faces.size()));
  for (const auto& f : m.faces) {
    for (float c : {0.0f, 0.0f, 1.0f}) bin(s, c);
    for (uint32_t v : f)
      for (float c : {m.positions[v].x, m.positions[v].y, m.positions[v].z}) bin(s, c);
    bin<uint16_t>(s, 0);
  }
  return s;
}

void meshSeeds(const std::string& name, const TriMesh& m) {
  put("mesh_off", name + ".off", test::offText(m));
  put("mesh_off", name + "-binary.off", offBinary(m));
  put("mesh_obj", name + ".obj", obj(m, false));
  put("mesh_obj", name + "-lines.obj", obj(m, true));
  put("mesh_ply_ascii", name, plyBody(m, false));
  put("mesh_ply_binary", name, plyBody(m, true));
  put("mesh_stl_ascii", name, stlAsciiBody(m));
  put("mesh_stl_binary", name + ".stl", stlBinary(m));
}

std::string readAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void pmSeed(const std::string& name, const TriMesh& m) {
  auto pm = buildProgressiveMesh(m);
  if (!pm) return;
  const fs::path tmp = g_out / ("." + name + ".lpm");
  if (!savePm(tmp, *pm).ok()) return;
  const std::string bytes = readAll(tmp);
  fs::remove(tmp);
  put("pm_cache", name + "-raw", std::string(1, '\0') + bytes);
  put("pm_cache", name + "-consistent", std::string(1, '\1') + bytes);
}

// Intersection-line caches as lodline writes them (the key is the fuzz target's).
void intersectionSeed(const std::string& name, const std::vector<std::vector<glm::vec3>>& segments) {
  const fs::path tmp = g_out / ("." + name + ".lix");
  if (!saveIntersectionCache(tmp, 0x1234567890abcdefull, segments).ok()) return;
  const std::string bytes = readAll(tmp);
  fs::remove(tmp);
  const uint8_t mode = static_cast<uint8_t>(((segments.size() - 1) & 3) << 1);
  put("intersection_cache", name + "-raw", std::string(1, static_cast<char>(mode)) + bytes);
  put("intersection_cache", name + "-consistent", std::string(1, static_cast<char>(mode | 1)) + bytes);
}

void pngSeed(const std::string& name, int w, int h, png_uint_32 format) {
  png_image png;
  std::memset(&png, 0, sizeof(png));
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(w);
  png.height = static_cast<png_uint_32>(h);
  png.format = format;
  std::vector<uint8_t> pixels(PNG_IMAGE_SIZE(png));
  for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = static_cast<uint8_t>(i * 37 + 11);
  png_alloc_size_t size = 0;
  if (!png_image_write_to_memory(&png, nullptr, &size, 0, pixels.data(), 0, nullptr)) return;
  std::string bytes(size, '\0');
  if (!png_image_write_to_memory(&png, bytes.data(), &size, 0, pixels.data(), 0, nullptr)) return;
  put("detail_map_png", name + ".png", bytes);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::cerr << "usage: lodline_fuzz_seeds OUT_DIR [MESH_DIR]\n";
    return 2;
  }
  g_out = argv[1];
  fs::create_directories(g_out);

  const std::vector<std::pair<std::string, TriMesh>> generated = {
      {"icosphere1", makeIcoSphere(1.0f, 1)},  {"torus", makeTorus(1.0f, 0.3f, 8, 6)},
      {"grid", makeGrid(2.0f, 3)},             {"cylinder", makeCylinder(0.5f, 1.0f, 6, 2)},
      {"knot", makeTorusKnot(2, 3, 1.0f, 0.2f, 24, 5, 0.1f)},
      {"box", makeRoundedBox({1.0f, 0.5f, 0.25f}, 0.0f, 2, 1)}};
  for (const auto& [name, m] : generated) {
    meshSeeds(name, m);
    pmSeed(name, m);
  }
  intersectionSeed("empty", {{}});
  intersectionSeed("circle", {{{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 1, 0}, {1, 1, 0}, {0, 0, 0}}, {}});
  intersectionSeed("three", {{{0, 0, 0}, {0, 0, 1}}, {{0, 1, 0}, {0, 1, 1}}, {}});
  // Small CGAL demo meshes: the OFF file as it is, the others converted.
  if (argc == 3 && fs::is_directory(argv[2])) {
    for (const auto& e : fs::directory_iterator(argv[2])) {
      if (e.path().extension() != ".off" || !e.is_regular_file() || e.file_size() > 8192) continue;
      const std::string name = "cgal-" + e.path().stem().string();
      put("mesh_off", name + ".off", readAll(e.path()));
      auto m = loadMesh(e.path());
      if (!m) continue;
      m->marked_edges.clear();
      put("mesh_off", name + "-binary.off", offBinary(*m));
      put("mesh_obj", name + ".obj", obj(*m, false));
      put("mesh_ply_ascii", name, plyBody(*m, false));
      put("mesh_ply_binary", name, plyBody(*m, true));
      put("mesh_stl_ascii", name, stlAsciiBody(*m));
      put("mesh_stl_binary", name + ".stl", stlBinary(*m));
      pmSeed(name, *m);
    }
  }

  Bounds bounds = computeBounds(generated[0].second.positions);
  for (const std::string& name : builtinPathNames()) {
    auto path = builtinPath(name, bounds, 35.0f, 1.5f, 4.0);
    if (!path) continue;
    const fs::path tmp = g_out / ("." + name + ".json");
    if (!saveCameraPath(tmp, *path).ok()) continue;
    put("camera_path", name + ".json", readAll(tmp));
    fs::remove(tmp);
  }
  put("camera_path", "minimal.json", R"({"keys": [{"time": 0, "eye": [0, 0, 5], "target": [0, 0, 0]}]})");
  put("camera_path", "two.json",
      R"({"keys": [{"time": 0, "eye": [0, 0, 5], "target": [0, 0, 0], "up": [0, 1, 0], "fov": 35},)"
      R"( {"time": 2.5, "eye": [5, 1, 0], "target": [0, 0.5, 0], "fov": 20}]})");

  pngSeed("grey", 16, 9, PNG_FORMAT_GRAY);
  pngSeed("grey-alpha", 7, 5, PNG_FORMAT_GA);
  pngSeed("rgb", 12, 8, PNG_FORMAT_RGB);
  pngSeed("rgba", 5, 13, PNG_FORMAT_RGBA);
  pngSeed("argb", 3, 3, PNG_FORMAT_ARGB);
  pngSeed("grey16", 8, 8, PNG_FORMAT_LINEAR_Y);
  pngSeed("rgba16", 4, 6, PNG_FORMAT_LINEAR_RGB_ALPHA);
  pngSeed("one", 1, 1, PNG_FORMAT_GRAY);
  // Scene files (docs/scenes.md): the fuzz target puts a tetrahedron "m.off" beside each input.
  put("scene_json", "one.json", R"({"objects": [{"mesh": "m.off"}]})");
  put("scene_json", "placed.json",
      R"({"lodline": 1, "description": "two placed objects", "objects": [)"
      R"({"name": "a", "mesh": "m.off", "translate": [1, 0, -2], "rotate": [0, 45, 10], "scale": 2,)"
      R"( "detail_factor": 0.5, "style": "toon", "lines": "contour,crease", "line_width": 2},)"
      R"({"mesh": "m.off", "quaternion": [0, 0.7071, 0, 0.7071], "scale": [1, 2, 0.5], "chamfer": "on",)"
      R"( "chamfer_radius": 0.01, "line_style": ["contour=#402010:1.5"]}],)"
      R"( "settings": {"target-area": 8, "smoothing": "on", "size": "320x240"},)"
      R"( "camera": {"eye": [0, 1, 6], "target": [0, 0, 0], "up": [0, 1, 0], "fov": 30},)"
      R"( "light": {"direction": [0.3, 0.6, 1]}})");
  put("scene_json", "matrix.json",
      R"({"objects": [{"mesh": "m.off", "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0.5,0,0,1]}],)"
      R"( "camera": {"view": [20, 10, 3]}})");
  put("scene_json", "include.json", R"({"objects": [{"scene": "one.json", "translate": [0, 1, 0]}]})");
  put("scene_json", "paint.json",
      R"({"objects": [{"mesh": "m.off", "paint": [{"plane": [0, 1, 0, 0.3]}, {"plane": [1, 1, 0, 0.1], "thickness": 0.2}],)"
      R"( "lines": "contour,material"}]})");

  // Stroke style files (docs/strokes.md): the fuzz target puts a brush "b.png" beside each input.
  put("stroke_style", "all.json", R"({"all": {"cap": "butt", "taper_in": 5, "taper_out": 8, "taper_min": 0.2}})");
  put("stroke_style", "kinds.json",
      R"({"all": {"color": "#202020", "width_scale": 1.2, "depth_thickness": 0.3, "strength_opacity": 0.5},)"
      R"( "suggestive": {"dash": [4, 2], "jitter": 0.5, "jitter_period": 20, "seed": 7, "min_length": 3},)"
      R"( "contour": {"brush": "b.png", "brush_period": 32, "curvature_thickness": 0.5, "cap": "square"},)"
      R"( "crease": {"brush": "pencil"}, "boundary": {"brush": "none", "depth_opacity": 0.2}})");

  // glTF: a cube, and two nodes in a hierarchy with translation, rotation and scale.
  test::GltfTestNode child = test::gltfCube();
  child.name = "child";
  child.parent = 0;
  child.translation = {2.0f, 0.0f, 0.0f};
  child.rotation = {0.0f, 0.3826834f, 0.0f, 0.9238795f};
  child.scale = {0.5f, 1.0f, 2.0f};
  for (const std::string ext : {"gltf", "glb"}) {
    const fs::path tmp = g_out / (".seed." + ext);
    test::writeGltf(tmp, {test::gltfCube()});
    put(ext, "cube." + ext, readAll(tmp));
    test::writeGltf(tmp, {test::gltfCube(), child});
    put(ext, "two-nodes." + ext, readAll(tmp));
    fs::remove(tmp);
  }
  std::cout << "lodline_fuzz_seeds: wrote " << g_written << " seed files into " << g_out.string() << "\n";
  return 0;
}
