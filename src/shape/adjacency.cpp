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

  // Vertex → faces (counting sort keeps faces in increasing order per vertex).
  out.vertex_face_offsets.assign(nv + 1, 0);
  for (uint32_t f = 0; f < nf; ++f) {
    if (!out.face_valid[f]) continue;
    for (uint32_t v : mesh.faces[f]) ++out.vertex_face_offsets[v + 1];
  }
  for (uint32_t v = 0; v < nv; ++v) out.vertex_face_offsets[v + 1] += out.vertex_face_offsets[v];
  const uint32_t corner_total = out.vertex_face_offsets[nv];
  out.vertex_faces.resize(corner_total);
  out.vertex_face_corners.resize(corner_total);
  {
    std::vector<uint32_t> cursor(out.vertex_face_offsets.begin(), out.vertex_face_offsets.end() - 1);
    for (uint32_t f = 0; f < nf; ++f) {
      if (!out.face_valid[f]) continue;
      for (uint8_t c = 0; c < 3; ++c) {
        const uint32_t v = mesh.faces[f][c];
        out.vertex_faces[cursor[v]] = f;
        out.vertex_face_corners[cursor[v]] = c;
        ++cursor[v];
      }
    }
  }

  // Vertex → distinct neighbours, and edges (each created by its smaller vertex).
  out.vertex_vertex_offsets.assign(nv + 1, 0);
  out.vertex_vertices.clear();
  out.vertex_vertices.reserve(corner_total * 2);
  out.edge_offsets.assign(nv + 1, 0);
  out.edges.clear();
  out.edges.reserve(corner_total / 2 + nv);
  for (uint32_t v = 0; v < nv; ++v) {
    const size_t ring_begin = out.vertex_vertices.size();
    for (uint32_t i = out.vertex_face_offsets[v]; i < out.vertex_face_offsets[v + 1]; ++i) {
      const auto& t = mesh.faces[out.vertex_faces[i]];
      const uint8_t c = out.vertex_face_corners[i];
      for (uint32_t w : {t[(c + 1) % 3], t[(c + 2) % 3]}) {
        bool seen = false;
        for (size_t k = ring_begin; k < out.vertex_vertices.size(); ++k)
          if (out.vertex_vertices[k] == w) { seen = true; break; }
        if (!seen) out.vertex_vertices.push_back(w);
      }
    }
    out.vertex_vertex_offsets[v + 1] = static_cast<uint32_t>(out.vertex_vertices.size());
    for (size_t k = ring_begin; k < out.vertex_vertices.size(); ++k)
      if (out.vertex_vertices[k] > v) out.edges.push_back({v, out.vertex_vertices[k]});
    out.edge_offsets[v + 1] = static_cast<uint32_t>(out.edges.size());
  }

  // Faces on edges and edges of faces.
  const size_t ne = out.edges.size();
  out.edge_faces.assign(ne, {kNoIndex, kNoIndex});
  out.edge_face_count.assign(ne, 0);
  out.face_edges.assign(nf, {kNoIndex, kNoIndex, kNoIndex});
  for (uint32_t f = 0; f < nf; ++f) {
    if (!out.face_valid[f]) continue;
    const auto& t = mesh.faces[f];
    for (int j = 0; j < 3; ++j) {
      const uint32_t e = out.findEdge(t[j], t[(j + 1) % 3]);
      LODLINE_ASSERT(e != kNoIndex);
      out.face_edges[f][j] = e;
      const uint32_t k = out.edge_face_count[e]++;
      if (k < 2) out.edge_faces[e][k] = f;
    }
  }

  out.vertex_on_boundary.assign(nv, 0);
  for (size_t e = 0; e < ne; ++e) {
    if (out.edge_face_count[e] != 2) {
      out.vertex_on_boundary[out.edges[e][0]] = 1;
      out.vertex_on_boundary[out.edges[e][1]] = 1;
    }
  }
}

}  // namespace lodline
