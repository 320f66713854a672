// View-dependent floating-cell vertex clustering (Pan, Zhou, Shi, "Real-time rendering
// algorithm based on hybrid static and dynamic simplification methods"; docs/design.md §2.4).
// See vertex_clustering.h for the radius derivation.
#include "lod/vertex_clustering.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/trigonometric.hpp>

namespace lodline {

namespace {

constexpr uint32_t kUnassigned = 0xfffffffeu;
constexpr float kPi = 3.14159265358979f;

uint8_t outcode(const glm::vec4& c) {
  uint8_t o = 0;
  if (c.x < -c.w) o |= 1;
  if (c.x > c.w) o |= 2;
  if (c.y < -c.w) o |= 4;
  if (c.y > c.w) o |= 8;
  if (c.z < -c.w) o |= 16;
  if (c.z > c.w) o |= 32;
  return o;
}

uint64_t hashTriple(std::array<uint32_t, 3> t) {
  std::sort(t.begin(), t.end());
  uint64_t h = 0x9e3779b97f4a7c15ull;
  for (uint32_t v : t) {
    h ^= v;
    h *= 0xff51afd7ed558ccdull;
    h ^= h >> 33;
  }
  return h;
}

bool sameCorners(std::array<uint32_t, 3> a, std::array<uint32_t, 3> b) {
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  return a == b;
}

}  // namespace

VertexClustering::VertexClustering(TriMesh mesh) : mesh_(std::move(mesh)) {
  const uint32_t n = static_cast<uint32_t>(mesh_.positions.size());
  const uint32_t nf = static_cast<uint32_t>(mesh_.faces.size());
  // Incident faces (CSR).
  vf_start_.assign(n + 1, 0);
  for (const auto& f : mesh_.faces)
    for (uint32_t v : f) ++vf_start_[v + 1];
  for (uint32_t v = 0; v < n; ++v) vf_start_[v + 1] += vf_start_[v];
  vf_faces_.resize(vf_start_[n]);
  {
    std::vector<uint32_t> fill(vf_start_.begin(), vf_start_.end() - 1);
    for (uint32_t f = 0; f < nf; ++f)
      for (uint32_t v : mesh_.faces[f]) vf_faces_[fill[v]++] = f;
  }
  // Face normals and area-weighted vertex normals.
  face_normal_.resize(nf);
  vertex_normal_.assign(n, glm::vec3(0.0f));
  for (uint32_t f = 0; f < nf; ++f) {
    const auto& c = mesh_.faces[f];
    const glm::vec3 cr = glm::cross(mesh_.positions[c[1]] - mesh_.positions[c[0]],
                                    mesh_.positions[c[2]] - mesh_.positions[c[0]]);
    const float len = glm::length(cr);
    face_normal_[f] = len > 0.0f ? cr / len : glm::vec3(0.0f);
    for (uint32_t v : c) vertex_normal_[v] += cr;  // |cr| = 2·area
  }
  for (auto& nv : vertex_normal_) {
    const float len = glm::length(nv);
    nv = len > 0.0f ? nv / len : glm::vec3(0.0f);
  }
  // Boundary and non-manifold edges: an undirected edge not shared by exactly two faces.
  boundary_.assign(n, 0);
  {
    std::vector<uint64_t> edges;
    edges.reserve(3 * static_cast<size_t>(nf));
    for (const auto& c : mesh_.faces)
      for (int i = 0; i < 3; ++i) {
        const uint32_t a = c[i], b = c[(i + 1) % 3];
        edges.push_back((static_cast<uint64_t>(std::min(a, b)) << 32) | std::max(a, b));
      }
    std::sort(edges.begin(), edges.end());
    for (size_t i = 0; i < edges.size();) {
      size_t j = i;
      while (j < edges.size() && edges[j] == edges[i]) ++j;
      if (j - i != 2) {
        boundary_[static_cast<uint32_t>(edges[i] >> 32)] = 1;
        boundary_[static_cast<uint32_t>(edges[i] & 0xffffffffu)] = 1;
      }
      i = j;
    }
  }
  // Weights C_i: mean angle between the vertex normal and its faces' normals.
  weight_.assign(n, 0.0f);
  for (uint32_t v = 0; v < n; ++v) {
    if (boundary_[v]) {
      weight_[v] = kPi;  // maximal: boundary vertices are kept
      continue;
    }
    double sum = 0.0;
    uint32_t count = 0;
    for (uint32_t k = vf_start_[v]; k < vf_start_[v + 1]; ++k) {
      const glm::vec3& fnrm = face_normal_[vf_faces_[k]];
      if (fnrm == glm::vec3(0.0f)) continue;
      sum += std::acos(std::clamp(glm::dot(vertex_normal_[v], fnrm), -1.0f, 1.0f));
      ++count;
    }
    weight_[v] = count ? static_cast<float>(sum / count) : 0.0f;
  }
  order_.resize(n);
  std::iota(order_.begin(), order_.end(), 0u);
  std::stable_sort(order_.begin(), order_.end(),
                   [&](uint32_t a, uint32_t b) { return weight_[a] > weight_[b]; });
  rep_.assign(n, kClusterCulled);
  radius_.assign(n, 0.0f);
  outside_.assign(n, 0);
}

void VertexClustering::cluster(const Camera& camera, int width, int height, const ClusterParams& params) {
  const uint32_t n = static_cast<uint32_t>(mesh_.positions.size());
  const uint32_t nf = static_cast<uint32_t>(mesh_.faces.size());
  stats_ = {};
  const float aspect = static_cast<float>(width) / static_cast<float>(std::max(height, 1));
  const glm::mat4 view = camera.view();
  const glm::mat4 mvp = camera.projection(aspect) * view;
  const glm::vec3 fwd = camera.forward();
  // R = base · z (perspective) or base (orthographic), before the foveation factor.
  const float sqrt_k = std::sqrt(std::max(params.pixel_error, 0.0f));
  const float tan_half = std::tan(0.5f * glm::radians(camera.fov_deg));
  const float base = camera.orthographic ? sqrt_k * camera.ortho_height / static_cast<float>(height)
                                         : sqrt_k * 2.0f * tan_half / static_cast<float>(height);
  const glm::vec2 focus = params.focus_px.x < 0.0f || params.focus_px.y < 0.0f
                              ? glm::vec2(0.5f * static_cast<float>(width), 0.5f * static_cast<float>(height))
                              : params.focus_px;
  const float f_px = 0.5f * static_cast<float>(height) / tan_half;  // focal length in pixels
  const glm::vec3 gaze_cam =
      glm::normalize(glm::vec3(focus.x - 0.5f * static_cast<float>(width), 0.5f * static_cast<float>(height) - focus.y, -f_px));

  // 1. Culling: frustum outcodes per vertex; a vertex is visible when inside the frustum and
  // at least one incident face faces the camera.
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  uint32_t visible = 0;
  for (uint32_t v = 0; v < n; ++v) {
    const glm::vec3& p = mesh_.positions[v];
    outside_[v] = outcode(mvp * glm::vec4(p, 1.0f));
    bool vis = !params.cull || outside_[v] == 0;
    if (vis && params.cull) {
      vis = false;
      for (uint32_t k = vf_start_[v]; k < vf_start_[v + 1] && !vis; ++k) {
        const uint32_t f = vf_faces_[k];
        const glm::vec3 d = camera.orthographic ? fwd : p - camera.eye;
        vis = glm::dot(face_normal_[f], d) < 0.0f;
      }
    }
    if (vf_start_[v] == vf_start_[v + 1]) vis = false;  // isolated
    if (!vis) {
      rep_[v] = kClusterCulled;
      radius_[v] = 0.0f;
      ++stats_.culled_vertices;
      continue;
    }
    rep_[v] = kUnassigned;
    float k_scale = 1.0f;
    const glm::vec3 pc = glm::vec3(view * glm::vec4(p, 1.0f));
    if (params.foveation > 0.0f && !camera.orthographic) {
      const float len = glm::length(pc);
      const float q = len > 0.0f ? glm::degrees(std::acos(std::clamp(glm::dot(pc / len, gaze_cam), -1.0f, 1.0f))) : 0.0f;
      const float fac = 90.0f / (90.0f - std::min(q, 80.0f));
      k_scale = std::pow(fac * fac, params.foveation);
    }
    const float z = std::max(-pc.z, 0.0f);
    radius_[v] = (camera.orthographic ? base : base * z) * std::sqrt(k_scale);
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
    ++visible;
  }

  // 2. Uniform grid over the visible vertices (counting sort into cells). Cell size: the
  // median radius, grown until there are at most ~8 cells per visible vertex.
  uint32_t nx = 1, ny = 1, nz = 1;
  float cell = 1.0f;
  if (visible > 0) {
    cell_items_.clear();
    for (uint32_t v = 0; v < n; ++v)
      if (rep_[v] == kUnassigned) cell_items_.push_back(v);
    auto mid = cell_items_.begin() + cell_items_.size() / 2;
    std::nth_element(cell_items_.begin(), mid, cell_items_.end(),
                     [&](uint32_t a, uint32_t b) { return radius_[a] < radius_[b]; });
    cell = std::max(radius_[*mid], 1e-12f);
    const glm::vec3 ext = hi - lo;
    const double limit = 8.0 * visible + 64.0;
    for (;;) {
      const double cx = std::floor(ext.x / cell) + 1, cy = std::floor(ext.y / cell) + 1, cz = std::floor(ext.z / cell) + 1;
      if (cx * cy * cz <= limit) {
        nx = static_cast<uint32_t>(cx), ny = static_cast<uint32_t>(cy), nz = static_cast<uint32_t>(cz);
        break;
      }
      cell *= 1.5f;
    }
  }
  const size_t cells = static_cast<size_t>(nx) * ny * nz;
  auto cellCoord = [&](float x, float origin, uint32_t count) {
    const float c = std::floor((x - origin) / cell);
    return static_cast<uint32_t>(std::clamp(c, 0.0f, static_cast<float>(count - 1)));
  };
  cell_start_.assign(cells + 1, 0);
  cell_of_.resize(n);
  for (uint32_t v = 0; v < n; ++v) {
    if (rep_[v] != kUnassigned) continue;
    const glm::vec3& p = mesh_.positions[v];
    const size_t c = cellCoord(p.x, lo.x, nx) + static_cast<size_t>(nx) * (cellCoord(p.y, lo.y, ny) + static_cast<size_t>(ny) * cellCoord(p.z, lo.z, nz));
    cell_of_[v] = static_cast<uint32_t>(c);
    ++cell_start_[c + 1];
  }
  for (size_t c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
  cell_items_.resize(visible);
  {
    // cell_of_ is reused as the fill cursor after its value is read.
    for (uint32_t v = 0; v < n; ++v) {
      if (rep_[v] != kUnassigned) continue;
      cell_items_[cell_start_[cell_of_[v]]++] = v;
    }
    for (size_t c = cells; c > 0; --c) cell_start_[c] = cell_start_[c - 1];
    cell_start_[0] = 0;
  }

  // 3. Clustering in weight order.
  for (uint32_t v : order_) {
    if (rep_[v] != kUnassigned) continue;
    rep_[v] = v;
    ++stats_.representatives;
    const glm::vec3 p = mesh_.positions[v];
    const float r = radius_[v], r2 = r * r;
    const uint32_t x0 = cellCoord(p.x - r, lo.x, nx), x1 = cellCoord(p.x + r, lo.x, nx);
    const uint32_t y0 = cellCoord(p.y - r, lo.y, ny), y1 = cellCoord(p.y + r, lo.y, ny);
    const uint32_t z0 = cellCoord(p.z - r, lo.z, nz), z1 = cellCoord(p.z + r, lo.z, nz);
    for (uint32_t z = z0; z <= z1; ++z)
      for (uint32_t y = y0; y <= y1; ++y)
        for (uint32_t x = x0; x <= x1; ++x) {
          const size_t c = x + static_cast<size_t>(nx) * (y + static_cast<size_t>(ny) * z);
          for (uint32_t k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
            const uint32_t w = cell_items_[k];
            if (rep_[w] != kUnassigned || boundary_[w]) continue;
            const glm::vec3 d = mesh_.positions[w] - p;
            if (glm::dot(d, d) <= r2) {
              rep_[w] = v;
              ++stats_.absorbed;
            }
          }
        }
  }

  // 4. Faces: keep those with a visible corner (partly culled ones whole, culled corners at
  // their own vertex) and front-facing ones straddling the frustum; drop collapsed ones and
  // duplicates (the later input face of a duplicate pair is dropped).
  constexpr std::array<uint32_t, 3> kNoFace{kClusterCulled, kClusterCulled, kClusterCulled};
  candidate_.resize(nf);
  size_t cap = 16;
  while (cap < 2 * static_cast<size_t>(nf)) cap <<= 1;
  hash_.assign(cap, 0);
  for (uint32_t f = 0; f < nf; ++f) {
    candidate_[f] = kNoFace;
    const auto& c = mesh_.faces[f];
    const bool all_culled = rep_[c[0]] == kClusterCulled && rep_[c[1]] == kClusterCulled && rep_[c[2]] == kClusterCulled;
    if (all_culled) {
      const glm::vec3 d = camera.orthographic ? fwd : mesh_.positions[c[0]] - camera.eye;
      const bool front = glm::dot(face_normal_[f], d) < 0.0f;
      if (params.cull && (!front || (outside_[c[0]] & outside_[c[1]] & outside_[c[2]]) != 0)) {
        ++stats_.culled_faces;
        continue;
      }
    }
    std::array<uint32_t, 3> m;
    for (int i = 0; i < 3; ++i) m[i] = rep_[c[i]] == kClusterCulled ? c[i] : rep_[c[i]];
    if (m[0] == m[1] || m[1] == m[2] || m[2] == m[0]) {
      ++stats_.collapsed_faces;
      continue;
    }
    const glm::vec3 cr = glm::cross(mesh_.positions[m[1]] - mesh_.positions[m[0]],
                                    mesh_.positions[m[2]] - mesh_.positions[m[0]]);
    if (!(glm::dot(cr, cr) > 0.0f)) {
      ++stats_.collapsed_faces;
      continue;
    }
    size_t h = hashTriple(m) & (cap - 1);
    bool dup = false;
    while (hash_[h] != 0) {
      std::array<uint32_t, 3>& other = candidate_[hash_[h] - 1];
      if (sameCorners(other, m)) {
        dup = true;
        // Opposite orientation: the two faces fold onto each other; drop both so the
        // surface closes over the fold instead of keeping a one-sided flap.
        const bool same_orientation = (other[0] == m[0] && other[1] == m[1]) ||
                                      (other[0] == m[1] && other[1] == m[2]) ||
                                      (other[0] == m[2] && other[1] == m[0]);
        if (!same_orientation) {
          other = kNoFace;
          ++stats_.duplicate_faces;
        }
        break;
      }
      h = (h + 1) & (cap - 1);
    }
    if (dup) {
      ++stats_.duplicate_faces;
      continue;
    }
    candidate_[f] = m;
    hash_[h] = f + 1;
  }
  // Stable slots: free the slots of faces that changed or went, refill them with the new
  // ones, append the rest, then compact from the end.
  face_slot_.resize(nf, kClusterCulled);
  free_slots_.clear();
  slot_free_.assign(out_faces_.size(), 0);
  for (uint32_t f = 0; f < nf; ++f) {
    const uint32_t s = face_slot_[f];
    if (s == kClusterCulled) continue;
    if (candidate_[f] != out_faces_[s]) {
      free_slots_.push_back(s);
      slot_free_[s] = 1;
      face_slot_[f] = kClusterCulled;
    }
  }
  size_t next_free = 0;
  for (uint32_t f = 0; f < nf; ++f) {
    if (candidate_[f] == kNoFace || face_slot_[f] != kClusterCulled) continue;
    uint32_t s;
    if (next_free < free_slots_.size()) {
      s = free_slots_[next_free++];
      slot_free_[s] = 0;
    } else {
      s = static_cast<uint32_t>(out_faces_.size());
      out_faces_.push_back({});
      slot_face_.resize(out_faces_.size());
      slot_free_.push_back(0);
    }
    out_faces_[s] = candidate_[f];
    slot_face_[s] = f;
    face_slot_[f] = s;
  }
  if (next_free < free_slots_.size()) {
    std::sort(free_slots_.begin() + static_cast<std::ptrdiff_t>(next_free), free_slots_.end());
    size_t size = out_faces_.size();
    for (size_t i = next_free; i < free_slots_.size(); ++i) {
      const uint32_t s = free_slots_[i];
      while (size > 0 && slot_free_[size - 1]) --size;
      if (s >= size) break;
      const uint32_t last = static_cast<uint32_t>(size - 1);
      out_faces_[s] = out_faces_[last];
      slot_face_[s] = slot_face_[last];
      face_slot_[slot_face_[s]] = s;
      slot_free_[s] = 0;
      slot_free_[last] = 1;
      --size;
    }
    while (size > 0 && slot_free_[size - 1]) --size;
    out_faces_.resize(size);
    slot_face_.resize(size);
  }
  stats_.faces = static_cast<uint32_t>(out_faces_.size());
}

}  // namespace lodline
