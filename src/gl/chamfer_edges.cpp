// Sharp-edge finding for the chamfer highlights (Wei, Shi, Yong 2014; docs/design.md §2.2).
#include "gl/chamfer_edges.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace lodline {
namespace {

bool lessPos(const glm::vec3& a, const glm::vec3& b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  return a.z < b.z;
}

// Welds vertices at exactly equal positions: scratch.weld[v] = welded index; fills
// scratch.welded (positions of the welded vertices, faces re-indexed; faces with an index out
// of range keep it, and buildAdjacency treats them as invalid).
void weld(std::span<const glm::vec3> positions, std::span<const std::array<uint32_t, 3>> faces,
          ChamferEdgeScratch& s) {
  const uint32_t nv = static_cast<uint32_t>(positions.size());
  s.order.resize(nv);
  for (uint32_t v = 0; v < nv; ++v) s.order[v] = v;
  std::sort(s.order.begin(), s.order.end(), [&](uint32_t a, uint32_t b) {
    if (positions[a] == positions[b]) return a < b;
    return lessPos(positions[a], positions[b]);
  });
  s.weld.assign(nv, 0);
  s.welded.positions.clear();
  s.welded.marked_edges.clear();
  for (uint32_t i = 0; i < nv; ++i) {
    const uint32_t v = s.order[i];
    if (i == 0 || positions[v] != positions[s.order[i - 1]]) s.welded.positions.push_back(positions[v]);
    s.weld[v] = static_cast<uint32_t>(s.welded.positions.size() - 1);
  }
  s.welded.faces.resize(faces.size());
  for (size_t f = 0; f < faces.size(); ++f)
    for (int j = 0; j < 3; ++j)
      s.welded.faces[f][j] = faces[f][j] < nv ? s.weld[faces[f][j]] : faces[f][j];
}

}  // namespace

void prepareChamferMesh(std::span<const glm::vec3> positions,
                        std::span<const std::array<uint32_t, 3>> faces, ChamferEdgeScratch& s) {
  weld(positions, faces, s);
  buildAdjacency(s.welded, s.adjacency);
}

size_t ChamferEdges::countAtLeast(float threshold_deg) const {
  // angle_deg is sorted in decreasing order.
  return static_cast<size_t>(
      std::partition_point(angle_deg.begin(), angle_deg.end(),
                           [&](float a) { return a >= threshold_deg; }) -
      angle_deg.begin());
}

void findChamferEdges(std::span<const glm::vec3> positions,
                      std::span<const std::array<uint32_t, 3>> faces,
                      std::span<const EdgeKey> marked, float min_angle_deg,
                      ChamferEdgeScratch& s, ChamferEdges& out, bool prepared) {
  out.vertices.clear();
  out.normal1.clear();
  out.normal2.clear();
  out.inward1.clear();
  out.inward2.clear();
  out.angle_deg.clear();
  if (!prepared) prepareChamferMesh(positions, faces, s);
  computeFaceNormals(s.welded, s.face_normals);
  const MeshAdjacency& adj = s.adjacency;
  const size_t ne = adj.edgeCount();
  // A representative original vertex per welded vertex, for the output indices.
  std::vector<uint32_t>& rep = s.order;  // reuse: order is no longer needed
  rep.assign(s.welded.positions.size(), 0);
  for (uint32_t v = static_cast<uint32_t>(positions.size()); v-- > 0;) rep[s.weld[v]] = v;

  std::vector<float>& angle = s.angle;
  angle.assign(ne, -1.0f);
  const float rad_to_deg = 180.0f / std::numbers::pi_v<float>;
  for (size_t e = 0; e < ne; ++e) {
    if (adj.edge_face_count[e] != 2) continue;
    const glm::vec3 n1 = s.face_normals[adj.edge_faces[e][0]];
    const glm::vec3 n2 = s.face_normals[adj.edge_faces[e][1]];
    if (n1 == glm::vec3(0.0f) || n2 == glm::vec3(0.0f)) continue;
    const float a = std::atan2(glm::length(glm::cross(n1, n2)), glm::dot(n1, n2)) * rad_to_deg;
    if (a >= min_angle_deg) angle[e] = a;
  }
  const uint32_t nw = static_cast<uint32_t>(s.welded.positions.size());
  for (const EdgeKey& m : marked) {
    if (m[0] >= positions.size() || m[1] >= positions.size()) continue;
    const uint32_t a = s.weld[m[0]], b = s.weld[m[1]];
    if (a == b || a >= nw || b >= nw) continue;
    const uint32_t e = adj.findEdge(a, b);
    if (e == kNoIndex || adj.edge_face_count[e] != 2) continue;
    angle[e] = kMarkedEdgeAngleDeg;
  }
  s.sorted.clear();
  for (uint32_t e = 0; e < ne; ++e)
    if (angle[e] >= 0.0f) s.sorted.push_back(e);
  std::stable_sort(s.sorted.begin(), s.sorted.end(),
                   [&](uint32_t a, uint32_t b) { return angle[a] > angle[b]; });
  auto inward = [&](uint32_t e, uint32_t f) {
    const glm::vec3 a = s.welded.positions[adj.edges[e][0]], b = s.welded.positions[adj.edges[e][1]];
    const auto& t = s.welded.faces[f];
    const glm::vec3 c =
        (s.welded.positions[t[0]] + s.welded.positions[t[1]] + s.welded.positions[t[2]]) / 3.0f;
    const glm::vec3 axis = glm::normalize(b - a);
    const glm::vec3 d = (c - a) - glm::dot(c - a, axis) * axis;
    const float l = glm::length(d);
    return l > 0.0f ? d / l : glm::vec3(0.0f);
  };
  for (uint32_t e : s.sorted) {
    out.vertices.push_back({rep[adj.edges[e][0]], rep[adj.edges[e][1]]});
    out.inward1.push_back(inward(e, adj.edge_faces[e][0]));
    out.inward2.push_back(inward(e, adj.edge_faces[e][1]));
    out.normal1.push_back(s.face_normals[adj.edge_faces[e][0]]);
    out.normal2.push_back(s.face_normals[adj.edge_faces[e][1]]);
    out.angle_deg.push_back(angle[e]);
  }
}

void computeCornerNormals(std::span<const glm::vec3> positions,
                          std::span<const std::array<uint32_t, 3>> faces, float smooth_angle_deg,
                          ChamferEdgeScratch& s, std::vector<glm::vec3>& out, bool prepared) {
  if (!prepared) prepareChamferMesh(positions, faces, s);
  const MeshAdjacency& adj = s.adjacency;
  const size_t nf = faces.size();
  // Area-weighted (unnormalised) face normals of the welded mesh.
  std::vector<glm::vec3>& an = s.face_normals;
  an.resize(nf);
  for (size_t f = 0; f < nf; ++f) {
    if (!adj.face_valid[f]) {
      an[f] = glm::vec3(0.0f);
      continue;
    }
    const auto& t = s.welded.faces[f];
    an[f] = glm::cross(s.welded.positions[t[1]] - s.welded.positions[t[0]],
                       s.welded.positions[t[2]] - s.welded.positions[t[0]]);
  }
  const float cos_limit = std::cos(smooth_angle_deg * std::numbers::pi_v<float> / 180.0f);
  out.assign(3 * nf, glm::vec3(0.0f, 0.0f, 1.0f));
  for (size_t f = 0; f < nf; ++f) {
    if (!adj.face_valid[f]) continue;
    const float lf = glm::length(an[f]);
    const glm::vec3 nf_unit = lf > 0.0f ? an[f] / lf : glm::vec3(0.0f);
    for (int j = 0; j < 3; ++j) {
      const uint32_t v = s.welded.faces[f][j];
      glm::vec3 sum(0.0f);
      for (uint32_t k = adj.vertex_face_begin[v]; k < adj.vertex_face_end[v]; ++k) {
        const uint32_t g = adj.vertex_faces[k];
        const float lg = glm::length(an[g]);
        if (lg > 0.0f && glm::dot(an[g] / lg, nf_unit) >= cos_limit) sum += an[g];
      }
      const float l = glm::length(sum);
      out[3 * f + j] = l > 0.0f ? sum / l : (lf > 0.0f ? nf_unit : glm::vec3(0.0f, 0.0f, 1.0f));
    }
  }
}

}  // namespace lodline
