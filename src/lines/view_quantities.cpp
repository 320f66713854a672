// DeCarlo et al. 2003 §3–4 and DeCarlo et al. 2004 §3; see view_quantities.h.
#include "lines/view_quantities.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "core/simd_clones.h"

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
    vdir = len > 0.0f ? d * (1.0f / len) : s.normals[i];
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
  const float csc = 1.0f / std::sqrt(sin2), csc2 = csc * csc;
  const float tau = (s.k2[i] - s.k1[i]) * u * v * csc2;
  // sinθ·Dw kr = sinθ·C(ŵ,ŵ,ŵ) − 2·τ²·cosθ.
  sin_dwkr = cwww * csc2 - 2.0f * va.ndotv * tau * tau;
  dwkr = sin_dwkr * csc;
}

}  // namespace

namespace {

// Flat views of computeViewQuantities()' inputs and outputs.
struct ViewArrays {
  const float* pos;
  const float* nrm;
  const float* pd1;
  const float* pd2;
  const float* k1;
  const float* k2;
  const float* dc;
  float* ndotv;
  float* kr;
  float* dwkr;
  float* num;
  float ex, ey, ez, ox, oy, oz, sc_threshold;
};

// The arithmetic of viewAt() and derivativeAt() (computeSuggestiveQuantities() must agree
// bit for bit), without branches, over blocks of vertices whose vec3 fields are first copied
// to plain per-component arrays, so that the compiler runs it four vertices at a time: the
// square roots and divisions are most of the view stage's time (one of each for the view
// direction and one of each for the derivative: their reciprocals are multiplied by).
template <bool kOrtho, bool kDerivs>
[[gnu::always_inline]] inline void viewRange(const ViewArrays& a, size_t begin, size_t end) {
  // Whole blocks in local arrays (a short last block padded with harmless values): a fixed
  // trip count over memory nothing else aliases is what the vectoriser needs.
  constexpr size_t kBlock = 64;
  alignas(16) float nx[kBlock], ny[kBlock], nz[kBlock], dx[kBlock], dy[kBlock], dz[kBlock];
  alignas(16) float p1x[kBlock], p1y[kBlock], p1z[kBlock], p2x[kBlock], p2y[kBlock], p2z[kBlock];
  alignas(16) float c0[kBlock], c1[kBlock], c2[kBlock], c3[kBlock], k1[kBlock], k2[kBlock];
  alignas(16) float o_ndotv[kBlock], o_kr[kBlock], o_dwkr[kBlock], o_num[kBlock];
  const float ex = a.ex, ey = a.ey, ez = a.ez, ox = a.ox, oy = a.oy, oz = a.oz, thr = a.sc_threshold;
  for (size_t b = begin; b < end; b += kBlock) {
    const size_t n = std::min(kBlock, end - b);
    for (size_t j = 0; j < n; ++j) {
      const size_t i = b + j;
      nx[j] = a.nrm[3 * i];
      ny[j] = a.nrm[3 * i + 1];
      nz[j] = a.nrm[3 * i + 2];
      if constexpr (!kOrtho) {
        dx[j] = ex - a.pos[3 * i];
        dy[j] = ey - a.pos[3 * i + 1];
        dz[j] = ez - a.pos[3 * i + 2];
      }
      p1x[j] = a.pd1[3 * i];
      p1y[j] = a.pd1[3 * i + 1];
      p1z[j] = a.pd1[3 * i + 2];
      p2x[j] = a.pd2[3 * i];
      p2y[j] = a.pd2[3 * i + 1];
      p2z[j] = a.pd2[3 * i + 2];
      k1[j] = a.k1[i];
      k2[j] = a.k2[i];
      if constexpr (kDerivs) {
        c0[j] = a.dc[4 * i];
        c1[j] = a.dc[4 * i + 1];
        c2[j] = a.dc[4 * i + 2];
        c3[j] = a.dc[4 * i + 3];
      }
    }
    for (size_t j = n; j < kBlock; ++j) {
      nx[j] = ny[j] = nz[j] = dx[j] = dy[j] = dz[j] = 1.0f;
      p1x[j] = p1y[j] = p1z[j] = p2x[j] = p2y[j] = p2z[j] = 1.0f;
      c0[j] = c1[j] = c2[j] = c3[j] = k1[j] = k2[j] = 0.0f;
    }
    for (size_t j = 0; j < kBlock; ++j) {
      float vx = ox, vy = oy, vz = oz;
      if constexpr (!kOrtho) {
        const float len = std::sqrt(dx[j] * dx[j] + dy[j] * dy[j] + dz[j] * dz[j]);
        const bool far = len > 0.0f;
        const float inv = 1.0f / (far ? len : 1.0f);
        const float qx = dx[j] * inv, qy = dy[j] * inv, qz = dz[j] * inv;
        vx = far ? qx : nx[j];
        vy = far ? qy : ny[j];
        vz = far ? qz : nz[j];
      }
      const float ndotv = vx * nx[j] + vy * ny[j] + vz * nz[j];
      const float u = vx * p1x[j] + vy * p1y[j] + vz * p1z[j];
      const float v = vx * p2x[j] + vy * p2y[j] + vz * p2z[j];
      o_ndotv[j] = ndotv;
      const float u2 = u * u, v2 = v * v;
      o_kr[j] = k1[j] * u2 + k2[j] * v2;
      if constexpr (kDerivs) {
        const float sin2 = u2 + v2;
        const bool ok = sin2 > 1e-12f;
        const float s2 = ok ? sin2 : 1.0f;
        const float cwww = u2 * (u * c0[j] + 3.0f * v * c1[j]) + v2 * (3.0f * u * c2[j] + v * c3[j]);
        const float csc = 1.0f / std::sqrt(s2), csc2 = csc * csc;
        const float tau = (k2[j] - k1[j]) * u * v * csc2;
        const float sd = cwww * csc2 - 2.0f * ndotv * tau * tau;
        const float sin_dwkr = ok ? sd : 0.0f;
        const float dw = sin_dwkr * csc;
        o_dwkr[j] = ok ? dw : 0.0f;
        o_num[j] = sin_dwkr - thr * ndotv;
      }
    }
    std::copy_n(o_ndotv, n, a.ndotv + b);
    std::copy_n(o_kr, n, a.kr + b);
    if constexpr (kDerivs) {
      std::copy_n(o_dwkr, n, a.dwkr + b);
      std::copy_n(o_num, n, a.num + b);
    }
  }
}

// viewRange() for the view's kind, compiled three times: for AVX-512F and AVX2 (sixteen and
// eight vertices a step) where the processor has them, and for plain x86-64. No FMA in any,
// so all give the same bits.
LODLINE_AVX512_CLONES void viewRangeOf(const ViewArrays& a, bool ortho, bool derivs, size_t begin, size_t end) {
  if (ortho) {
    if (derivs) viewRange<true, true>(a, begin, end);
    else viewRange<true, false>(a, begin, end);
  } else {
    if (derivs) viewRange<false, true>(a, begin, end);
    else viewRange<false, false>(a, begin, end);
  }
}

}  // namespace

void computeViewQuantities(const SurfaceFields& s, const ViewSpec& view, float sc_threshold,
                           ViewQuantities& out, WorkerPool* pool) {
  const size_t nv = s.positions.size();
  const bool with_derivs = s.dcurv.size() == nv && nv > 0;
  out.view = view;
  out.ndotv.resize(nv);
  out.kr.resize(nv);
  out.dwkr.resize(with_derivs ? nv : 0);
  out.sc_num.resize(with_derivs ? nv : 0);
  if (nv == 0) return;
  const glm::vec3 ortho_dir = glm::normalize(view.toward_viewer);
  const ViewArrays a{&s.positions[0].x, &s.normals[0].x, &s.pdir1[0].x, &s.pdir2[0].x, s.k1.data(), s.k2.data(),
                     with_derivs ? &s.dcurv[0].x : nullptr, out.ndotv.data(), out.kr.data(), out.dwkr.data(),
                     out.sc_num.data(), view.eye.x, view.eye.y, view.eye.z, ortho_dir.x,
                     ortho_dir.y, ortho_dir.z, sc_threshold};
  auto range = [&](size_t begin, size_t end) { viewRangeOf(a, view.orthographic, with_derivs, begin, end); };
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
  const glm::vec3 ortho_dir = glm::normalize(view.toward_viewer);
  for (uint32_t i : vertices) {
    if (i >= nv) continue;
    const ViewAt va = viewAt(s, view, ortho_dir, i);
    float sin_dwkr, dwkr;
    derivativeAt(s, i, va, sin_dwkr, dwkr);
    out.dwkr[i] = dwkr;
    out.sc_num[i] = sin_dwkr - sc_threshold * va.ndotv;
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

void suggestiveHighlightTest(float sc_threshold, ViewQuantities& view) {
  const size_t n = view.sc_num.size();
  if (n == 0 || view.ndotv.size() != n) {
    view.sh_num.clear();
    return;
  }
  view.sh_num.resize(n);
  const float two_t = 2.0f * sc_threshold;
  for (size_t i = 0; i < n; ++i) view.sh_num[i] = -view.sc_num[i] - two_t * view.ndotv[i];
}

}  // namespace lodline
