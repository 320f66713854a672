// Temporal smoothing of the quantities lines are drawn from (Jeong, Ni, Lee, Markosian 2005,
// "Detail control in line drawings of 3D meshes", §3.3): per-vertex normals, radial
// curvature kr and its derivative Dw kr are blended over frames, p ← (1−w)·p + w·q, with
// w = 1 − (1−α)^(1/n), n = f·t, so a new value is reached to a fraction α within t seconds at
// f frames per second. Under level of detail the state follows the vertex hierarchy: a
// vertex created by a split starts from its parent's smoothed values, a collapse hands the
// mean of its two children's values to the parent.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "lines/view_quantities.h"

namespace lodline {

class AdaptiveMesh;

/// Defaults: α = 0.9 reached within t = 0.8 s; f is the capture frame rate when capturing
/// and the measured frame rate when viewing.
struct SmoothingParams {
  bool enabled = true;  ///< false: lines follow the raw values (`--smoothing off`)
  float alpha = 0.9f;   ///< fraction of a new value reached within `seconds`
  float seconds = 0.8f; ///< t, seconds
};

/// w = 1 − (1−α)^(1/(f·t)); 1 (no smoothing) when f·t ≤ 1. E.g. α 0.9, t 0.8 s, f 25 → 0.1087.
float smoothingWeight(float alpha, float seconds, float fps);

class TemporalSmoother {
 public:
  /// Forgets all state: the next blend() takes the raw values as they are.
  void reset() { initialized_ = false; }

  /// Carries the state across the last adapt() of `lod` (slots whose PM node changed inherit
  /// from the hierarchy as described above). Call once per adapt, before blend().
  void followHierarchy(const AdaptiveMesh& lod);

  /// Blends this frame's raw normals into the state (weight `w`) and renormalises; returns the
  /// smoothed normals (vertexCount entries).
  std::span<const glm::vec3> blendNormals(std::span<const glm::vec3> raw, float w);

  /// Blends kr and Dw kr of `view` into the state and writes the smoothed values back into
  /// `view`, recomputing the suggestive-contour test from them (sc_num = sinθ·Dw kr −
  /// threshold·cosθ, sc_den = cosθ, as computeViewQuantities does). `sc_threshold` as there.
  void blendView(ViewQuantities& view, float w, float sc_threshold);
  /// Per vertex, how much the smoothed kr (kr·sin²θ, as ViewQuantities holds it) changed in
  /// the last blendView(): what moves the smoothed zero sets across the surface (0 for
  /// vertices without history).
  std::span<const float> krChange() const { return kr_change_; }

  /// Blends Dw kr at `vertices` only (when it is computed only next to kr zero crossings,
  /// see ShapeParams::lazy_derivatives) and recomputes the suggestive-contour test there. A
  /// vertex's Dw kr keeps its history only across consecutive calls that include it (or its
  /// parent/children, through followHierarchy); otherwise it starts from this frame's value.
  void blendSuggestive(ViewQuantities& view, std::span<const uint32_t> vertices, float w,
                       float sc_threshold);

 private:
  bool initialized_ = false;
  bool view_initialized_ = false;
  std::vector<glm::vec3> normals_;
  std::vector<float> kr_, dwkr_;
  std::vector<float> kr_change_;  // blendView: new − old smoothed kr per slot
  // blendSuggestive: per slot, the call (dw_frame_) that last blended its Dw kr (0: never).
  std::vector<uint32_t> dwkr_frame_;
  uint32_t dw_frame_ = 0;
  std::vector<uint8_t> fresh_;  // per slot: no history, take this frame's values
  // Hierarchy bookkeeping: PM node held by each slot after the last followHierarchy(), and
  // the slot of each node (kNoSlot when inactive).
  std::vector<uint32_t> slot_node_, node_slot_;
  std::vector<uint32_t> changed_;  // scratch: slots whose node changed this frame
  std::vector<glm::vec3> prev_normals_;  // scratch: last frame's values during followHierarchy
  std::vector<float> prev_kr_, prev_dwkr_;
  std::vector<uint32_t> prev_dwkr_frame_;
};

}  // namespace lodline
