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
#include <limits>
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

/// Indexed 4-ary min-heap of vertices keyed by their collapse cost: at most one entry per
/// vertex, re-keyed in place when its best collapse changes, so no stale entries are pushed
/// and popped (a lazy heap popped about three stale entries per collapse). Keys sit apart from
/// ids, so a sift compares four neighbouring floats.
class CostHeap {
 public:
  void reset(uint32_t vertices) {
    pos_.assign(vertices, kNone);
    key_.clear();
    id_.clear();
  }
  bool empty() const { return id_.empty(); }
  uint32_t top() const { return id_[0]; }
  /// Inserts v or changes its key.
  void set(uint32_t v, float key) {
    uint32_t i = pos_[v];
    if (i == kNone) {
      i = static_cast<uint32_t>(id_.size());
      id_.push_back(v);
      key_.push_back(key);
      pos_[v] = i;
      up(i);
      return;
    }
    const float old = key_[i];
    key_[i] = key;
    if (key < old) up(i);
    else down(i);
  }
  void erase(uint32_t v) {
    const uint32_t i = pos_[v];
    if (i == kNone) return;
    pos_[v] = kNone;
    const uint32_t last = static_cast<uint32_t>(id_.size()) - 1;
    if (i != last) {
      const float old = key_[i];
      id_[i] = id_[last];
      key_[i] = key_[last];
      pos_[id_[i]] = i;
      id_.pop_back();
      key_.pop_back();
      if (key_[i] < old) up(i);
      else down(i);
      return;
    }
    id_.pop_back();
    key_.pop_back();
  }
  /// Appends without ordering; heapify() afterwards (one O(n) construction).
  void append(uint32_t v, float key) {
    pos_[v] = static_cast<uint32_t>(id_.size());
    id_.push_back(v);
    key_.push_back(key);
  }
  void heapify() {
    for (size_t i = id_.size() / 4 + 1; i-- > 0;) down(static_cast<uint32_t>(i));
  }

 private:
  void place(uint32_t i, uint32_t v, float key) {
    id_[i] = v;
    key_[i] = key;
    pos_[v] = i;
  }
  void up(uint32_t i) {
    const uint32_t v = id_[i];
    const float key = key_[i];
    while (i > 0) {
      const uint32_t parent = (i - 1) / 4;
      if (!(key < key_[parent])) break;
      place(i, id_[parent], key_[parent]);
      i = parent;
    }
    place(i, v, key);
  }
  void down(uint32_t i) {
    const uint32_t n = static_cast<uint32_t>(id_.size());
    if (i >= n) return;
    const uint32_t v = id_[i];
    const float key = key_[i];
    for (;;) {
      const uint32_t first = 4 * i + 1;
      if (first >= n) break;
      const uint32_t end = std::min(first + 4, n);
      uint32_t best = first;
      for (uint32_t c = first + 1; c < end; ++c)
        if (key_[c] < key_[best]) best = c;
      if (!(key_[best] < key)) break;
      place(i, id_[best], key_[best]);
      i = best;
    }
    place(i, v, key);
  }

  std::vector<uint32_t> pos_;  // per vertex: its index in the heap, or kNone
  std::vector<float> key_;
  std::vector<uint32_t> id_;
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
    return (v_[v].flags & (kPmBoundary | kPmFrozen)) == 0 && v_[v].alive;
  }
  uint32_t cornerOf(uint32_t f, uint32_t v) const {
    const auto& c = f_[f].v;
    return c[0] == v ? 0 : c[1] == v ? 1 : c[2] == v ? 2 : 3;
  }
  /// Counter-clockwise ring of an interior vertex into `out` (false if it is open or too
  /// long, which cannot happen for collapsible vertices of a consistent structure).
  bool ring(uint32_t v, std::vector<RingFace>& out) const;
  void buildAdjacency();
  void computeQuadrics();
  /// Is the half-edge collapse u→t valid? `ring_u` is u's ring; leaves t's ring in ring_b_
  /// (collapse() relies on it when valid() said yes).
  bool valid(uint32_t u, uint32_t t, const std::vector<RingFace>& ring_u);
  /// Recomputes u's best target; with `validate` only a valid one is pushed.
  void update(uint32_t u, bool validate);
  /// The same, with u's ring already in `ring_u` (ring_a_ or ring_c_).
  void updateWithRing(uint32_t u, bool validate, const std::vector<RingFace>& ring_u);
  /// Every vertex's first best target, from one pass over the faces (each interior directed
  /// edge lies in one face), then one heap construction.
  void initialTargets();
  /// After u collapsed into t, neighbour w of t: only w's candidate t changed (and u is gone),
  /// so a full update is needed only when w's best was u or t; otherwise w→t is compared with
  /// w's current best. The same choices as a full update, for a fraction of its cost.
  void updateNeighbour(uint32_t w, uint32_t u, uint32_t t);
  void collapse(uint32_t u, uint32_t t);

  const TriMesh& mesh_;
  const PmBuildParams& params_;
  const PmProgress& progress_;
  uint32_t n_ = 0, nf_ = 0;

  /// Corners and the neighbours across (c[i], c[i+1]) side by side: a ring walk reads both
  /// from one cache line.
  struct Face {
    std::array<uint32_t, 3> v;
    std::array<uint32_t, 3> n;
    glm::vec3 normal0;  // unit input face normal (zero if degenerate)
  };
  std::vector<Face> f_;
  std::vector<uint8_t> alive_f_;
  /// Everything the collapse loop reads or writes of a vertex, in one record of two cache
  /// lines: the loop visits vertices in cost order, all over the mesh, and with one array per
  /// field each vertex it touched cost a cache miss per field (memory latency was most of a
  /// million-face build).
  struct alignas(64) Vert {
    Quadric q;
    glm::vec3 p;                // position (half-edge collapses keep the survivor's)
    uint32_t target = kNone;    // best collapse target, kNone: none (then not in the heap)
    float cost = 0.0f;          // its cost
    float other = 0.0f;         // a lower bound of the costs of the other candidates
    uint32_t vface = kNone;     // one alive incident face
    uint32_t stamp = 0;         // link-condition marks (epoch_)
    uint32_t node = 0;          // current hierarchy node
    uint8_t flags = 0;          // kPmBoundary | kPmFrozen
    uint8_t alive = 1;
  };
  std::vector<Vert> v_;
  uint32_t epoch_ = 0;
  CostHeap heap_;  // the collapsible vertices that have a target, by Vert::cost
  std::vector<RingFace> ring_a_, ring_b_, ring_c_;
  std::vector<std::pair<float, uint32_t>> cand_;
  float cos_change_ = 0, cos_dev_ = 0;
  HugeVector<VertexSplit> splits_;
  uint32_t alive_faces_ = 0;
};

bool Builder::ring(uint32_t v, std::vector<RingFace>& out) const {
  out.clear();
  const uint32_t start = v_[v].vface;
  uint32_t f = start;
  do {
    const uint32_t i = cornerOf(f, v);
    if (i == 3) return false;
    out.push_back({f, i});
    f = f_[f].n[prev3(i)];
    if (f == kNone || out.size() > 4096) return false;
  } while (f != start);
  return true;
}

void Builder::buildAdjacency() {
  v_.resize(n_);
  for (uint32_t v = 0; v < n_; ++v) {
    v_[v].p = mesh_.positions[v];
    v_[v].node = v;
  }
  f_.resize(nf_);
  for (uint32_t f = 0; f < nf_; ++f) f_[f] = {mesh_.faces[f], {kNone, kNone, kNone}, glm::vec3(0.0f)};
  alive_f_.assign(nf_, 1);
  // Outgoing half-edges per origin vertex (CSR); degenerate faces are left out.
  std::vector<uint32_t> start(n_ + 1, 0);
  std::vector<uint8_t> degenerate(nf_, 0);
  for (uint32_t f = 0; f < nf_; ++f) {
    const auto& c = f_[f].v;
    if (c[0] == c[1] || c[1] == c[2] || c[2] == c[0]) {
      degenerate[f] = 1;
      for (uint32_t v : c) v_[v].flags |= kPmFrozen;
      continue;
    }
    for (uint32_t v : c) ++start[v + 1];
  }
  for (uint32_t v = 0; v < n_; ++v) start[v + 1] += start[v];
  std::vector<uint32_t> fill(start.begin(), start.end() - 1);
  std::vector<uint32_t> out(start[n_]);   // half-edge id 3f+i, from c[i] to c[i+1]
  std::vector<uint32_t> head(start[n_]);  // its head c[i+1], beside it: the scans stay in the lists
  for (uint32_t f = 0; f < nf_; ++f) {
    if (degenerate[f]) continue;
    for (uint32_t i = 0; i < 3; ++i) {
      const uint32_t k = fill[f_[f].v[i]]++;
      out[k] = 3 * f + i;
      head[k] = f_[f].v[next3(i)];
    }
    for (uint32_t v : f_[f].v) v_[v].vface = f;
  }
  const bool materials = mesh_.face_materials.size() == nf_;
  for (uint32_t f = 0; f < nf_; ++f) {
    if (degenerate[f]) continue;
    for (uint32_t i = 0; i < 3; ++i) {
      const uint32_t a = f_[f].v[i], b = f_[f].v[next3(i)];
      uint32_t twins = 0, twin = kNone, same = 0;
      for (uint32_t k = start[b]; k < start[b + 1]; ++k)
        if (head[k] == a) { ++twins; twin = out[k] / 3; }
      for (uint32_t k = start[a]; k < start[a + 1]; ++k)
        if (head[k] == b) ++same;
      if (twins == 1 && same == 1) {
        f_[f].n[i] = twin;
        // A material boundary keeps its vertices (material lines stay exact at every level of
        // detail; Hoppe 1996 §3.3 keeps such discontinuity curves too, less strictly).
        if (materials && mesh_.face_materials[f] != mesh_.face_materials[twin]) {
          v_[a].flags |= kPmFrozen;
          v_[b].flags |= kPmFrozen;
        }
      } else if (twins == 0 && same == 1) {
        v_[a].flags |= kPmBoundary;
        v_[b].flags |= kPmBoundary;
      } else {
        v_[a].flags |= kPmFrozen;
        v_[b].flags |= kPmFrozen;
      }
    }
  }
  // Vertex manifoldness: the fan reached by rotation must hold every incident face.
  for (uint32_t v = 0; v < n_; ++v) {
    const uint32_t count = start[v + 1] - start[v];
    if (count == 0) { v_[v].flags |= kPmFrozen; continue; }
    if (v_[v].flags & kPmFrozen) continue;
    uint32_t seen = 0;
    bool open = false;
    const uint32_t f0 = v_[v].vface;
    uint32_t f = f0;
    do {  // counter-clockwise
      ++seen;
      const uint32_t i = cornerOf(f, v);
      f = f_[f].n[prev3(i)];
      if (f == kNone) { open = true; break; }
    } while (f != f0 && seen <= count);
    if (open) {  // clockwise from the start to the other end of the fan
      f = f_[f0].n[cornerOf(f0, v)];
      while (f != kNone && seen <= count) {
        ++seen;
        f = f_[f].n[cornerOf(f, v)];
      }
      v_[v].flags |= kPmBoundary;
    }
    if (seen != count) v_[v].flags |= kPmFrozen;
  }
  for (uint32_t f = 0; f < nf_; ++f) alive_f_[f] = 1;
  alive_faces_ = nf_;
}

void Builder::computeQuadrics() {
  for (uint32_t f = 0; f < nf_; ++f) {
    const auto& c = f_[f].v;
    const glm::dvec3 a(mesh_.positions[c[0]]), b(mesh_.positions[c[1]]), d(mesh_.positions[c[2]]);
    const glm::dvec3 n = glm::cross(b - a, d - a);
    const double len = glm::length(n);
    if (!(len > 0.0)) { f_[f].normal0 = glm::vec3(0.0f); continue; }
    const glm::dvec3 un = n / len;
    f_[f].normal0 = glm::vec3(un);
    const double area = 0.5 * len;
    for (uint32_t v : c) v_[v].q.addPlane(un, -glm::dot(un, a), area);
  }
}

bool Builder::valid(uint32_t u, uint32_t t, const std::vector<RingFace>& ring_u) {
  if (!collapsible(t) || !collapsible(u)) return false;
  const uint32_t val_u = static_cast<uint32_t>(ring_u.size());
  // fl = (u, t, l) holds u→t; fr = (u, r, t) holds t→u.
  uint32_t fl = kNone, fr = kNone, l = kNone, r = kNone;
  for (const RingFace& rf : ring_u) {
    const auto& c = f_[rf.face].v;
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
  if (epoch_ == 0) { for (Vert& v : v_) v.stamp = 0; epoch_ = 1; }
  for (const RingFace& rf : ring_u) v_[f_[rf.face].v[next3(rf.corner)]].stamp = epoch_;
  uint32_t common = 0;
  for (const RingFace& rf : ring_b_) {
    const uint32_t w = f_[rf.face].v[next3(rf.corner)];
    if (w != u && v_[w].stamp == epoch_) ++common;
  }
  if (common != 2) return false;
  // Geometry of the faces that move (those around u except fl, fr).
  const glm::vec3 pt = v_[t].p, pu = v_[u].p;
  for (const RingFace& rf : ring_u) {
    if (rf.face == fl || rf.face == fr) continue;
    const auto& c = f_[rf.face].v;
    const glm::vec3 a = v_[c[next3(rf.corner)]].p;
    const glm::vec3 b = v_[c[prev3(rf.corner)]].p;
    const glm::vec3 n_old = glm::cross(a - pu, b - pu);
    const glm::vec3 n_new = glm::cross(a - pt, b - pt);
    const float len_new = glm::length(n_new), len_old = glm::length(n_old);
    if (!(len_new > 0.0f)) return false;
    const glm::vec3 un = n_new / len_new;
    if (len_old > 0.0f && glm::dot(un, n_old / len_old) < cos_change_) return false;
    const glm::vec3& n0 = f_[rf.face].normal0;
    if ((n0.x != 0.0f || n0.y != 0.0f || n0.z != 0.0f) && glm::dot(un, n0) < cos_dev_) return false;
    const float q_new = faceQuality(pt, a, b);
    if (q_new < params_.min_face_quality && q_new < faceQuality(pu, a, b)) return false;
  }
  return true;
}

void Builder::update(uint32_t u, bool validate) {
  if (!collapsible(u) || !ring(u, ring_a_)) {
    v_[u].target = kNone;
    heap_.erase(u);
    return;
  }
  updateWithRing(u, validate, ring_a_);
}

void Builder::updateWithRing(uint32_t u, bool validate, const std::vector<RingFace>& ring_u) {
  Vert& vu = v_[u];
  vu.target = kNone;
  cand_.clear();
  if (collapsible(u)) {
    for (const RingFace& rf : ring_u) {
      const uint32_t t = f_[rf.face].v[next3(rf.corner)];
      if (!collapsible(t)) continue;
      cand_.push_back({static_cast<float>(std::max(0.0, evalSum(vu.q, v_[t].q, v_[t].p))), t});
    }
    std::sort(cand_.begin(), cand_.end());
  }
  for (size_t k = 0; k < cand_.size(); ++k) {
    const auto [cost, t] = cand_[k];
    if (validate && !valid(u, t, ring_u)) continue;
    vu.target = t;
    vu.cost = cost;
    // The others' cheapest: the next one, or the first if an invalid one came before.
    vu.other = k > 0 ? cand_[0].first
                     : cand_.size() > 1 ? cand_[1].first : std::numeric_limits<float>::infinity();
    heap_.set(u, cost);
    return;
  }
  heap_.erase(u);
}

void Builder::initialTargets() {
  // The cheapest (cost, target) pair per vertex, as update() chooses it, and the others' cheapest.
  for (Vert& v : v_) v.other = std::numeric_limits<float>::infinity();
  for (uint32_t f = 0; f < nf_; ++f) {
    const auto& c = f_[f].v;
    for (uint32_t i = 0; i < 3; ++i) {
      const uint32_t u = c[i], t = c[next3(i)];
      if (!collapsible(u) || !collapsible(t)) continue;
      Vert& vu = v_[u];
      const float cost = static_cast<float>(std::max(0.0, evalSum(vu.q, v_[t].q, v_[t].p)));
      if (vu.target == kNone || cost < vu.cost || (cost == vu.cost && t < vu.target)) {
        if (vu.target != kNone) vu.other = std::min(vu.other, vu.cost);
        vu.target = t;
        vu.cost = cost;
      } else {
        vu.other = std::min(vu.other, cost);
      }
    }
  }
  heap_.reset(n_);
  for (uint32_t v = 0; v < n_; ++v)
    if (v_[v].target != kNone) heap_.append(v, v_[v].cost);
  heap_.heapify();
}

void Builder::collapse(uint32_t u, uint32_t t) {
  // ring_a_ holds u's ring (the main loop's, checked by valid()).
  uint32_t fl = kNone, fr = kNone, cl = 0, cr = 0;
  for (const RingFace& rf : ring_a_) {
    const auto& c = f_[rf.face].v;
    if (c[next3(rf.corner)] == t) { fl = rf.face; cl = rf.corner; }
    if (c[prev3(rf.corner)] == t) { fr = rf.face; cr = rf.corner; }
  }
  // fl = (u, t, l): edges (u,t)→fr, (t,l)→fn_tl, (l,u)→fn_ul.
  // fr = (u, r, t): edges (u,r)→fn_ur, (r,t)→fn_rt, (t,u)→fl.
  const uint32_t fn_tl = f_[fl].n[next3(cl)], fn_ul = f_[fl].n[prev3(cl)];
  const uint32_t fn_ur = f_[fr].n[cr], fn_rt = f_[fr].n[next3(cr)];
  const uint32_t l = f_[fl].v[prev3(cl)], r = f_[fr].v[next3(cr)];

  VertexSplit s;
  s.vt = v_[t].node;
  s.vu = v_[u].node;
  s.fl = fl;
  s.fr = fr;
  s.fn = {fn_tl, fn_ul, fn_ur, fn_rt};
  splits_.push_back(s);

  for (const RingFace& rf : ring_a_)
    if (rf.face != fl && rf.face != fr) f_[rf.face].v[rf.corner] = t;
  auto relink = [&](uint32_t f, uint32_t from, uint32_t to) {
    for (uint32_t k = 0; k < 3; ++k)
      if (f_[f].n[k] == from) { f_[f].n[k] = to; return; }
  };
  relink(fn_tl, fl, fn_ul);
  relink(fn_ul, fl, fn_tl);
  relink(fn_ur, fr, fn_rt);
  relink(fn_rt, fr, fn_ur);
  alive_f_[fl] = alive_f_[fr] = 0;
  alive_faces_ -= 2;
  v_[t].vface = fn_tl;
  v_[l].vface = fn_tl;
  v_[r].vface = fn_rt;
  v_[u].alive = 0;
  v_[u].target = kNone;  // popped from the heap by the main loop
  v_[t].q.add(v_[u].q);
  v_[t].node = n_ + static_cast<uint32_t>(splits_.size()) - 1;

  // t's new ring, without walking it: its old faces (ring_b_, left by valid()) and u's, fl
  // and fr out. Not in rotation order, which the updates below do not need.
  ring_c_.clear();
  for (const RingFace& rf : ring_b_)
    if (rf.face != fl && rf.face != fr) ring_c_.push_back(rf);
  for (const RingFace& rf : ring_a_)
    if (rf.face != fl && rf.face != fr) ring_c_.push_back(rf);
  updateWithRing(t, false, ring_c_);
  for (const RingFace& rf : ring_c_) updateNeighbour(f_[rf.face].v[next3(rf.corner)], u, t);
}

void Builder::updateNeighbour(uint32_t w, uint32_t u, uint32_t t) {
  // Costs only grow as quadrics are summed, and w gains candidates only here, so `other`
  // stays a lower bound of every candidate but the target: when w→t costs no more than it,
  // t is w's best without looking at w's ring.
  Vert& vw = v_[w];
  const uint32_t old = vw.target;
  if (old == kNone || !collapsible(w) || !collapsible(t)) {
    update(w, false);
    return;
  }
  const float cost = static_cast<float>(std::max(0.0, evalSum(vw.q, v_[t].q, v_[t].p)));
  if (old == u || old == t) {  // the target merged into t: t is best if no other is cheaper
    if (!(cost <= vw.other)) {
      update(w, false);
      return;
    }
  } else if (cost < vw.cost) {  // t is cheaper than w's best, which becomes an other
    vw.other = std::min(vw.other, vw.cost);
  } else {
    vw.other = std::min(vw.other, cost);
    return;  // the heap's entry stays w's best
  }
  vw.target = t;
  vw.cost = cost;
  heap_.set(w, cost);
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
  splits_.reserve(n_);
  uint32_t collapsible_count = 0;
  for (uint32_t v = 0; v < n_; ++v) collapsible_count += collapsible(v);
  initialTargets();
  const uint32_t progress_step = std::max<uint32_t>(1, collapsible_count / 100);
  uint32_t next_report = progress_step;
  while (!heap_.empty() && alive_faces_ > params_.min_base_faces) {
    const uint32_t u = heap_.top();
    heap_.erase(u);
    if (!heap_.empty()) {  // most likely the next to go: its record and a face of its ring
      const Vert& next = v_[heap_.top()];
      if (next.vface != kNone) __builtin_prefetch(&f_[next.vface]);
    }
    if (!ring(u, ring_a_)) {
      v_[u].target = kNone;
      continue;
    }
    if (!valid(u, v_[u].target, ring_a_)) {
      updateWithRing(u, true, ring_a_);
      continue;
    }
    collapse(u, v_[u].target);
    if (progress_ && splits_.size() >= next_report) {
      next_report += progress_step;
      progress_(std::min(1.0f, static_cast<float>(splits_.size()) /
                                   static_cast<float>(std::max(1u, collapsible_count))));
    }
  }

  ProgressiveMesh pm;
  pm.positions = mesh_.positions;
  pm.faces = mesh_.faces;
  pm.vertex_flags.resize(n_);
  for (uint32_t v = 0; v < n_; ++v) pm.vertex_flags[v] = v_[v].flags;
  pm.splits = std::move(splits_);
  for (uint32_t f = 0; f < nf_; ++f) {
    if (!alive_f_[f]) continue;
    pm.base_faces.push_back(f);
    std::array<uint32_t, 3> c;
    for (int i = 0; i < 3; ++i) c[i] = v_[f_[f].v[i]].node;
    pm.base_corners.push_back(c);
    pm.base_neighbors.push_back(f_[f].n);
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
