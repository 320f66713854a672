#include "test_util.h"

#include <atomic>
#include <random>
#include <sstream>
#include <system_error>

#include <cstdio>
#include <cstdlib>

#include <sys/wait.h>
#include <unistd.h>

namespace lodline::test {

std::filesystem::path dataMesh(const std::string& name) {
  // LODLINE_DATA_MESHES in the environment: the meshes elsewhere (a benchmark bundle run on
  // another machine, scripts/gpu_bench_bundle.sh).
  const char* env = std::getenv("LODLINE_DATA_MESHES");
  const std::filesystem::path p = std::filesystem::path(env && *env ? env : LODLINE_DATA_MESHES) / name;
  return std::filesystem::exists(p) ? p : std::filesystem::path();
}

int runCommand(const std::string& command, std::string* output) {
  FILE* pipe = popen(("EGL_PLATFORM=surfaceless " + command + " 2>&1").c_str(), "r");
  if (!pipe) return -1;
  std::string out;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof(buf), pipe)) > 0) out.append(buf, n);
  const int status = pclose(pipe);
  if (output) *output = out;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

int runLodline(const std::string& args, std::string* output) {
#ifdef LODLINE_BINARY
  return runCommand(std::string(LODLINE_BINARY) + " " + args, output);
#else
  (void)args;
  (void)output;
  return -1;
#endif
}

TempDir::TempDir() {
  static std::atomic<int> counter{0};
  std::random_device rd;
  path_ = std::filesystem::temp_directory_path() /
          ("lodline-test-" + std::to_string(getpid()) + "-" + std::to_string(counter++) + "-" +
           std::to_string(rd()));
  std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

}  // namespace lodline::test

#include <algorithm>
#include <cstring>
#include <fstream>

#include <nlohmann/json.hpp>

namespace lodline::test {
namespace {

std::string base64(const std::vector<uint8_t>& data) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < data.size(); i += 3) {
    const uint32_t n = (uint32_t(data[i]) << 16) | (i + 1 < data.size() ? uint32_t(data[i + 1]) << 8 : 0) |
                       (i + 2 < data.size() ? uint32_t(data[i + 2]) : 0);
    out += k[(n >> 18) & 63];
    out += k[(n >> 12) & 63];
    out += i + 1 < data.size() ? k[(n >> 6) & 63] : '=';
    out += i + 2 < data.size() ? k[n & 63] : '=';
  }
  return out;
}

}  // namespace

void writeGltf(const std::filesystem::path& path, const std::vector<GltfTestNode>& nodes) {
  std::vector<uint8_t> buffer;
  nlohmann::json j;
  j["asset"] = {{"version", "2.0"}};
  j["scene"] = 0;
  nlohmann::json roots = nlohmann::json::array(), jn = nlohmann::json::array(), meshes = nlohmann::json::array(),
                 accessors = nlohmann::json::array(), views = nlohmann::json::array();
  for (size_t i = 0; i < nodes.size(); ++i) {
    const GltfTestNode& n = nodes[i];
    auto append = [&](const void* data, size_t bytes) {
      while (buffer.size() % 4) buffer.push_back(0);
      const size_t offset = buffer.size();
      buffer.resize(offset + bytes);
      std::memcpy(buffer.data() + offset, data, bytes);
      views.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}});
      return views.size() - 1;
    };
    const size_t pv = append(n.positions.data(), n.positions.size() * 12);
    const size_t iv = append(n.indices.data(), n.indices.size() * 4);
    std::array<float, 3> mn{1e30f, 1e30f, 1e30f}, mx{-1e30f, -1e30f, -1e30f};
    for (const auto& p : n.positions)
      for (int k = 0; k < 3; ++k) mn[k] = std::min(mn[k], p[k]), mx[k] = std::max(mx[k], p[k]);
    accessors.push_back({{"bufferView", pv}, {"componentType", 5126}, {"count", n.positions.size()}, {"type", "VEC3"},
                         {"min", mn}, {"max", mx}});
    accessors.push_back({{"bufferView", iv}, {"componentType", 5125}, {"count", n.indices.size()}, {"type", "SCALAR"}});
    meshes.push_back({{"primitives", {{{"attributes", {{"POSITION", accessors.size() - 2}}},
                                       {"indices", accessors.size() - 1}, {"mode", 4}}}}});
    nlohmann::json node = {{"mesh", i}, {"translation", n.translation}, {"rotation", n.rotation}, {"scale", n.scale}};
    if (!n.name.empty()) node["name"] = n.name;
    jn.push_back(node);
    if (n.parent < 0) roots.push_back(i);
  }
  for (size_t i = 0; i < nodes.size(); ++i)
    if (nodes[i].parent >= 0) jn[nodes[i].parent]["children"].push_back(i);
  j["scenes"] = {{{"nodes", roots}}};
  j["nodes"] = jn;
  j["meshes"] = meshes;
  j["accessors"] = accessors;
  j["bufferViews"] = views;
  const bool binary = path.extension() == ".glb";
  while (buffer.size() % 4) buffer.push_back(0);
  if (binary) {
    j["buffers"] = {{{"byteLength", buffer.size()}}};
    std::string text = j.dump();
    while (text.size() % 4) text.push_back(' ');
    std::ofstream out(path, std::ios::binary);
    auto u32 = [&](uint32_t v) { out.write(reinterpret_cast<const char*>(&v), 4); };
    u32(0x46546C67);  // "glTF"
    u32(2);
    u32(static_cast<uint32_t>(12 + 8 + text.size() + 8 + buffer.size()));
    u32(static_cast<uint32_t>(text.size()));
    u32(0x4E4F534A);  // "JSON"
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    u32(static_cast<uint32_t>(buffer.size()));
    u32(0x004E4942);  // "BIN\0"
    out.write(reinterpret_cast<const char*>(buffer.data()), static_cast<std::streamsize>(buffer.size()));
  } else {
    j["buffers"] = {{{"byteLength", buffer.size()}, {"uri", "data:application/octet-stream;base64," + base64(buffer)}}};
    std::ofstream(path) << j.dump(1);
  }
}

GltfTestNode gltfCube() {
  GltfTestNode n;
  // Per face: the axis, its sign; corners counter-clockwise seen from outside.
  for (int axis = 0; axis < 3; ++axis)
    for (int sign : {-1, 1}) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const uint32_t base = static_cast<uint32_t>(n.positions.size());
      const float cu[4] = {-1, 1, 1, -1}, cv[4] = {-1, -1, 1, 1};
      for (int c = 0; c < 4; ++c) {
        std::array<float, 3> p{};
        p[axis] = static_cast<float>(sign);
        p[u] = cu[c];
        p[v] = sign > 0 ? cv[c] : -cv[c];
        n.positions.push_back(p);
      }
      for (uint32_t t : {0u, 1u, 2u, 0u, 2u, 3u}) n.indices.push_back(base + t);
    }
  return n;
}

std::string pngHeaderOnly(uint32_t w, uint32_t h) {
  auto be32 = [](std::string& s, uint32_t v) {
    for (int k = 3; k >= 0; --k) s.push_back(static_cast<char>((v >> (8 * k)) & 0xff));
  };
  auto chunk = [&](std::string& out, const std::string& type, const std::string& data) {
    be32(out, static_cast<uint32_t>(data.size()));
    const std::string td = type + data;
    out += td;
    uint32_t crc = 0xffffffffu;  // CRC-32 of type and data (PNG spec, ISO 3309)
    for (unsigned char c : td) {
      crc ^= c;
      for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
    }
    be32(out, crc ^ 0xffffffffu);
  };
  std::string ihdr;
  be32(ihdr, w);
  be32(ihdr, h);
  ihdr += std::string("\x08\x00\x00\x00\x00", 5);  // 8-bit grey, no interlace
  std::string png = "\x89PNG\r\n\x1a\n";
  chunk(png, "IHDR", ihdr);
  // The start of the pixel data (zlib header and an empty stored block): libpng reads the
  // header up to here, the pixels would follow.
  chunk(png, "IDAT", std::string("\x78\x01\x00\x00\x00\xff\xff", 7));
  chunk(png, "IEND", "");
  return png;
}

std::string offText(const TriMesh& m) {
  std::ostringstream o;
  o << "OFF\n" << m.positions.size() << ' ' << m.faces.size() << " 0\n";
  for (const auto& p : m.positions) o << p.x << ' ' << p.y << ' ' << p.z << '\n';
  for (const auto& f : m.faces) o << "3 " << f[0] << ' ' << f[1] << ' ' << f[2] << '\n';
  return o.str();
}

TriMesh shuffledMesh(TriMesh m, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<uint32_t> perm(m.positions.size());
  for (uint32_t i = 0; i < perm.size(); ++i) perm[i] = i;
  std::shuffle(perm.begin(), perm.end(), rng);
  std::vector<glm::vec3> pos(m.positions.size());
  for (uint32_t i = 0; i < perm.size(); ++i) pos[perm[i]] = m.positions[i];
  m.positions = pos;
  for (auto& f : m.faces)
    for (auto& v : f) v = perm[v];
  for (auto& e : m.marked_edges)
    for (auto& v : e) v = perm[v];
  std::vector<size_t> order(m.faces.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), rng);
  std::vector<std::array<uint32_t, 3>> faces;
  std::vector<uint32_t> materials;
  for (size_t i : order) {
    faces.push_back(m.faces[i]);
    if (m.face_materials.size() == m.faces.size()) materials.push_back(m.face_materials[i]);
  }
  m.faces = std::move(faces);
  m.face_materials = std::move(materials);
  return m;
}

}  // namespace lodline::test
