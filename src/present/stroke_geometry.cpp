#include "present/stroke_geometry.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace lodline {
namespace {

bool finite(glm::vec2 p) { return std::isfinite(p.x) && std::isfinite(p.y); }

float distanceToSegment(glm::vec2 p, glm::vec2 a, glm::vec2 b) {
  const glm::vec2 ab = b - a;
  const float len2 = glm::dot(ab, ab);
  const float t = len2 > 0.0f ? std::clamp(glm::dot(p - a, ab) / len2, 0.0f, 1.0f) : 0.0f;
  return glm::length(p - (a + t * ab));
}

// Douglas–Peucker on scratch.points / scratch.alpha in place: keeps the ends and every
// point farther than `tol` from the chord of the section that holds it.
void simplify(float tol, StrokeGeometryScratch& s) {
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
      const float d = distanceToSegment(s.points[i], s.points[a], s.points[b]);
      if (d > worst) worst = d, at = i;
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
      ++m;
    }
  s.points.resize(m);
  s.alpha.resize(m);
}

glm::vec2 perp(glm::vec2 t) { return {-t.y, t.x}; }

struct Emitter {
  std::vector<StrokeVertex>& out;
  float half_width, alpha_scale, cap;

  StrokeVertex vertex(glm::vec2 px, glm::vec2 local, float alpha, float piece_cap) const {
    return {px, local, half_width, alpha * alpha_scale, piece_cap, 0.0f};
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
  // The band from `p` outwards along `dir` by `reach` (a cap or half a join's disc), `e`
  // either side: local.x runs 0 → reach.
  void cap_piece(glm::vec2 p, glm::vec2 dir, float e, float reach, float alpha, float piece_cap) {
    const glm::vec2 n = perp(dir);
    quad(vertex(p + e * n, {0.0f, e}, alpha, piece_cap), vertex(p - e * n, {0.0f, -e}, alpha, piece_cap),
         vertex(p + reach * dir + e * n, {reach, e}, alpha, piece_cap),
         vertex(p + reach * dir - e * n, {reach, -e}, alpha, piece_cap));
  }
};

}  // namespace

size_t appendStrokeGeometry(std::span<const glm::vec2> points, std::span<const float> alpha, float width_px,
                            const StrokeGeometryParams& params, std::vector<StrokeVertex>& out,
                            StrokeGeometryScratch& scratch) {
  if (!(width_px > 0.0f) || !std::isfinite(width_px)) return 0;
  const float half_width = 0.5f * std::max(width_px, 1.0f);
  const float alpha_scale = std::min(width_px, 1.0f);
  auto& P = scratch.points;
  auto& A = scratch.alpha;
  P.clear();
  A.clear();
  for (size_t i = 0; i < points.size(); ++i) {
    if (!finite(points[i])) continue;
    const float a = i < alpha.size() ? alpha[i] : 1.0f;
    if (!P.empty() && glm::length(points[i] - P.back()) < 1e-3f) {
      A.back() = std::max(A.back(), a);
      continue;
    }
    P.push_back(points[i]);
    A.push_back(a);
  }
  if (P.empty()) return 0;
  simplify(params.simplify_px, scratch);

  Emitter emit{out, half_width, alpha_scale, static_cast<float>(params.cap)};
  const float e = half_width + 1.0f;  // the band's reach from the centre line
  const float cap_reach = params.cap == StrokeCap::kButt ? 1.0f : e;
  const float round = static_cast<float>(StrokeCap::kRound);
  if (P.size() == 1) {
    if (params.cap == StrokeCap::kButt) return 0;
    emit.cap_piece(P[0], {1.0f, 0.0f}, e, cap_reach, A[0], emit.cap);
    emit.cap_piece(P[0], {-1.0f, 0.0f}, e, cap_reach, A[0], emit.cap);
    return 0;
  }
  const size_t n = P.size();
  glm::vec2 t = glm::normalize(P[1] - P[0]);
  emit.cap_piece(P[0], -t, e, cap_reach, A[0], emit.cap);
  StrokeVertex left = emit.vertex(P[0] + e * perp(t), {0.0f, e}, A[0], emit.cap);
  StrokeVertex right = emit.vertex(P[0] - e * perp(t), {0.0f, -e}, A[0], emit.cap);
  for (size_t i = 1; i < n; ++i) {
    const glm::vec2 nrm = perp(t);
    if (i + 1 == n) {
      emit.quad(left, right, emit.vertex(P[i] + e * nrm, {0.0f, e}, A[i], emit.cap),
                emit.vertex(P[i] - e * nrm, {0.0f, -e}, A[i], emit.cap));
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
      const StrokeVertex l2 = emit.vertex(P[i] + miter, {0.0f, e}, A[i], emit.cap);
      const StrokeVertex r2 = emit.vertex(P[i] - miter, {0.0f, -e}, A[i], emit.cap);
      emit.quad(left, right, l2, r2);
      left = l2;
      right = r2;
    } else {
      // Round: the band ends square on both sides and a disc covers the outer wedge.
      emit.quad(left, right, emit.vertex(P[i] + e * nrm, {0.0f, e}, A[i], emit.cap),
                emit.vertex(P[i] - e * nrm, {0.0f, -e}, A[i], emit.cap));
      emit.cap_piece(P[i], t, e, e, A[i], round);
      emit.cap_piece(P[i], -t, e, e, A[i], round);
      left = emit.vertex(P[i] + e * n2, {0.0f, e}, A[i], emit.cap);
      right = emit.vertex(P[i] - e * n2, {0.0f, -e}, A[i], emit.cap);
    }
    t = t2;
  }
  emit.cap_piece(P[n - 1], t, e, cap_reach, A[n - 1], emit.cap);
  return n - 1;
}

}  // namespace lodline
