#include "core/mesh_order.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include <glm/common.hpp>

namespace lodline {
namespace {

// The low 10 bits of x spread to every third bit (bit i → bit 3i).
uint32_t spreadBits(uint32_t x) {
  x &= 0x3ff;
  x = (x | (x << 16)) & 0x030000ff;
  x = (x | (x << 8)) & 0x0300f00f;
  x = (x | (x << 4)) & 0x030c30c3;
  x = (x | (x << 2)) & 0x09249249;
  return x;
}

// A median corner spread at most this is local already: the corners' per-vertex records lie
// within a few kilobytes (a generated tube stored ring by ring: its ring size). Such a mesh
// keeps its order, which also suits the rasteriser's vertex cache.
constexpr uint32_t kLocalSpread = 256;

uint32_t spreadOf(const std::array<uint32_t, 3>& f) {
  return std::max({f[0], f[1], f[2]}) - std::min({f[0], f[1], f[2]});
}

uint32_t median(std::vector<uint32_t>& v) {
  if (v.empty()) return 0;
  auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace

bool orderForLocality(TriMesh& mesh, std::vector<uint32_t>* stored_to_drawn) {
  if (stored_to_drawn) stored_to_drawn->clear();
  const size_t nv = mesh.positions.size(), nf = mesh.faces.size();
  if (nv == 0 || nf == 0 || nv > UINT32_MAX || nf > UINT32_MAX) return false;
  // Invalid meshes are left as they are, for validateMesh to report.
  for (const glm::vec3& p : mesh.positions)
    if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))) return false;
  for (const auto& c : mesh.faces)
    if (c[0] >= nv || c[1] >= nv || c[2] >= nv) return false;
  // A local order is kept as it is, before any sorting.
  const uint32_t before = medianCornerSpread(mesh);
  if (before <= kLocalSpread) return false;
  const Bounds b = computeBounds(mesh.positions);
  const glm::vec3 extent = glm::max(b.max - b.min, glm::vec3(1e-30f));
  // Vertices by Morton code, stably (ties keep the stored order).
  std::vector<uint32_t> code(nv), by_code(nv), tmp;
  for (uint32_t i = 0; i < nv; ++i) {
    code[i] = mortonCode((mesh.positions[i] - b.min) / extent);
    by_code[i] = i;
  }
  sortByCode(code, by_code, tmp);
  std::vector<uint32_t> remap(nv);
  for (uint32_t i = 0; i < nv; ++i) remap[by_code[i]] = i;
  // Only where it helps: the median spread of the faces' corners after against before.
  std::vector<uint32_t> spreads(nf);
  for (size_t f = 0; f < nf; ++f) {
    const auto& c = mesh.faces[f];
    spreads[f] = spreadOf({remap[c[0]], remap[c[1]], remap[c[2]]});
  }
  if (!(median(spreads) < before)) return false;
  std::vector<glm::vec3> positions(nv);
  for (uint32_t i = 0; i < nv; ++i) positions[i] = mesh.positions[by_code[i]];
  mesh.positions = std::move(positions);
  for (auto& f : mesh.faces)
    for (auto& v : f) v = remap[v];
  for (auto& e : mesh.marked_edges)
    for (auto& v : e) v = v < nv ? remap[v] : v;  // an index out of range stays so
  // Faces by their lowest corner, stably.
  std::vector<uint32_t> order, start;
  orderByLowestCorner(mesh.faces, static_cast<uint32_t>(nv), order, start);
  std::vector<std::array<uint32_t, 3>> faces(nf);
  for (size_t k = 0; k < nf; ++k) faces[k] = mesh.faces[order[k]];
  mesh.faces = std::move(faces);
  if (mesh.face_materials.size() == nf) {
    std::vector<uint32_t> materials(nf);
    for (size_t k = 0; k < nf; ++k) materials[k] = mesh.face_materials[order[k]];
    mesh.face_materials = std::move(materials);
  }
  if (stored_to_drawn) *stored_to_drawn = std::move(remap);
  return true;
}

uint32_t mortonCode(const glm::vec3& t) {
  auto cell = [](float x) {  // x in [0, 1] → 0..1023 (NaN → 0)
    return x >= 0.0f ? static_cast<uint32_t>(std::min(x, 1.0f) * 1023.0f) : 0u;
  };
  return spreadBits(cell(t.x)) | (spreadBits(cell(t.y)) << 1) | (spreadBits(cell(t.z)) << 2);
}

void sortByCode(std::span<const uint32_t> code, std::vector<uint32_t>& items, std::vector<uint32_t>& tmp) {
  std::array<uint32_t, 1025> count;
  tmp.resize(items.size());
  for (int shift = 0; shift < 30; shift += 10) {
    count.fill(0u);
    for (uint32_t i : items) ++count[((code[i] >> shift) & 1023u) + 1];
    for (size_t k = 1; k < count.size(); ++k) count[k] += count[k - 1];
    for (uint32_t i : items) tmp[count[(code[i] >> shift) & 1023u]++] = i;
    items.swap(tmp);
  }
}

void orderByLowestCorner(std::span<const std::array<uint32_t, 3>> faces, uint32_t vertex_count,
                         std::vector<uint32_t>& order, std::vector<uint32_t>& start) {
  start.assign(static_cast<size_t>(vertex_count) + 1, 0u);
  for (const auto& f : faces) ++start[std::min({f[0], f[1], f[2]}) + 1];
  for (size_t v = 1; v <= vertex_count; ++v) start[v] += start[v - 1];
  order.resize(faces.size());
  for (uint32_t f = 0; f < faces.size(); ++f) {
    const auto& c = faces[f];
    order[start[std::min({c[0], c[1], c[2]})]++] = f;
  }
}

uint32_t medianCornerSpread(const TriMesh& mesh) {
  std::vector<uint32_t> spreads(mesh.faces.size());
  for (size_t f = 0; f < mesh.faces.size(); ++f) spreads[f] = spreadOf(mesh.faces[f]);
  return median(spreads);
}

}  // namespace lodline
