#include "frame/temporal_smoothing.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "lod/adaptive_mesh.h"

namespace lodline {
namespace {
constexpr uint32_t kNoSlot = 0xffffffffu;
}

float smoothingWeight(float alpha, float seconds, float fps) {
  const float n = fps * seconds;
  if (!(n > 1.0f) || !(alpha > 0.0f) || alpha >= 1.0f) return 1.0f;
  return 1.0f - std::pow(1.0f - alpha, 1.0f / n);
}

void TemporalSmoother::followHierarchy(const AdaptiveMesh& lod) {
  const ProgressiveMesh& pm = lod.pm();
  const auto nodes = lod.slotVertices();
  const uint32_t n = static_cast<uint32_t>(nodes.size());
  if (node_slot_.size() != pm.nodeCount()) node_slot_.assign(pm.nodeCount(), kNoSlot);
  if (slot_node_.size() < n) slot_node_.resize(n, kPmNone);
  // Slots whose node changed, found by comparing with last frame's slot→node map (a linear
  // pass, ~0.1 ms per 100k slots). Within one adapt a node may split, collapse and move
  // between slots several times, so values follow node identity, not slot identity.
  changed_.clear();
  for (uint32_t s = 0; s < n; ++s)
    if (nodes[s] != slot_node_[s]) changed_.push_back(s);
  if (initialized_ && !changed_.empty() && !lod.changes().everything) {
    const bool view_state = view_initialized_;
    // Last frame's values, read by node through node_slot_ (still last frame's map).
    prev_normals_.assign(normals_.begin(), normals_.end());
    if (view_state) {
      prev_kr_.assign(kr_.begin(), kr_.end());
      prev_dwkr_.assign(dwkr_.begin(), dwkr_.end());
      prev_dwkr_frame_.assign(dwkr_frame_.begin(), dwkr_frame_.end());
      prev_dwkr_frame_.resize(prev_dwkr_.size(), 0);
    }
    if (fresh_.size() < n) fresh_.resize(n, 1);
    if (normals_.size() < n) normals_.resize(n, glm::vec3(0, 0, 1));
    if (view_state && kr_.size() < n) {
      kr_.resize(n, 0.0f);
      dwkr_.resize(n, 0.0f);
    }
    if (view_state) dwkr_frame_.resize(std::max<size_t>(dwkr_frame_.size(), n), 0);
    for (Extra& e : extra_) {
      if (!e.on) continue;
      e.prev.assign(e.v.begin(), e.v.end());
      if (e.v.size() < n) e.v.resize(n, 0.0f);
      e.fresh.resize(std::max<size_t>(e.fresh.size(), n), 1);
      if (!e.dir_on) continue;
      e.prev_dir.assign(e.dir.begin(), e.dir.end());
      if (e.dir.size() < n) e.dir.resize(n, glm::vec3(1, 0, 0));
    }
    auto old_slot = [&](uint32_t node) {
      const uint32_t s = node != kPmNone ? node_slot_[node] : kNoSlot;
      return s < prev_normals_.size() ? s : kNoSlot;
    };
    for (uint32_t s : changed_) {
      const uint32_t now = nodes[s];
      if (now == kPmNone) continue;  // freed slot
      fresh_[s] = 0;
      uint32_t a = old_slot(now), b = kNoSlot;  // the node itself, moved to another slot
      if (a == kNoSlot) a = old_slot(pm.parent[now]);  // split: start from the parent
      if (a == kNoSlot && !pm.isLeaf(now)) {           // collapse: mean of the children
        a = old_slot(pm.split(now).vt);
        b = old_slot(pm.split(now).vu);
        if (a == kNoSlot) std::swap(a, b);
      }
      for (Extra& e : extra_) {
        if (!e.on) continue;
        const bool has_a = a < e.prev.size(), has_b = b < e.prev.size();
        e.fresh[s] = !has_a;
        if (has_a) e.v[s] = has_b ? 0.5f * (e.prev[a] + e.prev[b]) : e.prev[a];
        if (!e.dir_on || a >= e.prev_dir.size()) continue;
        glm::vec3 t = e.prev_dir[a];
        if (b < e.prev_dir.size()) {  // the children's directions, agreed, averaged
          const glm::vec3 tb = e.prev_dir[b];
          const glm::vec3 m = t + (glm::dot(t, tb) < 0.0f ? -tb : tb);
          if (glm::length(m) > 1e-12f) t = glm::normalize(m);
          // The value's sign follows the direction: the second child's counts flipped.
          if (glm::dot(e.prev_dir[a], tb) < 0.0f && has_a && has_b) e.v[s] = 0.5f * (e.prev[a] - e.prev[b]);
        }
        e.dir[s] = t;
      }
      if (a == kNoSlot) {
        fresh_[s] = 1;  // several levels at once: no meaningful history
        if (view_state) dwkr_frame_[s] = 0;
        continue;
      }
      glm::vec3 nrm = prev_normals_[a];
      if (b != kNoSlot) {
        const glm::vec3 m = prev_normals_[a] + prev_normals_[b];
        if (glm::length(m) > 1e-12f) nrm = glm::normalize(m);
      }
      normals_[s] = nrm;
      if (view_state && a < prev_kr_.size()) {
        kr_[s] = b != kNoSlot && b < prev_kr_.size() ? 0.5f * (prev_kr_[a] + prev_kr_[b]) : prev_kr_[a];
        dwkr_[s] = b != kNoSlot && b < prev_kr_.size() ? 0.5f * (prev_dwkr_[a] + prev_dwkr_[b]) : prev_dwkr_[a];
        // Lazily computed Dw kr: the history is as recent as the older of the two sources.
        dwkr_frame_[s] = b != kNoSlot && b < prev_kr_.size()
                             ? std::min(prev_dwkr_frame_[a], prev_dwkr_frame_[b])
                             : prev_dwkr_frame_[a];
      }
    }
  }
  if (lod.changes().everything) {
    // Everything was rebuilt (fully refined/coarsened): no meaningful history.
    initialized_ = false;
    view_initialized_ = false;
    for (Extra& e : extra_) e.on = e.dir_on = false;
  }
  // The new map.
  for (uint32_t s : changed_) {
    const uint32_t before = slot_node_[s];
    if (before != kPmNone && node_slot_[before] == s) node_slot_[before] = kNoSlot;
  }
  for (uint32_t s : changed_) {
    slot_node_[s] = nodes[s];
    if (nodes[s] != kPmNone) node_slot_[nodes[s]] = s;
  }
}

std::span<const glm::vec3> TemporalSmoother::blendNormals(std::span<const glm::vec3> raw, float w) {
  if (!initialized_) {
    normals_.assign(raw.begin(), raw.end());
    fresh_.assign(raw.size(), 0);
    initialized_ = true;
    view_initialized_ = false;
    return normals_;
  }
  normals_.resize(raw.size());
  fresh_.resize(raw.size(), 1);
  for (size_t i = 0; i < raw.size(); ++i) {
    const glm::vec3 b = fresh_[i] ? raw[i] : (1.0f - w) * normals_[i] + w * raw[i];
    const float len = glm::length(b);
    normals_[i] = len > 1e-12f ? b / len : raw[i];
  }
  return normals_;
}

void TemporalSmoother::blendView(ViewQuantities& view, float w, float sc_threshold) {
  const size_t n = view.kr.size();
  if (!view_initialized_) {
    kr_.assign(view.kr.begin(), view.kr.end());
    dwkr_.assign(n, 0.0f);
    if (view.dwkr.size() == n) dwkr_.assign(view.dwkr.begin(), view.dwkr.end());
    dwkr_frame_.assign(n, 0);
    view_initialized_ = true;
  }
  kr_.resize(n, 0.0f);
  dwkr_.resize(n, 0.0f);
  kr_change_.assign(n, 0.0f);
  const bool has_dw = view.dwkr.size() == n;
  fresh_.resize(n, 1);
  dwkr_frame_.resize(n, 0);
  for (size_t i = 0; i < n; ++i) {
    const float wi = fresh_[i] ? 1.0f : w;  // fresh vertices start from this frame's values
    const bool fresh = fresh_[i] != 0;
    if (fresh_[i]) dwkr_frame_[i] = 0;
    fresh_[i] = 0;
    const float before = kr_[i];
    kr_[i] = (1.0f - wi) * kr_[i] + wi * view.kr[i];
    if (!fresh) kr_change_[i] = kr_[i] - before;
    view.kr[i] = kr_[i];
    if (has_dw) {
      dwkr_[i] = (1.0f - wi) * dwkr_[i] + wi * view.dwkr[i];
      view.dwkr[i] = dwkr_[i];
    }
  }
  if (has_dw && view.sc_num.size() == n) {
    for (size_t i = 0; i < n; ++i) view.sc_num[i] = suggestiveTest(view.ndotv[i], view.dwkr[i], sc_threshold);
  }
}

void TemporalSmoother::blendSuggestive(ViewQuantities& view, std::span<const uint32_t> vertices,
                                       float w, float sc_threshold) {
  const size_t n = view.ndotv.size();
  if (view.dwkr.size() != n || view.sc_num.size() != n) return;
  dwkr_.resize(n, 0.0f);
  dwkr_frame_.resize(n, 0);
  ++dw_frame_;
  for (uint32_t i : vertices) {
    if (i >= n) continue;
    const bool continuous = dwkr_frame_[i] != 0 && dwkr_frame_[i] + 1 == dw_frame_;
    const float wi = continuous ? w : 1.0f;
    dwkr_[i] = (1.0f - wi) * dwkr_[i] + wi * view.dwkr[i];
    dwkr_frame_[i] = dw_frame_;
    view.dwkr[i] = dwkr_[i];
    view.sc_num[i] = suggestiveTest(view.ndotv[i], view.dwkr[i], sc_threshold);
  }
}

std::span<const float> TemporalSmoother::blendScalar(Channel c, std::span<const float> raw, float w) {
  Extra& e = extra_[c];
  const size_t n = raw.size();
  if (!e.on) {
    e.v.assign(raw.begin(), raw.end());
    e.fresh.assign(n, 0);
    e.on = true;
    return e.v;
  }
  e.v.resize(n, 0.0f);
  e.fresh.resize(n, 1);
  for (size_t i = 0; i < n; ++i) {
    e.v[i] = e.fresh[i] ? raw[i] : (1.0f - w) * e.v[i] + w * raw[i];
    e.fresh[i] = 0;
  }
  return e.v;
}

void TemporalSmoother::blendDirected(Channel c, std::span<glm::vec3> dir, std::span<float> value, float w,
                                     std::span<const uint8_t> valid) {
  Extra& e = extra_[c];
  const size_t n = dir.size();
  if (value.size() != n) return;
  const bool partial = valid.size() == n;
  if (!e.on || !e.dir_on) {
    e.dir.assign(dir.begin(), dir.end());
    e.v.assign(value.begin(), value.end());
    e.fresh.assign(n, 0);
    if (partial)
      for (size_t i = 0; i < n; ++i) e.fresh[i] = valid[i] == 0;
    e.on = e.dir_on = true;
    return;
  }
  e.dir.resize(n, glm::vec3(1, 0, 0));
  e.v.resize(n, 0.0f);
  e.fresh.resize(n, 1);
  for (size_t i = 0; i < n; ++i) {
    if (partial && !valid[i]) {
      e.fresh[i] = 1;
      continue;
    }
    glm::vec3 d = dir[i];
    float v = value[i];
    if (!e.fresh[i]) {
      if (glm::dot(d, e.dir[i]) < 0.0f) {  // agree with the smoothed direction
        d = -d;
        v = -v;
      }
      const glm::vec3 b = (1.0f - w) * e.dir[i] + w * d;
      const float len = glm::length(b);
      d = len > 1e-12f ? b / len : d;
      v = (1.0f - w) * e.v[i] + w * v;
    }
    e.fresh[i] = 0;
    e.dir[i] = dir[i] = d;
    e.v[i] = value[i] = v;
  }
}

}  // namespace lodline
