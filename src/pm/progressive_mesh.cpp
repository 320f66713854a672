// Progressive mesh construction by quadric-error half-edge collapses.
//
//   Garland, Heckbert 1997, "Surface simplification using quadric error metrics", §4-5
//     (area-weighted plane quadrics, greedy collapses from a priority queue).
//   Hoppe 1996, "Progressive meshes", §3-4 (ecol/vsplit records; legality: link condition,
//     no fold-over).
//   Hoppe 1997, "View-dependent refinement of progressive meshes", §3 (vertex hierarchy and
//     the neighbour faces fn0..fn3 recorded for every split).
//   Hoppe 1998, "Efficient implementation of progressive meshes", §4 (half-edge collapses:
//     the survivor keeps its position, which suits geomorphs).
//
// Connectivity during the build is a flat face-adjacency structure (3 corners and 3
// neighbour faces per face, one incident face per vertex); faces keep their input ids.
#include "pm/progressive_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "core/hash.h"

namespace lodline {

namespace {

constexpr uint32_t kNone = kPmNone;

inline uint32_t next3(uint32_t i) { return i == 2 ? 0 : i + 1; }
inline uint32_t prev3(uint32_t i) { return i == 0 ? 2 : i - 1; }

/// Symmetric 4x4 quadric (Garland-Heckbert), in double.
struct Quadric {
  double a2 = 0, ab = 0, ac = 0, ad = 0, b2 = 0, bc = 0, bd = 0, c2 = 0, cd = 0, d2 = 0;
  void addPlane(const glm::dvec3& n, double d, double w) {
    a2 += w * n.x * n.x; ab += w * n.x * n.y; ac += w * n.x * n.z; ad += w * n.x * d;
    b2 += w * n.y * n.y; bc += w * n.y * n.z; bd += w * n.y * d;
    c2 += w * n.z * n.z; cd += w * n.z * d; d2 += w * d * d;
  }
  void add(const Quadric& q) {
    a2 += q.a2; ab += q.ab; ac += q.ac; ad += q.ad; b2 += q.b2;
    bc += q.bc; bd += q.bd; c2 += q.c2; cd += q.cd; d2 += q.d2;
  }
  double eval(double x, double y, double z) const {
    return x * (a2 * x + 2 * (ab * y + ac * z + ad)) + y * (b2 * y + 2 * (bc * z + bd)) +
           z * (c2 * z + 2 * cd) + d2;
  }
};
/// Sum of two quadrics evaluated at p, without forming the sum.
inline double evalSum(const Quadric& q1, const Quadric& q2, const glm::vec3& p) {
  return q1.eval(p.x, p.y, p.z) + q2.eval(p.x, p.y, p.z);
}

struct HeapEntry {
  float cost;
  uint32_t u;
  uint32_t version;
};
struct HeapGreater {
  bool operator()(const HeapEntry& a, const HeapEntry& b) const { return a.cost > b.cost; }
};

inline float faceQuality(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  const glm::vec3 n = glm::cross(b - a, c - a);
  const float l = glm::dot(b - a, b - a) + glm::dot(c - b, c - b) + glm::dot(a - c, a - c);
  if (!(l > 0.0f)) return 0.0f;
  return 3.4641016f * glm::length(n) / l;  // 4√3·A / Σl² with A = |n|/2
}

/// One entry of a vertex ring: face, corner index of the centre vertex in that face.
struct RingFace {
  uint32_t face;
  uint32_t corner;
};

class Builder {
 public:
  Builder(const TriMesh& mesh, const PmBuildParams& params, const PmProgress& progress)
      : mesh_(mesh), params_(params), progress_(progress) {}

  Result<ProgressiveMesh> run();

 private:
  bool collapsible(uint32_t v) const {
    return (flags_[v] & (kPmBoundary | kPmFrozen)) == 0 && alive_v_[v];
  }
  uint32_t cornerOf(uint32_t f, uint32_t v) const {
    const auto& c = fv_[f];
    return c[0] == v ? 0 : c[1] == v ? 1 : c[2] == v ? 2 : 3;
  }
  /// Counter-clockwise ring of an interior vertex into `out` (false if it is open or too
  /// long, which cannot happen for collapsible vertices of a consistent structure).
  bool ring(uint32_t v, std::vector<RingFace>& out) const;
  void buildAdjacency();
  void computeQuadrics();
  /// Is the half-edge collapse u→t valid? `ring_u` is u's ring.
  bool valid(uint32_t u, uint32_t t, const std::vector<RingFace>& ring_u);
  /// Recomputes u's best target; with `validate` only a valid one is pushed.
  void update(uint32_t u, bool validate);
  /// After u collapsed into t, neighbour w of t: only w's candidate t changed (and u is gone),
  /// so a full update is needed only when w's best was u or t; otherwise w→t is compared with
  /// w's current best. The same choices as a full update, for a fraction of its cost.
  void updateNeighbour(uint32_t w, uint32_t u, uint32_t t);
  void collapse(uint32_t u, uint32_t t);

  const TriMesh& mesh_;
  const PmBuildParams& params_;
  const PmProgress& progress_;
  uint32_t n_ = 0, nf_ = 0;

  std::vector<std::array<uint32_t, 3>> fv_;  // corners (vertex indices)
  std::vector<std::array<uint32_t, 3>> fn_;  // neighbours across (c[i], c[i+1])
  std::vector<uint8_t> alive_f_;
  std::vector<uint32_t> vface_;  // one alive incident face per vertex
  std::vector<uint8_t> flags_;
  std::vector<uint8_t> alive_v_;
  std::vector<uint32_t> cur_node_;
  std::vector<Quadric> quad_;
  std::vector<glm::vec3> fnormal0_;  // unit input face normals (zero if degenerate)
  std::vector<uint32_t> version_;
  std::vector<uint32_t> target_;
  std::vector<float> cost_;  // cost of the collapse to target_
  std::vector<uint32_t> stamp_;
  uint32_t epoch_ = 0;
  std::vector<HeapEntry> heap_;
  std::vector<RingFace> ring_a_, ring_b_, ring_c_;
  std::vector<std::pair<float, uint32_t>> cand_;
  float cos_change_ = 0, cos_dev_ = 0;
  std::vector<VertexSplit> splits_;
  uint32_t alive_faces_ = 0;
};

bool Builder::ring(uint32_t v, std::vector<RingFace>& out) const {
  out.clear();
  const uint32_t start = vface_[v];
  uint32_t f = start;
  do {
    const uint32_t i = cornerOf(f, v);
    if (i == 3) return false;
    out.push_back({f, i});
    f = fn_[f][prev3(i)];
    if (f == kNone || out.size() > 4096) return false;
  } while (f != start);
  return true;
}

void Builder::buildAdjacency() {
  fv_ = mesh_.faces;
  fn_.assign(nf_, {kNone, kNone, kNone});
  alive_f_.assign(nf_, 1);
  flags_.assign(n_, 0);
  vface_.assign(n_, kNone);
  // Outgoing half-edges per origin vertex (CSR); degenerate faces are left out.
  std::vector<uint32_t> start(n_ + 1, 0);
  std::vector<uint8_t> degenerate(nf_, 0);
  for (uint32_t f = 0; f < nf_; ++f) {
    const auto& c = fv_[f];
    if (c[0] == c[1] || c[1] == c[2] || c[2] == c[0]) {
      degenerate[f] = 1;
      for (uint32_t v : c) flags_[v] |= kPmFrozen;
      continue;
    }
    for (uint32_t v : c) ++start[v + 1];
  }
  for (uint32_t v = 0; v < n_; ++v) start[v + 1] += start[v];
  std::vector<uint32_t> fill(start.begin(), start.end() - 1);
  std::vector<uint32_t> out(start[n_]);  // half-edge id 3f+i, from c[i] to c[i+1]
  for (uint32_t f = 0; f < nf_; ++f) {
    if (degenerate[f]) continue;
    for (uint32_t i = 0; i < 3; ++i) out[fill[fv_[f][i]]++] = 3 * f + i;
    for (uint32_t v : fv_[f]) vface_[v] = f;
  }
  auto head = [&](uint32_t h) { return fv_[h / 3][next3(h % 3)]; };
  const bool materials = mesh_.face_materials.size() == nf_;
  for (uint32_t f = 0; f < nf_; ++f) {
    if (degenerate[f]) continue;
    for (uint32_t i = 0; i < 3; ++i) {
      const uint32_t a = fv_[f][i], b = fv_[f][next3(i)];
      uint32_t twins = 0, twin = kNone, same = 0;
      for (uint32_t k = start[b]; k < start[b + 1]; ++k)
        if (head(out[k]) == a) { ++twins; twin = out[k] / 3; }
      for (uint32_t k = start[a]; k < start[a + 1]; ++k)
        if (head(out[k]) == b) ++same;
      if (twins == 1 && same == 1) {
        fn_[f][i] = twin;
        // A material boundary keeps its vertices (material lines stay exact at every level of
        // detail; Hoppe 1996 §3.3 keeps such discontinuity curves too, less strictly).
        if (materials && mesh_.face_materials[f] != mesh_.face_materials[twin]) {
          flags_[a] |= kPmFrozen;
          flags_[b] |= kPmFrozen;
        }
      } else if (twins == 0 && same == 1) {
        flags_[a] |= kPmBoundary;
        flags_[b] |= kPmBoundary;
      } else {
        flags_[a] |= kPmFrozen;
        flags_[b] |= kPmFrozen;
      }
    }
  }
  // Vertex manifoldness: the fan reached by rotation must hold every incident face.
  for (uint32_t v = 0; v < n_; ++v) {
    const uint32_t count = start[v + 1] - start[v];
    if (count == 0) { flags_[v] |= kPmFrozen; continue; }
    if (flags_[v] & kPmFrozen) continue;
    uint32_t seen = 0;
    bool open = false;
    const uint32_t f0 = vface_[v];
    uint32_t f = f0;
    do {  // counter-clockwise
      ++seen;
      const uint32_t i = cornerOf(f, v);
      f = fn_[f][prev3(i)];
      if (f == kNone) { open = true; break; }
    } while (f != f0 && seen <= count);
    if (open) {  // clockwise from the start to the other end of the fan
      f = fn_[f0][cornerOf(f0, v)];
      while (f != kNone && seen <= count) {
        ++seen;
        f = fn_[f][cornerOf(f, v)];
      }
      flags_[v] |= kPmBoundary;
    }
    if (seen != count) flags_[v] |= kPmFrozen;
  }
  for (uint32_t f = 0; f < nf_; ++f) alive_f_[f] = 1;
  alive_faces_ = nf_;
}

void Builder::computeQuadrics() {
  quad_.assign(n_, Quadric{});
  fnormal0_.resize(nf_);
  for (uint32_t f = 0; f < nf_; ++f) {
    const auto& c = fv_[f];
    const glm::dvec3 a(mesh_.positions[c[0]]), b(mesh_.positions[c[1]]), d(mesh_.positions[c[2]]);
    const glm::dvec3 n = glm::cross(b - a, d - a);
    const double len = glm::length(n);
    if (!(len > 0.0)) { fnormal0_[f] = glm::vec3(0.0f); continue; }
    const glm::dvec3 un = n / len;
    fnormal0_[f] = glm::vec3(un);
    const double area = 0.5 * len;
    for (uint32_t v : c) quad_[v].addPlane(un, -glm::dot(un, a), area);
  }
}

bool Builder::valid(uint32_t u, uint32_t t, const std::vector<RingFace>& ring_u) {
  if (!collapsible(t) || !collapsible(u)) return false;
  const uint32_t val_u = static_cast<uint32_t>(ring_u.size());
  // fl = (u, t, l) holds u→t; fr = (u, r, t) holds t→u.
  uint32_t fl = kNone, fr = kNone, l = kNone, r = kNone;
  for (const RingFace& rf : ring_u) {
    const auto& c = fv_[rf.face];
    if (c[next3(rf.corner)] == t) { fl = rf.face; l = c[prev3(rf.corner)]; }
    if (c[prev3(rf.corner)] == t) { fr = rf.face; r = c[next3(rf.corner)]; }
  }
  if (fl == kNone || fr == kNone || fl == fr || l == r) return false;
  // Link condition: the common neighbours of u and t are exactly l and r.
  if (!ring(t, ring_b_)) return false;
  const uint32_t val_t = static_cast<uint32_t>(ring_b_.size());
  const uint32_t new_valence = val_t + val_u - 4;
  if (val_t + val_u < 7 || new_valence > params_.max_valence) return false;
  ++epoch_;
  if (epoch_ == 0) { std::fill(stamp_.begin(), stamp_.end(), 0u); epoch_ = 1; }
  for (const RingFace& rf : ring_u) stamp_[fv_[rf.face][next3(rf.corner)]] = epoch_;
  uint32_t common = 0;
  for (const RingFace& rf : ring_b_) {
    const uint32_t w = fv_[rf.face][next3(rf.corner)];
    if (w != u && stamp_[w] == epoch_) ++common;
  }
  if (common != 2) return false;
  // Geometry of the faces that move (those around u except fl, fr).
  const glm::vec3 pt = mesh_.positions[t], pu = mesh_.positions[u];
  for (const RingFace& rf : ring_u) {
    if (rf.face == fl || rf.face == fr) continue;
    const auto& c = fv_[rf.face];
    const glm::vec3 a = mesh_.positions[c[next3(rf.corner)]];
    const glm::vec3 b = mesh_.positions[c[prev3(rf.corner)]];
    const glm::vec3 n_old = glm::cross(a - pu, b - pu);
    const glm::vec3 n_new = glm::cross(a - pt, b - pt);
    const float len_new = glm::length(n_new), len_old = glm::length(n_old);
    if (!(len_new > 0.0f)) return false;
    const glm::vec3 un = n_new / len_new;
    if (len_old > 0.0f && glm::dot(un, n_old / len_old) < cos_change_) return false;
    const glm::vec3& n0 = fnormal0_[rf.face];
    if ((n0.x != 0.0f || n0.y != 0.0f || n0.z != 0.0f) && glm::dot(un, n0) < cos_dev_) return false;
    const float q_new = faceQuality(pt, a, b);
    if (q_new < params_.min_face_quality && q_new < faceQuality(pu, a, b)) return false;
  }
  return true;
}

void Builder::update(uint32_t u, bool validate) {
  ++version_[u];
  target_[u] = kNone;
  if (!collapsible(u) || !ring(u, ring_a_)) return;
  cand_.clear();
  for (const RingFace& rf : ring_a_) {
    const uint32_t t = fv_[rf.face][next3(rf.corner)];
    if (!collapsible(t)) continue;
    const glm::vec3& p = mesh_.positions[t];
    cand_.push_back({static_cast<float>(std::max(0.0, evalSum(quad_[u], quad_[t], p))), t});
  }
  if (cand_.empty()) return;
  std::sort(cand_.begin(), cand_.end());
  for (const auto& [cost, t] : cand_) {
    if (validate && !valid(u, t, ring_a_)) continue;
    target_[u] = t;
    cost_[u] = cost;
    heap_.push_back({cost, u, version_[u]});
    std::push_heap(heap_.begin(), heap_.end(), HeapGreater{});
    return;
  }
}

void Builder::collapse(uint32_t u, uint32_t t) {
  ring(u, ring_a_);
  uint32_t fl = kNone, fr = kNone, cl = 0, cr = 0;
  for (const RingFace& rf : ring_a_) {
    const auto& c = fv_[rf.face];
    if (c[next3(rf.corner)] == t) { fl = rf.face; cl = rf.corner; }
    if (c[prev3(rf.corner)] == t) { fr = rf.face; cr = rf.corner; }
  }
  // fl = (u, t, l): edges (u,t)→fr, (t,l)→fn_tl, (l,u)→fn_ul.
  // fr = (u, r, t): edges (u,r)→fn_ur, (r,t)→fn_rt, (t,u)→fl.
  const uint32_t fn_tl = fn_[fl][next3(cl)], fn_ul = fn_[fl][prev3(cl)];
  const uint32_t fn_ur = fn_[fr][cr], fn_rt = fn_[fr][next3(cr)];
  const uint32_t l = fv_[fl][prev3(cl)], r = fv_[fr][next3(cr)];

  VertexSplit s;
  s.vt = cur_node_[t];
  s.vu = cur_node_[u];
  s.fl = fl;
  s.fr = fr;
  s.fn = {fn_tl, fn_ul, fn_ur, fn_rt};
  splits_.push_back(s);

  for (const RingFace& rf : ring_a_)
    if (rf.face != fl && rf.face != fr) fv_[rf.face][rf.corner] = t;
  auto relink = [&](uint32_t f, uint32_t from, uint32_t to) {
    for (uint32_t k = 0; k < 3; ++k)
      if (fn_[f][k] == from) { fn_[f][k] = to; return; }
  };
  relink(fn_tl, fl, fn_ul);
  relink(fn_ul, fl, fn_tl);
  relink(fn_ur, fr, fn_rt);
  relink(fn_rt, fr, fn_ur);
  alive_f_[fl] = alive_f_[fr] = 0;
  alive_faces_ -= 2;
  vface_[t] = fn_tl;
  vface_[l] = fn_tl;
  vface_[r] = fn_rt;
  alive_v_[u] = 0;
  ++version_[u];
  quad_[t].add(quad_[u]);
  cur_node_[t] = n_ + static_cast<uint32_t>(splits_.size()) - 1;

  update(t, false);
  ring(t, ring_c_);
  for (const RingFace& rf : ring_c_) updateNeighbour(fv_[rf.face][next3(rf.corner)], u, t);
}

void Builder::updateNeighbour(uint32_t w, uint32_t u, uint32_t t) {
  const uint32_t old = target_[w];
  if (old == kNone || old == u || old == t || !collapsible(w) || !collapsible(t)) {
    update(w, false);
    return;
  }
  const float cost =
      static_cast<float>(std::max(0.0, evalSum(quad_[w], quad_[t], mesh_.positions[t])));
  if (!(cost < cost_[w])) return;  // the entry in the heap stays w's best
  ++version_[w];
  target_[w] = t;
  cost_[w] = cost;
  heap_.push_back({cost, w, version_[w]});
  std::push_heap(heap_.begin(), heap_.end(), HeapGreater{});
}

Result<ProgressiveMesh> Builder::run() {
  n_ = static_cast<uint32_t>(mesh_.positions.size());
  nf_ = static_cast<uint32_t>(mesh_.faces.size());
  if (nf_ == 0) return Error::runtime("mesh has no faces");
  if (mesh_.positions.size() >= kNone / 2 || mesh_.faces.size() >= kNone / 2)
    return Error::runtime("mesh too large for 32-bit indices");
  for (uint32_t v = 0; v < n_; ++v) {
    const glm::vec3& p = mesh_.positions[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      return Error::runtime("vertex " + std::to_string(v) + " has a non-finite coordinate");
  }
  for (uint32_t f = 0; f < nf_; ++f)
    for (uint32_t v : mesh_.faces[f])
      if (v >= n_)
        return Error::runtime("face " + std::to_string(f) + " references vertex " +
                              std::to_string(v) + " (" + std::to_string(n_) + " vertices)");
  cos_change_ = std::cos(glm::radians(params_.max_normal_change_deg));
  cos_dev_ = std::cos(glm::radians(params_.max_normal_deviation_deg));

  buildAdjacency();
  computeQuadrics();
  alive_v_.assign(n_, 1);
  cur_node_.resize(n_);
  for (uint32_t v = 0; v < n_; ++v) cur_node_[v] = v;
  version_.assign(n_, 0);
  target_.assign(n_, kNone);
  cost_.assign(n_, 0.0f);
  stamp_.assign(n_, 0);
  splits_.reserve(n_);
  heap_.reserve(4 * static_cast<size_t>(n_));
  uint32_t collapsible_count = 0;
  for (uint32_t v = 0; v < n_; ++v) {
    if (!collapsible(v)) continue;
    ++collapsible_count;
    update(v, false);
  }
  const uint32_t progress_step = std::max<uint32_t>(1, collapsible_count / 100);
  uint32_t next_report = progress_step;
  while (!heap_.empty() && alive_faces_ > params_.min_base_faces) {
    std::pop_heap(heap_.begin(), heap_.end(), HeapGreater{});
    const HeapEntry e = heap_.back();
    heap_.pop_back();
    if (e.version != version_[e.u] || target_[e.u] == kNone) continue;
    if (!ring(e.u, ring_a_)) {
      target_[e.u] = kNone;
      continue;
    }
    if (!valid(e.u, target_[e.u], ring_a_)) {
      update(e.u, true);
      continue;
    }
    collapse(e.u, target_[e.u]);
    if (progress_ && splits_.size() >= next_report) {
      next_report += progress_step;
      progress_(std::min(1.0f, static_cast<float>(splits_.size()) /
                                   static_cast<float>(std::max(1u, collapsible_count))));
    }
  }

  ProgressiveMesh pm;
  pm.positions = mesh_.positions;
  pm.faces = mesh_.faces;
  pm.vertex_flags = flags_;
  pm.splits = std::move(splits_);
  for (uint32_t f = 0; f < nf_; ++f) {
    if (!alive_f_[f]) continue;
    pm.base_faces.push_back(f);
    std::array<uint32_t, 3> c;
    for (int i = 0; i < 3; ++i) c[i] = cur_node_[fv_[f][i]];
    pm.base_corners.push_back(c);
    pm.base_neighbors.push_back(fn_[f]);
  }
  pm.content_hash = meshContentHash(mesh_);
  pm.params_hash = buildParamsHash(params_);
  Status st = pm.finalize("progressive mesh build");
  if (!st.ok()) return st.error();
  if (progress_) progress_(1.0f);
  return pm;
}

}  // namespace

uint64_t meshContentHash(const TriMesh& mesh) {
  uint64_t h = hashBytes(mesh.positions.data(), mesh.positions.size() * sizeof(glm::vec3));
  h = hashBytes(mesh.faces.data(), mesh.faces.size() * sizeof(mesh.faces[0]), h);
  // Materials change the build (their boundaries are kept); a mesh without keeps its hash.
  if (!mesh.face_materials.empty())
    h = hashBytes(mesh.face_materials.data(), mesh.face_materials.size() * sizeof(uint32_t), h);
  return h;
}

uint64_t buildParamsHash(const PmBuildParams& p) {
  const float f[3] = {p.max_normal_change_deg, p.max_normal_deviation_deg, p.min_face_quality};
  const uint32_t u[2] = {p.max_valence, p.min_base_faces};
  return hashBytes(u, sizeof(u), hashBytes(f, sizeof(f)));
}

Result<ProgressiveMesh> buildProgressiveMesh(const TriMesh& mesh, const PmBuildParams& params,
                                             const PmProgress& progress) {
  Builder b(mesh, params, progress);
  return b.run();
}

Status ProgressiveMesh::finalize(const std::string& what) {
  auto fail = [&](const std::string& msg) { return Status(Error::runtime(what + ": " + msg)); };
  const uint32_t n = vertexCount(), nf = faceCount();
  if (vertex_flags.size() != n) return fail("vertex flag count differs from vertex count");
  if (static_cast<uint64_t>(n) + splits.size() >= kPmNone / 2) return fail("too many nodes");
  for (uint32_t f = 0; f < nf; ++f)
    for (uint32_t v : faces[f])
      if (v >= n) return fail("face " + std::to_string(f) + " has vertex index out of range");
  for (const glm::vec3& p : positions)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      return fail("non-finite vertex position");
  const uint32_t nn = nodeCount();
  parent.assign(nn, kPmNone);
  origin.resize(nn);
  face_parent.assign(nf, kPmNone);
  std::vector<uint8_t> is_base(nf, 0);
  for (uint32_t v = 0; v < n; ++v) origin[v] = v;
  for (uint32_t i = 0; i < splits.size(); ++i) {
    const uint32_t s = n + i;
    const VertexSplit& vs = splits[i];
    const std::string where = "split " + std::to_string(i) + ": ";
    if (vs.vt >= s || vs.vu >= s || vs.vt == vs.vu) return fail(where + "bad children");
    if (parent[vs.vt] != kPmNone || parent[vs.vu] != kPmNone)
      return fail(where + "child already has a parent");
    parent[vs.vt] = parent[vs.vu] = s;
    origin[s] = origin[vs.vt];
    if (vs.fl >= nf || vs.fr >= nf || vs.fl == vs.fr) return fail(where + "bad faces fl/fr");
    if (face_parent[vs.fl] != kPmNone || face_parent[vs.fr] != kPmNone)
      return fail(where + "face created twice");
    face_parent[vs.fl] = face_parent[vs.fr] = s;
    for (uint32_t f : vs.fn)
      if (f >= nf || f == vs.fl || f == vs.fr) return fail(where + "bad neighbour face");
  }
  if (base_corners.size() != base_faces.size() || base_neighbors.size() != base_faces.size())
    return fail("base mesh arrays differ in size");
  for (uint32_t f : base_faces) {
    if (f >= nf || face_parent[f] != kPmNone || is_base[f])
      return fail("base face id " + std::to_string(f) + " invalid or created twice");
    is_base[f] = 1;
  }
  if (base_faces.size() + 2 * splits.size() != nf)
    return fail("faces not all accounted for by the base mesh and the splits");
  for (size_t k = 0; k < base_faces.size(); ++k) {
    for (int i = 0; i < 3; ++i) {
      const uint32_t c = base_corners[k][i], g = base_neighbors[k][i];
      if (c >= nn || parent[c] != kPmNone) return fail("base corner is not a root node");
      if (g != kPmNone && (g >= nf || !is_base[g])) return fail("base neighbour out of range");
    }
  }
  roots.clear();
  for (uint32_t v = 0; v < nn; ++v)
    if (parent[v] == kPmNone) roots.push_back(v);
  return Status::success();
}

TriMesh ProgressiveMesh::baseMesh(std::vector<uint32_t>* base_node_ids) const {
  TriMesh m;
  std::vector<uint32_t> index(nodeCount(), kPmNone);
  if (base_node_ids) base_node_ids->clear();
  for (uint32_t r : roots) {
    index[r] = static_cast<uint32_t>(m.positions.size());
    m.positions.push_back(nodePosition(r));
    if (base_node_ids) base_node_ids->push_back(r);
  }
  for (const auto& c : base_corners) m.faces.push_back({index[c[0]], index[c[1]], index[c[2]]});
  return m;
}

// ---- Error-bounded static simplification (Pan, Zhou, Shi; docs/design.md §2.4) ----

TriMesh pmLevelMesh(const ProgressiveMesh& pm, uint32_t collapses) {
  const uint32_t n = pm.vertexCount();
  collapses = std::min<uint32_t>(collapses, static_cast<uint32_t>(pm.splits.size()));
  // Union-find over input vertices: collapse i merges origin(vu) into origin(vt).
  std::vector<uint32_t> up(n);
  for (uint32_t v = 0; v < n; ++v) up[v] = v;
  std::vector<uint8_t> removed(pm.faceCount(), 0);
  for (uint32_t i = 0; i < collapses; ++i) {
    const VertexSplit& s = pm.splits[i];
    up[pm.origin[s.vu]] = pm.origin[s.vt];
    removed[s.fl] = removed[s.fr] = 1;
  }
  auto find = [&](uint32_t v) {
    uint32_t r = v;
    while (up[r] != r) r = up[r];
    while (up[v] != r) {
      const uint32_t next = up[v];
      up[v] = r;
      v = next;
    }
    return r;
  };
  TriMesh m;
  std::vector<uint32_t> index(n, kPmNone);
  for (uint32_t f = 0; f < pm.faceCount(); ++f) {
    if (removed[f]) continue;
    std::array<uint32_t, 3> c;
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = find(pm.faces[f][k]);
      if (index[v] == kPmNone) {
        index[v] = static_cast<uint32_t>(m.positions.size());
        m.positions.push_back(pm.positions[v]);
      }
      c[k] = index[v];
    }
    m.faces.push_back(c);
  }
  return m;
}

BoundedSimplification simplifyWithinBound(const ProgressiveMesh& pm, double bound, const MeshErrorFn& error) {
  BoundedSimplification best;
  best.mesh = pmLevelMesh(pm, 0);  // the input itself: error 0
  auto ok = [&](uint32_t k, TriMesh& mesh, double& e) {
    mesh = pmLevelMesh(pm, k);
    e = error(mesh);
    ++best.evaluations;
    return e >= 0.0 && e <= bound;
  };
  uint32_t lo = 0, hi = static_cast<uint32_t>(pm.splits.size());  // lo: measured within the bound
  TriMesh mesh;
  double e = 0.0;
  if (hi > 0 && ok(hi, mesh, e)) {
    best.mesh = std::move(mesh);
    best.collapses = hi;
    best.error = e;
    return best;
  }
  while (hi - lo > 1) {
    const uint32_t mid = lo + (hi - lo) / 2;
    if (ok(mid, mesh, e)) {
      lo = mid;
      best.mesh = std::move(mesh);
      best.collapses = mid;
      best.error = e;
    } else {
      hi = mid;
    }
  }
  return best;
}

}  // namespace lodline
