#include "lines/stroke_curve.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace lodline {
namespace {

constexpr float kPi = 3.14159265358979f;

glm::vec2 safeNormalize(glm::vec2 v, glm::vec2 fallback) {
  const float len = glm::length(v);
  return len > 1e-9f ? v / len : fallback;
}

// Bernstein basis of degree 3.
float b0(float t) { return (1.0f - t) * (1.0f - t) * (1.0f - t); }
float b1(float t) { return 3.0f * t * (1.0f - t) * (1.0f - t); }
float b2(float t) { return 3.0f * t * t * (1.0f - t); }
float b3(float t) { return t * t * t; }

// Curve fitting over d[first..last] (Schneider 1990). `t1` points from d[first] into the
// curve, `t2` from d[last] back into it.
class Fitter {
 public:
  Fitter(const std::vector<glm::vec2>& d, float tolerance, std::vector<float>& u, std::vector<glm::vec2>& out)
      : d_(d), tol2_(tolerance * tolerance), u_(u), out_(out) {}

  size_t fit(size_t first, size_t last, glm::vec2 t1, glm::vec2 t2) {
    if (last - first > 1 && straight(first, last)) {  // a line: controls on the chord
      const glm::vec2 a = d_[first], b = d_[last];
      emit(a + (b - a) / 3.0f, a + 2.0f * (b - a) / 3.0f, b);
      return 1;
    }
    if (last - first == 1) {
      const float dist = glm::length(d_[last] - d_[first]) / 3.0f;
      emit(d_[first] + t1 * dist, d_[last] + t2 * dist, d_[last]);
      return 1;
    }
    chordParameters(first, last);
    glm::vec2 bez[4];
    generate(first, last, t1, t2, bez);
    size_t split = first;
    float err = maxError(first, last, bez, split);
    if (err < tol2_) {
      emit(bez[1], bez[2], bez[3]);
      return 1;
    }
    // Close enough that a better parameterisation may do (iteration error: 4× tolerance).
    if (err < 16.0f * tol2_) {
      for (int it = 0; it < 8; ++it) {
        reparameterise(first, last, bez);
        generate(first, last, t1, t2, bez);
        err = maxError(first, last, bez, split);
        if (err < tol2_) {
          emit(bez[1], bez[2], bez[3]);
          return 1;
        }
      }
    }
    split = std::clamp(split, first + 1, last - 1);
    const glm::vec2 center = safeNormalize(d_[split - 1] - d_[split + 1], -t1);
    return fit(first, split, t1, center) + fit(split, last, -center, t2);
  }

 private:
  // Every sample within the tolerance of the chord d[first]–d[last].
  bool straight(size_t first, size_t last) const {
    const glm::vec2 a = d_[first], ab = d_[last] - a;
    const float len2 = glm::dot(ab, ab);
    if (len2 <= 0.0f) return false;
    for (size_t i = first + 1; i < last; ++i) {
      const float t = std::clamp(glm::dot(d_[i] - a, ab) / len2, 0.0f, 1.0f);
      const glm::vec2 e = a + t * ab - d_[i];
      if (glm::dot(e, e) >= tol2_) return false;
    }
    return true;
  }

  void emit(glm::vec2 c1, glm::vec2 c2, glm::vec2 end) {
    out_.push_back(c1);
    out_.push_back(c2);
    out_.push_back(end);
  }

  void chordParameters(size_t first, size_t last) {
    u_.assign(last - first + 1, 0.0f);
    for (size_t i = first + 1; i <= last; ++i) u_[i - first] = u_[i - first - 1] + glm::length(d_[i] - d_[i - 1]);
    const float total = u_.back();
    for (float& v : u_) v = total > 0.0f ? v / total : 0.0f;
  }

  // Least-squares inner control points along the fixed end tangents.
  void generate(size_t first, size_t last, glm::vec2 t1, glm::vec2 t2, glm::vec2* bez) const {
    const glm::vec2 p0 = d_[first], p3 = d_[last];
    float c00 = 0.0f, c01 = 0.0f, c11 = 0.0f, x0 = 0.0f, x1 = 0.0f;
    for (size_t i = first; i <= last; ++i) {
      const float t = u_[i - first];
      const glm::vec2 a0 = t1 * b1(t), a1 = t2 * b2(t);
      c00 += glm::dot(a0, a0);
      c01 += glm::dot(a0, a1);
      c11 += glm::dot(a1, a1);
      const glm::vec2 tmp = d_[i] - (p0 * (b0(t) + b1(t)) + p3 * (b2(t) + b3(t)));
      x0 += glm::dot(a0, tmp);
      x1 += glm::dot(a1, tmp);
    }
    const float det = c00 * c11 - c01 * c01;
    float alpha_l = 0.0f, alpha_r = 0.0f;
    if (std::abs(det) > 1e-12f) {
      alpha_l = (x0 * c11 - x1 * c01) / det;
      alpha_r = (c00 * x1 - c01 * x0) / det;
    }
    const float seg = glm::length(p3 - p0);
    const float eps = 1e-6f * seg;
    if (!(alpha_l > eps) || !(alpha_r > eps) || !std::isfinite(alpha_l) || !std::isfinite(alpha_r))
      alpha_l = alpha_r = seg / 3.0f;  // the heuristic of the paper when the solve degenerates
    bez[0] = p0;
    bez[1] = p0 + t1 * alpha_l;
    bez[2] = p3 + t2 * alpha_r;
    bez[3] = p3;
  }

  float maxError(size_t first, size_t last, const glm::vec2* bez, size_t& split) const {
    float worst = 0.0f;
    split = (first + last) / 2;
    for (size_t i = first + 1; i < last; ++i) {
      const glm::vec2 e = bezierPoint(bez, u_[i - first]) - d_[i];
      const float e2 = glm::dot(e, e);
      if (e2 >= worst) {
        worst = e2;
        split = i;
      }
    }
    return worst;
  }

  // One Newton–Raphson step per sample towards the nearest curve point.
  void reparameterise(size_t first, size_t last, const glm::vec2* bez) {
    const glm::vec2 q1[3] = {3.0f * (bez[1] - bez[0]), 3.0f * (bez[2] - bez[1]), 3.0f * (bez[3] - bez[2])};
    const glm::vec2 q2[2] = {2.0f * (q1[1] - q1[0]), 2.0f * (q1[2] - q1[1])};
    for (size_t i = first; i <= last; ++i) {
      float& t = u_[i - first];
      const glm::vec2 q = bezierPoint(bez, t);
      const float s = 1.0f - t;
      const glm::vec2 d1 = q1[0] * s * s + q1[1] * 2.0f * s * t + q1[2] * t * t;
      const glm::vec2 d2 = q2[0] * s + q2[1] * t;
      const float num = glm::dot(q - d_[i], d1);
      const float den = glm::dot(d1, d1) + glm::dot(q - d_[i], d2);
      if (std::abs(den) > 1e-12f) t = std::clamp(t - num / den, 0.0f, 1.0f);
    }
  }

  const std::vector<glm::vec2>& d_;
  float tol2_;
  std::vector<float>& u_;
  std::vector<glm::vec2>& out_;
};

// Index of the point `reach` px of arc length before (dir < 0) or after i, or the end.
size_t reachFrom(const std::vector<float>& arc, size_t i, float reach, int dir) {
  size_t j = i;
  if (dir < 0) {
    while (j > 0 && arc[i] - arc[j] < reach) --j;
  } else {
    while (j + 1 < arc.size() && arc[j] - arc[i] < reach) ++j;
  }
  return j;
}

// The corners of the polyline p (arc length `arc`): its two ends and every point where it
// turns by more than corner_deg over corner_reach_px, the sharpest of a cluster.
void findCorners(const std::vector<glm::vec2>& p, const std::vector<float>& arc, const StrokeCurveParams& params,
                 std::vector<size_t>& corners) {
  const size_t n = p.size();
  corners.assign(1, 0);
  const float cos_limit = std::cos(params.corner_deg * kPi / 180.0f);
  const float reach = std::max(params.corner_reach_px, 1e-3f);
  float best_cos = 2.0f;
  size_t best = 0;
  for (size_t i = 1; i + 1 < n; ++i) {
    const size_t a = reachFrom(arc, i, reach, -1), b = reachFrom(arc, i, reach, 1);
    const glm::vec2 d1 = safeNormalize(p[i] - p[a], glm::vec2(1, 0));
    const glm::vec2 d2 = safeNormalize(p[b] - p[i], d1);
    const float c = glm::dot(d1, d2);
    if (c < cos_limit) {
      if (best == 0 || arc[i] - arc[best] > reach) {
        if (best != 0) corners.push_back(best);
        best = i;
        best_cos = c;
      } else if (c < best_cos) {
        best = i;
        best_cos = c;
      }
    }
  }
  if (best != 0) corners.push_back(best);
  corners.push_back(n - 1);
}

// The section p[c0..c1] resampled at spacing_px of arc length (both ends exact) into
// sc.samples and smoothed into sc.smooth (m + 1 samples each; returns m).
int smoothSection(const std::vector<glm::vec2>& p, const std::vector<float>& arc, size_t c0, size_t c1,
                  const StrokeCurveParams& params, StrokeCurveScratch& sc) {
  const float len = arc[c1] - arc[c0];
  const float spacing = std::max(params.spacing_px, 0.05f);
  // Resample the section at a fixed arc-length spacing, both ends exact.
  const int m = std::max(1, static_cast<int>(std::ceil(len / spacing)));
  sc.samples.clear();
  size_t seg = c0;
  for (int j = 0; j <= m; ++j) {
    const float s = arc[c0] + len * static_cast<float>(j) / static_cast<float>(m);
    while (seg + 1 < c1 && arc[seg + 1] < s) ++seg;
    const float l = arc[seg + 1] - arc[seg];
    const float t = l > 0.0f ? std::clamp((s - arc[seg]) / l, 0.0f, 1.0f) : 0.0f;
    sc.samples.push_back(p[seg] + t * (p[seg + 1] - p[seg]));
  }
  sc.samples.front() = p[c0];
  sc.samples.back() = p[c1];
  // Gaussian along the arc. Beyond an end the section is continued by its point
  // reflection through that end (2·end − mirror sample), so the end stays fixed, a straight
  // or evenly curving end is undisturbed, and the zig-zag is smoothed up to the end.
  const float sigma = params.smoothing_px / (len / static_cast<float>(m));
  sc.smooth = sc.samples;
  if (sigma > 1e-3f && m >= 2) {
    const int half = std::min(static_cast<int>(std::ceil(3.0f * sigma)), m);
    sc.weights.resize(static_cast<size_t>(half) + 1);
    for (int o = 0; o <= half; ++o)
      sc.weights[static_cast<size_t>(o)] = std::exp(-0.5f * static_cast<float>(o * o) / (sigma * sigma));
    auto at = [&](int j) -> glm::vec2 {
      if (j < 0) return 2.0f * sc.samples.front() - sc.samples[static_cast<size_t>(-j)];
      if (j > m) return 2.0f * sc.samples.back() - sc.samples[static_cast<size_t>(2 * m - j)];
      return sc.samples[static_cast<size_t>(j)];
    };
    for (int j = 1; j < m; ++j) {
      glm::vec2 acc(0.0f);
      float wsum = 0.0f;
      for (int o = -half; o <= half; ++o) {
        const float g = sc.weights[static_cast<size_t>(o < 0 ? -o : o)];
        acc += g * at(j + o);
        wsum += g;
      }
      sc.smooth[static_cast<size_t>(j)] = acc / wsum;
    }
  }
  return m;
}

}  // namespace

bool isStraightSegment(const glm::vec2* p) {
  const glm::vec2 ab = p[3] - p[0];
  return glm::length(p[1] - (p[0] + ab / 3.0f)) < 1e-3f && glm::length(p[2] - (p[0] + 2.0f * ab / 3.0f)) < 1e-3f;
}

glm::vec2 bezierPoint(const glm::vec2* p, float t) {
  return p[0] * b0(t) + p[1] * b1(t) + p[2] * b2(t) + p[3] * b3(t);
}

size_t fitStrokeCurve(std::span<const glm::vec2> polyline, const StrokeCurveParams& params,
                      std::vector<glm::vec2>& out, StrokeCurveScratch& sc) {
  // Finite points, repeated ones dropped.
  sc.clean.clear();
  for (const glm::vec2& p : polyline) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;
    if (sc.clean.empty() || glm::length(p - sc.clean.back()) > 1e-4f) sc.clean.push_back(p);
  }
  const size_t n = sc.clean.size();
  if (n < 2) return 0;
  sc.arc.assign(n, 0.0f);
  for (size_t i = 1; i < n; ++i) sc.arc[i] = sc.arc[i - 1] + glm::length(sc.clean[i] - sc.clean[i - 1]);

  findCorners(sc.clean, sc.arc, params, sc.corners);

  out.push_back(sc.clean.front());
  size_t segments = 0;
  const float spacing = std::max(params.spacing_px, 0.05f);
  for (size_t k = 0; k + 1 < sc.corners.size(); ++k) {
    const size_t c0 = sc.corners[k], c1 = sc.corners[k + 1];
    smoothSection(sc.clean, sc.arc, c0, c1, params, sc);
    // End tangents, second-order one-sided differences over the smoothing scale (a plain
    // chord to a point a few px in would tilt a long arm by a pixel on a gentle arc; a
    // shorter base would follow what is left of the zig-zag).
    const size_t last = sc.smooth.size() - 1;
    const float base_px = std::max(2.0f, 2.0f * params.smoothing_px);
    const size_t h = std::max<size_t>(1, static_cast<size_t>(std::lround(base_px / spacing)));
    const glm::vec2 chord = safeNormalize(sc.smooth[last] - sc.smooth[0], glm::vec2(1, 0));
    glm::vec2 t1, t2;
    if (2 * h <= last) {
      t1 = safeNormalize(-3.0f * sc.smooth[0] + 4.0f * sc.smooth[h] - sc.smooth[2 * h], chord);
      t2 = safeNormalize(-3.0f * sc.smooth[last] + 4.0f * sc.smooth[last - h] - sc.smooth[last - 2 * h], -chord);
    } else {
      t1 = safeNormalize(sc.smooth[std::min(h, last)] - sc.smooth[0], chord);
      t2 = safeNormalize(sc.smooth[last - std::min(h, last)] - sc.smooth[last], -chord);
    }
    Fitter fitter(sc.smooth, params.tolerance_px, sc.params, out);
    segments += fitter.fit(0, last, t1, t2);
  }
  return segments;
}

void smoothPolyline(std::span<glm::vec2> points, const StrokeCurveParams& params, StrokeCurveScratch& sc) {
  const size_t n = points.size();
  if (n < 3 || !(params.smoothing_px > 0.0f)) return;
  for (const glm::vec2& p : points)
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return;
  sc.clean.assign(points.begin(), points.end());
  sc.arc.assign(n, 0.0f);
  for (size_t i = 1; i < n; ++i) sc.arc[i] = sc.arc[i - 1] + glm::length(sc.clean[i] - sc.clean[i - 1]);
  findCorners(sc.clean, sc.arc, params, sc.corners);
  for (size_t k = 0; k + 1 < sc.corners.size(); ++k) {
    const size_t c0 = sc.corners[k], c1 = sc.corners[k + 1];
    const float len = sc.arc[c1] - sc.arc[c0];
    if (c1 <= c0 + 1 || !(len > 0.0f)) continue;
    const int m = smoothSection(sc.clean, sc.arc, c0, c1, params, sc);
    // Each point between the corners onto the smoothed curve at its own arc length.
    for (size_t i = c0 + 1; i < c1; ++i) {
      const float x = std::clamp((sc.arc[i] - sc.arc[c0]) / len, 0.0f, 1.0f) * static_cast<float>(m);
      const int j = std::min(static_cast<int>(x), m - 1);
      const float t = x - static_cast<float>(j);
      const glm::vec2 q = sc.smooth[static_cast<size_t>(j)] +
                          t * (sc.smooth[static_cast<size_t>(j) + 1] - sc.smooth[static_cast<size_t>(j)]);
      // At most max_shift_px from where it was (StrokeCurveParams).
      const glm::vec2 d = q - sc.clean[i];
      const float dl = glm::length(d);
      points[i] = params.max_shift_px > 0.0f && dl > params.max_shift_px ? sc.clean[i] + d * (params.max_shift_px / dl) : q;
    }
  }
}

}  // namespace lodline
