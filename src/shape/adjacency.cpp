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
  // which also hands it to the face sides it lies on (faces in increasing order).
  out.vertex_vertex_offsets.assign(nv + 1, 0);
  out.vertex_vertices.clear();
  out.vertex_vertices.reserve(corner_total);
  out.edge_offsets.assign(nv + 1, 0);
  out.edges.clear();
  out.edges.reserve(corner_total / 2 + nv);
  out.edge_faces.clear();
  out.edge_faces.reserve(corner_total / 2 + nv);
  out.edge_face_count.clear();
  out.edge_face_count.reserve(corner_total / 2 + nv);
  out.face_edges.assign(nf, {kNoIndex, kNoIndex, kNoIndex});
  for (uint32_t v = 0; v < nv; ++v) {
    const size_t ring_begin = out.vertex_vertices.size();
    const uint32_t first_edge = static_cast<uint32_t>(out.edges.size());
    // Index of the edge (v, w) for w > v, creating it on first sight.
    auto edgeTo = [&](uint32_t w) {
      for (uint32_t e = first_edge; e < out.edges.size(); ++e)
        if (out.edges[e][1] == w) return e;
      out.edges.push_back({v, w});
      out.edge_faces.push_back({kNoIndex, kNoIndex});
      out.edge_face_count.push_back(0);
      return static_cast<uint32_t>(out.edges.size() - 1);
    };
    auto addFace = [&](uint32_t e, uint32_t f) {
      const uint32_t k = out.edge_face_count[e]++;
      if (k < 2) out.edge_faces[e][k] = f;
    };
    for (uint32_t i = out.vertex_face_offsets[v]; i < out.vertex_face_offsets[v + 1]; ++i) {
      const uint32_t f = out.vertex_faces[i];
      const auto& t = mesh.faces[f];
      const uint8_t c = out.vertex_face_corners[i];
      const uint32_t next = t[(c + 1) % 3], prev = t[(c + 2) % 3];
      for (uint32_t w : {next, prev}) {
        bool seen = false;
        for (size_t k = ring_begin; k < out.vertex_vertices.size(); ++k)
          if (out.vertex_vertices[k] == w) { seen = true; break; }
        if (!seen) out.vertex_vertices.push_back(w);
      }
      if (next > v) {  // side c joins corners c and c+1
        const uint32_t e = edgeTo(next);
        out.face_edges[f][c] = e;
        addFace(e, f);
      }
      if (prev > v) {  // side c+2 joins corners c+2 and c
        const uint32_t e = edgeTo(prev);
        out.face_edges[f][(c + 2) % 3] = e;
        addFace(e, f);
      }
    }
    out.vertex_vertex_offsets[v + 1] = static_cast<uint32_t>(out.vertex_vertices.size());
    out.edge_offsets[v + 1] = static_cast<uint32_t>(out.edges.size());
  }
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
