// DeCarlo et al. 2003 §3–4 and DeCarlo et al. 2004 §3; see view_quantities.h.
#include "lines/view_quantities.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

namespace lodline {

ViewSpec ViewSpec::fromCamera(const Camera& cam) {
  ViewSpec v;
  v.orthographic = cam.orthographic;
  v.eye = cam.eye;
  v.toward_viewer = -cam.forward();
  return v;
}

namespace {

// n·v̂ and the coordinates (u, v) of v̂ in the principal frame at vertex i.
struct ViewAt {
  float ndotv, u, v;
};
inline ViewAt viewAt(const SurfaceFields& s, const ViewSpec& view, const glm::vec3& ortho_dir,
                     size_t i) {
  glm::vec3 vdir = ortho_dir;
  if (!view.orthographic) {
    const glm::vec3 d = view.eye - s.positions[i];
    const float len = glm::length(d);
    vdir = len > 0.0f ? d / len : s.normals[i];
  }
  return {glm::dot(vdir, s.normals[i]), glm::dot(vdir, s.pdir1[i]), glm::dot(vdir, s.pdir2[i])};
}

// sinθ·Dw kr and Dw kr at vertex i (0 where sinθ vanishes).
inline void derivativeAt(const SurfaceFields& s, size_t i, const ViewAt& va, float& sin_dwkr,
                         float& dwkr) {
  const float u = va.u, v = va.v, u2 = u * u, v2 = v * v;
  const float sin2 = u2 + v2;
  sin_dwkr = dwkr = 0.0f;
  if (!(sin2 > 1e-12f)) return;
  const glm::vec4& c = s.dcurv[i];
  // C(w,w,w) with the unnormalised w = (u, v): sin³θ·C(ŵ,ŵ,ŵ).
  const float cwww = u2 * (u * c[0] + 3.0f * v * c[1]) + v2 * (3.0f * u * c[2] + v * c[3]);
  const float csc2 = 1.0f / sin2;
  const float tau = (s.k2[i] - s.k1[i]) * u * v * csc2;
  // sinθ·Dw kr = sinθ·C(ŵ,ŵ,ŵ) − 2·τ²·cosθ.
  sin_dwkr = cwww * csc2 - 2.0f * va.ndotv * tau * tau;
  dwkr = sin_dwkr / std::sqrt(sin2);
}

}  // namespace

void computeViewQuantities(const SurfaceFields& s, const ViewSpec& view, float sc_threshold,
                           ViewQuantities& out, WorkerPool* pool) {
  const size_t nv = s.positions.size();
  const bool with_derivs = s.dcurv.size() == nv && nv > 0;
  out.ndotv.resize(nv);
  out.kr.resize(nv);
  out.dwkr.resize(with_derivs ? nv : 0);
  out.sc_num.resize(with_derivs ? nv : 0);
  out.sc_den.resize(with_derivs ? nv : 0);
  const glm::vec3 ortho_dir = glm::normalize(view.toward_viewer);
  auto range = [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      const ViewAt va = viewAt(s, view, ortho_dir, i);
      out.ndotv[i] = va.ndotv;
      const float u2 = va.u * va.u, v2 = va.v * va.v;
      out.kr[i] = s.k1[i] * u2 + s.k2[i] * v2;
      if (!with_derivs) continue;
      float sin_dwkr, dwkr;
      derivativeAt(s, i, va, sin_dwkr, dwkr);
      out.dwkr[i] = dwkr;
      out.sc_num[i] = sin_dwkr - sc_threshold * va.ndotv;
      out.sc_den[i] = va.ndotv;
    }
  };
  if (pool) {
    pool->forRange(nv, 4096, range);
  } else {
    range(0, nv);
  }
}

void computeSuggestiveQuantities(const SurfaceFields& s, const ViewSpec& view, float sc_threshold,
                                 std::span<const uint32_t> vertices, ViewQuantities& out) {
  const size_t nv = s.positions.size();
  if (s.dcurv.size() != nv) return;
  out.dwkr.resize(nv, 0.0f);
  out.sc_num.resize(nv, 0.0f);
  out.sc_den.resize(nv, 0.0f);
  const glm::vec3 ortho_dir = glm::normalize(view.toward_viewer);
  for (uint32_t i : vertices) {
    if (i >= nv) continue;
    const ViewAt va = viewAt(s, view, ortho_dir, i);
    float sin_dwkr, dwkr;
    derivativeAt(s, i, va, sin_dwkr, dwkr);
    out.dwkr[i] = dwkr;
    out.sc_num[i] = sin_dwkr - sc_threshold * va.ndotv;
    out.sc_den[i] = va.ndotv;
  }
}

void suggestiveMotionGain(std::span<const glm::vec3> positions, const ViewQuantities& view,
                          std::span<const float> kr_change, const Camera& camera, int image_height, float dt,
                          float start_px_s, float end_px_s, std::vector<float>& out, WorkerPool* pool) {
  const size_t n = positions.size();
  out.assign(n, 1.0f);
  if (view.dwkr.size() != n || view.ndotv.size() != n || kr_change.size() != n || image_height <= 0 ||
      !(dt > 0.0f) || !(end_px_s > 0.0f))
    return;
  const float start = std::min(start_px_s, end_px_s);
  const glm::vec3 eye = camera.eye, fwd = camera.forward();
  // Pixels per model unit: the image height over the visible height at the vertex's depth.
  const float half_h = 0.5f * static_cast<float>(image_height);
  const float ortho_scale = static_cast<float>(image_height) / std::max(camera.ortho_height, 1e-12f);
  const float tan_half = std::tan(glm::radians(camera.fov_deg) * 0.5f);
  auto run = [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      const float c = view.ndotv[i], dw = view.dwkr[i], change = kr_change[i];
      const float sin2 = 1.0f - c * c;
      if (change == 0.0f || !(dw > 0.0f) || !(sin2 > 1e-6f)) continue;
      float px_per_unit = ortho_scale;
      if (!camera.orthographic) {
        const float z = glm::dot(positions[i] - eye, fwd);
        if (!(z > 0.0f)) continue;
        px_per_unit = half_h / (z * tan_half);
      }
      // The zero set moves |Δkr| / Dw kr along ŵ (kr here is kr·sin²θ), seen × cosθ.
      const float speed = std::abs(change) / (sin2 * dw) * std::abs(c) * px_per_unit / dt;
      if (!std::isfinite(speed) || speed >= end_px_s) {
        out[i] = 0.0f;
        continue;
      }
      if (speed <= start) continue;
      const float t = (speed - start) / (end_px_s - start);
      out[i] = 1.0f - t * t * (3.0f - 2.0f * t);
    }
  };
  if (pool) pool->forRange(n, 8192, run);
  else run(0, n);
}

}  // namespace lodline
