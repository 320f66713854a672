// tinygltf is header-only: its implementation lives in this translation unit only. Images
// are never decoded (lodline draws geometry), so stb_image is left out.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include "io/load_gltf.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <functional>
#include <unordered_map>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "core/printable.h"
#include "io/input_check.h"
#include "io/load_mesh.h"

namespace lodline {
namespace {

// Images are skipped: accept them without decoding.
bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int,
               void*) {
  return true;
}

std::string oneLine(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  while (!s.empty() && (s.back() == ' ' || s.back() == '.')) s.pop_back();
  return printableText(s, 400);
}

// Largest file tinygltf may read (the .gltf/.glb itself or an external buffer): it reads
// whole files into memory.
constexpr uintmax_t kMaxGltfFileBytes = uintmax_t{2} << 30;

// tinygltf's existence test opens the file, which blocks on a FIFO: stat it instead.
bool fileExistsNoOpen(const std::string& path, void*) {
  std::error_code ec;
  return std::filesystem::exists(path, ec);
}

// tinygltf's file reads go through here: a buffer URI naming a FIFO, a device or a directory
// is refused instead of blocking or reading forever, and sizes are bounded.
bool readWholeFileChecked(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  if (Status s = checkInputFile(path, "glTF file or buffer"); !s) {
    if (err) *err += s.error().message + "\n";
    return false;
  }
  std::error_code ec;
  const uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec || size > kMaxGltfFileBytes) {
    if (err) *err += path + (ec ? ": cannot read its size" : ": larger than 2 GiB") + "\n";
    return false;
  }
  return tinygltf::ReadWholeFile(out, err, path, user);
}

// A checked view of an accessor's elements: every read stays inside its buffer.
struct AccessorView {
  const unsigned char* base = nullptr;
  size_t stride = 0;
  size_t count = 0;
  int component = 0;  // TINYGLTF_COMPONENT_TYPE_*
  int type = 0;       // TINYGLTF_TYPE_*
};

Result<AccessorView> viewAccessor(const tinygltf::Model& m, int index, const std::string& what) {
  if (index < 0 || static_cast<size_t>(index) >= m.accessors.size())
    return Error::runtime(what + ": accessor " + std::to_string(index) + " does not exist");
  const tinygltf::Accessor& a = m.accessors[index];
  const std::string where = what + ": accessor " + std::to_string(index);
  if (a.sparse.isSparse) return Error::runtime(where + ": sparse accessors are not supported");
  if (a.bufferView < 0 || static_cast<size_t>(a.bufferView) >= m.bufferViews.size())
    return Error::runtime(where + ": has no valid buffer view");
  const tinygltf::BufferView& bv = m.bufferViews[a.bufferView];
  if (bv.buffer < 0 || static_cast<size_t>(bv.buffer) >= m.buffers.size())
    return Error::runtime(where + ": buffer view " + std::to_string(a.bufferView) + " names no valid buffer");
  const std::vector<unsigned char>& data = m.buffers[bv.buffer].data;
  const int comp_size = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType));
  const int comps = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type));
  if (comp_size <= 0 || comps <= 0) return Error::runtime(where + ": unknown component or element type");
  const int stride = a.ByteStride(bv);
  if (stride <= 0) return Error::runtime(where + ": invalid byte stride");
  const size_t elem = static_cast<size_t>(comp_size) * static_cast<size_t>(comps);
  // Everything read lies in [view start + accessor offset, + stride·(count−1) + elem),
  // which must fit the view, which must fit the buffer (all in 128 bits of headroom).
  const unsigned __int128 view_end = static_cast<unsigned __int128>(bv.byteOffset) + bv.byteLength;
  const unsigned __int128 need =
      a.count == 0 ? 0
                   : static_cast<unsigned __int128>(a.byteOffset) +
                         static_cast<unsigned __int128>(stride) * (a.count - 1) + elem;
  if (view_end > data.size() || need > bv.byteLength)
    return Error::runtime(where + ": reads past the end of its buffer (" + std::to_string(a.count) + " elements)");
  AccessorView v;
  v.base = data.data() + bv.byteOffset + a.byteOffset;
  v.stride = static_cast<size_t>(stride);
  v.count = a.count;
  v.component = a.componentType;
  v.type = a.type;
  return v;
}

glm::mat4 nodeMatrix(const tinygltf::Node& n) {
  if (n.matrix.size() == 16) {
    glm::mat4 m;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m[c][r] = static_cast<float>(n.matrix[static_cast<size_t>(c * 4 + r)]);
    return m;
  }
  glm::mat4 m(1.0f);
  if (n.translation.size() == 3)
    m = glm::translate(m, glm::vec3(n.translation[0], n.translation[1], n.translation[2]));
  if (n.rotation.size() == 4) {
    // glTF stores (x, y, z, w); glm's constructor takes (w, x, y, z).
    glm::quat q(static_cast<float>(n.rotation[3]), static_cast<float>(n.rotation[0]),
                static_cast<float>(n.rotation[1]), static_cast<float>(n.rotation[2]));
    const float len = glm::length(q);
    if (len > 0.0f && std::isfinite(len)) m *= glm::mat4_cast(q / len);
  }
  if (n.scale.size() == 3) m = glm::scale(m, glm::vec3(n.scale[0], n.scale[1], n.scale[2]));
  return m;
}

// Appends the triangles of one primitive to `mesh`, welding positions equal to the bit.
Status appendPrimitive(const tinygltf::Model& m, const tinygltf::Primitive& p, const std::string& where,
                       TriMesh& mesh, std::unordered_map<uint64_t, std::vector<uint32_t>>& weld) {
  const auto pos_it = p.attributes.find("POSITION");
  if (pos_it == p.attributes.end()) return Error::runtime(where + ": has no POSITION attribute");
  auto pos = viewAccessor(m, pos_it->second, where);
  if (!pos) return pos.error();
  if (pos->type != TINYGLTF_TYPE_VEC3 || pos->component != TINYGLTF_COMPONENT_TYPE_FLOAT)
    return Error::runtime(where + ": POSITION must be VEC3 of floats");
  // Welded index of each of the primitive's vertices.
  std::vector<uint32_t> remap(pos->count);
  for (size_t i = 0; i < pos->count; ++i) {
    float xyz[3];
    std::memcpy(xyz, pos->base + i * pos->stride, sizeof(xyz));
    if (!std::isfinite(xyz[0]) || !std::isfinite(xyz[1]) || !std::isfinite(xyz[2]))
      return Error::runtime(where + ": vertex " + std::to_string(i) + " has a non-finite coordinate (NaN or inf)");
    const glm::vec3 v(xyz[0] + 0.0f, xyz[1] + 0.0f, xyz[2] + 0.0f);  // +0: -0 welds with 0
    uint32_t bits[3];
    std::memcpy(bits, &v, sizeof(bits));
    const uint64_t key = (static_cast<uint64_t>(bits[0]) * 0x9E3779B97F4A7C15ull) ^
                         (static_cast<uint64_t>(bits[1]) * 0xC2B2AE3D27D4EB4Full) ^ bits[2];
    auto& bucket = weld[key];
    uint32_t found = UINT32_MAX;
    for (uint32_t c : bucket)
      if (mesh.positions[c] == v) found = c;
    if (found == UINT32_MAX) {
      found = static_cast<uint32_t>(mesh.positions.size());
      mesh.positions.push_back(v);
      bucket.push_back(found);
    }
    remap[i] = found;
  }

  std::vector<uint32_t> idx;
  if (p.indices >= 0) {
    auto ind = viewAccessor(m, p.indices, where);
    if (!ind) return ind.error();
    if (ind->type != TINYGLTF_TYPE_SCALAR) return Error::runtime(where + ": indices must be scalars");
    idx.resize(ind->count);
    for (size_t i = 0; i < ind->count; ++i) {
      const unsigned char* e = ind->base + i * ind->stride;
      uint32_t v = 0;
      switch (ind->component) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: v = *e; break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
          uint16_t s;
          std::memcpy(&s, e, sizeof(s));
          v = s;
          break;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: std::memcpy(&v, e, sizeof(v)); break;
        default: return Error::runtime(where + ": indices must be unsigned bytes, shorts or ints");
      }
      if (v >= pos->count)
        return Error::runtime(where + ": index " + std::to_string(v) + " out of range (" +
                              std::to_string(pos->count) + " vertices)");
      idx[i] = v;
    }
  } else {
    idx.resize(pos->count);
    for (size_t i = 0; i < idx.size(); ++i) idx[i] = static_cast<uint32_t>(i);
  }

  auto add = [&](uint32_t a, uint32_t b, uint32_t c) {
    const uint32_t wa = remap[a], wb = remap[b], wc = remap[c];
    if (wa != wb && wb != wc && wa != wc) mesh.faces.push_back({wa, wb, wc});  // welding may degenerate
  };
  const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    for (size_t i = 0; i + 2 < idx.size(); i += 3) add(idx[i], idx[i + 1], idx[i + 2]);
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    for (size_t i = 0; i + 2 < idx.size(); ++i)
      if (i % 2 == 0) add(idx[i], idx[i + 1], idx[i + 2]);
      else add(idx[i + 1], idx[i], idx[i + 2]);
  } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
    for (size_t i = 1; i + 1 < idx.size(); ++i) add(idx[0], idx[i], idx[i + 1]);
  }  // points and lines: nothing to draw as a surface
  return {};
}

}  // namespace

Result<std::vector<GltfMeshNode>> loadGltf(const std::filesystem::path& path) {
  const std::string name = path.string();
  if (Status s = checkInputFile(path, "glTF file"); !s) return s.error();
  std::string ext = path.extension().string();
  for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));

  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(skipImage, nullptr);
  loader.SetFsCallbacks({&fileExistsNoOpen, &tinygltf::ExpandFilePath, &readWholeFileChecked,
                         &tinygltf::WriteWholeFile, nullptr});
  std::string err, warn;
  bool ok = false;
  try {
    ok = ext == ".glb" ? loader.LoadBinaryFromFile(&model, &err, &warn, name)
                       : loader.LoadASCIIFromFile(&model, &err, &warn, name);
  } catch (const std::exception& e) {
    return Error::runtime(name + ": cannot read glTF (" + oneLine(e.what()) + ")");
  }
  if (!ok) return Error::runtime(name + ": cannot read glTF (" + oneLine(err.empty() ? "unknown error" : err) + ")");

  // Root nodes: those of the default scene, else of the first scene, else every node that
  // is nobody's child.
  std::vector<int> roots;
  if (!model.scenes.empty()) {
    const int s = model.defaultScene >= 0 && static_cast<size_t>(model.defaultScene) < model.scenes.size()
                      ? model.defaultScene
                      : 0;
    roots = model.scenes[s].nodes;
  } else {
    std::vector<uint8_t> is_child(model.nodes.size(), 0);
    for (const auto& n : model.nodes)
      for (int c : n.children)
        if (c >= 0 && static_cast<size_t>(c) < model.nodes.size()) is_child[c] = 1;
    for (size_t i = 0; i < model.nodes.size(); ++i)
      if (!is_child[i]) roots.push_back(static_cast<int>(i));
  }

  std::vector<GltfMeshNode> out;
  // Depth-first over the node tree; a node met twice (a cycle or a shared child, both
  // invalid glTF) is an error rather than an endless walk.
  std::vector<uint8_t> visited(model.nodes.size(), 0);
  std::vector<std::pair<int, glm::mat4>> stack;
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.emplace_back(*it, glm::mat4(1.0f));
  while (!stack.empty()) {
    const auto [ni, parent] = stack.back();
    stack.pop_back();
    if (ni < 0 || static_cast<size_t>(ni) >= model.nodes.size())
      return Error::runtime(name + ": node " + std::to_string(ni) + " does not exist");
    if (visited[ni]) return Error::runtime(name + ": node " + std::to_string(ni) + " is reached twice (node graph is not a tree)");
    visited[ni] = 1;
    const tinygltf::Node& node = model.nodes[ni];
    const glm::mat4 world = parent * nodeMatrix(node);
    for (int k = 0; k < 16; ++k)
      if (!std::isfinite(glm::value_ptr(world)[k]))
        return Error::runtime(name + ": node " + std::to_string(ni) + " has a non-finite transform");
    if (node.mesh >= 0) {
      if (static_cast<size_t>(node.mesh) >= model.meshes.size())
        return Error::runtime(name + ": node " + std::to_string(ni) + " names mesh " + std::to_string(node.mesh) +
                              ", which does not exist");
      const tinygltf::Mesh& mesh = model.meshes[node.mesh];
      GltfMeshNode g;
      g.node = ni;
      g.name = !node.name.empty() ? node.name : !mesh.name.empty() ? mesh.name : "node" + std::to_string(ni);
      g.transform = world;
      std::unordered_map<uint64_t, std::vector<uint32_t>> weld;
      for (size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
        const std::string where = name + ": mesh " + std::to_string(node.mesh) + " primitive " + std::to_string(pi);
        if (Status s = appendPrimitive(model, mesh.primitives[pi], where, g.mesh, weld); !s) return s.error();
        // The primitive's material (index + 1; 0: none) for its faces: material lines.
        g.mesh.face_materials.resize(g.mesh.faces.size(), static_cast<uint32_t>(mesh.primitives[pi].material + 1));
      }
      const auto& fm = g.mesh.face_materials;
      if (std::adjacent_find(fm.begin(), fm.end(), std::not_equal_to<>()) == fm.end()) g.mesh.face_materials.clear();
      if (!g.mesh.faces.empty()) {
        // Drop vertices no triangle uses (those of point and line primitives).
        std::vector<uint32_t> used(g.mesh.positions.size(), UINT32_MAX);
        std::vector<glm::vec3> kept;
        for (auto& f : g.mesh.faces)
          for (uint32_t& v : f) {
            if (used[v] == UINT32_MAX) {
              used[v] = static_cast<uint32_t>(kept.size());
              kept.push_back(g.mesh.positions[v]);
            }
            v = used[v];
          }
        g.mesh.positions = std::move(kept);
        if (Status s = validateMesh(g.mesh, name + ": mesh " + std::to_string(node.mesh)); !s) return s.error();
        out.push_back(std::move(g));
      }
    }
    for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) stack.emplace_back(*it, world);
  }
  if (out.empty()) return Error::runtime(name + ": no triangle meshes in the glTF scene");
  return out;
}

}  // namespace lodline
