// DeCarlo et al. 2003 §3–4 and DeCarlo et al. 2004 §3; see view_quantities.h.
#include "lines/view_quantities.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace lodline {

ViewSpec ViewSpec::fromCamera(const Camera& cam) {
  ViewSpec v;
  v.orthographic = cam.orthographic;
  v.eye = cam.eye;
  v.toward_viewer = -cam.forward();
  return v;
}

void computeViewQuantities(const SurfaceFields& s, const ViewSpec& view, float sc_threshold,
                           ViewQuantities& out) {
  const size_t nv = s.positions.size();
  const bool with_derivs = s.dcurv.size() == nv && nv > 0;
  out.ndotv.resize(nv);
  out.kr.resize(nv);
  out.dwkr.resize(with_derivs ? nv : 0);
  out.sc_num.resize(with_derivs ? nv : 0);
  out.sc_den.resize(with_derivs ? nv : 0);
  const glm::vec3 ortho_dir = glm::normalize(view.toward_viewer);
  for (size_t i = 0; i < nv; ++i) {
    glm::vec3 vdir = ortho_dir;
    if (!view.orthographic) {
      const glm::vec3 d = view.eye - s.positions[i];
      const float len = glm::length(d);
      vdir = len > 0.0f ? d / len : s.normals[i];
    }
    const float ndotv = glm::dot(vdir, s.normals[i]);
    const float u = glm::dot(vdir, s.pdir1[i]), v = glm::dot(vdir, s.pdir2[i]);
    const float u2 = u * u, v2 = v * v;
    out.ndotv[i] = ndotv;
    out.kr[i] = s.k1[i] * u2 + s.k2[i] * v2;
    if (!with_derivs) continue;
    const float sin2 = u2 + v2;
    float sin_dwkr = 0.0f, dwkr = 0.0f;  // sinθ·Dw kr and Dw kr
    if (sin2 > 1e-12f) {
      const glm::vec4& c = s.dcurv[i];
      // C(w,w,w) with the unnormalised w = (u, v): sin³θ·C(ŵ,ŵ,ŵ).
      const float cwww = u2 * (u * c[0] + 3.0f * v * c[1]) + v2 * (3.0f * u * c[2] + v * c[3]);
      const float csc2 = 1.0f / sin2;
      const float tau = (s.k2[i] - s.k1[i]) * u * v * csc2;
      // sinθ·Dw kr = sinθ·C(ŵ,ŵ,ŵ) − 2·τ²·cosθ.
      sin_dwkr = cwww * csc2 - 2.0f * ndotv * tau * tau;
      dwkr = sin_dwkr / std::sqrt(sin2);
    }
    out.dwkr[i] = dwkr;
    out.sc_num[i] = sin_dwkr - sc_threshold * ndotv;
    out.sc_den[i] = ndotv;
  }
}

}  // namespace lodline
