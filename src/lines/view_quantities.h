// Per-view, per-vertex quantities of the line drawing: n·v, radial curvature and its
// directional derivative, and the suggestive-contour test.
//
// Papers: D. DeCarlo, A. Finkelstein, S. Rusinkiewicz, A. Santella, "Suggestive Contours for
// Conveying Shape" (SIGGRAPH 2003), §3–4 (kr, Dw kr > 0, the tanθ-scaled threshold); D.
// DeCarlo, A. Finkelstein, S. Rusinkiewicz, "Interactive Rendering of Suggestive Contours
// with Temporal Coherence" (NPAR 2004), §3 (Dw kr = C(w,w,w) − 2·τ²·cotθ, the term for w
// turning as one moves along w). See docs/design.md §3.4.
//
// Notation: v̂ = unit vector from the surface point to the eye, θ = angle between n and v̂,
// w = projection of v̂ onto the tangent plane (|w| = sinθ), ŵ = w/|w|, u = v̂·e1, v = v̂·e2
// in the principal frame (u² + v² = sin²θ), τ = II(ŵ, ŵ⊥) = (k2 − k1)·u·v/(u² + v²).
// The signs were checked against finite differences of the analytic torus (tests/lines).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "core/camera.h"
#include "core/worker_pool.h"
#include "shape/shape_cache.h"

namespace lodline {

/// Where the view vector at a vertex points.
struct ViewSpec {
  bool orthographic = false;       ///< false: perspective, v̂ = normalize(eye − p)
  glm::vec3 eye{0.0f, 0.0f, 3.0f}; ///< perspective eye position, model units
  /// Orthographic: unit direction from the scene toward the viewer (v̂ for every vertex).
  glm::vec3 toward_viewer{0.0f, 0.0f, 1.0f};

  /// The view of `cam` (orthographic cameras look along cam.forward()).
  static ViewSpec fromCamera(const Camera& cam);
};

/// Caller-owned outputs of computeViewQuantities(); every array gets vertexCount floats.
/// Reused between frames (no allocation once sized).
struct ViewQuantities {
  ViewSpec view;              ///< the view they were computed for
  std::vector<float> ndotv;   ///< n·v̂ = cosθ (> 0 front-facing)
  std::vector<float> kr;      ///< kr·sin²θ = k1·u² + k2·v² (same zero set and sign as kr)
  std::vector<float> dwkr;    ///< Dw kr = C(ŵ,ŵ,ŵ) − 2·τ²·cotθ, 1/units²; 0 where sinθ < 1e-6
  /// Suggestive-contour test: keep kr = 0 points where sc_num/ndotv > 0, i.e.
  /// tanθ·Dw kr > threshold. sc_num = sinθ·Dw kr − threshold·cosθ (no division by n·v; the
  /// denominator cosθ is ndotv itself). Empty when the fields carry no derivative tensor.
  std::vector<float> sc_num;
  /// Suggestive-highlight test (DeCarlo & Rusinkiewicz 2007): −tanθ·Dw kr > threshold, as
  /// sh_num = −sinθ·Dw kr − threshold·cosθ over ndotv; filled by suggestiveHighlightTest().
  std::vector<float> sh_num;
  /// Level-set kinds (lines/level_lines.h); each empty when its kind is off.
  std::vector<float> isophote, isophote_test;    ///< wave of n·l/spacing; n·l > −spacing/2
  std::vector<float> topo;                       ///< wave of height/spacing
  std::vector<float> parabolic, parabolic_test;  ///< k1·k2·fs²; max|k|·fs − threshold
};

/// Fills `out` for the view `view`. `sc_threshold` is the absolute threshold on tanθ·Dw kr
/// in 1/units² (LineParams::suggestive_threshold / fs²). `fields` must hold vertexCount
/// entries in every array (dcurv may be empty: then dwkr and sc_num are left empty).
/// `pool` (optional) splits the vertices over its threads; the result is the same.
void computeViewQuantities(const SurfaceFields& fields, const ViewSpec& view, float sc_threshold,
                           ViewQuantities& out, WorkerPool* pool = nullptr);

/// The derivative quantities alone (dwkr, sc_num), at `vertices` only: sizes those
/// arrays to vertexCount and leaves the other entries as they were. Same values as
/// computeViewQuantities gives there; fields.dcurv must be current at `vertices` (a lazily
/// evaluated ShapeCache computes it only where suggestive contours can be).
void computeSuggestiveQuantities(const SurfaceFields& fields, const ViewSpec& view, float sc_threshold,
                                 std::span<const uint32_t> vertices, ViewQuantities& out);

/// The motion fade of suggestive contours (DeCarlo, Finkelstein, Rusinkiewicz 2004, §4): a
/// suggestive contour moves across the surface as the view changes, at a speed of
/// |∂kr/∂t| / Dw kr along ŵ (the zero set of kr moves where kr changes, slowly where kr
/// rises steeply), which the image shows foreshortened by cosθ. Per vertex, `out` gets
/// 1 − smoothstep(start_px_s, end_px_s, that speed in px/s), with ∂kr/∂t from `kr_change`
/// (the change of the smoothed kr·sin²θ over the last `dt` seconds, TemporalSmoother::
/// krChange()) and the pixels per model unit at the vertex's depth for an image
/// `image_height` px high. 1 where the speed is unknown (no change recorded, Dw kr ≤ 0,
/// sinθ ≈ 0). `view` must hold this frame's (smoothed) n·v, kr and Dw kr.
void suggestiveMotionGain(std::span<const glm::vec3> positions, const ViewQuantities& view,
                          std::span<const float> kr_change, const Camera& camera, int image_height, float dt,
                          float start_px_s, float end_px_s, std::vector<float>& out, WorkerPool* pool = nullptr);

/// Fills view.sh_num from view.sc_num and view.ndotv (sinθ·Dw kr = sc_num + threshold·cosθ),
/// so it follows whatever smoothing the suggestive test had; cleared when sc_num is empty.
void suggestiveHighlightTest(float sc_threshold, ViewQuantities& view);

/// The suggestive-contour test from n·v and Dw kr (as computeViewQuantities forms it).
/// Its denominator is ndotv.
inline float suggestiveTest(float ndotv, float dwkr, float sc_threshold) {
  return std::sqrt(std::max(0.0f, 1.0f - ndotv * ndotv)) * dwkr - sc_threshold * ndotv;
}

}  // namespace lodline
