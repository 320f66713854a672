#include "io/mesh_paint.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <glm/geometric.hpp>

namespace lodline {
namespace {

// A crossing closer than this fraction of its edge to one end moves to that end: the
// material line then leaves the plane by at most 5% of an edge, and no sliver is made.
constexpr float kSnap = 0.05f;

uint64_t edgeKey(uint32_t a, uint32_t b) {
  if (a > b) std::swap(a, b);
  return (uint64_t(a) << 32) | b;
}

bool opposite(int8_t a, int8_t b) { return (a > 0 && b < 0) || (a < 0 && b > 0); }

// One plane n·p = d. `side` gets, per vertex, −1, 0 (on the plane) or +1; the other planes'
// sides (`earlier`) are extended to the vertices this cut adds. Returns the edges cut.
size_t cutAlongPlane(TriMesh& mesh, glm::vec3 n, float d, std::vector<int8_t>& side,
                     std::vector<std::vector<int8_t>>& earlier) {
  const size_t nv = mesh.positions.size();
  std::vector<float> s(nv);
  for (size_t v = 0; v < nv; ++v) s[v] = glm::dot(n, mesh.positions[v]) - d;
  auto sign = [&](uint32_t v) -> int8_t { return s[v] > 0.0f ? 1 : s[v] < 0.0f ? -1 : 0; };
  // Crossings near an end put that end on the plane (its position is kept).
  for (const auto& f : mesh.faces)
    for (int i = 0; i < 3; ++i) {
      const uint32_t a = f[i], b = f[(i + 1) % 3];
      if (!opposite(sign(a), sign(b))) continue;
      const float t = s[a] / (s[a] - s[b]);
      if (t < kSnap) s[a] = 0.0f;
      else if (t > 1.0f - kSnap) s[b] = 0.0f;
    }
  side.resize(nv);
  for (uint32_t v = 0; v < nv; ++v) side[v] = sign(v);

  std::unordered_map<uint64_t, uint32_t> cut;
  auto crossing = [&](uint32_t a, uint32_t b) {
    const uint64_t key = edgeKey(a, b);
    if (auto it = cut.find(key); it != cut.end()) return it->second;
    if (a > b) std::swap(a, b);  // one position per edge whichever face asks first
    const float t = s[a] / (s[a] - s[b]);
    const uint32_t m = static_cast<uint32_t>(mesh.positions.size());
    mesh.positions.push_back(mesh.positions[a] + t * (mesh.positions[b] - mesh.positions[a]));
    side.push_back(0);
    // Edge a–b does not cross an earlier plane (that cut came first): the new vertex lies on
    // whichever side of it a non-zero end does.
    for (auto& e : earlier) e.push_back(e[a] != 0 ? e[a] : e[b]);
    cut.emplace(key, m);
    return m;
  };

  const bool materials = mesh.face_materials.size() == mesh.faces.size();
  std::vector<std::array<uint32_t, 3>> faces;
  std::vector<uint32_t> face_materials;
  faces.reserve(mesh.faces.size());
  auto emit = [&](const uint32_t* poly, int count, size_t f) {
    auto push = [&](uint32_t a, uint32_t b, uint32_t c) {
      faces.push_back({a, b, c});
      if (materials) face_materials.push_back(mesh.face_materials[f]);
    };
    if (count == 3) {
      push(poly[0], poly[1], poly[2]);
    } else if (count == 4) {  // the shorter diagonal
      const auto& p = mesh.positions;
      if (glm::distance(p[poly[0]], p[poly[2]]) <= glm::distance(p[poly[1]], p[poly[3]])) {
        push(poly[0], poly[1], poly[2]);
        push(poly[0], poly[2], poly[3]);
      } else {
        push(poly[1], poly[2], poly[3]);
        push(poly[1], poly[3], poly[0]);
      }
    }
  };
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto c = mesh.faces[f];
    if (!opposite(side[c[0]], side[c[1]]) && !opposite(side[c[1]], side[c[2]]) && !opposite(side[c[2]], side[c[0]])) {
      emit(c.data(), 3, f);
      continue;
    }
    // Walk the triangle; each side's polygon takes its own corners, corners on the plane and
    // the crossings (a triangle and a triangle or quad).
    uint32_t pos[4], neg[4];
    int np = 0, nn = 0;
    for (int i = 0; i < 3; ++i) {
      const uint32_t v = c[i], w = c[(i + 1) % 3];
      if (side[v] >= 0) pos[np++] = v;
      if (side[v] <= 0) neg[nn++] = v;
      if (opposite(side[v], side[w])) {
        const uint32_t m = crossing(v, w);
        pos[np++] = m;
        neg[nn++] = m;
      }
    }
    emit(pos, np, f);
    emit(neg, nn, f);
  }
  mesh.faces = std::move(faces);
  if (materials) mesh.face_materials = std::move(face_materials);

  std::vector<EdgeKey> marked;
  marked.reserve(mesh.marked_edges.size() + cut.size());
  for (const EdgeKey& e : mesh.marked_edges) {
    if (auto it = cut.find(edgeKey(e[0], e[1])); it != cut.end()) {
      marked.push_back({e[0], it->second});
      marked.push_back({it->second, e[1]});
    } else {
      marked.push_back(e);
    }
  }
  mesh.marked_edges = std::move(marked);
  return cut.size();
}

// −1, 0 or +1: the side of a face already cut by the plane (its corners never disagree).
int faceSide(const std::array<uint32_t, 3>& f, const std::vector<int8_t>& side) {
  int out = 0;
  for (uint32_t v : f)
    if (side[v] != 0) out = side[v];
  return out;
}

}  // namespace

Result<PaintInfo> paintMesh(TriMesh& mesh, std::span<const PaintRegion> regions, const std::string& what) {
  PaintInfo info;
  if (regions.empty()) return info;
  struct Plane {
    glm::vec3 n;
    float d;
  };
  std::vector<Plane> planes;  // per region: its plane, then a slab's far plane
  std::vector<std::array<int, 2>> region_planes;
  for (size_t k = 0; k < regions.size(); ++k) {
    const PaintRegion& r = regions[k];
    const std::string where = what + ": paint region " + std::to_string(k);
    const float len = glm::length(r.normal);
    if (!std::isfinite(len) || !(len > 0.0f)) return Error::runtime(where + ": the plane's normal must be finite and not zero");
    if (!std::isfinite(r.offset)) return Error::runtime(where + ": the plane's offset must be finite");
    if (!std::isfinite(r.thickness) || r.thickness < 0.0f)
      return Error::runtime(where + ": the thickness must be finite and >= 0");
    const glm::vec3 n = r.normal / len;
    const float d = r.offset / len;
    region_planes.push_back({static_cast<int>(planes.size()), r.thickness > 0.0f ? static_cast<int>(planes.size()) + 1 : -1});
    planes.push_back({n, d});
    if (r.thickness > 0.0f) planes.push_back({n, d + r.thickness});
  }

  std::vector<std::vector<int8_t>> sides;
  for (const Plane& p : planes) {
    std::vector<int8_t> side;
    info.cut_edges += cutAlongPlane(mesh, p.n, p.d, side, sides);
    sides.push_back(std::move(side));
  }

  // A mesh without materials is one material, index 0.
  if (mesh.face_materials.size() != mesh.faces.size()) mesh.face_materials.assign(mesh.faces.size(), 0);
  const uint32_t base = *std::max_element(mesh.face_materials.begin(), mesh.face_materials.end()) + 1;
  std::vector<uint8_t> painted(mesh.faces.size(), 0);
  for (size_t k = 0; k < regions.size(); ++k) {
    const auto [lo, hi] = region_planes[k];
    for (size_t f = 0; f < mesh.faces.size(); ++f) {
      const bool inside = faceSide(mesh.faces[f], sides[lo]) >= 0 && (hi < 0 || faceSide(mesh.faces[f], sides[hi]) <= 0);
      if (!inside) continue;
      mesh.face_materials[f] = base + static_cast<uint32_t>(k);
      painted[f] = 1;
    }
  }
  info.painted_faces = static_cast<size_t>(std::count(painted.begin(), painted.end(), 1));
  // One material over the whole mesh is the same as none (TriMesh::face_materials).
  const auto& fm = mesh.face_materials;
  if (std::adjacent_find(fm.begin(), fm.end(), std::not_equal_to<>()) == fm.end()) mesh.face_materials.clear();
  return info;
}

}  // namespace lodline
