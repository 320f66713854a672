// Ohtake, Belyaev, Seidel 2004 §2 (ridges and valleys, per-face extraction with the principal
// directions' signs agreed); see ridge_lines.h.
#include "lines/ridge_lines.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace lodline {

namespace {

constexpr uint8_t kRidgeCandidate = 1, kValleyCandidate = 2;

// Per vertex: may a ridge (bit 0) or valley (bit 1) pass through a face around it.
void candidateCodes(const SurfaceFields& f, const RidgeSpec& spec, std::vector<uint8_t>& code) {
  const size_t n = f.positions.size();
  code.assign(n, 0);
  if (f.k1.size() != n || f.k2.size() != n) return;
  const float fs = spec.feature_size > 0.0f ? spec.feature_size : 1.0f;
  const float half = 0.5f * spec.threshold / fs;
  for (size_t v = 0; v < n; ++v) {
    const float k1 = f.k1[v], k2 = f.k2[v];
    uint8_t c = 0;
    if (spec.ridges && k1 > -k2 && k1 > half) c |= kRidgeCandidate;
    if (spec.valleys && -k2 > k1 && -k2 > half) c |= kValleyCandidate;
    code[v] = c;
  }
}

// The kinds whose bit all three corners of face f share.
inline uint8_t faceCandidates(const std::array<uint32_t, 3>& t, const uint8_t* code) {
  return static_cast<uint8_t>(code[t[0]] & code[t[1]] & code[t[2]]);
}

struct Field {  // one kind's view of the shape: curvature, direction, its derivative along it
  LineKind kind;
  float sign;  // +1 ridges (k1, e1, C111); −1 valleys (−k2, e2, −C222)
  std::span<const float> k;
  std::span<const glm::vec3> e;
  int component;  // 0: C111, 3: C222
  float curvature(uint32_t v) const { return sign * k[v]; }
  float derivative(uint32_t v, std::span<const glm::vec4> dcurv) const { return sign * dcurv[v][component]; }
};

void faceRidge(std::span<const glm::vec3> positions, const std::array<uint32_t, 3>& t,
               const std::array<uint32_t, 3>& face_edges, uint32_t face, const Field& fld,
               std::span<const glm::vec4> dcurv, float th_fs, float fs, LineSet& out) {
  // Agreement of the directions along each side j (corners j, j+1).
  float side_sign[3];
  for (int j = 0; j < 3; ++j)
    side_sign[j] = glm::dot(fld.e[t[j]], fld.e[t[(j + 1) % 3]]) < 0.0f ? -1.0f : 1.0f;
  if (side_sign[0] * side_sign[1] * side_sign[2] < 0.0f) return;  // the field turns in the face
  struct Crossing {
    glm::vec3 p;
    float strength;
    uint32_t id;
  };
  Crossing x[2];
  int nx = 0;
  for (int j = 0; j < 3; ++j) {
    uint32_t a = t[j], b = t[(j + 1) % 3];
    if (b < a) std::swap(a, b);  // from the edge's first vertex, as both faces compute it
    const float da = fld.derivative(a, dcurv), db = side_sign[j] * fld.derivative(b, dcurv);
    if ((da < 0.0f) == (db < 0.0f)) continue;
    float s = da / (da - db);
    if (!(s >= 0.0f && s <= 1.0f)) s = 0.5f;
    if (nx == 2) return;  // three crossings cannot happen with agreeing signs; NaN input
    x[nx++] = {(1.0f - s) * positions[a] + s * positions[b],
               (1.0f - s) * fld.curvature(a) + s * fld.curvature(b), face_edges[j]};
  }
  if (nx != 2) return;
  // A maximum along e: in the face's frame (directions agreed with corner 0's), the
  // derivative decreases along e.
  const float s01 = side_sign[0], s02 = side_sign[2];  // corner 2 to 0 is side 2
  const float d0 = fld.derivative(t[0], dcurv), d1 = s01 * fld.derivative(t[1], dcurv),
              d2 = s02 * fld.derivative(t[2], dcurv);
  const glm::vec3 p0 = positions[t[0]], e1 = positions[t[1]] - p0, e2 = positions[t[2]] - p0;
  const glm::vec3 n = glm::cross(e1, e2);
  const float nn = glm::dot(n, n);
  if (!(nn > 0.0f)) return;
  const glm::vec3 grad = ((d1 - d0) * glm::cross(e2, n) + (d2 - d0) * glm::cross(n, e1)) / nn;
  const glm::vec3 dir = fld.e[t[0]] + s01 * fld.e[t[1]] + s02 * fld.e[t[2]];
  if (!(glm::dot(grad, dir) < 0.0f)) return;
  // Strength: |k|·fs against the threshold, faded over one more threshold.
  auto alpha = [&](float k) { return std::clamp((k * fs - th_fs) / th_fs, 0.0f, 1.0f); };
  const float a0 = alpha(x[0].strength), a1 = alpha(x[1].strength);
  if (!(a0 > 0.0f || a1 > 0.0f)) return;
  pushSegment(out, fld.kind, face, x[0].p, x[0].id, a0, x[1].p, x[1].id, a1);
}

}  // namespace

void ridgeCandidateVertices(std::span<const std::array<uint32_t, 3>> faces, const MeshAdjacency& adj,
                            const SurfaceFields& fields, const RidgeSpec& spec, std::vector<uint8_t>& mark,
                            std::vector<uint32_t>& out) {
  out.clear();
  const size_t nv = fields.positions.size();
  if (!(spec.ridges || spec.valleys) || adj.face_count != faces.size() || adj.vertex_count != nv) return;
  std::vector<uint8_t> code;
  candidateCodes(fields, spec, code);
  mark.assign(nv, 0);
  for (size_t f = 0; f < faces.size(); ++f) {
    if (!adj.face_valid[f] || !faceCandidates(faces[f], code.data())) continue;
    for (uint32_t v : faces[f]) mark[v] = 1;
  }
  for (uint32_t v = 0; v < nv; ++v) {
    if (!mark[v]) continue;
    out.push_back(v);
    mark[v] = 0;
  }
}

void extractRidges(std::span<const glm::vec3> positions, std::span<const std::array<uint32_t, 3>> faces,
                   const MeshAdjacency& adj, const SurfaceFields& fields, const RidgeSpec& spec,
                   LineScratch& scratch, LineSet& out) {
  const size_t nv = positions.size();
  if (!(spec.ridges || spec.valleys) || !(spec.threshold > 0.0f)) return;
  if (adj.face_count != faces.size() || adj.vertex_count != nv || fields.k1.size() != nv ||
      fields.k2.size() != nv || fields.pdir1.size() != nv || fields.pdir2.size() != nv || fields.dcurv.size() != nv)
    return;
  candidateCodes(fields, spec, scratch.vertex_code);
  const uint8_t* code = scratch.vertex_code.data();
  const float fs = spec.feature_size > 0.0f ? spec.feature_size : 1.0f;
  const Field kinds[2] = {{LineKind::kRidge, 1.0f, fields.k1, fields.pdir1, 0},
                          {LineKind::kValley, -1.0f, fields.k2, fields.pdir2, 3}};
  for (int k = 0; k < 2; ++k) {  // kinds in order, then faces: deterministic output
    const uint8_t bit = k == 0 ? kRidgeCandidate : kValleyCandidate;
    if (k == 0 ? !spec.ridges : !spec.valleys) continue;
    for (size_t f = 0; f < faces.size(); ++f) {
      if (!adj.face_valid[f] || !(faceCandidates(faces[f], code) & bit)) continue;
      faceRidge(positions, faces[f], adj.face_edges[f], static_cast<uint32_t>(f), kinds[k], fields.dcurv,
                spec.threshold, fs, out);
    }
  }
}

}  // namespace lodline
