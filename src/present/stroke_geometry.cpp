#include "present/stroke_geometry.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "present/segment_grid.h"

namespace lodline {
namespace {

bool finite(glm::vec2 p) { return std::isfinite(p.x) && std::isfinite(p.y); }

// How far point i is from what the chord a-b predicts for it: its distance to the chord in
// pixels, its width's difference from the width interpolated there, and 5 × its opacity's
// (so 0.05 of opacity weighs like the 0.25 px tolerance).
float chordError(const StrokeGeometryScratch& s, bool with_u, uint32_t i, uint32_t a, uint32_t b) {
  const glm::vec2 p = s.points[i], pa = s.points[a], ab = s.points[b] - pa;
  const float t = nearestOnSegment(p, pa, ab);
  const float d = glm::length(p - (pa + t * ab));
  const float dw = std::abs(s.width[i] - (s.width[a] + t * (s.width[b] - s.width[a])));
  const float da = std::abs(s.alpha[i] - (s.alpha[a] + t * (s.alpha[b] - s.alpha[a])));
  const float du = with_u ? std::abs(s.u[i] - (s.u[a] + t * (s.u[b] - s.u[a]))) : 0.0f;
  return std::max({d, dw, du, 5.0f * da});
}

}  // namespace

void simplifyStroke(float tol, bool with_u, StrokeGeometryScratch& s) {
  const uint32_t n = static_cast<uint32_t>(s.points.size());
  if (n < 3 || !(tol > 0.0f)) return;
  s.keep.assign(n, 0);
  s.keep[0] = s.keep[n - 1] = 1;
  s.stack.clear();
  s.stack.emplace_back(0, n - 1);
  while (!s.stack.empty()) {
    const auto [a, b] = s.stack.back();
    s.stack.pop_back();
    float worst = -1.0f;
    uint32_t at = a;
    for (uint32_t i = a + 1; i < b; ++i) {
      const float e = chordError(s, with_u, i, a, b);
      if (e > worst) worst = e, at = i;
    }
    if (worst > tol) {
      s.keep[at] = 1;
      s.stack.emplace_back(a, at);
      s.stack.emplace_back(at, b);
    }
  }
  uint32_t m = 0;
  for (uint32_t i = 0; i < n; ++i)
    if (s.keep[i]) {
      s.points[m] = s.points[i];
      s.alpha[m] = s.alpha[i];
      s.width[m] = s.width[i];
      s.u[m] = s.u[i];
      ++m;
    }
  s.points.resize(m);
  s.alpha.resize(m);
  s.width.resize(m);
  s.u.resize(m);
}

namespace {

glm::vec2 perp(glm::vec2 t) { return {-t.y, t.x}; }

// One point of the stroke as drawn: half width (at least half a pixel), opacity (a width
// under a pixel fades instead), parameter.
struct Section {
  float half_width, alpha, u;
};

struct Emitter {
  std::vector<StrokeVertex>& out;
  float cap;

  StrokeVertex vertex(glm::vec2 px, glm::vec2 local, const Section& s, float piece_cap, float u) const {
    return {px, local, s.half_width, s.alpha, piece_cap, u};
  }
  // Two triangles: a0-a1 across one end, b0-b1 across the other (a0 and b0 on one side).
  void quad(const StrokeVertex& a0, const StrokeVertex& a1, const StrokeVertex& b0, const StrokeVertex& b1) {
    out.push_back(a0);
    out.push_back(a1);
    out.push_back(b0);
    out.push_back(a1);
    out.push_back(b1);
    out.push_back(b0);
  }
  // The band from `p` outwards along `dir` by `reach` (a cap or half a join's disc), e
  // either side: local.x runs 0 → reach, u moves with it by `u_sign`.
  void cap_piece(glm::vec2 p, glm::vec2 dir, const Section& s, float reach, float piece_cap, float u_sign) {
    const float e = s.half_width + 1.0f;
    const glm::vec2 n = perp(dir);
    const float u1 = s.u + u_sign * reach;
    quad(vertex(p + e * n, {0.0f, e}, s, piece_cap, s.u), vertex(p - e * n, {0.0f, -e}, s, piece_cap, s.u),
         vertex(p + reach * dir + e * n, {reach, e}, s, piece_cap, u1),
         vertex(p + reach * dir - e * n, {reach, -e}, s, piece_cap, u1));
  }
};

}  // namespace

size_t appendStrokeGeometry(std::span<const glm::vec2> points, std::span<const float> alpha,
                            std::span<const float> width, std::span<const float> u,
                            const StrokeGeometryParams& params,
                            std::vector<StrokeVertex>& out, StrokeGeometryScratch& scratch) {
  auto& P = scratch.points;
  auto& A = scratch.alpha;
  auto& Wd = scratch.width;
  auto& S = scratch.u;
  P.clear();
  A.clear();
  Wd.clear();
  S.clear();
  float last_arc = 0.0f;
  for (size_t i = 0; i < points.size(); ++i) {
    if (!finite(points[i])) continue;
    const float a = i < alpha.size() ? alpha[i] : 1.0f;
    float w = i < width.size() ? width[i] : 1.0f;
    if (!(w > 0.0f) || !std::isfinite(w)) w = 0.0f;
    if (!P.empty() && glm::length(points[i] - P.back()) < 1e-3f) {
      A.back() = std::max(A.back(), a);
      Wd.back() = std::max(Wd.back(), w);
      continue;
    }
    // The parameter: given, or the arc length so far (of the points kept).
    float arc = 0.0f;
    if (!P.empty()) arc = last_arc + glm::length(points[i] - P.back());
    last_arc = arc;
    S.push_back(i < u.size() && std::isfinite(u[i]) ? u[i] : arc);
    P.push_back(points[i]);
    A.push_back(a);
    Wd.push_back(w);
  }
  if (P.empty() || *std::max_element(Wd.begin(), Wd.end()) <= 0.0f) return 0;
  // A given parameter may jump (seams): its points are kept.
  simplifyStroke(params.simplify_px, !u.empty(), scratch);

  auto section = [&](size_t i) {
    const float w = Wd[i];
    return Section{0.5f * std::max(w, 1.0f), A[i] * std::min(w, 1.0f), S[i]};
  };
  Emitter emit{out, static_cast<float>(params.cap)};
  auto reach = [&](const Section& s) { return params.cap == StrokeCap::kButt ? 1.0f : s.half_width + 1.0f; };
  const float round = static_cast<float>(StrokeCap::kRound);
  if (P.size() == 1) {
    if (params.cap == StrokeCap::kButt) return 0;
    const Section s = section(0);
    emit.cap_piece(P[0], {1.0f, 0.0f}, s, reach(s), emit.cap, 1.0f);
    emit.cap_piece(P[0], {-1.0f, 0.0f}, s, reach(s), emit.cap, -1.0f);
    return 0;
  }
  const size_t n = P.size();
  glm::vec2 t = glm::normalize(P[1] - P[0]);
  Section s0 = section(0);
  emit.cap_piece(P[0], -t, s0, reach(s0), emit.cap, -1.0f);
  float e = s0.half_width + 1.0f;  // the band's reach from the centre line here
  StrokeVertex left = emit.vertex(P[0] + e * perp(t), {0.0f, e}, s0, emit.cap, s0.u);
  StrokeVertex right = emit.vertex(P[0] - e * perp(t), {0.0f, -e}, s0, emit.cap, s0.u);
  for (size_t i = 1; i < n; ++i) {
    const Section si = section(i);
    e = si.half_width + 1.0f;
    const glm::vec2 nrm = perp(t);
    if (i + 1 == n) {
      emit.quad(left, right, emit.vertex(P[i] + e * nrm, {0.0f, e}, si, emit.cap, si.u),
                emit.vertex(P[i] - e * nrm, {0.0f, -e}, si, emit.cap, si.u));
      break;
    }
    const glm::vec2 t2 = glm::normalize(P[i + 1] - P[i]);
    const glm::vec2 n2 = perp(t2);
    const glm::vec2 m = nrm + n2;
    const float m_len = glm::length(m);
    const float cos_half = m_len > 1e-6f ? glm::dot(m / m_len, nrm) : 0.0f;
    if (cos_half > 0.0f && 1.0f / cos_half <= params.miter_limit) {
      // Mitred: both sides meet on the bisector, at distance e from either segment's line.
      const glm::vec2 miter = (e / cos_half) * (m / m_len);
      const StrokeVertex l2 = emit.vertex(P[i] + miter, {0.0f, e}, si, emit.cap, si.u);
      const StrokeVertex r2 = emit.vertex(P[i] - miter, {0.0f, -e}, si, emit.cap, si.u);
      emit.quad(left, right, l2, r2);
      left = l2;
      right = r2;
    } else {
      // Round: the band ends square on both sides and a disc covers the outer wedge.
      emit.quad(left, right, emit.vertex(P[i] + e * nrm, {0.0f, e}, si, emit.cap, si.u),
                emit.vertex(P[i] - e * nrm, {0.0f, -e}, si, emit.cap, si.u));
      emit.cap_piece(P[i], t, si, e, round, 1.0f);
      emit.cap_piece(P[i], -t, si, e, round, -1.0f);
      left = emit.vertex(P[i] + e * n2, {0.0f, e}, si, emit.cap, si.u);
      right = emit.vertex(P[i] - e * n2, {0.0f, -e}, si, emit.cap, si.u);
    }
    t = t2;
  }
  const Section sn = section(n - 1);
  emit.cap_piece(P[n - 1], t, sn, reach(sn), emit.cap, 1.0f);
  return n - 1;
}


}  // namespace lodline
