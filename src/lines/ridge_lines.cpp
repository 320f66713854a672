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
  const float* d;  // C111 or C222 of vertex v at d[v·stride]
  size_t stride;
  float strength(uint32_t v) const { return sign * k[v]; }
  const glm::vec3& direction(uint32_t v) const { return e[v]; }
  float derivative(uint32_t v) const { return sign * d[v * stride]; }
};

// A field given by three per-vertex arrays (apparent ridges: q1, t1, Dt1 q1; principal
// highlights: their strength, the dominant direction e, v̂·e).
struct ArrayField {
  std::span<const float> strength_;
  std::span<const glm::vec3> direction_;
  std::span<const float> derivative_;
  float strength(uint32_t v) const { return strength_[v]; }
  const glm::vec3& direction(uint32_t v) const { return direction_[v]; }
  float derivative(uint32_t v) const { return derivative_[v]; }
};

// The maximum of fld.strength along fld.direction in face f, if one crosses it: the zero set
// of the derivative, with the directions' signs agreed along each edge, where the derivative
// decreases along the direction. Endpoint alpha fades from 0 at th_fs (on strength·fs) to 1
// at twice it.
template <bool kMaximum = true, class F>
void faceMaximum(std::span<const glm::vec3> positions, const std::array<uint32_t, 3>& t,
                 const std::array<uint32_t, 3>& face_edges, uint32_t face, LineKind kind, const F& fld,
                 float th_fs, float fs, LineSet& out) {
  // Agreement of the directions along each side j (corners j, j+1).
  float side_sign[3];
  for (int j = 0; j < 3; ++j)
    side_sign[j] = glm::dot(fld.direction(t[j]), fld.direction(t[(j + 1) % 3])) < 0.0f ? -1.0f : 1.0f;
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
    const float da = fld.derivative(a), db = side_sign[j] * fld.derivative(b);
    if ((da < 0.0f) == (db < 0.0f)) continue;
    float s = da / (da - db);
    if (!(s >= 0.0f && s <= 1.0f)) s = 0.5f;
    if (nx == 2) return;  // three crossings cannot happen with agreeing signs; NaN input
    x[nx++] = {(1.0f - s) * positions[a] + s * positions[b], (1.0f - s) * fld.strength(a) + s * fld.strength(b),
               face_edges[j]};
  }
  if (nx != 2) return;
  if constexpr (kMaximum) {
    // A maximum: in the face's frame (directions agreed with corner 0's), the derivative
    // decreases along the direction.
    const float s01 = side_sign[0], s02 = side_sign[2];  // corner 2 to 0 is side 2
    const float d0 = fld.derivative(t[0]), d1 = s01 * fld.derivative(t[1]), d2 = s02 * fld.derivative(t[2]);
    const glm::vec3 p0 = positions[t[0]], e1 = positions[t[1]] - p0, e2 = positions[t[2]] - p0;
    const glm::vec3 n = glm::cross(e1, e2);
    const float nn = glm::dot(n, n);
    if (!(nn > 0.0f)) return;
    const glm::vec3 grad = ((d1 - d0) * glm::cross(e2, n) + (d2 - d0) * glm::cross(n, e1)) / nn;
    const glm::vec3 dir = fld.direction(t[0]) + s01 * fld.direction(t[1]) + s02 * fld.direction(t[2]);
    if (!(glm::dot(grad, dir) < 0.0f)) return;
  }
  auto alpha = [&](float k) { return std::clamp((k * fs - th_fs) / th_fs, 0.0f, 1.0f); };
  const float a0 = alpha(x[0].strength), a1 = alpha(x[1].strength);
  if (!(a0 > 0.0f || a1 > 0.0f)) return;
  pushSegment(out, kind, face, x[0].p, x[0].id, a0, x[1].p, x[1].id, a1);
}

}  // namespace

void ridgeCandidateVertices(std::span<const std::array<uint32_t, 3>> faces, const MeshAdjacency& adj,
                            const SurfaceFields& fields, const RidgeSpec& spec, std::vector<uint8_t>& code,
                            std::vector<uint8_t>& mark, std::vector<uint32_t>& out) {
  out.clear();
  const size_t nv = fields.positions.size();
  if (!(spec.ridges || spec.valleys) || adj.face_count != faces.size() || adj.vertex_count != nv) return;
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
                   LineScratch& scratch, LineSet& out, std::span<const float> c111,
                   std::span<const float> c222) {
  const size_t nv = positions.size();
  if (!(spec.ridges || spec.valleys) || !(spec.threshold > 0.0f) || nv == 0) return;
  if (adj.face_count != faces.size() || adj.vertex_count != nv || fields.k1.size() != nv ||
      fields.k2.size() != nv || fields.pdir1.size() != nv || fields.pdir2.size() != nv || fields.dcurv.size() != nv)
    return;
  candidateCodes(fields, spec, scratch.vertex_code);
  const uint8_t* code = scratch.vertex_code.data();
  const float fs = spec.feature_size > 0.0f ? spec.feature_size : 1.0f;
  // C111 and C222 from the tensors (stride 4 floats) unless given on their own.
  const bool own1 = c111.size() == nv, own2 = c222.size() == nv;
  const Field kinds[2] = {
      {LineKind::kRidge, 1.0f, fields.k1, fields.pdir1, own1 ? c111.data() : &fields.dcurv[0][0], own1 ? 1u : 4u},
      {LineKind::kValley, -1.0f, fields.k2, fields.pdir2, own2 ? c222.data() : &fields.dcurv[0][3], own2 ? 1u : 4u}};
  for (int k = 0; k < 2; ++k) {  // kinds in order, then faces: deterministic output
    const uint8_t bit = k == 0 ? kRidgeCandidate : kValleyCandidate;
    if (k == 0 ? !spec.ridges : !spec.valleys) continue;
    for (size_t f = 0; f < faces.size(); ++f) {
      if (!adj.face_valid[f] || !(faceCandidates(faces[f], code) & bit)) continue;
      faceMaximum(positions, faces[f], adj.face_edges[f], static_cast<uint32_t>(f), kinds[k].kind, kinds[k],
                  spec.threshold, fs, out);
    }
  }
}

void computeApparentRidgeQuantities(std::span<const std::array<uint32_t, 3>> faces, const MeshAdjacency& adj,
                                    const SurfaceFields& f, const ViewSpec& view, ApparentRidgeQuantities& out,
                                    WorkerPool* pool) {
  const size_t nv = f.positions.size();
  out.ndotv.assign(nv, 0.0f);
  out.q1.assign(nv, 0.0f);
  out.t1.assign(nv, glm::vec3(0.0f));
  out.dt1q1.assign(nv, 0.0f);
  if (f.normals.size() != nv || f.k1.size() != nv || f.k2.size() != nv || f.pdir1.size() != nv ||
      f.pdir2.size() != nv || adj.vertex_count != nv || adj.face_count != faces.size())
    return;
  const glm::vec3 ortho = glm::length(view.toward_viewer) > 0.0f ? glm::normalize(view.toward_viewer)
                                                                 : glm::vec3(0.0f, 0.0f, 1.0f);
  auto view_dependent = [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      const glm::vec3 n = f.normals[i];
      glm::vec3 vdir = ortho;
      if (!view.orthographic) {
        const glm::vec3 d = view.eye - f.positions[i];
        const float len = glm::length(d);
        vdir = len > 0.0f ? d / len : n;
      }
      const float ndotv = glm::dot(n, vdir);
      out.ndotv[i] = ndotv;
      // ŵ in the principal frame, and secθ − 1.
      float u = glm::dot(vdir, f.pdir1[i]), w = glm::dot(vdir, f.pdir2[i]);
      const float sin_t = std::sqrt(u * u + w * w);
      float c = 0.0f;
      if (sin_t > 1e-6f) {
        u /= sin_t;
        w /= sin_t;
        c = 1.0f / std::max(std::abs(ndotv), kApparentRidgeMinCos) - 1.0f;
      } else {
        u = w = 0.0f;
      }
      const float k1 = f.k1[i], k2 = f.k2[i];
      const float q11 = k1 * (1.0f + c * u * u), q12 = k1 * c * u * w;
      const float q21 = k2 * c * u * w, q22 = k2 * (1.0f + c * w * w);
      // The largest eigenvalue of QᵀQ and its eigenvector: q1² and t1 (principal frame).
      const float a = q11 * q11 + q21 * q21, b = q11 * q12 + q21 * q22, d = q12 * q12 + q22 * q22;
      const float half = 0.5f * (a - d);
      const float lambda = 0.5f * (a + d) + std::sqrt(half * half + b * b);
      out.q1[i] = std::sqrt(std::max(lambda, 0.0f));
      float tx, ty;
      if (std::abs(b) > 1e-12f * std::max(1.0f, lambda)) {
        const float x1 = b, y1 = lambda - a, x2 = lambda - d, y2 = b;  // two forms of one vector
        if (x1 * x1 + y1 * y1 >= x2 * x2 + y2 * y2) {
          tx = x1;
          ty = y1;
        } else {
          tx = x2;
          ty = y2;
        }
      } else if (a >= d) {
        tx = 1.0f;
        ty = 0.0f;
      } else {
        tx = 0.0f;
        ty = 1.0f;
      }
      // On the surface: P⁻¹t1 = t1 + (secθ − 1)(t1·ŵ)ŵ.
      const float tw = tx * u + ty * w;
      tx += c * tw * u;
      ty += c * tw * w;
      const glm::vec3 t = tx * f.pdir1[i] + ty * f.pdir2[i];
      const float len = glm::length(t);
      out.t1[i] = len > 0.0f ? t / len : f.pdir1[i];
    }
  };
  if (pool) pool->forRange(nv, 4096, view_dependent);
  else view_dependent(0, nv);
  // Dt1 q1: the area-weighted mean of the gradients of q1 over the faces around a vertex.
  auto gradient = [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      glm::vec3 g(0.0f);
      float weight = 0.0f;
      for (uint32_t k = adj.vertex_face_begin[i]; k < adj.vertex_face_end[i]; ++k) {
        const uint32_t fi = adj.vertex_faces[k];
        if (!adj.face_valid[fi]) continue;
        const auto& t = faces[fi];
        const glm::vec3 p0 = f.positions[t[0]], e1 = f.positions[t[1]] - p0, e2 = f.positions[t[2]] - p0;
        const glm::vec3 n = glm::cross(e1, e2);
        const float nn = glm::dot(n, n);
        if (!(nn > 0.0f)) continue;
        const float q0 = out.q1[t[0]];
        // The face's gradient times its doubled area |n|, then divided by the ring's Σ|n|.
        const float area2 = std::sqrt(nn);
        g += ((out.q1[t[1]] - q0) * glm::cross(e2, n) + (out.q1[t[2]] - q0) * glm::cross(n, e1)) / area2;
        weight += area2;
      }
      out.dt1q1[i] = weight > 0.0f ? glm::dot(g, out.t1[i]) / weight : 0.0f;  // 1/units²
    }
  };
  if (pool) pool->forRange(nv, 4096, gradient);
  else gradient(0, nv);
}

void extractApparentRidges(std::span<const glm::vec3> positions, std::span<const std::array<uint32_t, 3>> faces,
                           const MeshAdjacency& adj, const ApparentRidgeQuantities& q, float threshold,
                           float feature_size, LineSet& out) {
  const size_t nv = positions.size();
  if (!(threshold > 0.0f) || q.q1.size() != nv || q.t1.size() != nv || q.dt1q1.size() != nv ||
      q.ndotv.size() != nv || adj.face_count != faces.size() || adj.vertex_count != nv)
    return;
  const float fs = feature_size > 0.0f ? feature_size : 1.0f;
  const float half = 0.5f * threshold / fs;
  const ArrayField fld{q.q1, q.t1, q.dt1q1};
  for (size_t f = 0; f < faces.size(); ++f) {
    if (!adj.face_valid[f]) continue;
    const auto& t = faces[f];
    if (!(q.ndotv[t[0]] > 0.0f && q.ndotv[t[1]] > 0.0f && q.ndotv[t[2]] > 0.0f)) continue;
    if (q.q1[t[0]] < half && q.q1[t[1]] < half && q.q1[t[2]] < half) continue;
    faceMaximum(positions, t, adj.face_edges[f], static_cast<uint32_t>(f), LineKind::kApparentRidge, fld, threshold,
                fs, out);
  }
}

void computePrincipalHighlightQuantities(const SurfaceFields& f, const ViewSpec& view, float feature_size,
                                         PrincipalHighlightQuantities& out, WorkerPool* pool) {
  const size_t nv = f.positions.size();
  out.ndotv.assign(nv, 0.0f);
  out.e.assign(nv, glm::vec3(0.0f));
  out.vdote.assign(nv, 0.0f);
  out.strength.assign(nv, 0.0f);
  out.first.assign(nv, 0);
  if (f.normals.size() != nv || f.k1.size() != nv || f.k2.size() != nv || f.pdir1.size() != nv ||
      f.pdir2.size() != nv)
    return;
  const float fs2 = feature_size > 0.0f ? feature_size * feature_size : 1.0f;
  const glm::vec3 ortho = glm::length(view.toward_viewer) > 0.0f ? glm::normalize(view.toward_viewer)
                                                                 : glm::vec3(0.0f, 0.0f, 1.0f);
  auto per_vertex = [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      glm::vec3 vdir = ortho;
      if (!view.orthographic) {
        const glm::vec3 d = view.eye - f.positions[i];
        const float len = glm::length(d);
        vdir = len > 0.0f ? d / len : f.normals[i];
      }
      const float ndotv = glm::dot(f.normals[i], vdir);
      // The dominant curvature (larger magnitude) and its direction; convex only.
      const bool first = std::abs(f.k1[i]) >= std::abs(f.k2[i]);
      const float kd = first ? f.k1[i] : f.k2[i], ko = first ? f.k2[i] : f.k1[i];
      out.ndotv[i] = ndotv;
      out.first[i] = first ? 1 : 0;
      out.e[i] = first ? f.pdir1[i] : f.pdir2[i];
      out.vdote[i] = glm::dot(vdir, out.e[i]);
      out.strength[i] = kd > 0.0f && ndotv > 0.0f ? (kd * kd - ko * ko) * ndotv * fs2 : 0.0f;
    }
  };
  if (pool) pool->forRange(nv, 4096, per_vertex);
  else per_vertex(0, nv);
}

void extractPrincipalHighlights(std::span<const glm::vec3> positions, std::span<const std::array<uint32_t, 3>> faces,
                                const MeshAdjacency& adj, const PrincipalHighlightQuantities& q, float threshold,
                                LineSet& out) {
  const size_t nv = positions.size();
  if (!(threshold > 0.0f) || q.strength.size() != nv || q.e.size() != nv || q.vdote.size() != nv ||
      q.first.size() != nv ||
      q.ndotv.size() != nv || adj.face_count != faces.size() || adj.vertex_count != nv)
    return;
  const ArrayField fld{q.strength, q.e, q.vdote};
  const float half = 0.5f * threshold;
  for (size_t f = 0; f < faces.size(); ++f) {
    if (!adj.face_valid[f]) continue;
    const auto& t = faces[f];
    // Front-facing and convex at every corner (strength is 0 otherwise), strong at one.
    if (!(q.strength[t[0]] > 0.0f && q.strength[t[1]] > 0.0f && q.strength[t[2]] > 0.0f)) continue;
    if (q.strength[t[0]] < half && q.strength[t[1]] < half && q.strength[t[2]] < half) continue;
    // The same principal direction (that of k1, or of k2) at every corner: v̂·e1 and v̂·e2
    // are not comparable.
    if (q.first[t[0]] != q.first[t[1]] || q.first[t[1]] != q.first[t[2]]) continue;
    faceMaximum<false>(positions, t, adj.face_edges[f], static_cast<uint32_t>(f), LineKind::kPrincipalHighlight, fld,
                       threshold, 1.0f, out);
  }
}

}  // namespace lodline
