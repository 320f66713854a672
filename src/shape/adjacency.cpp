#include "shape/adjacency.h"

#include <algorithm>

#include <glm/geometric.hpp>

#include "core/result.h"

namespace lodline {

namespace {

// Free entries at the end of each ring after a build, so most in-place insertions need no
// relocation.
constexpr uint32_t kRingSlack = 2;

inline EdgeKey edgeKey(uint32_t a, uint32_t b) { return {std::min(a, b), std::max(a, b)}; }

}  // namespace

uint32_t MeshAdjacency::findEdge(uint32_t a, uint32_t b) const {
  if (a >= vertex_count || b >= vertex_count || a == b) return kNoIndex;
  const EdgeKey key = edgeKey(a, b);
  // The edges at corner c of a face are its sides c (corners c, c+1) and c+2 (c+2, c).
  for (uint32_t i = vertex_face_begin[a]; i < vertex_face_end[a]; ++i) {
    const auto& fe = face_edges[vertex_faces[i]];
    const uint8_t c = vertex_face_corners[i];
    for (const uint32_t e : {fe[c], fe[c == 0 ? 2 : c - 1]})
      if (e != kNoIndex && edges[e] == key) return e;
  }
  return kNoIndex;
}

void buildAdjacency(const TriMesh& mesh, MeshAdjacency& out) {
  buildAdjacency(mesh.faces, static_cast<uint32_t>(mesh.positions.size()), out);
}

void buildAdjacency(std::span<const std::array<uint32_t, 3>> faces, uint32_t nv, MeshAdjacency& out) {
  const uint32_t nf = static_cast<uint32_t>(faces.size());
  out.vertex_count = nv;
  out.face_count = nf;

  // Valid faces: three distinct, in-range indices.
  out.face_valid.resize(nf);
  for (uint32_t f = 0; f < nf; ++f) out.face_valid[f] = faceIsValid(faces[f], nv);

  // Vertex → faces: count, lay the rings out with slack, fill in increasing face order.
  out.vertex_face_begin.resize(nv);
  out.vertex_face_end.assign(nv, 0);
  out.ring_limit.resize(nv);
  for (uint32_t f = 0; f < nf; ++f) {
    if (!out.face_valid[f]) continue;
    for (uint32_t v : faces[f]) ++out.vertex_face_end[v];
  }
  uint32_t storage = 0, corner_total = 0;
  for (uint32_t v = 0; v < nv; ++v) {
    const uint32_t count = out.vertex_face_end[v];
    corner_total += count;
    out.vertex_face_begin[v] = out.vertex_face_end[v] = storage;
    storage += count + kRingSlack;
    out.ring_limit[v] = storage;
  }
  out.vertex_faces.resize(storage);
  out.vertex_face_corners.resize(storage);
  for (uint32_t f = 0; f < nf; ++f) {
    if (!out.face_valid[f]) continue;
    for (uint8_t c = 0; c < 3; ++c) {
      const uint32_t slot = out.vertex_face_end[faces[f][c]]++;
      out.vertex_faces[slot] = f;
      out.vertex_face_corners[slot] = c;
    }
  }
  out.free_edges.clear();

  // Edges: each edge is created by its smaller vertex, which also hands it to the face sides
  // it lies on (faces in increasing order). A stamp per neighbour (the current vertex + 1)
  // replaces searching the vertex's edges, so this is O(corners).
  // At most one edge per corner (half that on a closed mesh): reserved, not filled, so the
  // pages past the last edge are never touched (a fresh build's time is mostly page faults).
  out.edges.clear();
  out.edge_faces.clear();
  out.edge_face_count.clear();
  out.edges.reserve(corner_total);
  out.edge_faces.reserve(corner_total);
  out.edge_face_count.reserve(corner_total);
  out.face_edges.assign(nf, {kNoIndex, kNoIndex, kNoIndex});
  std::vector<uint32_t>& seen = out.scratch_seen;     // v + 1 once edge (v, w) exists
  std::vector<uint32_t>& edge_to = out.scratch_edge;  // edge (v, w) for w > v, valid if seen
  seen.assign(nv, 0);
  edge_to.resize(nv);
  uint32_t edge_count = 0;
  const uint32_t* vf = out.vertex_faces.data();
  const uint8_t* vc = out.vertex_face_corners.data();
  for (uint32_t v = 0; v < nv; ++v) {
    const uint32_t stamp = v + 1;
    for (uint32_t i = out.vertex_face_begin[v]; i < out.vertex_face_end[v]; ++i) {
      const uint32_t f = vf[i];
      const auto& t = faces[f];
      const uint8_t c = vc[i];
      const uint8_t c_next = c == 2 ? 0 : c + 1, c_prev = c == 0 ? 2 : c - 1;
      const uint32_t ends[2] = {t[c_next], t[c_prev]};
      // Side c joins corners c and c+1; side c+2 joins corners c+2 and c.
      const uint8_t sides[2] = {c, c_prev};
      for (int k = 0; k < 2; ++k) {
        const uint32_t w = ends[k];
        if (w < v) continue;
        if (seen[w] != stamp) {
          seen[w] = stamp;
          edge_to[w] = edge_count;
          out.edges.push_back({v, w});
          out.edge_faces.push_back({kNoIndex, kNoIndex});
          out.edge_face_count.push_back(0);
          ++edge_count;
        }
        const uint32_t e = edge_to[w];
        out.face_edges[f][sides[k]] = e;
        const uint32_t n = out.edge_face_count[e]++;
        if (n < 2) out.edge_faces[e][n] = f;
      }
    }
  }

  out.vertex_on_boundary.assign(nv, 0);
  for (size_t e = 0; e < edge_count; ++e) {
    if (out.edge_face_count[e] != 2) {
      out.vertex_on_boundary[out.edges[e][0]] = 1;
      out.vertex_on_boundary[out.edges[e][1]] = 1;
    }
  }
}

// ---------------------------------------------------------------------------------------
// In-place update

namespace {

// Removes face f from v's ring (kept sorted).
void ringRemove(MeshAdjacency& adj, uint32_t v, uint32_t f) {
  const uint32_t b = adj.vertex_face_begin[v], e = adj.vertex_face_end[v];
  uint32_t* faces = adj.vertex_faces.data();
  const uint32_t i = static_cast<uint32_t>(std::lower_bound(faces + b, faces + e, f) - faces);
  if (i == e || faces[i] != f) return;
  std::copy(faces + i + 1, faces + e, faces + i);
  std::copy(adj.vertex_face_corners.begin() + i + 1, adj.vertex_face_corners.begin() + e,
            adj.vertex_face_corners.begin() + i);
  adj.vertex_face_end[v] = e - 1;
}

// Inserts face f (v at its corner c) into v's ring in sorted position, moving the ring to
// the end of the storage with room to grow when it is full.
void ringInsert(MeshAdjacency& adj, uint32_t v, uint32_t f, uint8_t c) {
  uint32_t b = adj.vertex_face_begin[v], e = adj.vertex_face_end[v];
  if (e == adj.ring_limit[v]) {
    const uint32_t count = e - b, capacity = 2 * count + 4;
    const uint32_t nb = static_cast<uint32_t>(adj.vertex_faces.size());
    adj.vertex_faces.resize(nb + capacity);
    adj.vertex_face_corners.resize(nb + capacity);
    std::copy(adj.vertex_faces.begin() + b, adj.vertex_faces.begin() + e, adj.vertex_faces.begin() + nb);
    std::copy(adj.vertex_face_corners.begin() + b, adj.vertex_face_corners.begin() + e,
              adj.vertex_face_corners.begin() + nb);
    b = adj.vertex_face_begin[v] = nb;
    e = adj.vertex_face_end[v] = nb + count;
    adj.ring_limit[v] = nb + capacity;
  }
  uint32_t* faces = adj.vertex_faces.data();
  const uint32_t i = static_cast<uint32_t>(std::lower_bound(faces + b, faces + e, f) - faces);
  std::copy_backward(faces + i, faces + e, faces + e + 1);
  std::copy_backward(adj.vertex_face_corners.begin() + i, adj.vertex_face_corners.begin() + e,
                     adj.vertex_face_corners.begin() + e + 1);
  faces[i] = f;
  adj.vertex_face_corners[i] = c;
  adj.vertex_face_end[v] = e + 1;
}

// Face f no longer lies on edge e (f is already out of the rings).
void edgeRemoveFace(MeshAdjacency& adj, uint32_t e, uint32_t f) {
  uint32_t& n = adj.edge_face_count[e];
  auto& ef = adj.edge_faces[e];
  --n;
  if (ef[0] == f) {
    ef[0] = ef[1];
    ef[1] = kNoIndex;
  } else if (ef[1] == f) {
    ef[1] = kNoIndex;
  }
  if (n >= 2 && ef[1] == kNoIndex) {
    // A non-manifold edge lost one of its first two faces: the next smallest face on it
    // moves up. Faces on e are the faces around its first end with e as a side there.
    const uint32_t a = adj.edges[e][0];
    for (uint32_t i = adj.vertex_face_begin[a]; i < adj.vertex_face_end[a]; ++i) {
      const uint32_t g = adj.vertex_faces[i];
      if (g <= ef[0]) continue;
      const uint8_t c = adj.vertex_face_corners[i];
      if (adj.face_edges[g][c] == e || adj.face_edges[g][c == 0 ? 2 : c - 1] == e) {
        ef[1] = g;
        break;
      }
    }
  }
  if (n == 0) {
    adj.edges[e] = {0, 0};
    ef = {kNoIndex, kNoIndex};
    adj.free_edges.push_back(e);
  }
}

void edgeAddFace(MeshAdjacency& adj, uint32_t e, uint32_t f) {
  auto& ef = adj.edge_faces[e];
  ++adj.edge_face_count[e];
  if (ef[0] == kNoIndex) {
    ef[0] = f;
  } else if (f < ef[0]) {
    ef[1] = ef[0];
    ef[0] = f;
  } else if (ef[1] == kNoIndex || f < ef[1]) {
    ef[1] = f;
  }
}

}  // namespace

bool updateAdjacency(const TriMesh& mesh, std::span<const std::array<uint32_t, 3>> old_faces,
                     std::span<const uint32_t> changed, MeshAdjacency& adj) {
  const uint32_t nv = static_cast<uint32_t>(mesh.positions.size());
  const uint32_t nf = static_cast<uint32_t>(mesh.faces.size());
  const uint32_t old_nv = adj.vertex_count, old_nf = adj.face_count;
  if (nv < old_nv || old_faces.size() != old_nf || adj.vertex_face_begin.size() != old_nv)
    return false;
  if (changed.size() * 8 > std::max<size_t>(std::max(nf, old_nf), 64)) return false;
  const size_t rebuild_storage = 3 * static_cast<size_t>(nf) + kRingSlack * static_cast<size_t>(nv);
  if (adj.vertex_faces.size() > 2 * rebuild_storage + 1024) return false;

  // New vertices start with empty rings of no capacity (the first insertion moves them).
  const uint32_t storage = static_cast<uint32_t>(adj.vertex_faces.size());
  adj.vertex_face_begin.resize(nv, storage);
  adj.vertex_face_end.resize(nv, storage);
  adj.ring_limit.resize(nv, storage);
  adj.vertex_on_boundary.resize(nv, 0);
  std::vector<uint32_t>& touched = adj.scratch_edge;
  std::vector<uint8_t>& mark = adj.scratch_mark;  // 1: in `touched` (all 0 between calls)
  touched.clear();
  mark.resize(nv, 0);
  auto touch = [&](uint32_t v) {
    if (!mark[v]) {
      mark[v] = 1;
      touched.push_back(v);
    }
  };

  // Unchanged faces that the new vertices make valid join the faces to add.
  std::vector<uint32_t>& added = adj.scratch_added;
  added.assign(changed.begin(), changed.end());
  const uint32_t common = std::min(old_nf, nf);
  if (nv > old_nv && std::find(adj.face_valid.begin(), adj.face_valid.begin() + common, 0) !=
                         adj.face_valid.begin() + common) {
    for (uint32_t f = 0; f < common; ++f)
      if (!adj.face_valid[f] && old_faces[f] == mesh.faces[f] && faceIsValid(mesh.faces[f], nv))
        added.push_back(f);
  }

  // A changed slot usually keeps two of its corners (a split or collapse moves one corner
  // of the faces around it): a corner with the same vertex keeps its ring entry, and a side
  // with the same two ends keeps its edge, as removing and re-inserting them would leave
  // them. Bit c (corner c) and bit 3 + j (side j, corners j and j + 1) of kept[i] for changed[i].
  std::vector<uint8_t>& kept = adj.scratch_kept;
  kept.assign(changed.size(), 0);
  for (size_t i = 0; i < changed.size(); ++i) {
    const uint32_t f = changed[i];
    if (f >= old_nf || f >= nf || !adj.face_valid[f] || !faceIsValid(mesh.faces[f], nv)) continue;
    const auto &t = old_faces[f], &n = mesh.faces[f];
    uint8_t k = 0;
    for (int c = 0; c < 3; ++c) k |= static_cast<uint8_t>(t[c] == n[c]) << c;
    for (int j = 0; j < 3; ++j) {  // a side whose two corners are both kept
      const int j1 = j == 2 ? 0 : j + 1;
      k |= static_cast<uint8_t>((k >> j & 1) && (k >> j1 & 1)) << (3 + j);
    }
    kept[i] = k;
  }

  // 1. Take every changed slot's old face out of the rings and off its edges.
  for (size_t i = 0; i < changed.size(); ++i) {
    const uint32_t f = changed[i];
    if (f >= old_nf || !adj.face_valid[f]) continue;
    const auto& t = old_faces[f];
    for (int c = 0; c < 3; ++c) {
      if (!(kept[i] >> c & 1)) ringRemove(adj, t[c], f);
      touch(t[c]);
    }
    for (int j = 0; j < 3; ++j) {
      if (kept[i] >> (3 + j) & 1) continue;
      // Off the side first: f may still be in the ring that edgeRemoveFace() searches.
      const uint32_t e = adj.face_edges[f][j];
      adj.face_edges[f][j] = kNoIndex;
      edgeRemoveFace(adj, e, f);
    }
    adj.face_valid[f] = 0;
  }
  adj.face_valid.resize(nf, 0);
  adj.face_edges.resize(nf, {kNoIndex, kNoIndex, kNoIndex});
  adj.vertex_count = nv;
  adj.face_count = nf;

  // 2. Put the new faces in, and the unchanged faces that only the new vertices make valid
  // (an index that was out of range; found before step 1 below).
  for (size_t i = 0; i < added.size(); ++i) {
    const uint32_t f = added[i];
    if (f >= nf) continue;
    const auto& t = mesh.faces[f];
    if (!faceIsValid(t, nv)) continue;
    const uint8_t k = i < kept.size() ? kept[i] : 0;
    adj.face_valid[f] = 1;
    for (uint8_t c = 0; c < 3; ++c) {
      if (!(k >> c & 1)) ringInsert(adj, t[c], f, c);
      touch(t[c]);
    }
    for (int j = 0; j < 3; ++j) {
      if (k >> (3 + j) & 1) continue;
      const uint32_t a = t[j], b = t[j == 2 ? 0 : j + 1];
      uint32_t e = adj.findEdge(a, b);
      if (e == kNoIndex) {
        if (!adj.free_edges.empty()) {
          e = adj.free_edges.back();
          adj.free_edges.pop_back();
        } else {
          e = static_cast<uint32_t>(adj.edges.size());
          adj.edges.emplace_back();
          adj.edge_faces.emplace_back();
          adj.edge_face_count.push_back(0);
        }
        adj.edges[e] = edgeKey(a, b);
        adj.edge_faces[e] = {kNoIndex, kNoIndex};
        adj.edge_face_count[e] = 0;
      }
      adj.face_edges[f][j] = e;
      edgeAddFace(adj, e, f);
    }
  }

  // 3. Boundary flags of the vertices whose rings changed.
  for (uint32_t v : touched) {
    uint8_t on = 0;
    for (uint32_t i = adj.vertex_face_begin[v]; i < adj.vertex_face_end[v] && !on; ++i) {
      const auto& fe = adj.face_edges[adj.vertex_faces[i]];
      const uint8_t c = adj.vertex_face_corners[i];
      on = adj.edge_face_count[fe[c]] != 2 || adj.edge_face_count[fe[c == 0 ? 2 : c - 1]] != 2;
    }
    adj.vertex_on_boundary[v] = on;
    mark[v] = 0;
  }
  return true;
}

std::string checkAdjacency(const TriMesh& mesh, const MeshAdjacency& adj) {
  MeshAdjacency fresh;
  buildAdjacency(mesh, fresh);
  auto str = [](size_t x) { return std::to_string(x); };
  if (adj.vertex_count != fresh.vertex_count || adj.face_count != fresh.face_count)
    return "vertex or face count differs";
  if (adj.face_valid != fresh.face_valid) return "face_valid differs";
  if (adj.vertex_on_boundary != fresh.vertex_on_boundary) return "vertex_on_boundary differs";
  for (uint32_t v = 0; v < fresh.vertex_count; ++v) {
    const auto a = adj.facesOf(v), b = fresh.facesOf(v);
    if (!std::equal(a.begin(), a.end(), b.begin(), b.end())) return "ring of vertex " + str(v) + " differs";
    for (size_t k = 0; k < a.size(); ++k)
      if (adj.vertex_face_corners[adj.vertex_face_begin[v] + k] !=
          fresh.vertex_face_corners[fresh.vertex_face_begin[v] + k])
        return "corner in the ring of vertex " + str(v) + " differs";
  }
  size_t live = 0;
  for (size_t e = 0; e < adj.edges.size(); ++e) {
    if (adj.edge_face_count[e] == 0) {
      if (adj.edges[e] != EdgeKey{0, 0}) return "unused edge " + str(e) + " keeps its ends";
      continue;
    }
    ++live;
    const uint32_t g = fresh.findEdge(adj.edges[e][0], adj.edges[e][1]);
    if (g == kNoIndex || fresh.edges[g] != adj.edges[e]) return "edge " + str(e) + " does not exist";
    if (fresh.edge_face_count[g] != adj.edge_face_count[e] || fresh.edge_faces[g] != adj.edge_faces[e])
      return "faces of edge " + str(e) + " differ";
  }
  if (live != fresh.edges.size()) return "number of edges differs";
  for (uint32_t f = 0; f < fresh.face_count; ++f) {
    for (int j = 0; j < 3; ++j) {
      const uint32_t e = adj.face_edges[f][j], g = fresh.face_edges[f][j];
      if ((e == kNoIndex) != (g == kNoIndex)) return "side " + str(j) + " of face " + str(f) + " differs";
      if (e != kNoIndex && adj.edges[e] != fresh.edges[g])
        return "side " + str(j) + " of face " + str(f) + " names another edge";
    }
  }
  return "";
}

bool isClosedOutward(const TriMesh& mesh, const MeshAdjacency& adj) {
  const size_t nf = mesh.faces.size();
  if (nf == 0 || adj.face_valid.size() != nf) return false;
  for (uint8_t valid : adj.face_valid)
    if (!valid) return false;
  // Pieces: faces joined across edges (union-find with path halving).
  std::vector<uint32_t> parent(nf);
  for (uint32_t f = 0; f < nf; ++f) parent[f] = f;
  auto root = [&](uint32_t f) {
    while (parent[f] != f) f = parent[f] = parent[parent[f]];
    return f;
  };
  auto forward = [&](uint32_t f, uint32_t a, uint32_t b) {  // f runs a → b
    const auto& c = mesh.faces[f];
    return (c[0] == a && c[1] == b) || (c[1] == a && c[2] == b) || (c[2] == a && c[0] == b);
  };
  for (size_t e = 0; e < adj.edges.size(); ++e) {
    const uint32_t count = adj.edge_face_count[e];
    if (count == 0) continue;  // an unused entry after updates
    if (count != 2) return false;
    const uint32_t f = adj.edge_faces[e][0], g = adj.edge_faces[e][1];
    const EdgeKey& k = adj.edges[e];
    if (forward(f, k[0], k[1]) == forward(g, k[0], k[1])) return false;
    parent[root(f)] = root(g);
  }
  // Six times each piece's signed volume, about one vertex (no cancellation far from 0).
  const glm::dvec3 o(mesh.positions[mesh.faces[0][0]]);
  std::vector<double> volume(nf, 0.0);
  for (uint32_t f = 0; f < nf; ++f) {
    const auto& c = mesh.faces[f];
    const glm::dvec3 a = glm::dvec3(mesh.positions[c[0]]) - o, b = glm::dvec3(mesh.positions[c[1]]) - o,
                     d = glm::dvec3(mesh.positions[c[2]]) - o;
    volume[root(f)] += glm::dot(a, glm::cross(b, d));
  }
  for (uint32_t f = 0; f < nf; ++f)
    if (parent[f] == f && !(volume[f] > 0.0)) return false;
  return true;
}

}  // namespace lodline
