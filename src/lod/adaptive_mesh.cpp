// Selective refinement with image-space area control and geomorphs.
//
//   Hoppe 1997, "View-dependent refinement of progressive meshes": §4 (vsplit legal iff vs
//     active and fn0..fn3 active; ecol legal iff vt, vu active and the faces adjacent to fl,
//     fr are fn0..fn3; force_vsplit with an explicit stack; view frustum test with bounding
//     spheres, back-face test with cones of normals), §5 (adapt_refinement loop).
//   Hoppe 1998, "Efficient implementation of progressive meshes", §5 (flat arrays, free lists).
//   Jeong, Ni, Lee, Markosian 2005, "Detail control in line drawings of 3D meshes":
//     §3.1 (criterion: mean image-space area A_img = k·A/d² of the active faces around a
//     vertex; split above t_s·T, collapse below t_c·T; T varying per object, by a detail map,
//     with depth), §3.2 (geomorphs: collapses lock both vertices and morph them to the parent
//     position before executing; splits execute at once and the children morph out; speed
//     grows with the discrepancy between current and target area).
//
// Face ids are the input face ids; a face stores its 3 corner nodes and its 3 neighbour faces
// (across edge (c[i], c[i+1])). Rotation counter-clockwise around corner i goes through the
// neighbour across edge (c[i+2], c[i]).
#include "lod/adaptive_mesh.h"
#include "lod/fold_rules.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <numeric>
#include <string>
#include <type_traits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "core/mesh_order.h"

namespace lodline {
namespace {

constexpr uint32_t kNone = kPmNone;
constexpr size_t kMaxFan = 1024;
constexpr size_t kMaxStack = 1u << 20;
/// Frames before a vertex whose (forced) split was refused is tried again.
constexpr uint32_t kRetryFrames = 8;
/// Evaluation passes per frame at most (a pass repeats only while it changes a lot).
constexpr int kMaxPasses = 4;
/// A collapse also needs the mean around the parent afterwards below this × t_s·T, so that
/// the parent does not split again at the same view (the criterion itself reads the mean
/// before the collapse, Jeong §3.1; 2·t_c < t_s makes this hold for regular rings).
constexpr float kNoSplitBack = 0.9f;
/// While the camera recedes, a collapse's geomorph takes at most this share of the time its
/// faces take to shrink below the band (t_c·T/2), so coarsening keeps pace with a fast zoom.
constexpr float kLagShare = 0.25f;
/// Levels of blocking collapses unblockCollapse() follows, and the nodes it may visit per
/// blocked collapse (bounds its cost: each level may branch four ways).
constexpr int kUnblockDepth = 6;
constexpr uint32_t kUnblockVisits = 64;
/// Under a time budget a frame still evaluates at least 1/kMinEvaluatedShare of the active
/// vertices (and 32), so the round robin visits every vertex within that many frames.
constexpr size_t kMinEvaluatedShare = 8;
/// How many work-list entries ahead evaluatePass() prefetches per-node data.
constexpr size_t kPrefetchAhead = 8;
/// A collapse found illegal is not re-checked for this many frames unless vt's or vu's slot
/// changes (is marked dirty) first.
constexpr uint32_t kIllegalFrames = 16;
/// A vertex whose forced split was undone because the chain left its own split not due (see
/// forceSplit) is tried again before this many frames only if its ring mean, scaled as that
/// chain scaled it, would now be above t_s·T.
constexpr uint32_t kUndoneRecheckFrames = 32;
/// Consecutive refusals of a vertex's forced split (fold-overs) double its wait, at most
/// this many times (8 frames, then 16, 32, 64).
constexpr uint32_t kMaxRefusalShift = 3;
/// Rounds of corner splits one repair of a listed face may make in a frame (repairFolds()).
constexpr int kMaxRepairRounds = 32;
/// orderForLocality() runs once more than 1/kOrderFreshShare of the active vertices have taken
/// new slots since it last ran, on meshes of at least kOrderMinVertices active vertices
/// (smaller ones fit in the caches whatever their order).
constexpr uint32_t kOrderFreshShare = 4;
constexpr uint32_t kOrderMinVertices = 4096;
/// A collapse may turn a face over (against its full-detail normal) where the face then
/// covers less than this many pixels, which no drawing can show. At the coarsest levels after
/// a fast zoom-out, refusing such sub-pixel folds held whole regions finer than the view asks
/// for (docs/detail-control.md §7); the faces so folded are listed, and refined back where
/// they grow past this size (repairFolds()).
constexpr float kFoldAreaPx = 1.0f;

/// An index from a free list, the last freed first, or else the next unused one (`count`).
uint32_t takeIndex(std::vector<uint32_t>& free, uint32_t& count) {
  if (free.empty()) return count++;
  const uint32_t i = free.back();
  free.pop_back();
  return i;
}

/// v[0, new_to_old.size()) = v[new_to_old[i]], through `scratch` (bytes).
template <class T, class A>
void gatherInPlace(std::vector<T, A>& v, std::span<const uint32_t> new_to_old, std::vector<unsigned char>& scratch) {
  static_assert(std::is_trivially_copyable_v<T>);
  const size_t n = new_to_old.size();
  if (scratch.size() < n * sizeof(T)) scratch.resize(n * sizeof(T));
  for (size_t i = 0; i < n; ++i) std::memcpy(scratch.data() + i * sizeof(T), &v[new_to_old[i]], sizeof(T));
  if (n) std::memcpy(v.data(), scratch.data(), n * sizeof(T));
}

inline uint32_t next3(uint32_t i) { return i == 2 ? 0 : i + 1; }
inline uint32_t prev3(uint32_t i) { return i == 0 ? 2 : i - 1; }

inline float clampf(float x, float lo, float hi) { return std::min(std::max(x, lo), hi); }

}  // namespace

AdaptiveMesh::AdaptiveMesh(const ProgressiveMesh& pm) : pm_(pm) {
  n_nodes_ = pm.nodeCount();
  n_faces_ = pm.faceCount();
  const uint32_t n = pm.vertexCount();
  node_pos_.resize(n_nodes_);
  for (uint32_t v = 0; v < n_nodes_; ++v) node_pos_[v] = pm.positions[pm.origin[v]];
  if (!pm.positions.empty()) {
    const Bounds box = computeBounds(pm.positions);
    order_min_ = box.min;
    order_extent_ = glm::max(box.max - box.min, glm::vec3(1e-30f));
  }

  // Reference normals, leaf bounding spheres (1-ring reach) and leaf normal cones.
  ref_normal_.resize(n_faces_);
  std::vector<float> node_radius(n_nodes_, 0.0f);
  std::vector<glm::vec3> cone_axis(n_nodes_, glm::vec3(0.0f));
  for (uint32_t f = 0; f < n_faces_; ++f) {
    const auto& c = pm.faces[f];
    const glm::vec3 &a = pm.positions[c[0]], &b = pm.positions[c[1]], &d = pm.positions[c[2]];
    const glm::vec3 nn = glm::cross(b - a, d - a);
    const float len = glm::length(nn);
    ref_normal_[f] = len > 0.0f ? nn / len : glm::vec3(0.0f);
    for (int i = 0; i < 3; ++i) {
      const glm::vec3& p = pm.positions[c[i]];
      node_radius[c[i]] = std::max({node_radius[c[i]], glm::length(pm.positions[c[(i + 1) % 3]] - p),
                                     glm::length(pm.positions[c[(i + 2) % 3]] - p)});
      cone_axis[c[i]] += ref_normal_[f];
    }
  }
  std::vector<float> angle(n_nodes_, 0.0f);
  for (uint32_t v = 0; v < n; ++v) {
    const float len = glm::length(cone_axis[v]);
    if (len > 1e-6f) cone_axis[v] /= len;
    else angle[v] = static_cast<float>(M_PI);
  }
  for (uint32_t f = 0; f < n_faces_; ++f) {
    if (ref_normal_[f] == glm::vec3(0.0f)) continue;
    for (uint32_t v : pm.faces[f]) {
      const float a = std::acos(clampf(glm::dot(cone_axis[v], ref_normal_[f]), -1.0f, 1.0f));
      angle[v] = std::max(angle[v], a);
    }
  }
  // Internal nodes: children precede parents, so one forward pass merges bottom-up.
  for (uint32_t s = n; s < n_nodes_; ++s) {
    const VertexSplit& vs = pm.split(s);
    const glm::vec3 p = node_pos_[s];
    node_radius[s] = std::max(glm::length(node_pos_[vs.vt] - p) + node_radius[vs.vt],
                               glm::length(node_pos_[vs.vu] - p) + node_radius[vs.vu]);
    const glm::vec3 sum = cone_axis[vs.vt] + cone_axis[vs.vu];
    const float len = glm::length(sum);
    if (len < 1e-6f || angle[vs.vt] >= M_PI || angle[vs.vu] >= M_PI) {
      angle[s] = static_cast<float>(M_PI);
      continue;
    }
    const glm::vec3 axis = sum / len;
    cone_axis[s] = axis;
    const float a1 = std::acos(clampf(glm::dot(axis, cone_axis[vs.vt]), -1.0f, 1.0f)) + angle[vs.vt];
    const float a2 = std::acos(clampf(glm::dot(axis, cone_axis[vs.vu]), -1.0f, 1.0f)) + angle[vs.vu];
    angle[s] = std::min(static_cast<float>(M_PI), std::max(a1, a2));
  }
  bounds_.resize(n_nodes_);
  for (uint32_t v = 0; v < n_nodes_; ++v) {
    NodeBounds& b = bounds_[v];
    b.pos = node_pos_[v];
    b.radius = node_radius[v];
    b.axis = cone_axis[v];
    b.cone_sin = std::sin(angle[v]);
    b.cone_cos = std::cos(angle[v]);
    b.parent = pm.parent[v];
    b.sibling = (b.parent != kNone && pm.split(b.parent).vt == v) ? pm.split(b.parent).vu : kNone;
  }

  node_slot_.assign(n_nodes_, kNone);
  node_state_.assign(n_nodes_, 0);
  pending_pos_.assign(n_nodes_, kNone);
  retry_frame_.assign(n_nodes_, 0);
  chain_.reserve(1024);
  fv_.assign(n_faces_, {kNone, kNone, kNone});
  fnb_.assign(n_faces_, {kNone, kNone, kNone});
  face_pos_.assign(n_faces_, kNone);
  active_faces_.reserve(n_faces_);
  active_fs_.reserve(n_faces_);
  active_area_.reserve(n_faces_);
  const uint32_t cap = std::max<uint32_t>(n, 1);
  slot_node_.assign(cap, kNone);
  slot_face_.assign(cap, kNone);
  disp_.assign(cap, glm::vec3(0.0f));
  morph_from_.assign(cap, glm::vec3(0.0f));
  morph_to_.assign(cap, glm::vec3(0.0f));
  morph_t_.assign(cap, 0.0f);
  morph_rate_.assign(cap, 0.0f);
  morph_pos_.assign(cap, kNone);
  slot_locked_.assign(cap, 0);
  illegal_frame_.assign(cap, 0);
  undone_ratio_.assign(cap, 0.0f);
  refusals_.assign(cap, 0);
  pre_node_.assign(cap, kNone);
  pre_visible_.assign(cap, 0);
  pre_target_.assign(cap, 0.0f);
  eval_idle_.assign(cap, 0);
  dirty_stamp_.assign(cap, 0);
  ring_sum_.assign(cap, 0.0);
  slot_bounds_.assign(cap, NodeBounds{});
  slot_pos_.assign(cap, glm::vec3(0.0f));

  ring_cnt_.assign(cap, 0);
  moved_stamp_.assign(cap, 0);
  free_slots_.reserve(cap);
  eval_slot_.assign(cap, kNone);
  slot_eval_.assign(cap, kNone);
  eval_free_.reserve(cap);
  morphing_.reserve(cap);
  pending_.reserve(cap / 2 + 1);
  work_.reserve(2 * static_cast<size_t>(cap) + 16);
  stack_.reserve(1024);
  fan_u_.reserve(kMaxFan + 1);
  fan_t_.reserve(kMaxFan + 1);
  done_pending_.reserve(cap / 2 + 1);
  resetToBase();
}

void AdaptiveMesh::resetToBase() {
  std::fill(node_slot_.begin(), node_slot_.end(), kNone);
  std::fill(node_state_.begin(), node_state_.end(), 0);
  std::fill(pending_pos_.begin(), pending_pos_.end(), kNone);
  for (uint32_t f : active_faces_) face_pos_[f] = kNone;
  active_faces_.clear();
  active_fs_.clear();
  active_area_.clear();
  std::fill(slot_node_.begin(), slot_node_.end(), kNone);
  std::fill(morph_pos_.begin(), morph_pos_.end(), kNone);
  std::fill(eval_slot_.begin(), eval_slot_.begin() + eval_count_, kNone);
  slot_count_ = 0;
  active_vertices_ = 0;
  free_slots_.clear();
  eval_count_ = 0;
  eval_free_.clear();
  morphing_.clear();
  pending_.clear();
  folded_.clear();
  for (uint32_t r : pm_.roots) allocSlot(r);
  for (size_t k = 0; k < pm_.base_faces.size(); ++k) {
    const uint32_t f = pm_.base_faces[k];
    fv_[f] = pm_.base_corners[k];
    fnb_[f] = pm_.base_neighbors[k];
    activateFace(f);
    for (int i = 0; i < 3; ++i) active_fs_[face_pos_[f]][i] = node_slot_[fv_[f][i]];
    for (uint32_t v : fv_[f]) slot_face_[node_slot_[v]] = f;
    active_area_[face_pos_[f]] = have_view_ ? faceImageArea(f) : 0.0f;
    accumulate(f, 1.0f);
  }
  changes_.everything = true;
}

uint32_t AdaptiveMesh::allocSlot(uint32_t node) {
  const uint32_t slot = takeIndex(free_slots_, slot_count_);
  slot_node_[slot] = node;
  node_slot_[node] = slot;
  slot_face_[slot] = kNone;
  disp_[slot] = node_pos_[node];
  slot_bounds_[slot] = bounds_[node];
  slot_pos_[slot] = node_pos_[node];
  morph_pos_[slot] = kNone;
  slot_locked_[slot] = 0;
  illegal_frame_[slot] = 0;
  undone_ratio_[slot] = 0.0f;
  refusals_[slot] = 0;
  ring_sum_[slot] = 0.0;
  ring_cnt_[slot] = 0;
  eval_idle_[slot] = 0;
  ++active_vertices_;
  ++fresh_slots_;
  // Its place in the order of evaluation: taken as slots were before orderForLocality().
  const uint32_t e = takeIndex(eval_free_, eval_count_);
  eval_slot_[e] = slot;
  slot_eval_[slot] = e;
  return slot;
}

void AdaptiveMesh::freeSlot(uint32_t slot) {
  stopMorph(slot);
  node_slot_[slot_node_[slot]] = kNone;
  slot_node_[slot] = kNone;
  slot_face_[slot] = kNone;
  free_slots_.push_back(slot);
  eval_slot_[slot_eval_[slot]] = kNone;
  eval_free_.push_back(slot_eval_[slot]);
  --active_vertices_;
}

void AdaptiveMesh::activateFace(uint32_t f) {
  face_pos_[f] = static_cast<uint32_t>(active_faces_.size());
  active_faces_.push_back(f);
  active_fs_.push_back({kNone, kNone, kNone});
  active_area_.push_back(0.0f);
}

void AdaptiveMesh::deactivateFace(uint32_t f) {
  const uint32_t pos = face_pos_[f];
  const uint32_t last = active_faces_.back();
  active_faces_[pos] = last;
  active_fs_[pos] = active_fs_.back();
  active_area_[pos] = active_area_.back();
  face_pos_[last] = pos;
  active_faces_.pop_back();
  active_fs_.pop_back();
  active_area_.pop_back();
  face_pos_[f] = kNone;
}

void AdaptiveMesh::markDirty(uint32_t slot) {
  if (slot == kNone) return;
  // Its ring changed: the undone chain's scale no longer applies, a refused one may pass now.
  undone_ratio_[slot] = 0.0f;
  refusals_[slot] = 0;
  if (dirty_stamp_[slot] == frame_) return;
  dirty_stamp_[slot] = frame_;
  changes_.dirty.push_back(slot);
}

void AdaptiveMesh::markMoved(uint32_t slot) {
  if (moved_stamp_[slot] != frame_) {
    moved_stamp_[slot] = frame_;
    changes_.moved.push_back(slot);
  }
  markDirty(slot);
}

// ---------------------------------------------------------------------------------------
// View and criterion

Status AdaptiveMesh::setView(const Camera& camera, int width, int height,
                             const DetailParams& params) {
  if (width <= 0 || height <= 0)
    return Error::usage("image size " + std::to_string(width) + "x" + std::to_string(height) +
                        " must be positive");
  if (!(params.target_area > 0.0f) || !std::isfinite(params.target_area) ||
      !(params.object_factor > 0.0f) || !std::isfinite(params.object_factor))
    return Error::usage("target area and object factor must be positive");
  if (!(params.t_c > 0.0f) || !(2.0f * params.t_c < params.t_s) || !std::isfinite(params.t_s))
    return Error::usage("detail thresholds need 0 < 2·t_c < t_s (got t_c=" +
                        std::to_string(params.t_c) + ", t_s=" + std::to_string(params.t_s) + ")");
  if (!(params.morph_time >= 0.0f) || !(params.coarsen_time_factor >= 0.0f) ||
      !(params.max_morph_speedup >= 1.0f))
    return Error::usage("morph times must be ≥ 0 and max_morph_speedup ≥ 1");
  if (const DetailMap* m = params.detail_map.get()) {
    if (m->width <= 0 || m->height <= 0 ||
        m->values.size() != static_cast<size_t>(m->width) * static_cast<size_t>(m->height))
      return Error::usage("detail map: " + std::to_string(m->width) + "x" +
                          std::to_string(m->height) + " needs width·height values, got " +
                          std::to_string(m->values.size()));
    for (float v : m->values)
      if (!std::isfinite(v) || v < 0.0f)
        return Error::usage("detail map: values must be finite and ≥ 0");
  }
  params_ = params;
  camera_ = camera;
  width_ = width;
  height_ = height;
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  view_proj_ = camera.projection(aspect) * camera.view();
  const glm::mat4& m = view_proj_;
  auto row = [&](int i) { return glm::vec4(m[0][i], m[1][i], m[2][i], m[3][i]); };
  planes_ = {row(3) + row(0), row(3) - row(0), row(3) + row(1), row(3) - row(1), row(3) + row(2)};
  for (auto& p : planes_) {
    const float len = glm::length(glm::vec3(p));
    if (len > 0.0f) p /= len;
  }
  eye_ = camera.eye;
  forward_ = camera.forward();
  k_ = pixelAreaFactor(camera, height);
  t0_ = params.target_area * params.object_factor;
  focus_dist_ = std::max(glm::length(camera.target - camera.eye), 1e-6f);
  focal_px_ = 0.5f * static_cast<float>(height) / std::tan(0.5f * glm::radians(camera.fov_deg));
  focus_ = params.focus_px;
  if (focus_.x < 0.0f || focus_.y < 0.0f)
    focus_ = glm::vec2(0.5f * static_cast<float>(width), 0.5f * static_cast<float>(height));
  modifiers_ = params.detail_map != nullptr || params.depth_falloff != 0.0f ||
               params.foveation != 0.0f;
  have_view_ = true;
  return Status::success();
}

float AdaptiveMesh::targetAt(const glm::vec3& p) const {
  float t = t0_;
  if (!modifiers_) return t;
  if (params_.depth_falloff != 0.0f) {
    const float d = camera_.orthographic ? glm::dot(p - eye_, forward_) : glm::length(p - eye_);
    t *= std::pow(std::max(d / focus_dist_, 0.25f), params_.depth_falloff);
  }
  if (params_.detail_map || params_.foveation != 0.0f) {
    const glm::vec4 clip = view_proj_ * glm::vec4(p, 1.0f);
    if (clip.w <= 1e-9f) return t;
    const float px = (clip.x / clip.w * 0.5f + 0.5f) * static_cast<float>(width_);
    const float py = (0.5f - clip.y / clip.w * 0.5f) * static_cast<float>(height_);
    if (const DetailMap* map = params_.detail_map.get()) {
      const float u = clampf(px / static_cast<float>(width_), 0.0f, 1.0f) * map->width - 0.5f;
      const float v = clampf(py / static_cast<float>(height_), 0.0f, 1.0f) * map->height - 0.5f;
      const int x0 = std::clamp(static_cast<int>(std::floor(u)), 0, map->width - 1);
      const int y0 = std::clamp(static_cast<int>(std::floor(v)), 0, map->height - 1);
      const int x1 = std::min(x0 + 1, map->width - 1), y1 = std::min(y0 + 1, map->height - 1);
      const float fx = clampf(u - static_cast<float>(x0), 0.0f, 1.0f);
      const float fy = clampf(v - static_cast<float>(y0), 0.0f, 1.0f);
      auto at = [&](int x, int y) { return map->values[static_cast<size_t>(y) * map->width + x]; };
      const float val = (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x1, y0)) +
                        fy * ((1 - fx) * at(x0, y1) + fx * at(x1, y1));
      t *= std::max(val, params_.min_map_value);
    }
    if (params_.foveation != 0.0f) {
      const float q = std::min(std::atan(glm::length(glm::vec2(px, py) - focus_) / focal_px_),
                               glm::radians(80.0f));
      const float f = static_cast<float>(M_PI_2) / (static_cast<float>(M_PI_2) - q);
      t *= std::pow(f * f, params_.foveation);
    }
  }
  return t;
}

float AdaptiveMesh::triangleImageArea(const glm::vec3& a, const glm::vec3& b, const glm::vec3& d) const {
  const float area = 0.5f * glm::length(glm::cross(b - a, d - a));
  if (camera_.orthographic) return k_ * area;
  const glm::vec3 m = (a + b + d) * (1.0f / 3.0f) - eye_;
  const float near2 = std::max(camera_.near_plane * camera_.near_plane, 1e-20f);
  return k_ * area / std::max(glm::dot(m, m), near2);
}

float AdaptiveMesh::faceImageArea(uint32_t f) const {
  const auto& c = active_fs_[face_pos_[f]];
  return triangleImageArea(slot_pos_[c[0]], slot_pos_[c[1]], slot_pos_[c[2]]);
}

float AdaptiveMesh::faceImageAreaWith(uint32_t f, uint32_t moved, const glm::vec3& p) const {
  const auto& c = fv_[f];
  return triangleImageArea(c[0] == moved ? p : node_pos_[c[0]], c[1] == moved ? p : node_pos_[c[1]],
                           c[2] == moved ? p : node_pos_[c[2]]);
}

bool AdaptiveMesh::visible(const NodeBounds& nb) const {
  if (!params_.cull) return true;
  const glm::vec3 p = nb.pos;
  const float r = nb.radius;
  for (const glm::vec4& pl : planes_)
    if (glm::dot(glm::vec3(pl), p) + pl.w < -r) return false;
  if (nb.cone_cos <= 0.0f) return true;  // cone half-angle ≥ 90°
  glm::vec3 dir = forward_;
  float sin_b = 0.0f, cos_b = 1.0f;
  if (!camera_.orthographic) {
    dir = p - eye_;
    const float d = glm::length(dir);
    if (d <= r) return true;
    dir /= d;
    sin_b = r / d;
    cos_b = std::sqrt(std::max(0.0f, 1.0f - sin_b * sin_b));
  }
  const float cos_ab = nb.cone_cos * cos_b - nb.cone_sin * sin_b;
  if (cos_ab <= 0.0f) return true;
  const float sin_ab = nb.cone_sin * cos_b + nb.cone_cos * sin_b;
  return !(glm::dot(nb.axis, dir) > sin_ab);  // entirely back-facing → invisible
}

float AdaptiveMesh::ringMean(uint32_t v) const { return ringMeanAt(node_slot_[v]); }

uint32_t AdaptiveMesh::missingNeighbours(uint32_t v) const {
  uint32_t missing = 0;
  for (uint32_t f : pm_.split(v).fn) missing += face_pos_[f] == kNone;
  return missing;
}

float AdaptiveMesh::ringMeanAt(uint32_t slot) const {
  return ring_cnt_[slot] ? static_cast<float>(ring_sum_[slot] / ring_cnt_[slot]) : 0.0f;
}

void AdaptiveMesh::accumulate(uint32_t f, float sign) {
  const double a = static_cast<double>(sign) * active_area_[face_pos_[f]];
  const int32_t n = sign > 0.0f ? 1 : -1;
  for (uint32_t slot : active_fs_[face_pos_[f]]) {
    ring_sum_[slot] += a;
    ring_cnt_[slot] += n;
    touchSlot(slot);
  }
}

void AdaptiveMesh::touchSlot(uint32_t slot) {
  eval_idle_[slot] = 0;
  // A pair's collapse is evaluated from its vt child, reading vu's slot too.
  const NodeBounds& nb = slot_bounds_[slot];
  if (nb.sibling != kNone || nb.parent == kNone) return;  // a vt, or a root: nobody reads it
  if (const uint32_t s = node_slot_[pm_.split(nb.parent).vt]; s != kNone) eval_idle_[s] = 0;
}

bool AdaptiveMesh::collectFan(uint32_t v, uint32_t from, uint32_t to,
                              std::vector<uint32_t>& out) const {
  out.clear();
  uint32_t f = from;
  for (;;) {
    const uint32_t i = cornerOf(f, v);
    if (i == 3) return false;
    out.push_back(f);
    if (f == to) return true;
    f = fnb_[f][prev3(i)];
    if (f == kNone || f == from || out.size() >= kMaxFan) return false;
  }
}

// The mean image area of the faces around vt and vu before the collapse, from the two rings'
// accumulators alone (no face is read), so fl and fr, in both rings, count twice. pairMean()
// counts each face once, reading fl and fr (active while both children are: only the
// collapse of p removes them).
float AdaptiveMesh::ringsMean(uint32_t st, uint32_t su) const {
  const int32_t count = ring_cnt_[st] + ring_cnt_[su];
  return count > 0 ? static_cast<float>((ring_sum_[st] + ring_sum_[su]) / count) : 0.0f;
}

float AdaptiveMesh::pairMean(uint32_t st, uint32_t su, uint32_t p) const {
  const VertexSplit& vs = pm_.split(p);
  const int32_t count = ring_cnt_[st] + ring_cnt_[su] - 2;
  if (count <= 0 || face_pos_[vs.fl] == kNone || face_pos_[vs.fr] == kNone) return 0.0f;
  const double shared = static_cast<double>(active_area_[face_pos_[vs.fl]]) +
                        static_cast<double>(active_area_[face_pos_[vs.fr]]);
  return static_cast<float>((ring_sum_[st] + ring_sum_[su] - shared) / count);
}

// ln(area at the last adapt()'s view / area now) per second at p: > 0 while p's image shrinks.
float AdaptiveMesh::areaShrinkRate(const glm::vec3& p) const {
  if (!have_last_view_ || !(frame_dt_ > 0.0f)) return 0.0f;
  float ratio = last_k_ / k_;
  if (!camera_.orthographic) {
    const glm::vec3 now = p - eye_, before = p - last_eye_;
    ratio *= std::max(glm::dot(now, now), 1e-30f) / std::max(glm::dot(before, before), 1e-30f);
  }
  return std::log(ratio) / frame_dt_;
}

// Geomorph speed of a collapse whose faces' mean is `now`: it grows with the square of the
// discrepancy (a collapse far below its threshold finishes within a frame), and while the
// camera recedes the morph takes at most kLagShare of the time the faces take to leave the
// band, so the coarsening lag of a fast zoom-out stays bounded.
float AdaptiveMesh::collapseSpeedup(float now, float target, const glm::vec3& pos) const {
  const float t_c = params_.t_c, top = params_.max_morph_speedup;
  const float ratio = t_c * target / std::max(now, 1e-12f);
  float speedup = clampf(ratio * ratio, 1.0f, top);
  if (const float shrink = areaShrinkRate(pos); shrink > 0.0f) {
    const float left = std::log(std::max(now, 1e-12f) / (0.5f * t_c * target)) / shrink;  // s
    const float nominal = params_.morph_time * params_.coarsen_time_factor;
    speedup = left > 0.0f ? clampf(std::max(speedup, nominal / (kLagShare * left)), 1.0f, top) : top;
  }
  return speedup;
}

float AdaptiveMesh::predictedMean(uint32_t p) const {
  const VertexSplit& vs = pm_.split(p);
  if (!collectFan(vs.vu, vs.fn[1], vs.fn[2], fan_u_) ||
      !collectFan(vs.vt, vs.fn[3], vs.fn[0], fan_t_))
    return 0.0f;
  const glm::vec3 pp = node_pos_[p];
  float sum = 0.0f;
  for (uint32_t f : fan_u_) sum += faceImageAreaWith(f, vs.vu, pp);
  for (uint32_t f : fan_t_) sum += active_area_[face_pos_[f]];
  return sum / static_cast<float>(fan_u_.size() + fan_t_.size());
}

// ---------------------------------------------------------------------------------------
// Legality and the two operations

// ecolLegal() depends on the corners and neighbours of fl and fr only. Those change only by
// a split or collapse of vt or vu, or one that inserts or removes a face on an edge of fl or
// fr, and every such operation marks vt's or vu's slot dirty (its l/r or its own slots).
// So an illegal verdict holds until one of the two slots is dirtied; it expires after
// kIllegalFrames anyway, which bounds the delay if that reasoning ever misses a case.
bool AdaptiveMesh::collapseMayBeLegal(uint32_t st, uint32_t su, uint32_t p) {
  const uint32_t when = illegal_frame_[st];
  if (params_.geomorphs && when != 0 && frame_ - when < kIllegalFrames && dirty_stamp_[st] < when &&
      dirty_stamp_[su] < when)
    return false;
  if (ecolLegal(p)) return true;
  illegal_frame_[st] = frame_;
  return false;
}

bool AdaptiveMesh::ecolLegal(uint32_t p) const {
  if (pm_.isLeaf(p)) return false;
  const VertexSplit& vs = pm_.split(p);
  if (node_slot_[vs.vt] == kNone || node_slot_[vs.vu] == kNone) return false;
  if (face_pos_[vs.fl] == kNone || face_pos_[vs.fr] == kNone) return false;
  const auto &cl = fv_[vs.fl], &cr = fv_[vs.fr];
  const auto &nl = fnb_[vs.fl], &nr = fnb_[vs.fr];
  return cl[0] == vs.vu && cl[1] == vs.vt && cr[0] == vs.vt && cr[1] == vs.vu &&
         nl[0] == vs.fr && nl[1] == vs.fn[0] && nl[2] == vs.fn[1] && nr[0] == vs.fl &&
         nr[1] == vs.fn[2] && nr[2] == vs.fn[3];
}

namespace {
inline void relink(std::array<uint32_t, 3>& nb, uint32_t from, uint32_t to) {
  for (uint32_t& x : nb)
    if (x == from) { x = to; return; }
}
}  // namespace

bool AdaptiveMesh::flipped(uint32_t f) const {
  const auto& c = fv_[f];
  return !facesAlong(node_pos_[c[0]], node_pos_[c[1]], node_pos_[c[2]], ref_normal_[f]);
}

// The geometry test of a split or collapse for one of the faces it keeps, with corners q
// afterwards (final positions). A face already turned over does not refuse the operation (it
// is listed in folded_ and repaired there); a collapse may turn one over where it is then
// sub-pixel (kFoldAreaPx), and says so in *folds.
bool AdaptiveMesh::facingAllowed(uint32_t f, const glm::vec3 (&q)[3], bool* folds) const {
  if (facesAlong(q[0], q[1], q[2], ref_normal_[f])) return true;
  if (flipped(f)) return true;
  if (folds == nullptr || !have_view_ || !(triangleImageArea(q[0], q[1], q[2]) < kFoldAreaPx))
    return false;
  *folds = true;
  return true;
}

void AdaptiveMesh::listFlipped(std::span<const uint32_t> faces) {
  for (uint32_t f : faces)
    if (flipped(f) && std::find(folded_.begin(), folded_.end(), f) == folded_.end()) folded_.push_back(f);
}

// A split is refused only where it would turn a face over, through more than 90° from the
// face's normal before it. The full-detail normal, which the other tests compare with, is a
// poor reference for a coarse face: on a subdivided model a face that spans a leg or a trunk
// at a few hundred faces may point far from where its full-detail face does, and a split
// that turns it by a small angle can leave it more than 90° from there. Refusing those held
// the refined elephant's progressive mesh (built since 2026-12-05, in another collapse order)
// at 1,100 faces and a band fraction of 0.77 at its default view, legs and body drawn as a
// few large triangles, where the target asks for 17k (docs/detail-control.md §8). Such a face
// is listed with the folds; repairFolds() refines its corners until it faces as recorded.
// A face already against its full-detail normal (listed) is held to the same rule: a split
// may not turn it over either. One of no area now has no normal to turn from, and does not
// refuse, as before.
glm::vec3 AdaptiveMesh::faceNormalNow(uint32_t f) const {
  const auto& c = fv_[f];
  return glm::cross(node_pos_[c[1]] - node_pos_[c[0]], node_pos_[c[2]] - node_pos_[c[0]]);
}

bool AdaptiveMesh::splitFacingAllowed(uint32_t f, const glm::vec3 (&q)[3], bool& turned) const {
  if (facesAlong(q[0], q[1], q[2], ref_normal_[f])) return true;
  if (turnedOverFrom(q[0], q[1], q[2], faceNormalNow(f))) return false;
  turned = true;
  return true;
}

// A face a split creates had no normal before, so the test of the faces it keeps does not
// apply; it was held to its full-detail normal instead. At the coarse levels of a
// progressive mesh that refused, for good, splits whose new face ends a little over 90°
// from where its full-detail face points: on the bunny's default view about 120 vertices
// behind its ears (dot products of -0.1 to -0.4), and the back of its neck stayed one large
// triangle across the notch under the ear, drawn as a contour with a corner and a dangling
// piece (docs/detail-control.md §9). A new face is a fold only where it is turned over
// against the two faces it opens between, which is what this refuses; one merely against
// its full-detail normal is listed with the folds, and repairFolds() refines its corners
// once it covers a pixel.
bool AdaptiveMesh::splitNewFaceAllowed(uint32_t f, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                                       uint32_t side0, uint32_t side1, bool& turned) const {
  if (facesAlong(a, b, c, ref_normal_[f])) return true;
  if (turnedOverBetween(a, b, c, faceNormalNow(side0), faceNormalNow(side1))) return false;
  turned = true;
  return true;
}

bool AdaptiveMesh::doSplit(uint32_t s, bool check, bool morph) {
  if (pm_.isLeaf(s) || node_slot_[s] == kNone) return false;
  const VertexSplit& vs = pm_.split(s);
  const uint32_t fn_tl = vs.fn[0], fn_ul = vs.fn[1], fn_ur = vs.fn[2], fn_rt = vs.fn[3];
  for (uint32_t f : vs.fn)
    if (face_pos_[f] == kNone) return false;
  // l and r: the other ends of the edges (s, l) between fn_tl|fn_ul and (s, r) between
  // fn_ur|fn_rt; the whole ring must be fn_ul..fn_ur (becomes u's), fn_rt..fn_tl (t's).
  if (!collectFan(s, fn_ul, fn_ur, fan_u_)) return false;
  if (fnb_[fn_ur][prev3(cornerOf(fn_ur, s))] != fn_rt) return false;
  if (!collectFan(s, fn_rt, fn_tl, fan_t_)) return false;
  if (fnb_[fn_tl][prev3(cornerOf(fn_tl, s))] != fn_ul) return false;
  const uint32_t l = fv_[fn_ul][next3(cornerOf(fn_ul, s))];  // fn_ul = (s, l, ...)
  const uint32_t r = fv_[fn_rt][next3(cornerOf(fn_rt, s))];  // fn_rt = (s, r, ...)
  if (fv_[fn_tl][prev3(cornerOf(fn_tl, s))] != l || fv_[fn_ur][prev3(cornerOf(fn_ur, s))] != r)
    return false;
  const glm::vec3 pu = node_pos_[vs.vu], pt = node_pos_[vs.vt];
  bool turned = false;  // a kept or new face ends against its full-detail normal (not turned over)
  if (check) {
    for (uint32_t f : fan_u_) {
      const auto& c = fv_[f];
      const uint32_t i = cornerOf(f, s);
      glm::vec3 q[3] = {node_pos_[c[0]], node_pos_[c[1]], node_pos_[c[2]]};
      q[i] = pu;
      if (!splitFacingAllowed(f, q, turned)) return false;
    }
    if (!splitNewFaceAllowed(vs.fl, pu, pt, node_pos_[l], fn_tl, fn_ul, turned) ||
        !splitNewFaceAllowed(vs.fr, pt, pu, node_pos_[r], fn_ur, fn_rt, turned))
      return false;
  }
  // Pending collapses whose fl/fr are among fn0..3 would lose their neighbourhood: cancel.
  for (uint32_t f : vs.fn) {
    const uint32_t q = pm_.face_parent[f];
    if (q != kNone && (node_state_[q] & kPending)) cancelCollapse(q);
  }
  if (node_state_[s] & kLocked) cancelCollapse(pm_.parent[s]);

  for (uint32_t f : fan_u_) accumulate(f, -1.0f);  // these faces move to vu's ring
  const uint32_t st = node_slot_[s];
  const glm::vec3 parent_disp = disp_[st];
  node_slot_[s] = kNone;
  slot_node_[st] = vs.vt;
  node_slot_[vs.vt] = st;
  slot_bounds_[st] = bounds_[vs.vt];  // same position: vt keeps the parent's
  slot_pos_[st] = node_pos_[vs.vt];
  const uint32_t su = allocSlot(vs.vu);
  for (uint32_t f : fan_u_) {
    const uint32_t i = cornerOf(f, s);
    fv_[f][i] = vs.vu;
    active_fs_[face_pos_[f]][i] = su;
  }
  for (uint32_t f : fan_t_) fv_[f][cornerOf(f, s)] = vs.vt;  // slot unchanged
  relink(fnb_[fn_tl], fn_ul, vs.fl);
  relink(fnb_[fn_ul], fn_tl, vs.fl);
  relink(fnb_[fn_ur], fn_rt, vs.fr);
  relink(fnb_[fn_rt], fn_ur, vs.fr);
  fv_[vs.fl] = {vs.vu, vs.vt, l};
  fnb_[vs.fl] = {vs.fr, fn_tl, fn_ul};
  fv_[vs.fr] = {vs.vt, vs.vu, r};
  fnb_[vs.fr] = {vs.fl, fn_ur, fn_rt};
  activateFace(vs.fl);
  activateFace(vs.fr);
  active_fs_[face_pos_[vs.fl]] = {su, st, node_slot_[l]};
  active_fs_[face_pos_[vs.fr]] = {st, su, node_slot_[r]};
  slot_face_[st] = vs.fl;
  slot_face_[su] = vs.fl;
  if (morph && params_.morph_time > 0.0f) {
    const float dur = params_.morph_time / split_speedup_;
    startMorph(su, parent_disp, pu, dur);
  }
  if (have_view_) {
    for (uint32_t f : fan_u_) active_area_[face_pos_[f]] = faceImageArea(f);
    active_area_[face_pos_[vs.fl]] = faceImageArea(vs.fl);
    active_area_[face_pos_[vs.fr]] = faceImageArea(vs.fr);
  } else {
    active_area_[face_pos_[vs.fl]] = active_area_[face_pos_[vs.fr]] = 0.0f;
  }
  for (uint32_t f : fan_u_) accumulate(f, 1.0f);
  accumulate(vs.fl, 1.0f);
  accumulate(vs.fr, 1.0f);
  if (turned) {
    listFlipped(fan_u_);
    const uint32_t created[2] = {vs.fl, vs.fr};
    listFlipped(created);
  }
  changes_.split.push_back(s);
  markDirty(st);
  markDirty(su);
  markDirty(node_slot_[l]);
  markDirty(node_slot_[r]);
  ++stats_.splits;
  ++ops_;
  if (work_.size() + 2 <= work_.capacity()) {
    work_.push_back(st);
    work_.push_back(su);
  }
  return true;
}

bool AdaptiveMesh::doCollapse(uint32_t p, bool check) {
  if (!ecolLegal(p)) return false;
  const VertexSplit& vs = pm_.split(p);
  const uint32_t fn_tl = vs.fn[0], fn_ul = vs.fn[1], fn_ur = vs.fn[2], fn_rt = vs.fn[3];
  if (!collectFan(vs.vu, fn_ul, fn_ur, fan_u_) || !collectFan(vs.vt, fn_rt, fn_tl, fan_t_))
    return false;
  const glm::vec3 pp = node_pos_[p];
  bool folds = false;
  if (check && !fanFacingAllowed(vs.vu, pp, folds)) return false;
  if (node_state_[p] & kPending) removePending(p);
  node_state_[p] = 0;
  node_state_[vs.vt] = 0;
  node_state_[vs.vu] = 0;
  slot_locked_[node_slot_[vs.vt]] = slot_locked_[node_slot_[vs.vu]] = 0;
  for (uint32_t f : fan_u_) accumulate(f, -1.0f);
  accumulate(vs.fl, -1.0f);
  accumulate(vs.fr, -1.0f);
  const uint32_t st = node_slot_[vs.vt], su = node_slot_[vs.vu];
  for (uint32_t f : fan_u_) {
    const uint32_t i = cornerOf(f, vs.vu);
    fv_[f][i] = p;
    active_fs_[face_pos_[f]][i] = st;
  }
  for (uint32_t f : fan_t_) fv_[f][cornerOf(f, vs.vt)] = p;  // slot unchanged
  relink(fnb_[fn_tl], vs.fl, fn_ul);
  relink(fnb_[fn_ul], vs.fl, fn_tl);
  relink(fnb_[fn_ur], vs.fr, fn_rt);
  relink(fnb_[fn_rt], vs.fr, fn_ur);
  const uint32_t l = fv_[vs.fl][2], r = fv_[vs.fr][2];
  deactivateFace(vs.fl);
  deactivateFace(vs.fr);
  freeSlot(su);
  node_slot_[vs.vt] = kNone;
  slot_node_[st] = p;
  node_slot_[p] = st;
  slot_bounds_[st] = bounds_[p];
  slot_pos_[st] = node_pos_[p];
  slot_face_[st] = fn_tl;
  const uint32_t sl = node_slot_[l], sr = node_slot_[r];
  if (slot_face_[sl] == vs.fl) slot_face_[sl] = fn_tl;
  if (slot_face_[sr] == vs.fr) slot_face_[sr] = fn_rt;
  if (morph_pos_[st] == kNone) disp_[st] = pp;
  if (have_view_)
    for (uint32_t f : fan_u_) active_area_[face_pos_[f]] = faceImageArea(f);
  for (uint32_t f : fan_u_) accumulate(f, 1.0f);
  if (folds) {
    listFlipped(fan_u_);
    ++stats_.folds;
  }
  changes_.collapsed.push_back(p);
  markDirty(st);
  markDirty(su);
  markDirty(sl);
  markDirty(sr);
  ++stats_.collapses;
  ++ops_;
  return true;
}

bool AdaptiveMesh::forceSplit(uint32_t v, bool check, bool morph, float split_above) {
  if (retry_frame_[v] > frame_) return false;  // failed recently: back off
  stack_.clear();
  stack_.push_back(v);
  chain_.clear();
  size_t iterations = 0;
  bool ok = true;
  const float mean_before = split_above > 0.0f ? ringMean(v) : 0.0f;
  // Refusals in a row so far (the chain and its undo mark v's slot dirty, which resets them).
  const uint32_t refusals = node_slot_[v] != kNone ? refusals_[node_slot_[v]] : 0u;
  float undone_ratio = 0.0f;  // v's ring mean after the chain / before, when it undoes the chain
  while (!stack_.empty()) {
    if (stack_.size() > kMaxStack || ++iterations > 4 * kMaxStack) { ok = false; break; }
    const uint32_t x = stack_.back();
    if (pm_.isLeaf(x)) { ok = false; break; }
    if (splitDone(x)) {
      stack_.pop_back();
      continue;
    }
    if (node_slot_[x] == kNone) {
      const uint32_t q = pm_.parent[x];
      if (q == kNone) { ok = false; break; }
      stack_.push_back(q);
      continue;
    }
    bool ready = true;
    for (uint32_t f : pm_.split(x).fn) {
      if (face_pos_[f] != kNone) continue;
      ready = false;
      const uint32_t q = pm_.face_parent[f];
      if (q == kNone) { ok = false; break; }
      stack_.push_back(q);
    }
    if (!ok) break;
    if (!ready) continue;
    // The splits that made v's neighbourhood also made v's faces smaller. If v no longer needs
    // its own split, the chain is not worth keeping: its vertices are often back-facing, are
    // coarsened again next frame, and v wanted the split again — a cycle of 3 frames at a
    // fixed view (docs/temporal-coherence.md, "Limit cycles at a fixed view").
    if (x == v && split_above > 0.0f && !chain_.empty() && !(ringMean(v) > split_above)) {
      ok = false;
      if (mean_before > 0.0f) undone_ratio = ringMean(v) / mean_before;
      break;
    }
    if (!doSplit(x, check, morph)) { ok = false; break; }
    chain_.push_back(x);
    stack_.pop_back();
  }
  if (ok) return true;
  // A split of the chain was refused (it would fold a face over in this mixed-resolution
  // neighbourhood): undo the forced splits already made, most recent first, so the mesh is
  // unchanged, and retry this vertex only after a few frames.
  for (size_t i = chain_.size(); i-- > 0;) {
    if (!undoSplit(chain_[i])) break;
    auto it = std::find(changes_.split.rbegin(), changes_.split.rend(), chain_[i]);
    if (it != changes_.split.rend()) changes_.split.erase(std::next(it).base());
  }
  retry_frame_[v] = frame_ + kRetryFrames;
  if (const uint32_t slot = node_slot_[v]; slot != kNone) {
    undone_ratio_[slot] = undone_ratio;
    // A chain refused for a fold-over is refused again while v's ring stays as it is (a
    // change marks it dirty, which resets the count): each refusal in a row doubles the
    // wait, up to kRetryFrames << kMaxRefusalShift.
    if (undone_ratio == 0.0f) {
      retry_frame_[v] = frame_ + (kRetryFrames << refusals);
      refusals_[slot] = static_cast<uint8_t>(std::min(refusals + 1u, kMaxRefusalShift));
    }
  }
  return false;
}

// ---------------------------------------------------------------------------------------
// Geomorphs (Jeong §3.2)

void AdaptiveMesh::startMorph(uint32_t slot, const glm::vec3& from, const glm::vec3& to,
                              float duration) {
  if (!(duration > 0.0f)) {
    stopMorph(slot);
    disp_[slot] = to;
    markMoved(slot);
    return;
  }
  morph_from_[slot] = from;
  morph_to_[slot] = to;
  morph_t_[slot] = 0.0f;
  morph_rate_[slot] = 1.0f / duration;
  disp_[slot] = from;
  if (morph_pos_[slot] == kNone) {
    morph_pos_[slot] = static_cast<uint32_t>(morphing_.size());
    morphing_.push_back(slot);
  }
  markMoved(slot);
}

void AdaptiveMesh::stopMorph(uint32_t slot) {
  const uint32_t pos = morph_pos_[slot];
  if (pos == kNone) return;
  const uint32_t last = morphing_.back();
  morphing_[pos] = last;
  morph_pos_[last] = pos;
  morphing_.pop_back();
  morph_pos_[slot] = kNone;
}

void AdaptiveMesh::startCollapseMorph(uint32_t p, float speedup) {
  const VertexSplit& vs = pm_.split(p);
  node_state_[p] |= kPending;
  node_state_[vs.vt] |= kLocked;
  node_state_[vs.vu] |= kLocked;
  slot_locked_[node_slot_[vs.vt]] = slot_locked_[node_slot_[vs.vu]] = 1;
  touchSlot(node_slot_[vs.vt]);
  touchSlot(node_slot_[vs.vu]);
  pending_pos_[p] = static_cast<uint32_t>(pending_.size());
  pending_.push_back(p);
  const uint32_t su = node_slot_[vs.vu];
  startMorph(su, disp_[su], node_pos_[p],
             params_.morph_time * params_.coarsen_time_factor / speedup);
}

void AdaptiveMesh::removePending(uint32_t p) {
  const uint32_t pos = pending_pos_[p];
  const uint32_t last = pending_.back();
  pending_[pos] = last;
  pending_pos_[last] = pos;
  pending_.pop_back();
  pending_pos_[p] = kNone;
}

void AdaptiveMesh::cancelCollapse(uint32_t p) {
  if (!(node_state_[p] & kPending)) return;
  const VertexSplit& vs = pm_.split(p);
  removePending(p);
  node_state_[p] &= static_cast<uint8_t>(~kPending);
  node_state_[vs.vt] &= static_cast<uint8_t>(~kLocked);
  node_state_[vs.vu] &= static_cast<uint8_t>(~kLocked);
  slot_locked_[node_slot_[vs.vt]] = slot_locked_[node_slot_[vs.vu]] = 0;
  touchSlot(node_slot_[vs.vt]);
  touchSlot(node_slot_[vs.vu]);
  const uint32_t su = node_slot_[vs.vu];
  const float dur = params_.geomorphs ? params_.morph_time * params_.coarsen_time_factor : 0.0f;
  startMorph(su, disp_[su], node_pos_[vs.vu], dur);
}

void AdaptiveMesh::advanceMorphs(float dt) {
  for (size_t i = 0; i < morphing_.size();) {
    const uint32_t slot = morphing_[i];
    const float t = morph_t_[slot] + dt * morph_rate_[slot];
    markMoved(slot);
    if (t >= 1.0f || !params_.geomorphs) {
      disp_[slot] = morph_to_[slot];
      stopMorph(slot);  // swaps the last entry into i
      continue;
    }
    morph_t_[slot] = t;
    disp_[slot] = morph_from_[slot] + t * (morph_to_[slot] - morph_from_[slot]);
    ++i;
  }
  done_pending_.clear();
  for (uint32_t p : pending_) {
    const VertexSplit& vs = pm_.split(p);
    if (morph_pos_[node_slot_[vs.vu]] == kNone) done_pending_.push_back(p);  // vt may still
                                                                            // be morphing
  }
  for (uint32_t p : done_pending_) {
    if (!(node_state_[p] & kPending)) continue;
    if (!doCollapse(p, true)) cancelCollapse(p);
  }
}

void AdaptiveMesh::clearAllMorphs() {
  while (!pending_.empty()) cancelCollapse(pending_.back());
  while (!morphing_.empty()) {
    const uint32_t slot = morphing_.back();
    disp_[slot] = morph_to_[slot];
    stopMorph(slot);
  }
}

// ---------------------------------------------------------------------------------------
// The frame

// Whether evaluating the vertex `node` of `slot` would do nothing with the rings, locks and
// slots as they are: the branches of evaluatePass()'s loop that end in `continue` without an
// operation. Exactly those; anything that could change the answer clears the mark
// (touchSlot()).
bool AdaptiveMesh::idleAtStart(uint32_t slot, uint32_t node, bool vis, float target, float t_s,
                               float t_c) const {
  if (slot_locked_[slot]) return false;
  if (vis && !pm_.isLeaf(node) && ringMeanAt(slot) > t_s * target) return false;
  const NodeBounds& nb = slot_bounds_[slot];
  if (nb.sibling == kNone) return true;
  const uint32_t su = node_slot_[nb.sibling];
  if (su == kNone || slot_locked_[su]) return true;
  if (!vis && !visible(bounds_[nb.parent])) return false;
  return !(ringsMean(slot, su) < t_c * target);
}

void AdaptiveMesh::evaluatePass() {
  // The work list holds slots: the static data of an active vertex (position, bounds, parent)
  // is copied into its slot, so this loop reads slot arrays, not per-node ones.
  // In the order of evaluation (as slots were numbered before orderForLocality(), so that
  // renumbering the slots changes no decision), from where a budget stopped the last
  // evaluation (round robin).
  work_.clear();
  const uint32_t start = resume_eval_ < eval_count_ ? resume_eval_ : 0;
  for (uint32_t k = 0; k < eval_count_; ++k) {
    const uint32_t slot = eval_slot_[start + k < eval_count_ ? start + k : start + k - eval_count_];
    if (slot != kNone) work_.push_back(slot);
  }
  // Visibility and target of every listed vertex, in parallel: they depend only on the
  // slot's node (its bounds) and the view. Used while the slot still holds that node. And
  // whether the vertex has anything to do (idleAtStart): at T = 7 px² on an orbit nine in ten
  // have not, and the loop below skips them unless an operation touched their ring, lock or
  // sibling since (touchSlot), which leaves every decision as it was
  // (AdaptiveMesh.SkippingIdleVerticesChangesNoDecision). In slot order, not the order of
  // evaluation, so the reads and writes stream (every listed slot holds a node).
  const size_t listed = work_.size();
  const float t_s = params_.t_s, t_c = params_.t_c;
  auto classify = [&](size_t begin, size_t end) {
    for (size_t slot = begin; slot < end; ++slot) {
      // idleAtStart() reads the sibling's slot (a 1M-node array): fetch it ahead.
      if (slot + kPrefetchAhead < end)
        if (const uint32_t ahead = slot_bounds_[slot + kPrefetchAhead].sibling; ahead != kNone)
          __builtin_prefetch(&node_slot_[ahead]);
      const uint32_t node = slot_node_[slot];
      pre_node_[slot] = node;
      if (node == kNone) continue;
      const NodeBounds& nb = slot_bounds_[slot];
      const bool vis = visible(nb);
      const float target = targetAt(nb.pos);
      pre_visible_[slot] = vis;
      pre_target_[slot] = target;
      eval_idle_[slot] = idleAtStart(static_cast<uint32_t>(slot), node, vis, target, t_s, t_c);
    }
  };
  if (pool_) {
    pool_->forRange(slot_count_, 4096, classify);
  } else {
    classify(0, slot_count_);
  }
  const bool morph = params_.geomorphs && params_.morph_time > 0.0f;
  resume_eval_ = 0;
  for (size_t i = 0; i < work_.size(); ++i) {
    if ((params_.max_operations && ops_ >= params_.max_operations) ||
        (params_.max_adapt_ms > 0.0f && i % 32 == 0 && i >= std::max<size_t>(32, listed / kMinEvaluatedShare) &&
         adapt_clock_.elapsed() > params_.max_adapt_ms)) {
      if (i < listed) resume_eval_ = slot_eval_[work_[i]];  // the next frame starts here
      budget_spent_ = true;
      break;
    }
    const uint32_t slot = work_[i];
    const bool marked_idle = i < listed && eval_idle_[slot];
    if (marked_idle && !evaluate_every_vertex_) continue;
    // Evaluating every vertex (a check): count the marked ones that act after all.
    struct IdleCheck {
      AdaptiveMesh& mesh;
      bool on;
      uint32_t ops;
      size_t pending;
      ~IdleCheck() {
        if (on && (mesh.ops_ != ops || mesh.pending_.size() != pending)) ++mesh.idle_mispredictions_;
      }
    } idle_check{*this, marked_idle, ops_, pending_.size()};
    // The sibling's slot is the one per-node read of most iterations (a cache miss over a
    // 1M-node array): fetch it a few vertices ahead.
    if (i + kPrefetchAhead < work_.size()) {
      const uint32_t ahead_slot = work_[i + kPrefetchAhead];
      if (!eval_idle_[ahead_slot])
        if (const uint32_t ahead = slot_bounds_[ahead_slot].sibling; ahead != kNone)
          __builtin_prefetch(&node_slot_[ahead]);
    }
    const uint32_t v = slot_node_[slot];
    if (v == kNone) continue;
    const NodeBounds& nb = slot_bounds_[slot];
    const uint32_t p = nb.parent;
    const bool known = i < listed && pre_node_[slot] == v;
    const bool vis = known ? pre_visible_[slot] != 0 : visible(nb);
    if (slot_locked_[slot]) {
      // Off-screen: a pending collapse executes at once (p can only be invisible if v is).
      if (!vis && nb.sibling != kNone && !visible(bounds_[p])) {
        if (!doCollapse(p, true)) cancelCollapse(p);
      }
      continue;
    }
    if (vis && !pm_.isLeaf(v)) {
      const float target = known ? pre_target_[slot] : targetAt(nb.pos);
      const float mean = ringMeanAt(slot);  // (not ringMean(v): a node-indexed read misses)
      if (mean > t_s * target) {
        // The last forced split of v was undone because the chain brought v's mean below
        // t_s·T: try again early only if the same chain would now leave it above.
        const float undone = undone_ratio_[slot];
        if (undone > 0.0f && !(mean * undone > t_s * target) &&
            frame_ < retry_frame_[v] - kRetryFrames + kUndoneRecheckFrames)
          continue;
        // A split that needs a chain of forced splits first gains a face in v's ring for
        // each of fn0..fn3 the chain creates. When that alone would bring v's mean to
        // t_s·T, the chain would be made and undone (forceSplit): skip it as if it had
        // been, which it is in about nine cases of ten (docs/performance.md).
        if (const uint32_t missing = missingNeighbours(v); missing > 0) {
          const float ratio = static_cast<float>(ring_cnt_[slot]) / static_cast<float>(ring_cnt_[slot] + missing);
          if (!(mean * ratio > t_s * target)) {
            undone_ratio_[slot] = ratio;
            retry_frame_[v] = frame_ + kRetryFrames;
            continue;
          }
        }
        split_speedup_ = clampf(mean / (t_s * target), 1.0f, params_.max_morph_speedup);
        // A morph that would end within this frame is not worth showing.
        const bool show = morph && params_.morph_time / split_speedup_ > frame_dt_;
        forceSplit(v, true, show, t_s * target);
        continue;
      }
    }
    // Collapses are evaluated from the vt child only. (p cannot be pending here: its
    // children would be locked, and v is not.)
    const uint32_t vu = nb.sibling;
    if (vu == kNone) continue;
    const uint32_t su = node_slot_[vu];
    if (su == kNone || slot_locked_[su]) continue;
    // p's bounds contain v's, so p can only be invisible when v is.
    if (!vis && !visible(bounds_[p])) {
      if (collapseMayBeLegal(slot, su, p) && doCollapse(p, true) && work_.size() < work_.capacity())
        work_.push_back(slot);
      continue;
    }
    const float target = known ? pre_target_[slot] : targetAt(nb.pos);  // p has v's position
    // Jeong §3.1: collapse when the mean area around the two children falls below t_c·T,
    // unless the parent's mean afterwards (the number its split compares with t_s·T) would
    // split it again, so a pair never flips back and forth at a fixed view. Both means must
    // be below: the accumulators' one first (no face read), then the exact one, so slivers
    // fl and fr do not make a collapse early (docs/detail-control.md §7).
    if (!(ringsMean(slot, su) < t_c * target)) continue;
    const float now = pairMean(slot, su, p);
    if (!(now < t_c * target)) continue;
    if (!collapseMayBeLegal(slot, su, p)) {
      unblock_visits_ = 0;
      unblockCollapse(p, kUnblockDepth);
      continue;
    }
    if (!(predictedMean(p) < kNoSplitBack * t_s * target)) continue;
    const float speedup = collapseSpeedup(now, target, nb.pos);
    if (morph && params_.morph_time * params_.coarsen_time_factor / speedup > frame_dt_) {
      if (collapseGeometryOk(p)) startCollapseMorph(p, speedup);
    } else if (doCollapse(p, true) && work_.size() < work_.capacity()) {
      work_.push_back(slot);
    }
  }
}

// A collapse of p that is due but illegal waits, in Hoppe's scheme (1997 §4), until the
// finer faces between fl/fr and their recorded neighbours fn[i] are gone. Those faces' own
// collapses need not be due (their rings hold larger faces), and after a fast zoom-out such
// waits chain into a mesh several times finer than the view asks for, which stays so when the
// camera stops (docs/detail-control.md, "Coarsening that keeps up"). So the collapses that
// remove the blocking faces are made here (first those of their creators' children where
// these are split further), up to `depth` levels, each only where its parent would not split
// again at this view. They are executed at once: a geomorph per level would delay p by as
// many morphs. Returns whether an operation was made.
bool AdaptiveMesh::unblockCollapse(uint32_t p, int depth) {
  const VertexSplit& vs = pm_.split(p);
  if (face_pos_[vs.fl] == kNone || face_pos_[vs.fr] == kNone) return false;
  const auto &nl = fnb_[vs.fl], &nr = fnb_[vs.fr];
  const uint32_t across[4] = {nl[1], nl[2], nr[1], nr[2]};  // where fn[0..3] belong
  bool any = false;
  for (int i = 0; i < 4; ++i) {
    const uint32_t g = across[i];
    if (g == vs.fn[i]) continue;
    // A coarser neighbour (fn[i] not active yet) would need a split: not here.
    if (g == kNone || face_pos_[vs.fn[i]] == kNone) return any;
    const uint32_t q = pm_.face_parent[g];
    if (q == kNone || q == p) return any;
    any |= advanceCollapse(q, depth);
  }
  return any;
}

bool AdaptiveMesh::advanceCollapse(uint32_t q, int depth) {
  if (++unblock_visits_ > kUnblockVisits) return false;
  const VertexSplit& qs = pm_.split(q);
  const uint32_t qt = node_slot_[qs.vt], qu = node_slot_[qs.vu];
  if (qt == kNone || qu == kNone) {  // a child is split further: its collapse comes first
    if (depth == 0 || node_slot_[q] != kNone) return false;
    bool any = false;
    if (qt == kNone && !pm_.isLeaf(qs.vt)) any |= advanceCollapse(qs.vt, depth - 1);
    if (qu == kNone && !pm_.isLeaf(qs.vu)) any |= advanceCollapse(qs.vu, depth - 1);
    return any;
  }
  if (slot_locked_[qt] || slot_locked_[qu]) return false;  // collapsing already
  if (!ecolLegal(q)) return depth > 0 && unblockCollapse(q, depth - 1);
  if (!(predictedMean(q) < kNoSplitBack * params_.t_s * targetAt(node_pos_[q]))) return false;
  return doCollapse(q, true);
}

bool AdaptiveMesh::undoSplit(uint32_t x) {
  if (!doCollapse(x, false)) return false;
  changes_.collapsed.pop_back();
  --stats_.collapses;
  --stats_.splits;
  ops_ -= 2;
  return true;
}

void AdaptiveMesh::undoSplitsSince(size_t mark) {
  while (changes_.split.size() > mark) {
    const uint32_t x = changes_.split.back();
    if (!undoSplit(x)) break;
    changes_.split.pop_back();
    retry_frame_[x] = frame_ + kRetryFrames;
  }
}

// Faces a collapse turned over while sub-pixel (kFoldAreaPx), and faces a split left against
// their full-detail normal without turning them over (kept: splitFacingAllowed(); created:
// splitNewFaceAllowed()), are dropped from the list once gone or facing as recorded again;
// one of a pixel or more (for a fold: the camera came closer before a split undid it) has its
// corners refined within the frame: with every corner at full detail a face has its recorded
// geometry, so this ends, unless a corner's split is refused, and then the repair's splits are
// undone and wait (docs/detail-control.md §9). Nearly always the coarsening that a fold
// unblocked removes the face in the same frame.
void AdaptiveMesh::repairFolds() {
  // Packed in place. A repair's splits may list faces (appended, repaired in this loop too),
  // and the listing looks the face up over the whole list: an entry dropped here is cleared
  // at once, or its stale copy would make a face turned again look listed.
  size_t kept = 0;
  for (size_t k = 0; k < folded_.size(); ++k) {
    const uint32_t f = folded_[k];
    if (face_pos_[f] == kNone || !flipped(f)) {
      folded_[k] = kNone;
      continue;
    }
    if (!(faceImageArea(f) < kFoldAreaPx)) {
      // Down to the corners' full detail if need be, in this frame: a split that leaves the
      // face on its t side does not move it, and a repair spread over frames is collapsed
      // again by the criterion in between.
      const size_t mark = changes_.split.size();
      bool progress = true;
      for (int round = 0; progress && round < kMaxRepairRounds && face_pos_[f] != kNone && flipped(f); ++round) {
        progress = false;
        for (int i = 0; i < 3 && face_pos_[f] != kNone && flipped(f); ++i)
          if (const uint32_t c = fv_[f][i]; !pm_.isLeaf(c)) progress |= forceSplit(c, true, false);
      }
      // Where a corner's split is refused, the face stays turned and the splits made for it
      // would be collapsed by the criterion next frame and made again here, a split and a
      // collapse every frame at rest that redraws the lines there (the femur's default view
      // did so): they are undone and wait, as a refused forced chain does.
      if (face_pos_[f] != kNone && flipped(f)) {
        undoSplitsSince(mark);
      } else {
        ++stats_.fold_repairs;
      }
      if (face_pos_[f] == kNone || !flipped(f)) {
        folded_[k] = kNone;
        continue;
      }
    }
    folded_[kept++] = f;
  }
  folded_.resize(kept);
}

void AdaptiveMesh::adapt(float dt_seconds) {
  ++frame_;
  if (frame_ == 0) {  // stamp wrap-around
    std::fill(retry_frame_.begin(), retry_frame_.end(), 0u);
    std::fill(undone_ratio_.begin(), undone_ratio_.end(), 0.0f);  // its recheck window counts from retry_frame_
    std::fill(dirty_stamp_.begin(), dirty_stamp_.end(), 0u);
    std::fill(moved_stamp_.begin(), moved_stamp_.end(), 0u);
    std::fill(illegal_frame_.begin(), illegal_frame_.end(), 0u);
    frame_ = 1;
  }
  changes_.split.clear();
  changes_.collapsed.clear();
  changes_.moved.clear();
  changes_.dirty.clear();
  changes_.everything = false;
  stats_.splits = stats_.collapses = stats_.folds = stats_.fold_repairs = 0;
  stats_.slots_ordered = false;
  ops_ = 0;
  adapt_clock_.lap();
  budget_spent_ = false;
  if (!have_view_) return;
  stats_.target_area = t0_;
  if (active_vertices_ >= kOrderMinVertices && fresh_slots_ > active_vertices_ / kOrderFreshShare) {
    orderForLocality();
    stats_.slots_ordered = true;
  }

  // 1. Image areas of all active faces (and the band statistics of the incoming mesh): per
  // face in parallel, then summed into the rings in face order (the same sums as serially).
  std::atomic<uint32_t> visible{0}, in_band{0}, at_limit{0};
  const float near2 = std::max(camera_.near_plane * camera_.near_plane, 1e-20f);
  const FaceAreaView view{active_fs_.data(), slot_pos_.data(), planes_.data(), eye_, forward_, k_, near2,
                          camera_.orthographic};
  active_visible_.resize(active_faces_.size());
  auto areas = [&](size_t begin, size_t end) {
    faceImageAreas(view, begin, end, active_area_.data(), active_visible_.data());
    uint32_t vis = 0, band = 0, limit = 0;
    for (size_t k = begin; k < end; ++k) {
      if (!active_visible_[k]) continue;
      const auto& c = active_fs_[k];
      const float img = active_area_[k];
      ++vis;
      const float t =
          modifiers_ ? targetAt((slot_pos_[c[0]] + slot_pos_[c[1]] + slot_pos_[c[2]]) * (1.0f / 3.0f)) : t0_;
      if (const int side = bandSide(img, t); side == 0)
        ++band;
      else
        limit += atLimit({slot_node_[c[0]], slot_node_[c[1]], slot_node_[c[2]]}, side);
    }
    visible += vis;
    in_band += band;
    at_limit += limit;
  };
  if (pool_) {
    pool_->forRange(active_faces_.size(), 4096, areas);
  } else {
    areas(0, active_faces_.size());
  }
  std::fill(ring_sum_.begin(), ring_sum_.begin() + slot_count_, 0.0);
  std::fill(ring_cnt_.begin(), ring_cnt_.begin() + slot_count_, 0);
  for (size_t k = 0; k < active_faces_.size(); ++k) {
    const float img = active_area_[k];
    for (uint32_t slot : active_fs_[k]) {
      ring_sum_[slot] += img;
      ++ring_cnt_[slot];
    }
  }
  stats_.visible_faces = visible;
  stats_.band_fraction =
      visible ? static_cast<float>(in_band.load()) / static_cast<float>(visible.load()) : 1.0f;
  stats_.band_or_limit_fraction =
      visible ? static_cast<float>(in_band.load() + at_limit.load()) / static_cast<float>(visible.load()) : 1.0f;

  // Geomorphs switched off: finish what is in flight.
  if (!params_.geomorphs && (!morphing_.empty() || !pending_.empty())) advanceMorphs(0.0f);

  // 2. Evaluate every active vertex (children of this frame's splits are appended). Another
  // pass follows while a pass changes much (cascades of collapses that wait on each other).
  frame_dt_ = std::max(dt_seconds, 0.0f);
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    const uint32_t ops_before = ops_;
    evaluatePass();
    const uint32_t done = ops_ - ops_before;
    if (done <= std::max<uint32_t>(16, active_vertices_ / 64)) break;
    if (budget_spent_) break;
  }

  repairFolds();

  // 3. Geomorphs.
  advanceMorphs(std::max(dt_seconds, 0.0f));

  last_eye_ = eye_;
  last_k_ = k_;
  have_last_view_ = true;
  stats_.active_vertices = active_vertices_;
  stats_.active_faces = static_cast<uint32_t>(active_faces_.size());
  stats_.morphing = static_cast<uint32_t>(morphing_.size());
  stats_.pending_collapses = static_cast<uint32_t>(pending_.size());
  stats_.folded_faces = static_cast<uint32_t>(folded_.size());
}

// Splits take slots from the free list or the end, and faces join the active list at its end
// or in the place of a removed one, so after a while a face's corners and a vertex's faces lie
// far apart in memory: the stages downstream (shape, lines), which run over the slot-indexed
// mesh, then miss the cache on most reads (1.4-1.6x slower shape computes on a 1.1M knot at
// T = 7 px², docs/performance.md). Renumbering the slots along a Morton curve and sorting the
// faces by their lowest corner, as core/mesh_order.h does for input meshes, restores it. The
// consumers follow the vertices through the nodes their slots hold (every slot is marked
// dirty), as they do across splits and collapses. The vertices are still evaluated in the
// order their slots had without it (each slot keeps its place in that order, which is taken
// and released as slots were), because which of two competing operations comes first
// decides results: on a fast zoom-out of a torus, orders alone moved the band fraction at
// rest between 0.24 and 0.84 (docs/detail-control.md §7). So the adapted mesh is the same
// with or without renumbering, only numbered differently.
void AdaptiveMesh::orderForLocality() {
  fresh_slots_ = 0;
  const uint32_t old_count = slot_count_;
  order_code_.resize(old_count);
  order_items_.clear();
  for (uint32_t s = 0; s < old_count; ++s) {
    if (slot_node_[s] == kNone) continue;
    order_code_[s] = mortonCode((slot_bounds_[s].pos - order_min_) / order_extent_);
    order_items_.push_back(s);
  }
  sortByCode(order_code_, order_items_, order_tmp_);  // new slot → old slot
  const std::span<const uint32_t> new_to_old = order_items_;
  const uint32_t n = static_cast<uint32_t>(new_to_old.size());
  order_map_.assign(old_count, kNone);  // old slot → new slot
  for (uint32_t i = 0; i < n; ++i) order_map_[new_to_old[i]] = i;

  gatherInPlace(slot_node_, new_to_old, order_scratch_);
  gatherInPlace(slot_face_, new_to_old, order_scratch_);
  gatherInPlace(disp_, new_to_old, order_scratch_);
  gatherInPlace(morph_from_, new_to_old, order_scratch_);
  gatherInPlace(morph_to_, new_to_old, order_scratch_);
  gatherInPlace(morph_t_, new_to_old, order_scratch_);
  gatherInPlace(morph_rate_, new_to_old, order_scratch_);
  gatherInPlace(morph_pos_, new_to_old, order_scratch_);
  gatherInPlace(slot_locked_, new_to_old, order_scratch_);
  gatherInPlace(illegal_frame_, new_to_old, order_scratch_);
  gatherInPlace(undone_ratio_, new_to_old, order_scratch_);
  gatherInPlace(refusals_, new_to_old, order_scratch_);
  gatherInPlace(slot_bounds_, new_to_old, order_scratch_);
  gatherInPlace(slot_pos_, new_to_old, order_scratch_);
  gatherInPlace(ring_sum_, new_to_old, order_scratch_);
  gatherInPlace(ring_cnt_, new_to_old, order_scratch_);
  gatherInPlace(moved_stamp_, new_to_old, order_scratch_);
  gatherInPlace(slot_eval_, new_to_old, order_scratch_);
  // pre_node_/pre_visible_/pre_target_ are refilled by each pass.
  std::fill(slot_node_.begin() + n, slot_node_.begin() + old_count, kNone);
  std::fill(slot_face_.begin() + n, slot_face_.begin() + old_count, kNone);
  std::fill(morph_pos_.begin() + n, morph_pos_.begin() + old_count, kNone);
  for (uint32_t i = 0; i < n; ++i) {
    node_slot_[slot_node_[i]] = i;
    eval_slot_[slot_eval_[i]] = i;
  }
  for (uint32_t& s : morphing_) s = order_map_[s];
  slot_count_ = n;
  free_slots_.clear();

  // Faces by their lowest corner in the new numbering.
  for (auto& c : active_fs_)
    for (uint32_t& s : c) s = order_map_[s];
  orderByLowestCorner(active_fs_, n, order_tmp_, order_code_);  // new position → old position
  const std::span<const uint32_t> face_order = order_tmp_;
  gatherInPlace(active_faces_, face_order, order_scratch_);
  gatherInPlace(active_fs_, face_order, order_scratch_);
  gatherInPlace(active_area_, face_order, order_scratch_);
  for (uint32_t k = 0; k < active_faces_.size(); ++k) face_pos_[active_faces_[k]] = k;

  // The change lists in the new numbering: every slot dirty, the moved ones still moved.
  changes_.dirty.resize(n);
  std::iota(changes_.dirty.begin(), changes_.dirty.end(), 0u);
  std::fill(dirty_stamp_.begin(), dirty_stamp_.begin() + n, frame_);
  size_t kept = 0;
  for (uint32_t s : changes_.moved)
    if (s < old_count && order_map_[s] != kNone) changes_.moved[kept++] = order_map_[s];
  changes_.moved.resize(kept);
}

bool AdaptiveMesh::collapseGeometryOk(uint32_t p) const {
  const VertexSplit& vs = pm_.split(p);
  if (!collectFan(vs.vu, vs.fn[1], vs.fn[2], fan_u_)) return false;
  bool folds = false;
  return fanFacingAllowed(vs.vu, node_pos_[p], folds);
}

// The faces of fan_u_ (vu's fan, collected) with vu moved to p's position pp: facingAllowed for
// each; `folds` tells whether one would turn over (sub-pixel).
bool AdaptiveMesh::fanFacingAllowed(uint32_t vu, const glm::vec3& pp, bool& folds) const {
  for (uint32_t f : fan_u_) {
    const auto& c = fv_[f];
    glm::vec3 q[3] = {node_pos_[c[0]], node_pos_[c[1]], node_pos_[c[2]]};
    q[cornerOf(f, vu)] = pp;
    if (!facingAllowed(f, q, &folds)) return false;
  }
  return true;
}

void AdaptiveMesh::fullyRefine() {
  clearAllMorphs();
  std::fill(retry_frame_.begin(), retry_frame_.end(), 0u);
  std::fill(undone_ratio_.begin(), undone_ratio_.end(), 0.0f);  // its recheck window counts from retry_frame_
  for (;;) {  // work_ holds slots; splits append their children's slots
    work_.clear();
    for (uint32_t slot = 0; slot < slot_count_; ++slot) {
      const uint32_t v = slot_node_[slot];
      if (v != kNone && !pm_.isLeaf(v)) work_.push_back(slot);
    }
    if (work_.empty()) break;
    bool progress = false;
    for (size_t i = 0; i < work_.size(); ++i) {
      const uint32_t v = slot_node_[work_[i]];
      if (v == kNone || pm_.isLeaf(v)) continue;
      progress |= forceSplit(v, false, false);
    }
    if (!progress) break;
  }
  changes_.everything = true;
}

void AdaptiveMesh::fullyCoarsen() {
  clearAllMorphs();
  for (;;) {
    work_.clear();
    for (uint32_t slot = 0; slot < slot_count_; ++slot)
      if (slot_node_[slot] != kNone) work_.push_back(slot);
    bool progress = false;
    for (size_t i = 0; i < work_.size(); ++i) {
      const uint32_t slot = work_[i];
      const uint32_t v = slot_node_[slot];
      if (v == kNone) continue;
      const uint32_t p = pm_.parent[v];
      if (p == kNone || v != pm_.split(p).vt) continue;
      if (doCollapse(p, false)) {
        progress = true;
        if (work_.size() < work_.capacity()) work_.push_back(slot);  // now holds p
      }
    }
    if (!progress) break;
  }
  changes_.everything = true;
}

// ---------------------------------------------------------------------------------------
// Output and checks

void AdaptiveMesh::exportFaces(std::vector<std::array<uint32_t, 3>>& out) const {
  // active_fs_ holds the corner slots of every active face, kept in step by split/collapse.
  out.assign(active_fs_.begin(), active_fs_.end());
}

void AdaptiveMesh::exportCompact(TriMesh& out, std::vector<uint32_t>& node_ids) const {
  std::vector<uint32_t>& index = compact_index_;
  index.assign(slot_count_, kNone);
  out.positions.clear();
  out.faces.clear();
  out.marked_edges.clear();
  node_ids.clear();
  for (uint32_t slot = 0; slot < slot_count_; ++slot) {
    if (slot_node_[slot] == kNone) continue;
    index[slot] = static_cast<uint32_t>(out.positions.size());
    out.positions.push_back(disp_[slot]);
    node_ids.push_back(slot_node_[slot]);
  }
  out.faces.reserve(active_faces_.size());
  for (uint32_t f : active_faces_) {
    const auto& c = fv_[f];
    out.faces.push_back({index[node_slot_[c[0]]], index[node_slot_[c[1]]], index[node_slot_[c[2]]]});
  }
}

void AdaptiveMesh::measureBand(float& band_fraction, uint32_t& visible_faces,
                               float* band_or_limit_fraction) const {
  uint32_t visible = 0, in_band = 0, at_limit = 0;
  for (uint32_t f : active_faces_) {
    const auto& c = fv_[f];
    const glm::vec3 &a = node_pos_[c[0]], &b = node_pos_[c[1]], &d = node_pos_[c[2]];
    const glm::vec3 n = glm::cross(b - a, d - a);
    const glm::vec3 centre = (a + b + d) * (1.0f / 3.0f);
    const glm::vec3 view_dir = camera_.orthographic ? forward_ : centre - eye_;
    if (glm::dot(n, view_dir) >= 0.0f) continue;
    bool inside = true;
    for (const glm::vec4& pl : planes_) inside &= glm::dot(glm::vec3(pl), centre) + pl.w >= 0.0f;
    if (!inside) continue;
    ++visible;
    const float img = faceImageArea(f);
    const float t = modifiers_ ? targetAt(centre) : t0_;
    if (const int side = bandSide(img, t); side == 0)
      ++in_band;
    else
      at_limit += atLimit(c, side);
  }
  visible_faces = visible;
  band_fraction = visible ? static_cast<float>(in_band) / static_cast<float>(visible) : 1.0f;
  if (band_or_limit_fraction)
    *band_or_limit_fraction =
        visible ? static_cast<float>(in_band + at_limit) / static_cast<float>(visible) : 1.0f;
}

std::string AdaptiveMesh::checkInvariants() const {
  auto str = [](uint32_t x) { return std::to_string(x); };
  // Faces: list/positions, corners, adjacency.
  for (size_t k = 0; k < active_faces_.size(); ++k)
    if (face_pos_[active_faces_[k]] != k) return "face list position mismatch at " + str(k);
  size_t active_count = 0;
  std::vector<uint32_t> incident(n_nodes_, 0);
  for (uint32_t f = 0; f < n_faces_; ++f) {
    if (face_pos_[f] == kNone) continue;
    ++active_count;
    const auto& c = fv_[f];
    if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]) return "face " + str(f) + " is degenerate";
    for (int i = 0; i < 3; ++i) {
      if (c[i] >= n_nodes_ || node_slot_[c[i]] == kNone)
        return "face " + str(f) + " has inactive corner " + str(c[i]);
      if (active_fs_[face_pos_[f]][i] != node_slot_[c[i]])
        return "face " + str(f) + " has a stale corner slot (exportFaces reads them)";
      ++incident[c[i]];
      const uint32_t g = fnb_[f][i];
      if (g == kNone) continue;
      if (face_pos_[g] == kNone) return "face " + str(f) + " has inactive neighbour " + str(g);
      const uint32_t j = cornerOf(g, c[next3(i)]);
      if (j == 3 || fv_[g][next3(j)] != c[i] || fnb_[g][j] != f)
        return "faces " + str(f) + " and " + str(g) + " disagree about their shared edge";
    }
  }
  if (active_count != active_faces_.size()) return "face list size mismatch";
  // Slots and free list.
  std::vector<uint8_t> is_free(slot_count_, 0);
  for (uint32_t s : free_slots_) {
    if (s >= slot_count_ || is_free[s]) return "free list holds a bad or repeated slot";
    if (slot_node_[s] != kNone) return "free slot " + str(s) + " holds a vertex";
    is_free[s] = 1;
  }
  uint32_t used = 0;
  for (uint32_t s = 0; s < slot_count_; ++s) {
    const uint32_t v = slot_node_[s];
    if (v == kNone) {
      if (!is_free[s]) return "slot " + str(s) + " is neither used nor free";
      continue;
    }
    ++used;
    if (node_slot_[v] != s) return "slot " + str(s) + " and node " + str(v) + " disagree";
    if (slot_pos_[s] != node_pos_[v] || slot_bounds_[s].pos != node_pos_[v])
      return "slot " + str(s) + " does not hold node " + str(v) + "'s position";
    if (slot_eval_[s] >= eval_count_ || eval_slot_[slot_eval_[s]] != s)
      return "slot " + str(s) + " has no place in the order of evaluation";
    const uint32_t f = slot_face_[s];
    if (incident[v] == 0) {
      if (f != kNone) return "isolated vertex " + str(v) + " has a face";
      continue;
    }
    if (f == kNone || face_pos_[f] == kNone || cornerOf(f, v) == 3)
      return "vertex " + str(v) + " has a bad incident face";
    if (morph_pos_[s] == kNone && disp_[s] != node_pos_[v])
      return "vertex " + str(v) + " is displaced without a morph";
    if ((slot_locked_[s] != 0) != ((node_state_[v] & kLocked) != 0))
      return "slot " + str(s) + " disagrees with node " + str(v) + " about its lock";
  }
  if (used != active_vertices_) return "active vertex count mismatch";
  uint32_t placed = 0;
  for (uint32_t e = 0; e < eval_count_; ++e) placed += eval_slot_[e] != kNone;
  if (placed != active_vertices_ || placed + eval_free_.size() != eval_count_)
    return "the order of evaluation does not hold the active vertices";
  for (uint32_t v = 0; v < n_nodes_; ++v)
    if (node_slot_[v] != kNone && (node_slot_[v] >= slot_count_ || slot_node_[node_slot_[v]] != v))
      return "node " + str(v) + " points to a wrong slot";
  // The active front: no active node has an active ancestor; every leaf has one.
  for (uint32_t v = 0; v < pm_.vertexCount(); ++v) {
    uint32_t a = v, found = kNone, depth = 0;
    for (; a != kNone; a = pm_.parent[a], ++depth) {
      if (node_slot_[a] == kNone) continue;
      if (found != kNone) return "nodes " + str(found) + " and its ancestor " + str(a) + " both active";
      found = a;
    }
    if (found == kNone) return "leaf " + str(v) + " has no active ancestor";
  }
  // Manifold rings: rotation around each vertex meets every incident face exactly once.
  for (uint32_t s = 0; s < slot_count_; ++s) {
    const uint32_t v = slot_node_[s];
    if (v == kNone || incident[v] == 0) continue;
    if (pm_.vertex_flags[pm_.origin[v]] & kPmFrozen) continue;
    uint32_t count = 0;
    const uint32_t f0 = slot_face_[s];
    uint32_t f = f0;
    bool open = false;
    do {
      ++count;
      f = fnb_[f][prev3(cornerOf(f, v))];
      if (f == kNone) { open = true; break; }
    } while (f != f0 && count <= incident[v]);
    if (open) {
      f = fnb_[f0][cornerOf(f0, v)];
      while (f != kNone && count <= incident[v]) {
        ++count;
        f = fnb_[f][cornerOf(f, v)];
      }
    }
    if (count != incident[v])
      return "vertex " + str(v) + ": ring of " + str(count) + " faces, " + str(incident[v]) +
             " incident (not a manifold fan)";
  }
  // Face corners are the active ancestors of the input corners (up to rotation).
  auto activeAncestor = [&](uint32_t leaf) {
    uint32_t a = leaf;
    while (a != kNone && node_slot_[a] == kNone) a = pm_.parent[a];
    return a;
  };
  for (uint32_t f : active_faces_) {
    const auto& in = pm_.faces[f];
    const std::array<uint32_t, 3> want = {activeAncestor(in[0]), activeAncestor(in[1]),
                                          activeAncestor(in[2])};
    const auto& c = fv_[f];
    bool match = false;
    for (int r = 0; r < 3; ++r)
      match |= c[0] == want[r] && c[1] == want[(r + 1) % 3] && c[2] == want[(r + 2) % 3];
    if (!match) return "face " + str(f) + " corners are not the active ancestors of its input corners";
  }
  // Ring accumulators (sum and count of the areas of the faces around each slot).
  {
    std::vector<double> sum(slot_count_, 0.0);
    std::vector<int32_t> cnt(slot_count_, 0);
    for (uint32_t f : active_faces_)
      for (uint32_t v : fv_[f]) {
        sum[node_slot_[v]] += active_area_[face_pos_[f]];
        ++cnt[node_slot_[v]];
      }
    for (uint32_t s = 0; s < slot_count_; ++s) {
      if (slot_node_[s] == kNone) continue;
      if (cnt[s] != ring_cnt_[s]) return "ring face count of slot " + str(s) + " is stale";
      if (std::abs(sum[s] - ring_sum_[s]) > 1e-3 * (std::abs(sum[s]) + 1.0))
        return "ring area sum of slot " + str(s) + " is stale";
    }
  }
  // Pending collapses.
  for (size_t k = 0; k < pending_.size(); ++k) {
    const uint32_t p = pending_[k];
    if (pending_pos_[p] != k || !(node_state_[p] & kPending)) return "pending list inconsistent";
    const VertexSplit& vs = pm_.split(p);
    if (!(node_state_[vs.vt] & kLocked) || !(node_state_[vs.vu] & kLocked) || !ecolLegal(p))
      return "pending collapse " + str(p) + " is not locked/legal";
  }
  // No face flipped relative to its full-detail normal unless listed (the sub-pixel folds of
  // collapses, and faces splits left against that normal without turning them over).
  for (uint32_t f : active_faces_) {
    if (flipped(f) && std::find(folded_.begin(), folded_.end(), f) == folded_.end())
      return "face " + str(f) + " is flipped relative to its full-detail normal";
  }
  return "";
}

}  // namespace lodline
