// Temporal smoothing of the quantities lines are drawn from (Jeong, Ni, Lee, Markosian 2005,
// "Detail control in line drawings of 3D meshes", §3.3): per-vertex normals, radial
// curvature kr and its derivative Dw kr are blended over frames, p ← (1−w)·p + w·q, with
// w = 1 − (1−α)^(1/n), n = f·t, so a new value is reached to a fraction α within t seconds at
// f frames per second. Under level of detail the state follows the vertex hierarchy: a
// vertex created by a split starts from its parent's smoothed values, a collapse hands the
// mean of its two children's values to the parent.
#pragma once

#include <array>
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
  /// Per-vertex quantities of the other line kinds (docs/lines.md), smoothed like kr: the
  /// principal curvatures (ridges, valleys, parabolic lines, principal highlights), the
  /// apparent ridges' q1 and Dt1 q1 (with its direction t1), and the ridges' and valleys'
  /// derivatives C(e1,e1,e1) and C(e2,e2,e2) (with their principal directions).
  enum Channel { kK1 = 0, kK2, kQ1, kDt1q1, kC111, kC222, kChannelCount };

  /// Forgets all state: the next blend() takes the raw values as they are.
  void reset() {
    initialized_ = false;
    for (Extra& e : extra_) e.on = e.dir_on = false;
  }

  /// Carries the state across the last adapt() of `lod` (slots whose PM node changed inherit
  /// from the hierarchy as described above). Call once per adapt, before blend().
  void followHierarchy(const AdaptiveMesh& lod);

  /// Blends this frame's raw normals into the state (weight `w`) and renormalises; returns the
  /// smoothed normals (vertexCount entries).
  std::span<const glm::vec3> blendNormals(std::span<const glm::vec3> raw, float w);

  /// Blends kr and Dw kr of `view` into the state and writes the smoothed values back into
  /// `view`, recomputing the suggestive-contour test from them (sc_num = sinθ·Dw kr −
  /// threshold·cosθ, as computeViewQuantities does). `sc_threshold` as there.
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

  /// Blends this frame's `raw` values of channel `c` into its state (weight `w`; vertices
  /// without history take their raw value) and returns the smoothed values.
  std::span<const float> blendScalar(Channel c, std::span<const float> raw, float w);
  /// Blends a direction known only up to sign (`dir`, unit) and a value whose sign follows it
  /// (`value`, channel `c`), in place: each raw pair is first turned to agree with the
  /// smoothed direction, then both are blended (the direction renormalised). `valid`
  /// (optional, one byte per vertex): where 0, the raw pair is not known this frame (lazily
  /// computed quantities); it is left as it is and the vertex's history is dropped.
  void blendDirected(Channel c, std::span<glm::vec3> dir, std::span<float> value, float w,
                     std::span<const uint8_t> valid = {});
  /// Forgets channel `c` (with its direction): its next blend takes the raw values.
  void resetChannel(Channel c) { extra_[c].on = extra_[c].dir_on = false; }
  /// Whether channel `c` holds history (a blend since its last reset).
  bool channelOn(Channel c) const { return extra_[c].on; }

 private:
  struct Extra {
    bool on = false;
    std::vector<float> v, prev;
    std::vector<uint8_t> fresh;  // per slot: no history
    bool dir_on = false;         // blendDirected(): the smoothed direction the value follows
    std::vector<glm::vec3> dir, prev_dir;
  };
  std::array<Extra, kChannelCount> extra_;
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
