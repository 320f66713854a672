#include "shape/adjacency.h"

#include <algorithm>

#include "core/result.h"

namespace lodline {

uint32_t MeshAdjacency::findEdge(uint32_t a, uint32_t b) const {
  if (a > b) std::swap(a, b);
  if (a >= vertex_count || a == b) return kNoIndex;
  for (uint32_t e = edge_offsets[a]; e < edge_offsets[a + 1]; ++e)
    if (edges[e][1] == b) return e;
  return kNoIndex;
}

void buildAdjacency(const TriMesh& mesh, MeshAdjacency& out) {
  const uint32_t nv = static_cast<uint32_t>(mesh.positions.size());
  const uint32_t nf = static_cast<uint32_t>(mesh.faces.size());
  out.vertex_count = nv;
  out.face_count = nf;

  // Valid faces: three distinct, in-range indices.
  out.face_valid.assign(nf, 0);
  for (uint32_t f = 0; f < nf; ++f) {
    const auto& t = mesh.faces[f];
    out.face_valid[f] = t[0] < nv && t[1] < nv && t[2] < nv && t[0] != t[1] &&
                        t[1] != t[2] && t[2] != t[0];
  }

  // Vertex → faces (counting sort; filling from the back over faces in reverse keeps faces
  // in increasing order per vertex and needs no cursor array).
  out.vertex_face_offsets.assign(nv + 1, 0);
  for (uint32_t f = 0; f < nf; ++f) {
    if (!out.face_valid[f]) continue;
    for (uint32_t v : mesh.faces[f]) ++out.vertex_face_offsets[v + 1];
  }
  for (uint32_t v = 0; v < nv; ++v) out.vertex_face_offsets[v + 1] += out.vertex_face_offsets[v];
  const uint32_t corner_total = out.vertex_face_offsets[nv];
  out.vertex_faces.resize(corner_total);
  out.vertex_face_corners.resize(corner_total);
  for (uint32_t f = nf; f-- > 0;) {
    if (!out.face_valid[f]) continue;
    for (uint8_t c = 3; c-- > 0;) {
      const uint32_t slot = --out.vertex_face_offsets[mesh.faces[f][c] + 1];
      out.vertex_faces[slot] = f;
      out.vertex_face_corners[slot] = c;
    }
  }
  // Now vertex_face_offsets[v + 1] holds the start of v: shift down by one.
  for (uint32_t v = 0; v < nv; ++v) out.vertex_face_offsets[v] = out.vertex_face_offsets[v + 1];
  if (nv > 0) out.vertex_face_offsets[nv] = corner_total;

  // Vertex → distinct neighbours, and edges: each edge is created by its smaller vertex,
  // which also hands it to the face sides it lies on (faces in increasing order). A stamp
  // per neighbour (the current vertex + 1) replaces searching the ring and the vertex's
  // edges, so this is O(corners); the output is the same as a search would give.
  out.vertex_vertex_offsets.assign(nv + 1, 0);
  // A ring holds at most two neighbours per corner (an open fan has one more neighbour than
  // faces); every edge is created by one corner side.
  out.vertex_vertices.resize(2 * static_cast<size_t>(corner_total));
  out.edge_offsets.assign(nv + 1, 0);
  out.edges.resize(corner_total);
  out.edge_faces.resize(corner_total);
  out.edge_face_count.resize(corner_total);
  out.face_edges.assign(nf, {kNoIndex, kNoIndex, kNoIndex});
  std::vector<uint32_t>& seen = out.scratch_seen;   // v + 1 once w is in v's ring
  std::vector<uint32_t>& edge_to = out.scratch_edge;  // edge (v, w) for w > v, valid if seen
  seen.assign(nv, 0);
  edge_to.resize(nv);
  uint32_t ring_size = 0, edge_count = 0;
  const uint32_t* vf = out.vertex_faces.data();
  const uint8_t* vc = out.vertex_face_corners.data();
  for (uint32_t v = 0; v < nv; ++v) {
    const uint32_t stamp = v + 1;
    for (uint32_t i = out.vertex_face_offsets[v]; i < out.vertex_face_offsets[v + 1]; ++i) {
      const uint32_t f = vf[i];
      const auto& t = mesh.faces[f];
      const uint8_t c = vc[i];
      const uint8_t c_next = c == 2 ? 0 : c + 1, c_prev = c == 0 ? 2 : c - 1;
      const uint32_t ends[2] = {t[c_next], t[c_prev]};
      // Side c joins corners c and c+1; side c+2 joins corners c+2 and c.
      const uint8_t sides[2] = {c, c_prev};
      for (int k = 0; k < 2; ++k) {
        const uint32_t w = ends[k];
        const bool first = seen[w] != stamp;
        if (first) {
          seen[w] = stamp;
          out.vertex_vertices[ring_size++] = w;
        }
        if (w < v) continue;
        if (first) {
          edge_to[w] = edge_count;
          out.edges[edge_count] = {v, w};
          out.edge_faces[edge_count] = {kNoIndex, kNoIndex};
          out.edge_face_count[edge_count] = 0;
          ++edge_count;
        }
        const uint32_t e = edge_to[w];
        out.face_edges[f][sides[k]] = e;
        const uint32_t n = out.edge_face_count[e]++;
        if (n < 2) out.edge_faces[e][n] = f;
      }
    }
    out.vertex_vertex_offsets[v + 1] = ring_size;
    out.edge_offsets[v + 1] = edge_count;
  }
  out.vertex_vertices.resize(ring_size);
  out.edges.resize(edge_count);
  out.edge_faces.resize(edge_count);
  out.edge_face_count.resize(edge_count);
  const size_t ne = out.edges.size();

  out.vertex_on_boundary.assign(nv, 0);
  for (size_t e = 0; e < ne; ++e) {
    if (out.edge_face_count[e] != 2) {
      out.vertex_on_boundary[out.edges[e][0]] = 1;
      out.vertex_on_boundary[out.edges[e][1]] = 1;
    }
  }
}

}  // namespace lodline
