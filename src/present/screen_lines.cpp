#include "present/screen_lines.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "core/hash.h"

namespace lodline {
namespace {

// Value noise along a line (smooth between integer lattice points), in [−1, 1].
float noise1(uint32_t seed, float x) {
  auto lattice = [seed](int i) {
    return 2.0f * unitNoise((static_cast<uint64_t>(seed) << 32) ^ static_cast<uint32_t>(i)) - 1.0f;
  };
  const float f = std::floor(x);
  const int i = static_cast<int>(f);
  const float t = x - f, s = t * t * (3.0f - 2.0f * t);
  return lattice(i) + s * (lattice(i + 1) - lattice(i));
}

float smoothstep01(float x) {
  x = std::clamp(x, 0.0f, 1.0f);
  return x * x * (3.0f - 2.0f * x);
}

// The turning of the polyline at each point, per pixel of arc length, over ±`reach` px,
// times 8 px and clamped to [0, 1] (a bend of 1 turns by a radian within 8 px).
void computeBend(const std::vector<glm::vec2>& p, const std::vector<float>& s, float reach, std::vector<float>& out) {
  const size_t n = p.size();
  out.assign(n, 0.0f);
  size_t lo = 0, hi = 0;
  for (size_t i = 0; i < n; ++i) {
    while (lo < i && s[i] - s[lo + 1] >= reach) ++lo;
    if (hi < i) hi = i;
    while (hi + 1 < n && s[hi] - s[i] < reach) ++hi;
    if (lo == i || hi == i) continue;
    const glm::vec2 a = p[i] - p[lo], b = p[hi] - p[i];
    const float la = glm::length(a), lb = glm::length(b);
    if (!(la > 0.0f && lb > 0.0f)) continue;
    const float c = std::clamp(glm::dot(a, b) / (la * lb), -1.0f, 1.0f);
    out[i] = std::clamp(std::acos(c) / (s[hi] - s[lo]) * 8.0f, 0.0f, 1.0f);
  }
}

// Folds of a run in the image: where the line turns back (a step more than 120° from the way
// it came over its last 3 px), runs back over itself (every point of the excursion within
// 3/4 `width` of the line before the turn, at least `width` px back) and comes out ahead of
// the turn again without going farther than `reach` px from it. On a coarse mesh the zero
// set can double back across a face or two near the outline, and the stroke drew a spike of
// a few pixels over itself: a thick knot in the line (the cow's rump close up). The points
// of the excursion move onto the straight piece from the turn to where the line comes out
// ahead, in order, so the run goes on without turning back. The run's ends stay, and so does
// a turn the line does not come out of within reach (a hairpin, the tip of a thin part, a
// corner) or comes back from beside itself (fingers, teeth: a zig-zag of the shape).
void unfold(std::span<glm::vec2> p, float width, float reach) {
  const size_t n = p.size();
  size_t back = 0;  // the latest point at least 3 px behind p[i] (or the first)
  for (size_t i = 1; i + 1 < n; ++i) {
    while (back + 1 < i && glm::dot(p[i] - p[back + 1], p[i] - p[back + 1]) >= 9.0f) ++back;
    const glm::vec2 d = p[i] - p[back], o = p[i + 1] - p[i];
    const float ld = glm::length(d), lo = glm::length(o);
    if (!(ld > 1e-3f && lo > 1e-3f) || glm::dot(d, o) >= -0.5f * ld * lo) continue;
    const glm::vec2 dir = d / ld;
    // Whether q lies within 3/4 of `width` of the line before the turn (its last `reach` px):
    // over it. Within the whole width, the sides of thin parts of a shrinking model (fingers
    // a few pixels apart) were taken for folds, and a zoom-out's churn rose by 14%.
    auto overItself = [&](glm::vec2 q) {
      float arc = 0.0f;
      for (size_t k = i; k > 0 && arc <= reach; --k) {
        const glm::vec2 a = p[k - 1], ab = p[k] - a;
        const glm::vec2 off = q - (a + nearestOnSegment(q, a, ab) * ab);
        if (glm::dot(off, off) <= 0.5625f * width * width) return true;
        arc += glm::length(ab);
      }
      return false;
    };
    size_t j = i + 1;
    bool out = false;
    float deepest = 0.0f;  // how far back the excursion goes
    for (; j < n; ++j) {
      const glm::vec2 q = p[j] - p[i];
      const float ahead = glm::dot(q, dir);
      if (ahead > 0.0f) {
        out = true;
        break;
      }
      deepest = std::max(deepest, -ahead);
      if (glm::dot(q, q) > reach * reach || !overItself(p[j])) break;
    }
    if (!out || deepest < width) continue;  // shallower back-steps: the zig-zag smoothing takes out
    const glm::vec2 a = p[i], b = p[j];
    const float steps = static_cast<float>(j - i);
    for (size_t k = i + 1; k < j; ++k) p[k] = a + (b - a) * (static_cast<float>(k - i) / steps);
    i = j - 1;
  }
}

}  // namespace

void smoothRuns(StrokeRuns& runs, const LineStyles& style, StrokeCurveScratch& scratch) {
  StrokeCurveParams params;
  for (size_t r = 0; r < runs.strokeCount(); ++r) {
    params.smoothing_px = style[runs.kinds[r]].stroke.smoothing_px;
    const uint32_t b = runs.offsets[r], e = runs.offsets[r + 1];
    if (!(params.smoothing_px > 0.0f) || e < b + 3) continue;
    const float w = std::max(style[runs.kinds[r]].width_px, 1.0f);
    unfold(std::span<glm::vec2>(runs.points.data() + b, e - b), w, 4.0f * w);
    smoothPolyline(std::span<glm::vec2>(runs.points.data() + b, e - b), params, scratch);
    float length = 0.0f;
    for (uint32_t i = b + 1; i < e; ++i) length += glm::length(runs.points[i] - runs.points[i - 1]);
    if (r < runs.length_px.size()) runs.length_px[r] = length;
  }
}

bool strokeProfile(const StrokeRuns& runs, size_t r, float width_px, const StrokeStyle& st, const StrokeView& view,
                   std::span<const float> u, ScreenLinesScratch& sc) {
  const uint32_t b = runs.offsets[r], e = runs.offsets[r + 1];
  if (e <= b) return false;
  if (!u.empty() && u.size() < e) u = {};
  auto& P = sc.points;
  auto& A = sc.alpha;
  auto& W = sc.width;
  auto& S = sc.arc;
  P.assign(runs.points.begin() + b, runs.points.begin() + e);
  S.resize(P.size());
  S[0] = 0.0f;
  for (size_t i = 1; i < P.size(); ++i) S[i] = S[i - 1] + glm::length(P[i] - P[i - 1]);
  const float length = S.back();
  if (length < st.min_length_px) return false;
  const size_t n = P.size();
  if (u.empty()) sc.u.assign(S.begin(), S.end());
  else sc.u.assign(u.begin() + b, u.begin() + e);

  // Depth across the object's bounding sphere, and the bend, where the style uses them.
  const bool use_depth = st.depth_thickness != 0.0f || st.depth_opacity != 0.0f;
  const bool use_bend = st.curvature_thickness != 0.0f || st.curvature_opacity != 0.0f;
  auto& D = sc.depth;
  D.assign(n, 0.0f);
  if (use_depth && runs.positions.size() >= e) {
    const float zc = glm::dot(view.center - view.eye, view.forward);
    const float r2 = 2.0f * std::max(view.radius, 1e-12f);
    for (size_t i = 0; i < n; ++i) {
      const float z = glm::dot(runs.positions[b + i] - view.eye, view.forward);
      D[i] = std::clamp((z - (zc - 0.5f * r2)) / r2, 0.0f, 1.0f);
    }
  }
  if (use_bend) computeBend(P, S, 4.0f, sc.bend);
  else sc.bend.assign(n, 0.0f);

  A.resize(n);
  W.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const float strength = runs.alpha[b + i];
    const float d = D[i], bend = sc.bend[i];
    float taper = 1.0f;
    if (st.taper_in_px > 0.0f) taper = std::min(taper, smoothstep01(S[i] / st.taper_in_px));
    if (st.taper_out_px > 0.0f) taper = std::min(taper, smoothstep01((length - S[i]) / st.taper_out_px));
    taper = st.taper_min + (1.0f - st.taper_min) * taper;
    const float w = width_px * taper * (1.0f + st.depth_thickness * (1.0f - 2.0f * d)) *
                    (1.0f - st.strength_thickness * (1.0f - strength)) * (1.0f + st.curvature_thickness * bend);
    W[i] = std::max(w, 0.0f);
    A[i] = std::clamp((1.0f - st.strength_opacity * (1.0f - strength)) * (1.0f - st.depth_opacity * d) *
                          (1.0f - st.curvature_opacity * bend),
                      0.0f, 1.0f);
  }
  // Jitter: the centre line moved sideways by noise along the arc length.
  if (st.jitter_px > 0.0f && n >= 2) {
    sc.piece.assign(P.begin(), P.end());
    for (size_t i = 0; i < n; ++i) {
      const glm::vec2 d = sc.piece[std::min(i + 1, n - 1)] - sc.piece[i > 0 ? i - 1 : 0];
      const float len = glm::length(d);
      if (!(len > 0.0f)) continue;
      const glm::vec2 normal(-d.y / len, d.x / len);
      P[i] = sc.piece[i] + normal * (st.jitter_px * noise1(st.seed, sc.u[i] / st.jitter_period_px));
    }
  }
  return true;
}

namespace {

// Run r of `runs` as one stroke in style `st` (width `width_px`, parameter `u` per point or
// empty), cut into dashes of the parameter when the style has them. Returns the polyline
// segments drawn.
size_t styledRun(const StrokeRuns& runs, size_t r, float width_px, const StrokeStyle& st, const StrokeView& view,
                 std::span<const float> u, ScreenLines& out, ScreenLinesScratch& sc) {
  if (!strokeProfile(runs, r, width_px, st, view, u, sc)) return 0;
  const auto& P = sc.points;
  const auto& A = sc.alpha;
  const auto& W = sc.width;
  const auto& U = sc.u;
  const size_t n = P.size();
  StrokeGeometryParams gp;
  gp.cap = st.cap;
  const bool dashed = st.dash_on > 0.0f && st.dash_off > 0.0f;
  // The geometry needs the parameter only for a brush (dashes and jitter are applied here).
  const std::span<const float> brush_u = st.brush ? std::span<const float>(U) : std::span<const float>();
  if (!dashed) return appendStrokeGeometry(P, A, W, brush_u, gp, out.vertices, sc.geometry);

  // Dashes: the parts of the run where u mod period < on, segment by segment (u is linear
  // along a segment and may run either way), each a stroke of the points inside.
  const float on = std::max(st.dash_on, 0.5f), period = on + st.dash_off;
  size_t segments = 0;
  auto flush = [&] {
    if (sc.piece.size() >= 2)
      segments += appendStrokeGeometry(sc.piece, sc.piece_alpha, sc.piece_width,
                                       st.brush ? std::span<const float>(sc.piece_u) : std::span<const float>(), gp,
                                       out.vertices, sc.geometry);
    sc.piece.clear();
    sc.piece_alpha.clear();
    sc.piece_width.clear();
    sc.piece_u.clear();
  };
  auto push = [&](size_t i, float t) {
    sc.piece.push_back(P[i] + t * (P[i + 1] - P[i]));
    sc.piece_alpha.push_back(A[i] + t * (A[i + 1] - A[i]));
    sc.piece_width.push_back(W[i] + t * (W[i + 1] - W[i]));
    sc.piece_u.push_back(U[i] + t * (U[i + 1] - U[i]));
  };
  flush();
  for (size_t i = 0; i + 1 < n; ++i) {
    const float ua = U[i], ub = U[i + 1];
    const float lo = std::min(ua, ub), hi = std::max(ua, ub);
    if (!(hi > lo)) {  // no parameter change: on or off as a whole
      const float m = ua - std::floor(ua / period) * period;
      if (m < on) {
        if (sc.piece.empty()) push(i, 0.0f);
        push(i, 1.0f);
      } else {
        flush();
      }
      continue;
    }
    // The dashes [d, d + on) meeting [lo, hi], in the segment's t from its first point.
    auto& spans = sc.dash_spans;
    spans.clear();
    for (float d = std::floor(lo / period) * period; d < hi; d += period) {
      const float a = std::max(d, lo), c = std::min(d + on, hi);
      if (c <= a) continue;
      float t0 = (a - ua) / (ub - ua), t1 = (c - ua) / (ub - ua);
      if (t0 > t1) std::swap(t0, t1);
      spans.emplace_back(std::clamp(t0, 0.0f, 1.0f), std::clamp(t1, 0.0f, 1.0f));
    }
    std::sort(spans.begin(), spans.end());
    for (const auto& [t0, t1] : spans) {
      // A dash that does not start at this segment's first point ends the one before.
      if (t0 > 0.0f || sc.piece.empty()) {
        flush();
        push(i, t0);
      }
      push(i, t1);
      if (t1 < 1.0f) flush();
    }
    if (spans.empty() || spans.back().second < 1.0f) flush();
  }
  flush();
  return segments;
}

}  // namespace

void joinRuns(const StrokeRuns& runs, std::span<const float> u, const JoinParams& params, JoinedRuns& joined) {
  const size_t nr = runs.strokeCount();
  const bool with_u = !u.empty() && u.size() == runs.points.size();
  const bool with_pos = runs.positions.size() == runs.points.size();
  StrokeRuns& out = joined.runs;
  std::vector<float>& out_u = joined.u;
  out.clear();
  out_u.clear();
  joined.first_run.clear();
  out.offsets.push_back(0);
  auto endPoint = [&](size_t end) {
    const size_t r = end / 2;
    return end % 2 == 0 ? runs.points[runs.offsets[r]] : runs.points[runs.offsets[r + 1] - 1];
  };
  // The direction leaving run r's end (2r: its start, 2r + 1: its end), from the point about
  // 2 px inside it; zero for a run of no length.
  auto outward = [&](size_t end) {
    const size_t r = end / 2;
    const uint32_t b = runs.offsets[r], e = runs.offsets[r + 1];
    const glm::vec2 p = endPoint(end);
    glm::vec2 d(0.0f);
    for (uint32_t k = 1; k < e - b; ++k) {
      d = p - runs.points[end % 2 == 0 ? b + k : e - 1 - k];
      if (glm::dot(d, d) >= 4.0f) break;
    }
    const float l = glm::length(d);
    return l > 0.0f && std::isfinite(l) ? d / l : glm::vec2(0.0f);
  };
  const float min_cos = std::cos(glm::radians(std::clamp(params.max_turn_deg, 0.0f, 180.0f)));
  // Whether the line goes on from end e through the gap into end o.
  // Within `cos_limit`: both directions turn by at most its angle into each other and into
  // the gap (min_cos, or the stricter one of long bridges).
  auto continues = [&](size_t e, size_t o, float cos_limit) {
    const glm::vec2 te = outward(e), to = outward(o);
    if (glm::dot(te, -to) < cos_limit) return false;
    const glm::vec2 gap = endPoint(o) - endPoint(e);
    const float g = glm::length(gap);
    return g <= params.touch_px || (glm::dot(te, gap / g) >= cos_limit && glm::dot(-to, gap / g) >= cos_limit);
  };
  // Per kind, once: how near a line of its kind a run's point may lie to lie along it
  // (along_px, or the kind's stroke width where that is wider), and how far apart two ends
  // may be to be bridged (bridge_px, or the width + 1.5 px where that is more; 0 stays 0).
  // Widths count up to 16 px.
  // Gaps up to the width + 3 px (long_bridge_of) are bridged where the line runs straight on
  // through them (within 30°) and no other run crosses the gap, which needs the segment grid
  // below (along_px > 0).
  // A run lies along a line within the width + burr_px (beside_reach_of; 0: off) of one run
  // at least three times its length.
  std::array<float, kLineKindCount> reach_of{}, bridge_of{}, long_bridge_of{}, beside_reach_of{};
  float widest_reach = params.along_px, widest_bridge = params.bridge_px;
  const bool with_grid = params.along_px > 0.0f && nr > 1;
  const float burr = std::isfinite(params.burr_px) ? std::clamp(params.burr_px, 0.0f, 16.0f) : 0.0f;
  for (int k = 0; k < kLineKindCount; ++k) {
    const float w = std::isfinite(params.width_px[k]) ? std::clamp(params.width_px[k], 0.0f, 16.0f) : 0.0f;
    reach_of[k] = std::max(params.along_px, w);
    beside_reach_of[k] = burr > 0.0f && w > 0.0f ? std::max(reach_of[k], w + burr) : 0.0f;
    widest_reach = std::max(widest_reach, beside_reach_of[k]);
    bridge_of[k] = params.bridge_px > 0.0f && w > 0.0f ? std::max(params.bridge_px, w + 1.5f) : params.bridge_px;
    long_bridge_of[k] = params.bridge_px > 0.0f && w > 0.0f && with_grid ? std::max(bridge_of[k], w + 3.0f) : bridge_of[k];
    widest_reach = std::max(widest_reach, reach_of[k]);
    widest_bridge = std::max(widest_bridge, long_bridge_of[k]);
  }
  auto kindIndex = [](LineKind kind) { return static_cast<size_t>(kind); };
  // Runs lying along longer runs of their kind: every point of theirs, and every 2 px
  // between, within along_px of one of those.
  std::vector<uint8_t>& covered = joined.covered;
  covered.assign(nr, 0);
  if (with_grid) {
    auto finite = [](glm::vec2 p) {
      return std::isfinite(p.x) && std::isfinite(p.y) && std::abs(p.x) < 1e7f && std::abs(p.y) < 1e7f;
    };
    // The segments on a grid over the points, its cells at least along_px wide, at most
    // 2^20 of them.
    glm::vec2 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const glm::vec2& p : runs.points)
      if (finite(p)) lo = glm::min(lo, p), hi = glm::max(hi, p);
    float cell_px = std::max(8.0f, widest_reach);
    int gw = 1, gh = 1;
    if (lo.x <= hi.x) {
      while (true) {
        gw = static_cast<int>((hi.x - lo.x) / cell_px) + 1;
        gh = static_cast<int>((hi.y - lo.y) / cell_px) + 1;
        if (static_cast<int64_t>(gw) * gh <= (int64_t(1) << 20)) break;
        cell_px *= 2.0f;
      }
    }
    joined.grid.build(runs, lo, cell_px, gw, gh, finite);
    std::vector<uint32_t>& run_of = joined.run_of;
    run_of.assign(runs.points.size(), 0);
    for (size_t r = 0; r < nr; ++r)
      for (uint32_t i = runs.offsets[r]; i < runs.offsets[r + 1]; ++i) run_of[i] = static_cast<uint32_t>(r);
    // Whether `p` lies within √reach2 of segment i (points i and i + 1).
    auto segmentWithin = [&](glm::vec2 p, uint32_t i, float reach2) {
      const glm::vec2 a = runs.points[i], ab = runs.points[i + 1] - a;
      const glm::vec2 d = p - (a + nearestOnSegment(p, a, ab) * ab);
      return glm::dot(d, d) <= reach2;
    };
    // Whether `p` lies within the reach (along_px, or the kind's width) of a segment of a
    // longer run of run r's kind, or, for a run of another kind, within the wider of its and
    // the contour's reach of a contour, whatever their lengths: the outline is the line drawn
    // there (docs/strokes.md, "Other kinds on the outline").
    const size_t contour = kindIndex(LineKind::kContour);
    const bool contours_drawn = params.width_px[contour] > 0.0f;
    auto along = [&](glm::vec2 p, size_t r) {
      bool found = false;
      const size_t kind = kindIndex(runs.kinds[r]);
      const float reach = reach_of[kind], reach2 = reach * reach;
      const bool over_contours = contours_drawn && kind != contour;
      const float cross = over_contours ? std::max(reach, reach_of[contour]) : reach, cross2 = cross * cross;
      joined.grid.forEachNear(p, cross, [&](uint32_t i) {
        const uint32_t q = run_of[i];
        if (found || q == r || covered[q]) return;
        if (runs.kinds[q] == runs.kinds[r]) {
          if (runs.length_px[q] < runs.length_px[r] || (runs.length_px[q] == runs.length_px[r] && q > r)) return;
          found = segmentWithin(p, i, reach2);
        } else if (over_contours && runs.kinds[q] == LineKind::kContour) {
          found = segmentWithin(p, i, cross2);
        }
      });
      return found;
    };
    // Whether `p` lies within `reach` of a segment of run q.
    auto nearRun = [&](glm::vec2 p, uint32_t q, float reach) {
      bool found = false;
      joined.grid.forEachNear(p, reach, [&](uint32_t i) {
        if (!found && run_of[i] == q) found = segmentWithin(p, i, reach * reach);
      });
      return found;
    };
    // Whether `pred` holds at every point of run r and every 2 px between.
    auto allAlong = [&](uint32_t r, auto&& pred) {
      const uint32_t b = runs.offsets[r], e = runs.offsets[r + 1];
      bool all = pred(runs.points[b]);
      for (uint32_t i = b; all && i + 1 < e; ++i) {
        const glm::vec2 p = runs.points[i], q = runs.points[i + 1];
        if (!finite(q)) return false;
        const int steps = std::clamp(static_cast<int>(std::ceil(glm::length(q - p) / 2.0f)), 1, 4096);
        for (int k = 1; all && k <= steps; ++k) all = pred(p + (q - p) * (static_cast<float>(k) / steps));
      }
      return all;
    };
    // Whether an end of another run of run r's kind lies within `radius` of `p`.
    auto meetsAnEnd = [&](glm::vec2 p, size_t r, float radius) {
      bool found = false;
      const float radius2 = radius * radius;
      joined.grid.forEachNear(p, radius, [&](uint32_t i) {
        const uint32_t q = run_of[i];
        if (found || q == r || runs.kinds[q] != runs.kinds[r] || covered[q]) return;
        for (const uint32_t end : {runs.offsets[q], runs.offsets[q + 1] - 1})
          if (end == i || end == i + 1) {
            const glm::vec2 d = runs.points[end] - p;
            found = found || glm::dot(d, d) <= radius2;
          }
      });
      return found;
    };
    // Shortest first: of two runs along each other, the shorter goes.
    std::vector<uint32_t>& order = joined.order;
    order.resize(nr);
    for (uint32_t r = 0; r < nr; ++r) order[r] = r;
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
      return runs.length_px[a] != runs.length_px[b] ? runs.length_px[a] < runs.length_px[b] : a > b;
    });
    // Whether run r lies within the width + burr_px of one run of its kind at least three
    // times its length all along.
    auto besideOneLonger = [&](uint32_t r, size_t kind) {
      const float reach = beside_reach_of[kind];
      uint32_t tried[8];
      int n_tried = 0;
      bool beside = false;
      joined.grid.forEachNear(runs.points[runs.offsets[r]], reach, [&](uint32_t i) {
        const uint32_t q = run_of[i];
        if (beside || q == r || runs.kinds[q] != runs.kinds[r] || covered[q] ||
            runs.length_px[q] < 3.0f * runs.length_px[r] || n_tried == 8 ||
            std::find(tried, tried + n_tried, q) != tried + n_tried)
          return;
        tried[n_tried++] = q;
        // The last and the middle point first: most candidates part from r there.
        const uint32_t last = runs.offsets[r + 1] - 1, mid = (runs.offsets[r] + last) / 2;
        beside = nearRun(runs.points[last], q, reach) && nearRun(runs.points[mid], q, reach) &&
                 allAlong(r, [&](glm::vec2 p) { return nearRun(p, q, reach); });
      });
      return beside;
    };
    // Whether both ends of run r lie within a long bridge's reach of ends of other runs of its
    // kind that are drawn (not left out so far).
    auto linksTwoEnds = [&](uint32_t r, size_t kind) {
      return meetsAnEnd(runs.points[runs.offsets[r]], r, long_bridge_of[kind]) &&
             meetsAnEnd(runs.points[runs.offsets[r + 1] - 1], r, long_bridge_of[kind]);
    };
    // A run beside one run at least three times its length, within the width + burr_px of it
    // all along, only doubles that line: close up on a coarse mesh, dashes of 4–10 px of
    // contour stood 1.5–4.5 px beside the outline (burrs and ticks on the line), and longer
    // branches of the contour ran beside it (lenses: the cow's back, the armadillo's
    // shoulder). It is left out unless both its ends link other runs' ends (a corner of the
    // line, a piece between two gaps, a stretch of the outline between two pieces).
    std::vector<uint32_t>& linking = joined.linking;
    linking.clear();
    bool any_beside = false;
    for (const uint32_t r : order) {
      const uint32_t b = runs.offsets[r], e = runs.offsets[r + 1];
      if (e - b < 1 || !finite(runs.points[b])) continue;
      covered[r] = allAlong(r, [&](glm::vec2 p) { return along(p, r); });
      const size_t kind = kindIndex(runs.kinds[r]);
      if (covered[r] || !(beside_reach_of[kind] > 0.0f) || !besideOneLonger(r, kind)) continue;
      if (linksTwoEnds(r, kind)) {
        linking.push_back(r);
      } else {
        covered[r] = 1;
        any_beside = true;
      }
    }
    // A run kept for linking an end of a run that was left out after it (a longer one): looked
    // at again.
    if (any_beside)
      for (const uint32_t r : linking) {
        const size_t kind = kindIndex(runs.kinds[r]);
        covered[r] = !linksTwoEnds(r, kind) && besideOneLonger(r, kind);
      }
  }
  // Ends binned by cells of the farthest join; each end links to the nearest free end of
  // another run of its kind: first those that touch, then those a gap apart on one line.
  std::vector<int32_t>& link = joined.link;
  link.assign(2 * nr, -1);
  std::vector<uint8_t>& overlapping = joined.overlapping;
  overlapping.assign(2 * nr, 0);
  joined.skipped.assign(2 * nr, 0);
  const float overlap_px = std::isfinite(params.overlap_px) ? std::clamp(params.overlap_px, 0.0f, 64.0f) : 0.0f;
  // Whether end o of another run lies behind end e, side by side with it: the two run the same
  // way, each end at most overlap_px behind the other and within the kind's reach of the
  // line through the other end, and the run entered at o goes on past e by more than its
  // reach (so that what is left of it after the points behind e are dropped is a line).
  auto overlaps = [&](size_t e, size_t o) {
    const glm::vec2 te = outward(e), to = outward(o);
    if (glm::dot(te, -to) < min_cos) return false;
    const glm::vec2 g = endPoint(o) - endPoint(e);
    const float behind = -glm::dot(te, g), side = std::abs(te.x * g.y - te.y * g.x);
    const float behind_o = glm::dot(to, g), side_o = std::abs(to.x * g.y - to.y * g.x);
    const float w = reach_of[kindIndex(runs.kinds[e / 2])];  // the caller pairs ends of one kind
    return behind > 0.0f && behind <= overlap_px && side <= w && behind_o > 0.0f && behind_o <= overlap_px &&
           side_o <= w && runs.length_px[o / 2] > behind + w;
  };
  // Whether a segment of a run other than e's and o's crosses the gap between ends e and o
  // (the grid holds every run's segments when long bridges are allowed).
  auto gapCrossed = [&](size_t e, size_t o) {
    const glm::vec2 a = endPoint(e), ab = endPoint(o) - a;
    bool crossed = false;
    joined.grid.forEachNear(a + 0.5f * ab, 0.5f * glm::length(ab) + 1.0f, [&](uint32_t i) {
      const uint32_t q = joined.run_of[i];
      if (crossed || q == e / 2 || q == o / 2) return;
      const glm::vec2 c = runs.points[i], cd = runs.points[i + 1] - c;
      const float den = ab.x * cd.y - ab.y * cd.x;
      if (!(std::abs(den) > 0.0f)) return;
      const glm::vec2 ac = c - a;
      const float t = (ac.x * cd.y - ac.y * cd.x) / den, v = (ac.x * ab.y - ac.y * ab.x) / den;
      crossed = t >= 0.0f && t <= 1.0f && v >= 0.0f && v <= 1.0f;
    });
    return crossed;
  };
  // Gaps longer than bridge_of's: the line runs straight on (within 30°), nothing crosses.
  const float long_cos = std::cos(glm::radians(30.0f));
  // Ends that meet side by side: the two runs go the same way within 15°, and end o lies
  // beside end e (more than touch_px and at most the kind's reach across the line, at most
  // touch_px behind it and no farther ahead than across). Two pieces of one line offset by
  // a pixel or two (the outline's completing piece and the contour, on a coarse mesh):
  // bridged straight, the stroke stepped across; they are joined with the chain's end bent
  // over onto the entered run's line (JoinParams::step_px).
  std::vector<uint8_t>& side_step = joined.side_step;
  side_step.assign(2 * nr, 0);
  const float step_cos = std::cos(glm::radians(15.0f));
  auto sideStep = [&](size_t e, size_t o) {
    if (!(params.step_px > 0.0f)) return false;
    const glm::vec2 te = outward(e), to = outward(o);
    if (glm::dot(te, -to) < step_cos) return false;
    const glm::vec2 g = endPoint(o) - endPoint(e);
    const float ahead = glm::dot(te, g), across = std::abs(te.x * g.y - te.y * g.x);
    return across > params.touch_px && across <= reach_of[kindIndex(runs.kinds[e / 2])] && ahead >= -params.touch_px &&
           ahead <= across && runs.length_px[o / 2] >= 4.0f * params.step_px &&
           runs.length_px[e / 2] >= 4.0f * params.step_px;
  };
  const float reach = std::max({params.touch_px, widest_bridge, overlap_px});
  const float cell = std::max(reach, 1e-3f);
  auto& bins = joined.bins;
  bins.clear();
  auto key = [&](int x, int y) { return (uint64_t(uint32_t(x)) << 32) | uint32_t(y); };
  auto cellOf = [&](glm::vec2 p, int& x, int& y) {
    x = static_cast<int>(std::floor(p.x / cell));
    y = static_cast<int>(std::floor(p.y / cell));
  };
  for (size_t end = 0; end < 2 * nr; ++end) {
    const size_t r = end / 2;
    if (runs.offsets[r + 1] <= runs.offsets[r] || covered[r]) continue;
    const glm::vec2 p = endPoint(end);
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || std::abs(p.x) > 1e7f || std::abs(p.y) > 1e7f) continue;
    int x, y;
    cellOf(p, x, y);
    bins.emplace_back(key(x, y), static_cast<uint32_t>(end));
  }
  std::sort(bins.begin(), bins.end());
  for (int pass = 0; pass < 3; ++pass) {
    const bool bridging = pass == 1, overlapping_pass = pass == 2;
    if (bridging && params.bridge_px <= params.touch_px) continue;
    if (overlapping_pass && !(overlap_px > 0.0f)) continue;
    for (const auto& [k, e] : bins) {
      if (link[e] >= 0) continue;
      const glm::vec2 p = endPoint(e);
      int x, y;
      cellOf(p, x, y);
      const size_t kind = kindIndex(runs.kinds[e / 2]);
      float best = overlapping_pass ? overlap_px * 1.5f
                   : bridging       ? long_bridge_of[kind]
                                    : params.touch_px;
      int32_t best_end = -1;
      bool best_step = false;  // joined side by side (sideStep()), not along the line
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const uint64_t kk = key(x + dx, y + dy);
          for (auto it = std::lower_bound(bins.begin(), bins.end(), std::make_pair(kk, 0u));
               it != bins.end() && it->first == kk; ++it) {
            const uint32_t o = it->second;
            if (o / 2 == e / 2 || link[o] >= 0 || runs.kinds[o / 2] != runs.kinds[e / 2]) continue;
            const float d = glm::length(endPoint(o) - p);
            if (!(d <= best)) continue;
            if (overlapping_pass || !bridging) {
              if (!overlapping_pass || overlaps(e, o)) best = d, best_end = static_cast<int32_t>(o), best_step = false;
              continue;
            }
            const bool on_line = continues(e, o, min_cos);
            const bool bridged =
                on_line && (d <= bridge_of[kind] || (continues(e, o, long_cos) && !gapCrossed(e, o)));
            const bool stepped = !bridged && sideStep(e, o);
            if (bridged || stepped) best = d, best_end = static_cast<int32_t>(o), best_step = stepped && !on_line;
          }
        }
      if (best_end >= 0) {
        link[e] = best_end;
        link[static_cast<size_t>(best_end)] = static_cast<int32_t>(e);
        overlapping[e] = overlapping[static_cast<size_t>(best_end)] = overlapping_pass;
        side_step[e] = side_step[static_cast<size_t>(best_end)] = best_step;
      }
    }
  }
  // A free end that turns back within its last few pixels (a hook: on a coarse mesh the
  // contour's end, where it goes behind the surface at a cusp, keeps a pixel or two of the
  // turned branch in front of the depth test) is cut where it turns by over 75°: the number
  // of points left out there, 0 for none. Only where the hook is within max(hook_px, 1.5 ×
  // the kind's width) of the end and the run is at least three times that long.
  const float hook_cos = std::cos(glm::radians(75.0f));
  auto hookAt = [&](size_t end) -> uint32_t {
    const size_t r = end / 2;
    const uint32_t b = runs.offsets[r], e = runs.offsets[r + 1], n = e - b;
    if (!(params.hook_px > 0.0f) || !std::isfinite(params.hook_px) || n < 4) return 0;
    const float hook_reach = std::min(std::max(params.hook_px, 1.5f * reach_of[kindIndex(runs.kinds[r])]), 16.0f);
    if (!(runs.length_px[r] >= 3.0f * hook_reach)) return 0;
    auto at = [&](uint32_t k) { return runs.points[end % 2 == 0 ? b + k : e - 1 - k]; };
    float arc = 0.0f, best_cos = hook_cos;
    uint32_t best = 0;
    for (uint32_t k = 1; k + 2 < n; ++k) {
      arc += glm::length(at(k) - at(k - 1));
      if (!(arc <= hook_reach)) break;
      const glm::vec2 tail = at(0) - at(k);
      glm::vec2 body(0.0f);  // towards the end, over about `hook_reach` of the run before point k
      for (uint32_t j = k + 1; j < n; ++j) {
        body = at(k) - at(j);
        if (glm::dot(body, body) >= hook_reach * hook_reach) break;
      }
      const float lt = glm::length(tail), lb = glm::length(body);
      if (!(lt > 0.0f) || !(lb > 0.0f)) continue;
      const float c = glm::dot(tail, body) / (lt * lb);
      if (c < best_cos) best_cos = c, best = k;
    }
    return best;
  };
  // Chains: from each run with a free end (then the remaining cycles), run after run.
  std::vector<uint8_t>& done = joined.done;
  done.assign(covered.begin(), covered.end());  // covered runs are left out
  auto emit = [&](size_t start_run, size_t entry_end) {
    float length = 0.0f, weighted = 0.0f;
    size_t r = start_run, entry = entry_end;
    // Entering a run side by side with the one left (JoinParams::overlap_px): its points
    // behind the end left (along that end's outward direction) are skipped.
    glm::vec2 left_end(0.0f), left_dir(0.0f);
    bool trim = false, bent = false, step = false;
    while (true) {
      done[r] = 1;
      const uint32_t b = runs.offsets[r], e = runs.offsets[r + 1];
      const bool forward = entry % 2 == 0;
      if (step) {
        // Entered side by side (sideStep()): the chain's last step_px and more (four times
        // the offset) bend over onto the entered run's line, the weight rising linearly
        // with arc length to 1 at the chain's end, so the stroke does not step across.
        const glm::vec2 a = endPoint(entry), dir = -outward(entry);
        const size_t chain_begin = out.offsets.back();
        const glm::vec2 last = out.points.back();
        const float offset = std::abs(dir.x * (last.y - a.y) - dir.y * (last.x - a.x));
        const float span = std::max(params.step_px, 4.0f * offset);
        float arc = 0.0f;
        glm::vec2 after = last;  // the point after p as it was, before it moved
        for (size_t j = out.points.size(); j-- > chain_begin;) {
          arc += glm::length(after - out.points[j]);
          if (arc >= span) break;
          glm::vec2& p = out.points[j];
          after = p;
          const glm::vec2 q = a + glm::dot(p - a, dir) * dir;  // p's foot on the entered line
          if (glm::length(q - p) > offset + params.touch_px) break;  // the lines part: a corner
          p += (1.0f - arc / span) * (q - p);
        }
        bent = true;
      }
      uint32_t first = 0;
      if (trim)
        while (first + 1 < e - b && glm::dot(runs.points[forward ? b + first : e - 1 - first] - left_end, left_dir) <= 0.0f)
          ++first;
      const size_t exit = forward ? 2 * r + 1 : 2 * r;
      // Hooks at the chain's free ends (hookAt()).
      const uint32_t hook_in = !trim && link[entry] < 0 ? hookAt(entry) : 0;
      uint32_t hook_out = link[exit] < 0 ? hookAt(exit) : 0;
      if (first + hook_in + hook_out + 2 > e - b) hook_out = 0;
      first += hook_in;
      joined.skipped[entry] = first;
      joined.skipped[exit] = hook_out;
      if (trim && first > 0) {
        // The two lines lie side by side, a pixel or two apart: the end of the chain so far
        // bends over onto the entered run's line along the overlap (a smoothstep over the
        // distance that run starts behind), so the stroke does not step across at one point.
        auto at = [&](uint32_t k) { return runs.points[forward ? b + k : e - 1 - k]; };
        float back = 0.0f;
        for (uint32_t k = 0; k < first; ++k) back = std::max(back, glm::dot(left_end - at(k), left_dir));
        const size_t chain_begin = out.offsets.back();
        for (size_t j = out.points.size(); back > 0.0f && j-- > chain_begin;) {
          glm::vec2& p = out.points[j];
          const float d = glm::dot(left_end - p, left_dir);
          if (d > back) break;
          glm::vec2 q = p;
          float best = std::numeric_limits<float>::max();
          for (uint32_t k = 0; k < first; ++k) {
            const glm::vec2 a = at(k), ab = at(k + 1) - a;
            const float t = nearestOnSegment(p, a, ab);
            const glm::vec2 c = a + t * ab;
            const float d2 = glm::dot(c - p, c - p);
            if (d2 < best) best = d2, q = c;
          }
          const float w = 1.0f - std::max(d, 0.0f) / back, smooth = w * w * (3.0f - 2.0f * w);
          p += smooth * (q - p);
        }
        bent = true;
      }
      for (uint32_t k = first; k < e - b - hook_out; ++k) {
        const uint32_t i = forward ? b + k : e - 1 - k;
        out.points.push_back(runs.points[i]);
        if (with_pos) out.positions.push_back(runs.positions[i]);
        out.alpha.push_back(runs.alpha[i]);
        if (with_u) out_u.push_back(u[i]);
      }
      float run_length = runs.length_px[r];
      {
        auto at = [&](uint32_t k) { return runs.points[forward ? b + k : e - 1 - k]; };
        for (uint32_t k = 1; k <= first; ++k) run_length -= glm::length(at(k) - at(k - 1));
        for (uint32_t k = e - b - hook_out; k < e - b; ++k) run_length -= glm::length(at(k) - at(k - 1));
        run_length = std::max(run_length, 0.0f);
        if (trim) length += glm::length(at(first) - left_end);  // the piece joining them
      }
      length += run_length;
      weighted += run_length * runs.opacity[r];
      if (link[exit] < 0) break;
      const size_t next_entry = static_cast<size_t>(link[exit]);
      if (done[next_entry / 2]) break;  // a cycle closed
      trim = overlapping[exit] != 0;
      step = side_step[exit] != 0;
      if (trim) {
        left_end = endPoint(exit);
        left_dir = outward(exit);
      } else {
        length += glm::length(endPoint(next_entry) - endPoint(exit));  // the bridge
      }
      r = next_entry / 2;
      entry = next_entry;
    }
    if (bent) {  // the bent stretches changed the length: measured again, bridges included
      length = 0.0f;
      for (size_t j = out.offsets.back() + 1; j < out.points.size(); ++j)
        length += glm::length(out.points[j] - out.points[j - 1]);
    }
    joined.first_run.push_back(static_cast<uint32_t>(start_run));
    out.offsets.push_back(static_cast<uint32_t>(out.points.size()));
    out.kinds.push_back(runs.kinds[start_run]);
    out.strokes.push_back(runs.strokes[start_run]);
    out.length_px.push_back(length);
    out.opacity.push_back(length > 0.0f ? weighted / length : runs.opacity[start_run]);
  };
  for (size_t r = 0; r < nr; ++r) {
    if (done[r]) continue;
    if (link[2 * r] < 0) emit(r, 2 * r);
    else if (link[2 * r + 1] < 0) emit(r, 2 * r + 1);
  }
  for (size_t r = 0; r < nr; ++r)
    if (!done[r]) emit(r, 2 * r);
}

void appendRunAlone(const StrokeRuns& runs, const JoinedRuns& joined, size_t r, std::vector<glm::vec2>& out) {
  if (r >= runs.strokeCount() || (r < joined.covered.size() && joined.covered[r])) return;
  const std::vector<uint32_t>& skipped = joined.skipped;
  // Run q's points less those an overlap join left out at its ends.
  auto kept = [&](size_t q, uint32_t& b, uint32_t& e) {
    b = runs.offsets[q];
    e = runs.offsets[q + 1];
    if (2 * q + 1 < skipped.size() && skipped[2 * q] + skipped[2 * q + 1] + 2 <= e - b) {
      b += skipped[2 * q];
      e -= skipped[2 * q + 1];
    }
  };
  // Where the joined stroke goes on from end `en` to another run (a bridged gap, or the
  // step of an overlap join to the entered run's first kept point): that run's kept end
  // there, when this run draws the piece between (the lower end index), else null.
  auto reachTo = [&](size_t en) -> const glm::vec2* {
    if (en >= joined.link.size() || joined.link[en] < 0) return nullptr;
    const size_t o = static_cast<size_t>(joined.link[en]);
    if (o < en) return nullptr;
    uint32_t b = 0, e = 0;
    kept(o / 2, b, e);
    return &runs.points[o % 2 == 0 ? b : e - 1];
  };
  uint32_t b = 0, e = 0;
  kept(r, b, e);
  if (const glm::vec2* p = reachTo(2 * r)) out.push_back(*p);
  out.insert(out.end(), runs.points.begin() + b, runs.points.begin() + e);
  if (const glm::vec2* p = reachTo(2 * r + 1)) out.push_back(*p);
}

JoinParams joinParamsFor(const LineStyles& style) {
  JoinParams p;
  for (int k = 0; k < kLineKindCount; ++k)
    if (style.kinds[k].enabled) p.width_px[k] = style.kinds[k].width_px;
  return p;
}

void buildScreenLines(const StrokeRuns& visible, const StrokeRuns& hidden, const ObjectStyle& style,
                      const StrokeView& view, std::span<const float> visible_u, ScreenLines& out,
                      ScreenLinesScratch& scratch) {
  out.clear();
  joinRuns(visible, visible_u, joinParamsFor(style.lines), scratch.joined);
  const StrokeRuns& runs = scratch.joined.runs;
  const std::span<const float> runs_u = scratch.joined.u;
  for (int k = 0; k < kLineKindCount; ++k) {
    out.first[k] = static_cast<uint32_t>(out.vertices.size());
    const LineStyle& ls = style.lines.kinds[k];
    if (ls.enabled)
      for (size_t r = 0; r < runs.strokeCount(); ++r)
        if (static_cast<int>(runs.kinds[r]) == k)
          out.segments[k] +=
              static_cast<uint32_t>(styledRun(runs, r, ls.width_px, ls.stroke, view, runs_u, out, scratch));
    out.count[k] = static_cast<uint32_t>(out.vertices.size()) - out.first[k];
  }
  out.hidden_first = static_cast<uint32_t>(out.vertices.size());
  const HiddenLineStyle& h = style.hidden;
  if (h.enabled) {
    StrokeStyle hs;
    hs.cap = StrokeCap::kButt;
    if (h.dash_off > 0.0f) {
      hs.dash_on = h.dash_on;
      hs.dash_off = h.dash_off;
    }
    for (size_t r = 0; r < hidden.strokeCount(); ++r)
      out.hidden_segments += static_cast<uint32_t>(styledRun(hidden, r, h.width_px, hs, view, {}, out, scratch));
  }
  out.hidden_count = static_cast<uint32_t>(out.vertices.size()) - out.hidden_first;
}

}  // namespace lodline
