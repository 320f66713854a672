// DeCarlo et al. 2003 §4 and 2004 §3–4 (zero sets of n·v and kr, num/den test, fading);
// see lines.h.
#include "lines/lines.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace lodline {

void LineSet::clear() {
  points.clear();
  alpha.clear();
  point_ids.clear();
  kinds.clear();
  sources.clear();
  counts.fill(0);
}

namespace {

inline void pushSegment(LineSet& out, LineKind type, uint32_t source, const glm::vec3& p0,
                        uint32_t id0, float a0, const glm::vec3& p1, uint32_t id1, float a1) {
  out.points.push_back(p0);
  out.points.push_back(p1);
  out.alpha.push_back(a0);
  out.alpha.push_back(a1);
  out.point_ids.push_back(id0);
  out.point_ids.push_back(id1);
  out.kinds.push_back(type);
  out.sources.push_back(source);
  ++out.counts[static_cast<int>(type)];
}

inline float fadeAlpha(float num, float den, float fade) {
  if (!(fade > 0.0f)) return 1.0f;
  const float a = num / (num + fade * den);
  return std::isfinite(a) ? std::clamp(a, 0.0f, 1.0f) : 1.0f;
}

inline bool passes(float num, float den) { return (num > 0.0f && den > 0.0f) || (num < 0.0f && den < 0.0f); }

}  // namespace

void extractZeroSet(std::span<const glm::vec3> positions,
                    std::span<const std::array<uint32_t, 3>> faces,
                    const MeshAdjacency& adj, const ZeroSetInput& in, LineKind type,
                    LineScratch& scratch, LineSet& out) {
  const size_t ne = adj.edges.size();
  const size_t nv = positions.size();
  if (in.value.size() != nv || adj.vertex_count != nv || adj.face_count != faces.size()) return;
  const bool has_test = in.test_num.size() == nv;
  const bool has_den = has_test && in.test_den.size() == nv;
  const bool has_gate = in.gate.size() == nv;
  const bool has_gain = has_test && in.gain.size() == nv;
  const std::span<const float> val = in.value;

  // Pass 1, per edge: where does the value change sign, and what is the test there.
  scratch.crosses.resize(ne);
  scratch.cross_point.resize(ne);
  if (has_test) {
    scratch.cross_num.resize(ne);
    scratch.cross_den.resize(ne);
  }
  if (has_gain) scratch.cross_gain.resize(ne);
  auto crossings = [&](size_t begin, size_t end) {
    for (size_t e = begin; e < end; ++e) {
      const uint32_t a = adj.edges[e][0], b = adj.edges[e][1];
      const float va = val[a], vb = val[b];
      const bool c = (va < 0.0f) != (vb < 0.0f);
      scratch.crosses[e] = c;
      if (!c) continue;
      float t = va / (va - vb);
      if (!(t >= 0.0f && t <= 1.0f)) t = 0.5f;  // NaN input
      const float s = 1.0f - t;
      scratch.cross_point[e] = s * positions[a] + t * positions[b];
      if (has_test) {
        scratch.cross_num[e] = s * in.test_num[a] + t * in.test_num[b];
        scratch.cross_den[e] = has_den ? s * in.test_den[a] + t * in.test_den[b] : 1.0f;
      }
      if (has_gain) scratch.cross_gain[e] = s * in.gain[a] + t * in.gain[b];
    }
  };
  if (scratch.pool) {
    scratch.pool->forRange(ne, 8192, crossings);
  } else {
    crossings(0, ne);
  }

  // Pass 2, per face: join the two crossings, keeping the pieces that pass the test. Points
  // inside a face get ids from `interior` up, in face order.
  auto faces_pass = [&](size_t begin, size_t end, LineSet& dst, uint32_t& interior_id) {
    for (size_t f = begin; f < end; ++f) {
      if (!adj.face_valid[f]) continue;
      const auto& t = faces[f];
      const bool s0 = val[t[0]] < 0.0f, s1 = val[t[1]] < 0.0f, s2 = val[t[2]] < 0.0f;
      if (s0 == s1 && s1 == s2) continue;
      if (has_gate && (in.gate[t[0]] < in.gate_min || in.gate[t[1]] < in.gate_min ||
                       in.gate[t[2]] < in.gate_min))
        continue;
      if (has_test) {  // quick reject: the test fails at all three vertices
        bool all_fail = true;
        for (uint32_t v : t)
          if (passes(in.test_num[v], has_den ? in.test_den[v] : 1.0f)) { all_fail = false; break; }
        if (all_fail) continue;
      }
      // The lone corner i has the other sign; its two sides i and i-1 cross.
      const int i = (s0 == s1) ? 2 : (s0 == s2 ? 1 : 0);
      const uint32_t e1 = adj.face_edges[f][i];
      const uint32_t e2 = adj.face_edges[f][(i + 2) % 3];
      const glm::vec3& p1 = scratch.cross_point[e1];
      const glm::vec3& p2 = scratch.cross_point[e2];
      if (!has_test) {
        pushSegment(dst, type, static_cast<uint32_t>(f), p1, e1, 1.0f, p2, e2, 1.0f);
        continue;
      }
      const float n1 = scratch.cross_num[e1], n2 = scratch.cross_num[e2];
      const float d1 = scratch.cross_den[e1], d2 = scratch.cross_den[e2];
      // Breakpoints where num or den change sign along p1→p2 (linear interpolation).
      float z[4] = {0.0f, 0.0f, 0.0f, 1.0f};
      int nz = 1;
      if ((n1 >= 0.0f) != (n2 >= 0.0f)) z[nz++] = n1 / (n1 - n2);
      if ((d1 >= 0.0f) != (d2 >= 0.0f)) z[nz++] = d1 / (d1 - d2);
      z[nz++] = 1.0f;
      if (nz == 4 && z[2] < z[1]) std::swap(z[1], z[2]);
      for (int k = 0; k + 1 < nz; ++k) {
        const float za = z[k], zb = z[k + 1];
        if (!(zb > za)) continue;
        const float zm = 0.5f * (za + zb);
        const float nm = (1.0f - zm) * n1 + zm * n2, dm = (1.0f - zm) * d1 + zm * d2;
        if (!passes(nm, dm)) continue;
        const float na = (1.0f - za) * n1 + za * n2, da = (1.0f - za) * d1 + za * d2;
        const float nb = (1.0f - zb) * n1 + zb * n2, db = (1.0f - zb) * d1 + zb * d2;
        const glm::vec3 pa = k == 0 ? p1 : (1.0f - za) * p1 + za * p2;
        const glm::vec3 pb = k + 2 == nz ? p2 : (1.0f - zb) * p1 + zb * p2;
        const uint32_t ida = k == 0 ? e1 : interior_id++;
        const uint32_t idb = k + 2 == nz ? e2 : interior_id++;
        float ga = 1.0f, gb = 1.0f;
        if (has_gain) {
          const float g1 = scratch.cross_gain[e1], g2 = scratch.cross_gain[e2];
          ga = std::clamp((1.0f - za) * g1 + za * g2, 0.0f, 1.0f);
          gb = std::clamp((1.0f - zb) * g1 + zb * g2, 0.0f, 1.0f);
        }
        pushSegment(dst, type, static_cast<uint32_t>(f), pa, ida, ga * fadeAlpha(na, da, in.fade), pb,
                    idb, gb * fadeAlpha(nb, db, in.fade));
      }
    }
  };
  uint32_t interior_id = std::max(scratch.next_interior_id, static_cast<uint32_t>(ne));
  const size_t nf = faces.size();
  if (!scratch.pool || nf < 16384) {
    faces_pass(0, nf, out, interior_id);
  } else {
    // In parts on the worker threads, each into its own set with ids from ne, then appended
    // in face order with the ids shifted: the same output as one pass.
    const size_t parts = 4 * scratch.pool->threadCount();
    scratch.part_sets.resize(parts);
    scratch.part_interior.assign(parts, 0);
    scratch.pool->forRange(parts, 1, [&](size_t begin, size_t end) {
      for (size_t c = begin; c < end; ++c) {
        LineSet& part = scratch.part_sets[c];
        part.clear();
        uint32_t id = static_cast<uint32_t>(ne);
        faces_pass(nf * c / parts, nf * (c + 1) / parts, part, id);
        scratch.part_interior[c] = id - static_cast<uint32_t>(ne);
      }
    });
    for (size_t c = 0; c < parts; ++c) {
      const LineSet& part = scratch.part_sets[c];
      const uint32_t shift = interior_id - static_cast<uint32_t>(ne);
      out.points.insert(out.points.end(), part.points.begin(), part.points.end());
      out.alpha.insert(out.alpha.end(), part.alpha.begin(), part.alpha.end());
      for (uint32_t id : part.point_ids) out.point_ids.push_back(id >= ne ? id + shift : id);
      out.kinds.insert(out.kinds.end(), part.kinds.begin(), part.kinds.end());
      out.sources.insert(out.sources.end(), part.sources.begin(), part.sources.end());
      for (int k = 0; k < kLineKindCount; ++k) out.counts[k] += part.counts[k];
      interior_id += scratch.part_interior[c];
    }
  }
  scratch.next_interior_id = interior_id;
}

void extractEdgeLines(const TriMesh& mesh, const MeshAdjacency& adj,
                      std::span<const glm::vec3> face_normals, const LineParams& params,
                      LineScratch& scratch, LineSet& out, std::span<const uint8_t> crease_vertices) {
  const bool masked = crease_vertices.size() == mesh.positions.size();
  const size_t ne = adj.edges.size();
  if (adj.vertex_count != mesh.positions.size() || face_normals.size() != adj.face_count) return;
  const bool want_creases = params.creases;
  if (!want_creases && !params.boundaries) return;
  const float cos_limit =
      std::cos(params.crease_angle_deg * std::numbers::pi_v<float> / 180.0f);
  scratch.edge_mark.assign(ne, 0);  // 1 crease, 2 boundary
  if (want_creases && params.marked_edges) {
    for (const EdgeKey& k : mesh.marked_edges) {
      const uint32_t e = adj.findEdge(k[0], k[1]);
      if (e != kNoIndex) scratch.edge_mark[e] = 1;
    }
  }
  auto classify = [&](size_t begin, size_t end) {  // each edge writes only its own mark
    for (size_t e = begin; e < end; ++e) {
      const uint32_t count = adj.edge_face_count[e];
      if (count == 1) {
        scratch.edge_mark[e] = params.boundaries ? 2 : scratch.edge_mark[e];
      } else if (count == 2) {
        if (!want_creases || scratch.edge_mark[e]) continue;
        if (masked && (!crease_vertices[adj.edges[e][0]] || !crease_vertices[adj.edges[e][1]])) continue;
        const glm::vec3& n1 = face_normals[adj.edge_faces[e][0]];
        const glm::vec3& n2 = face_normals[adj.edge_faces[e][1]];
        if (glm::dot(n1, n1) == 0.0f || glm::dot(n2, n2) == 0.0f) continue;
        if (glm::dot(n1, n2) < cos_limit) scratch.edge_mark[e] = 1;
      } else if (count > 2 && want_creases && params.marked_edges) {
        scratch.edge_mark[e] = 1;
      }
    }
  };
  if (scratch.pool) {
    scratch.pool->forRange(ne, 8192, classify);
  } else {
    classify(0, ne);
  }
  for (size_t e = 0; e < ne; ++e) {
    const uint8_t m = scratch.edge_mark[e];
    if (m == 0 || (m == 1 && !want_creases)) continue;
    const uint32_t a = adj.edges[e][0], b = adj.edges[e][1];
    pushSegment(out, m == 2 ? LineKind::kBoundary : LineKind::kCrease, static_cast<uint32_t>(e),
                mesh.positions[a], a, 1.0f, mesh.positions[b], b, 1.0f);
  }
}

void extractMeshSilhouette(const TriMesh& mesh, const MeshAdjacency& adj, std::span<const glm::vec3> face_normals,
                           const ViewSpec& view, LineSet& out) {
  out.clear();
  // Facing of a face: the sign of n·(eye − p) at its first corner (perspective), or of
  // n·toward_viewer (orthographic); 0 for degenerate faces.
  auto facing = [&](uint32_t f) -> int {
    const glm::vec3& n = face_normals[f];
    if (glm::dot(n, n) == 0.0f) return 0;
    const glm::vec3 to_eye = view.orthographic ? view.toward_viewer : view.eye - mesh.positions[mesh.faces[f][0]];
    return glm::dot(n, to_eye) > 0.0f ? 1 : -1;
  };
  for (size_t e = 0; e < adj.edges.size(); ++e) {
    if (adj.edge_face_count[e] != 2) continue;
    const int a = facing(adj.edge_faces[e][0]), b = facing(adj.edge_faces[e][1]);
    if (a == 0 || b == 0 || a == b) continue;
    const uint32_t v0 = adj.edges[e][0], v1 = adj.edges[e][1];
    pushSegment(out, LineKind::kContour, static_cast<uint32_t>(e), mesh.positions[v0], v0, 1.0f, mesh.positions[v1],
                v1, 1.0f);
  }
}

void extractLines(const TriMesh& mesh, const MeshAdjacency& adj,
                  std::span<const glm::vec3> face_normals, const ViewQuantities& view,
                  const LineParams& params, float feature_size, LineScratch& scratch,
                  LineSet& out, std::span<const uint8_t> crease_vertices,
                  std::span<const float> suggestive_gain) {
  out.clear();
  scratch.next_interior_id = 0;
  const float fs = feature_size > 0.0f && std::isfinite(feature_size) ? feature_size : 1.0f;
  if (params.contours) {
    ZeroSetInput in;
    in.value = view.ndotv;
    if (params.contours_require_positive_kr) in.test_num = view.kr;
    extractZeroSet(mesh.positions, mesh.faces, adj, in, LineKind::kContour, scratch, out);
  }
  if (params.suggestive && view.sc_num.size() == mesh.positions.size()) {
    ZeroSetInput in;
    in.value = view.kr;
    in.test_num = view.sc_num;
    in.test_den = view.sc_den;
    in.gate = view.ndotv;
    in.gate_min = params.suggestive_min_ndotv;
    in.fade = params.suggestive_fade / (fs * fs);
    in.gain = suggestive_gain;
    extractZeroSet(mesh.positions, mesh.faces, adj, in, LineKind::kSuggestive, scratch, out);
  }
  extractEdgeLines(mesh, adj, face_normals, params, scratch, out, crease_vertices);
}

void LineExtractor::extract(const TriMesh& mesh, const ShapeCache& shape, const ViewSpec& view,
                            const LineParams& params, float feature_size, LineSet& out) {
  extract(mesh, shape, shape.fields(mesh), view, params, feature_size, out);
}

void LineExtractor::extract(const TriMesh& mesh, const ShapeCache& shape,
                            const SurfaceFields& fields, const ViewSpec& view,
                            const LineParams& params, float feature_size, LineSet& out) {
  const float fs = feature_size > 0.0f && std::isfinite(feature_size) ? feature_size : 1.0f;
  SurfaceFields f = fields;
  if (!params.suggestive) f.dcurv = {};
  computeViewQuantities(f, view, params.suggestive_threshold / (fs * fs), view_);
  extractLines(mesh, shape.adjacency(), shape.faceNormals(), view_, params, fs, scratch_, out);
}

}  // namespace lodline
