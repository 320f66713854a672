#include "present/outline.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <glm/geometric.hpp>

#include "present/segment_grid.h"

namespace lodline {
namespace {

struct Sample {
  glm::vec2 px;
  glm::vec3 p;
  float alpha;
  float eye_depth;
};

// Samples of run r's polyline at most 1 px apart, positions interpolated
// perspective-correctly (1/depth is linear in screen space).
void sampleRun(const StrokeRuns& runs, size_t r, const PixelProjector& proj, std::vector<Sample>& out) {
  out.clear();
  const uint32_t begin = runs.offsets[r], end = runs.offsets[r + 1];
  for (uint32_t i = begin; i + 1 < end; ++i) {
    const glm::vec2 a = runs.points[i], b = runs.points[i + 1];
    const glm::vec3 pa = runs.positions[i], pb = runs.positions[i + 1];
    const float za = std::max(proj.eyeDepth(pa), 1e-9f), zb = std::max(proj.eyeDepth(pb), 1e-9f);
    const int steps = std::clamp(static_cast<int>(std::ceil(glm::length(b - a))), 1, 4096);
    for (int k = 0; k < steps; ++k) {
      const float s = static_cast<float>(k) / static_cast<float>(steps);
      const float inv = (1.0f - s) / za + s / zb;
      const float t = (s / zb) / inv;
      out.push_back({a + s * (b - a), pa + t * (pb - pa), runs.alpha[i] + s * (runs.alpha[i + 1] - runs.alpha[i]),
                     1.0f / inv});
    }
  }
  if (end > begin)
    out.push_back({runs.points[end - 1], runs.positions[end - 1], runs.alpha[end - 1],
                   proj.eyeDepth(runs.positions[end - 1])});
}

void clearMask(LineMask& m, int width, int height) {
  m.width = width;
  m.height = height;
  m.on.assign(static_cast<size_t>(width) * height, 0);
}

void mark(LineMask& m, glm::vec2 px) {
  const int x = static_cast<int>(std::floor(px.x)), y = static_cast<int>(std::floor(px.y));
  if (x >= 0 && y >= 0 && x < m.width && y < m.height) m.on[static_cast<size_t>(y) * m.width + x] = 1;
}

bool near(const LineMask& m, glm::vec2 px, int r) {
  const int x = static_cast<int>(std::floor(px.x)), y = static_cast<int>(std::floor(px.y));
  for (int yy = std::max(0, y - r); yy <= std::min(m.height - 1, y + r); ++yy)
    for (int xx = std::max(0, x - r); xx <= std::min(m.width - 1, x + r); ++xx)
      if (m.at(xx, yy)) return true;
  return false;
}

bool onDiscontinuity(const DepthImage& depth, const PixelProjector& proj, glm::vec2 px, float eye_depth,
                     const OutlineParams& params) {
  const int x = static_cast<int>(std::floor(px.x)), y = static_cast<int>(std::floor(px.y));
  const int r = params.discontinuity_radius_px;
  const float limit = eye_depth * (1.0f + params.depth_jump);
  for (int yy = std::max(0, y - r); yy <= std::min(depth.height - 1, y + r); ++yy)
    for (int xx = std::max(0, x - r); xx <= std::min(depth.width - 1, x + r); ++xx) {
      const float d = depth.at(xx, yy);
      if (d >= 1.0f || proj.eyeDepthOfWindow(d) > limit) return true;
    }
  return false;
}

// The row-major key of the pixel holding `px`; false outside a W×H image.
bool pixelKey(glm::vec2 px, int W, int H, uint32_t& key) {
  const int x = static_cast<int>(std::floor(px.x)), y = static_cast<int>(std::floor(px.y));
  if (x < 0 || y < 0 || x >= W || y >= H) return false;
  key = static_cast<uint32_t>(y) * static_cast<uint32_t>(W) + static_cast<uint32_t>(x);
  return true;
}

// Orders entries with a pixel key, a run and an index by pixel (ties by run, then index, so
// every search below sees them in the same order).
template <class T>
void sortByPixel(std::vector<T>& v) {
  std::sort(v.begin(), v.end(), [](const T& a, const T& b) {
    return a.pixel != b.pixel ? a.pixel < b.pixel : (a.run != b.run ? a.run < b.run : a.index < b.index);
  });
}

// Calls f on the entries of `sorted` (sortByPixel) whose pixel lies within r pixels
// (Chebyshev) of q's, pixel by pixel; stops at the first call that returns true and says
// whether one did.
template <class T, class F>
bool anyNear(const std::vector<T>& sorted, glm::vec2 q, int r, int W, int H, F&& f) {
  const int x = static_cast<int>(std::floor(q.x)), y = static_cast<int>(std::floor(q.y));
  for (int yy = std::max(0, y - r); yy <= std::min(H - 1, y + r); ++yy)
    for (int xx = std::max(0, x - r); xx <= std::min(W - 1, x + r); ++xx) {
      const uint32_t key = static_cast<uint32_t>(yy) * static_cast<uint32_t>(W) + static_cast<uint32_t>(xx);
      auto it = std::lower_bound(sorted.begin(), sorted.end(), key, [](const T& c, uint32_t k) { return c.pixel < k; });
      for (; it != sorted.end() && it->pixel == key; ++it)
        if (f(*it)) return true;
    }
  return false;
}

// A completing piece spliced into contour run `run` in place of its samples [lo, hi]
// (indices of sampleRun()'s samples), oriented along the run.
struct Splice {
  uint32_t run, lo, hi;
  std::vector<Sample> samples;
};

// Appends the samples of splice `sp` into contour run `run` (sampleRun()'s samples) to
// `out`, each moved from the run's nearest point to the silhouette by a weight that rises
// smoothly from 0 at the piece's ends to 1 `ramp_px` inside them: the run leaves the contour
// and comes back to it without a step.
void blendSplice(const Splice& sp, const std::vector<Sample>& run, float ramp_px, std::vector<Sample>& out) {
  const size_t n = sp.samples.size();
  if (run.empty() || n == 0) return;
  // The run's nearest point is looked for a few samples past the stretch the piece replaces:
  // the piece's grown ends lie beside the samples just outside it.
  constexpr size_t kMargin = 4;
  const size_t lo = sp.lo >= kMargin ? sp.lo - kMargin : 0;
  const size_t hi = std::min(run.size() - 1, static_cast<size_t>(sp.hi) + kMargin);
  float total = 0.0f;
  for (size_t k = 1; k < n; ++k) total += glm::length(sp.samples[k].px - sp.samples[k - 1].px);
  const float ramp = std::min(ramp_px, 0.5f * total);
  float walked = 0.0f;
  for (size_t k = 0; k < n; ++k) {
    const Sample& q = sp.samples[k];
    if (k > 0) walked += glm::length(q.px - sp.samples[k - 1].px);
    // The run's nearest point (on its segments between lo and hi).
    Sample c = run[lo];
    float best = glm::length(q.px - c.px);
    for (size_t i = lo; i < hi; ++i) {
      const glm::vec2 a = run[i].px, ab = run[i + 1].px - a;
      const float t = nearestOnSegment(q.px, a, ab);
      const float d = glm::length(q.px - (a + t * ab));
      if (d < best) {
        best = d;
        c = {a + t * ab, run[i].p + t * (run[i + 1].p - run[i].p), run[i].alpha + t * (run[i + 1].alpha - run[i].alpha),
             run[i].eye_depth + t * (run[i + 1].eye_depth - run[i].eye_depth)};
      }
    }
    const float e = ramp > 0.0f ? std::clamp(std::min(walked, total - walked) / ramp, 0.0f, 1.0f) : 1.0f;
    const float w = e * e * (3.0f - 2.0f * e);
    out.push_back({c.px + w * (q.px - c.px), c.p + w * (q.p - c.p), c.alpha + w * (q.alpha - c.alpha),
                   c.eye_depth + w * (q.eye_depth - c.eye_depth)});
  }
}

// What becomes of a completing piece (docs/visibility.md, step 2).
struct PieceRole {
  enum Kind { kDraw, kSkip, kSplice } kind = kDraw;
  uint32_t run = 0, a = 0, b = 0;  // kSplice: the run, and its samples beside the two ends
};

// A contour sample this many samples (pixels) or fewer from its run's end is at the end: a
// piece from there continues the outline past the run rather than leaving it in its middle.
constexpr uint32_t kRunEndSamples = 3;

// Appends the samples [i, j) of one run as a run of `out`.
void emitRun(const std::vector<Sample>& samples, size_t i, size_t j, LineKind kind, uint32_t stroke, StrokeRuns& out) {
  if (out.offsets.empty()) out.offsets.push_back(0);
  float length = 0.0f, alpha = 0.0f;
  for (size_t k = i; k < j; ++k) {
    alpha += samples[k].alpha;
    if (k > i) length += glm::length(samples[k].px - samples[k - 1].px);
    // Samples inside a straight piece (same direction on both sides) are not points of the
    // run: every point is a joint where the drawn line can lose a row of samples.
    if (k > i && k + 1 < j) {
      const glm::vec2 d0 = samples[k].px - samples[k - 1].px, d1 = samples[k + 1].px - samples[k].px;
      const float l0 = glm::length(d0), l1 = glm::length(d1);
      if (l0 > 0.0f && l1 > 0.0f && std::abs(d0.x * d1.y - d0.y * d1.x) <= 1e-4f * l0 * l1 && glm::dot(d0, d1) > 0.0f &&
          std::abs(samples[k].alpha - 0.5f * (samples[k - 1].alpha + samples[k + 1].alpha)) < 1e-4f)
        continue;
    }
    out.points.push_back(samples[k].px);
    out.positions.push_back(samples[k].p);
    out.alpha.push_back(samples[k].alpha);
  }
  out.offsets.push_back(static_cast<uint32_t>(out.points.size()));
  out.kinds.push_back(kind);
  out.strokes.push_back(stroke);
  out.opacity.push_back(alpha / static_cast<float>(j - i));
  out.length_px.push_back(length);
}

// Appends run r of `from` to `to` unchanged.
void copyRun(const StrokeRuns& from, size_t r, StrokeRuns& to) {
  if (to.offsets.empty()) to.offsets.push_back(0);
  const uint32_t b = from.offsets[r], e = from.offsets[r + 1];
  to.points.insert(to.points.end(), from.points.begin() + b, from.points.begin() + e);
  to.positions.insert(to.positions.end(), from.positions.begin() + b, from.positions.begin() + e);
  to.alpha.insert(to.alpha.end(), from.alpha.begin() + b, from.alpha.begin() + e);
  to.offsets.push_back(static_cast<uint32_t>(to.points.size()));
  to.kinds.push_back(from.kinds[r]);
  to.strokes.push_back(from.strokes[r]);
  to.opacity.push_back(from.opacity[r]);
  to.length_px.push_back(from.length_px[r]);
}

// The point of run r within `reach_px` of arc length from its start (from its end when
// `at_end`) nearest to `target`: its segment (the index of the segment's point nearer the
// run's inside) and the distance.
struct EndHit {
  uint32_t inner = 0;
  float distance = std::numeric_limits<float>::infinity();
};
EndHit nearestNearEnd(const StrokeRuns& runs, size_t r, bool at_end, float reach_px, glm::vec2 target) {
  const uint32_t b = runs.offsets[r], e = runs.offsets[r + 1];
  EndHit hit;
  float walked = 0.0f;
  for (uint32_t k = 0; k + 1 < e - b && walked <= reach_px; ++k) {
    const uint32_t outer = at_end ? e - 1 - k : b + k, inner = at_end ? outer - 1 : outer + 1;
    const glm::vec2 a = runs.points[outer], ab = runs.points[inner] - a;
    const float t = nearestOnSegment(target, a, ab);
    const float d = glm::length(target - (a + t * ab));
    const float len = std::sqrt(glm::dot(ab, ab));
    if (d < hit.distance && walked + t * len <= reach_px) hit = {inner, d};  // only near the end
    walked += len;
  }
  return hit;
}

// The point of the polyline points[b, e) nearest to `q`: segment k (points k, k + 1), its
// parameter t and the distance.
struct PolylineHit {
  uint32_t k = 0;
  float t = 0.0f;
  float distance = std::numeric_limits<float>::infinity();
};
PolylineHit nearestOnPolyline(const std::vector<glm::vec2>& points, uint32_t b, uint32_t e, glm::vec2 q) {
  PolylineHit hit;
  for (uint32_t k = b; k + 1 < e; ++k) {
    const glm::vec2 a = points[k], ab = points[k + 1] - a;
    const float t = nearestOnSegment(q, a, ab);
    const float d = glm::length(q - (a + t * ab));
    if (d < hit.distance) hit = {k, t, d};
  }
  return hit;
}

// A point of a run as the rebuilding below handles it.
struct RunPoint {
  glm::vec2 px;
  glm::vec3 p;
  float alpha;
};

// Appends `pts` as a run of `out` with the kind, stroke and opacity of run r of `from`.
void pushRun(const std::vector<RunPoint>& pts, const StrokeRuns& from, size_t r, StrokeRuns& out) {
  if (pts.size() < 2) return;
  if (out.offsets.empty()) out.offsets.push_back(0);
  float length = 0.0f, alpha = 0.0f;
  for (size_t i = 0; i < pts.size(); ++i) {
    alpha += pts[i].alpha;
    out.points.push_back(pts[i].px);
    out.positions.push_back(pts[i].p);
    out.alpha.push_back(pts[i].alpha);
    if (i > 0) length += glm::length(pts[i].px - pts[i - 1].px);
  }
  out.offsets.push_back(static_cast<uint32_t>(out.points.size()));
  out.kinds.push_back(from.kinds[r]);
  out.strokes.push_back(from.strokes[r]);
  out.opacity.push_back(alpha / static_cast<float>(pts.size()));
  out.length_px.push_back(length);
}

// stitchToContourEnds()' reach and radius: a piece's grown end and two pixels more, and the
// contour radius and half a pixel.
float stitchReach(const OutlineParams& params) { return params.extend_px + 2.0f; }
float stitchRadius(const OutlineParams& params) { return static_cast<float>(params.contour_radius_px) + 0.5f; }

}  // namespace

void takeOverContourEnds(const StrokeRuns& contours, const StrokeRuns& fill, const OutlineParams& params,
                         StrokeRuns& contours_out) {
  const float reach_px = params.overlap_reach_px, radius_px = params.overlap_radius_px;
  const float min_stretch_px = params.min_drop_px, ramp_px = params.splice_ramp_px;
  const float stitch_reach_px = stitchReach(params), stitch_radius_px = stitchRadius(params);
  // Per contour run end (2c: start, 2c + 1: end): the point it is cut back to, if any.
  struct Cut {
    PolylineHit at;
    RunPoint onto{};  // the piece's end, where the cut run now ends
    bool set = false;
  };
  std::vector<Cut> cuts(2 * contours.strokeCount());
  auto pointAt = [](const StrokeRuns& runs, const PolylineHit& h) {
    const glm::vec2 a = runs.points[h.k], b = runs.points[h.k + 1];
    const glm::vec3 pa = runs.positions[h.k], pb = runs.positions[h.k + 1];
    return RunPoint{a + h.t * (b - a), pa + h.t * (pb - pa),
                    runs.alpha[h.k] + h.t * (runs.alpha[h.k + 1] - runs.alpha[h.k])};
  };
  bool any = false;
  for (size_t r = 0; r < fill.strokeCount(); ++r) {
    const uint32_t b = fill.offsets[r], e = fill.offsets[r + 1];
    if (e - b < 2) continue;
    float piece_length = 0.0f;
    for (uint32_t k = b + 1; k < e; ++k) piece_length += glm::length(fill.points[k] - fill.points[k - 1]);
    for (int side = 0; side < 2; ++side) {
      const glm::vec2 piece_end = fill.points[side == 1 ? e - 1 : b];
      // The piece's points within reach of its end, as a polyline [pb, pe).
      uint32_t pb = b, pe = e;
      {
        float walked = 0.0f;
        if (side == 1) {
          for (pb = e - 1; pb > b && walked <= reach_px; --pb) walked += glm::length(fill.points[pb] - fill.points[pb - 1]);
        } else {
          for (pe = b + 1; pe < e && walked <= reach_px; ++pe) walked += glm::length(fill.points[pe] - fill.points[pe - 1]);
        }
      }
      bool stitched = false;
      struct Candidate {
        size_t c;
        int which;
        PolylineHit at;
      } best{0, 0, {}};
      for (size_t c = 0; c < contours.strokeCount() && !stitched; ++c) {
        const uint32_t cb = contours.offsets[c], ce = contours.offsets[c + 1];
        if (contours.kinds[c] != LineKind::kContour || ce - cb < 2) continue;
        for (int which = 0; which < 2; ++which) {
          const glm::vec2 contour_end = contours.points[which == 1 ? ce - 1 : cb];
          if (glm::length(contour_end - piece_end) > reach_px + radius_px) continue;
          if (nearestNearEnd(fill, r, side == 1, stitch_reach_px, contour_end).distance <= stitch_radius_px) {
            stitched = true;  // the stitch meets it as it is
            break;
          }
          if (nearestOnPolyline(fill.points, pb, pe, contour_end).distance > radius_px) continue;
          // The contour's point nearest the piece's end, and the stretch from the contour's
          // end to it beside the piece all along (its points, and that point).
          const PolylineHit at = nearestOnPolyline(contours.points, cb, ce, piece_end);
          if (at.distance > radius_px || !(at.distance < best.at.distance)) continue;
          const RunPoint cut = pointAt(contours, at);
          bool beside = nearestOnPolyline(fill.points, pb, pe, cut.px).distance <= radius_px;
          float stretch = 0.0f;
          if (which == 0) {
            for (uint32_t k = cb; k <= at.k && beside; ++k) {
              beside = nearestOnPolyline(fill.points, pb, pe, contours.points[k]).distance <= radius_px;
              stretch += glm::length((k < at.k ? contours.points[k + 1] : cut.px) - contours.points[k]);
            }
          } else {
            for (uint32_t k = ce - 1; k > at.k && beside; --k) {
              beside = nearestOnPolyline(fill.points, pb, pe, contours.points[k]).distance <= radius_px;
              stretch += glm::length(contours.points[k] - (k - 1 > at.k ? contours.points[k - 1] : cut.px));
            }
          }
          // Beside it and along it: the stretch is no longer than the piece's part that
          // reaches over it (a contour that turns away and back is not this case).
          // A stretch shorter than min_stretch_px is left to the joining's gap bridge: bent
          // over it, the piece would make an S where the two lines meet nearly end to end.
          // And the piece draws more than the stretch it takes (a piece of a few pixels in a
          // fold's tangle does not take a contour's end).
          if (beside && stretch <= reach_px + radius_px && stretch >= min_stretch_px && piece_length >= 2.0f * stretch)
            best = {c, which, at};
        }
      }
      if (stitched || !(best.at.distance <= radius_px)) continue;
      Cut& cut = cuts[2 * best.c + best.which];
      if (cut.set) continue;  // one piece per contour end
      cut = {best.at, {piece_end, fill.positions[side == 1 ? e - 1 : b], fill.alpha[side == 1 ? e - 1 : b]}, true};
      any = true;
    }
  }
  contours_out.clear();
  if (!any) {
    appendStrokes(contours, contours_out);
    return;
  }
  std::vector<RunPoint> pts;
  for (size_t c = 0; c < contours.strokeCount(); ++c) {
    const uint32_t cb = contours.offsets[c], ce = contours.offsets[c + 1];
    const Cut &head = cuts[2 * c], &tail = cuts[2 * c + 1];
    if (!head.set && !tail.set) {
      copyRun(contours, c, contours_out);
      continue;
    }
    // The run from its head's cut (after point head.at.k) to its tail's (up to point
    // tail.at.k + 1); nothing is left when the two cuts cross.
    if (head.set && tail.set && (tail.at.k < head.at.k || (tail.at.k == head.at.k && tail.at.t <= head.at.t)))
      continue;
    pts.clear();
    const uint32_t from = head.set ? head.at.k + 1 : cb, to = tail.set ? tail.at.k + 1 : ce;
    auto add = [&](const RunPoint& q) {  // a cut at a point of the run is that point once
      if (pts.empty() || glm::length(q.px - pts.back().px) > 1e-4f) pts.push_back(q);
    };
    if (head.set) add(pointAt(contours, head.at));
    for (uint32_t k = from; k < to; ++k) add({contours.points[k], contours.positions[k], contours.alpha[k]});
    if (tail.set) add(pointAt(contours, tail.at));
    if (pts.size() < 2) continue;
    float total = 0.0f;
    for (size_t k = 1; k < pts.size(); ++k) total += glm::length(pts[k].px - pts[k - 1].px);
    for (int side = 0; side < 2; ++side) {
      const Cut& cut = side == 0 ? head : tail;
      if (!cut.set) continue;
      if (side == 0) std::reverse(pts.begin(), pts.end());
      // The run's points over its last max(ramp_px, 8 × the distance) px, and on to its next
      // point (the bend stays at points where the run already turns: on a straight stretch
      // its last segment turns by a degree or two), each moved towards the piece's end by a
      // weight that rises linearly with arc length to 1 at the end; the piece stays on the
      // outline. A run shorter than twice that bends over its last half (a point inserted).
      const glm::vec2 d = cut.onto.px - pts.back().px;
      const glm::vec3 dp = cut.onto.p - pts.back().p;
      const float want = std::max(ramp_px, 8.0f * glm::length(d)), half = 0.5f * total;
      size_t k = pts.size() - 1;
      float walked = 0.0f;
      while (k > 0 && walked < want) {
        const float len = glm::length(pts[k].px - pts[k - 1].px);
        if (walked + len > half) {  // stop inside this segment, at half the run
          const float t = len > 0.0f ? (half - walked) / len : 0.0f;
          const RunPoint q{pts[k].px + t * (pts[k - 1].px - pts[k].px), pts[k].p + t * (pts[k - 1].p - pts[k].p),
                           pts[k].alpha + t * (pts[k - 1].alpha - pts[k].alpha)};
          pts.insert(pts.begin() + static_cast<std::ptrdiff_t>(k), q);
          walked = half;
          break;
        }
        walked += len;
        --k;
      }
      // Points k + 1 … end move; point k (at arc `walked` from the end) stays.
      float arc = 0.0f;
      for (size_t j = pts.size() - 1; j > k && walked > 0.0f; --j) {
        const float w = 1.0f - arc / walked;
        arc += glm::length(pts[j].px - pts[j - 1].px);
        pts[j].px += w * d;
        pts[j].p += w * dp;
      }
      pts.back().px = cut.onto.px;
      pts.back().p = cut.onto.p;
      if (side == 0) std::reverse(pts.begin(), pts.end());
    }
    pushRun(pts, contours, c, contours_out);
  }
}

namespace {

// Completing pieces were grown along the silhouette over the contour's ends so that the two
// meet; drawn as they are, each junction would be two overlapping strokes (two caps, a bead
// where the style is translucent; two tapers, a pinch in the outline). A piece end that
// passes within `radius_px` of a contour run's end is cut back to that end instead, so that
// the two join into one stroke where the strokes are built (joinRuns(), screen_lines.h).
// A piece end that meets no contour end so, but has one within `gap_px` of it across the
// outline (every pixel of the gap within 2 px of `outline`), continuing the piece within 60°
// and not turning the contour back on itself, is carried on to it: at a corner of the
// outline the contour can end a few pixels short of the silhouette, the piece's growth does
// not reach it, and the outline broke there (the cow's neck meeting its chest close up).
void stitchToContourEnds(const StrokeRuns& contours, const StrokeRuns& fill, float reach_px, float radius_px,
                         float gap_px, const LineMask& outline, StrokeRuns& out) {
  out.clear();
  out.offsets.push_back(0);
  const size_t n = fill.strokeCount();
  // Per piece end (2r: start, 2r + 1: end): the contour end it meets (point index into
  // `contours`) and the piece's point it is cut back to.
  std::vector<uint32_t> meets(2 * n, UINT32_MAX);
  std::vector<EndHit> hits(2 * n);
  for (size_t r = 0; r < n; ++r) {
    const uint32_t b = fill.offsets[r], e = fill.offsets[r + 1];
    for (int side = 0; side < 2 && e - b >= 2; ++side) {
      // A point within reach_px of arc length from the piece's end lies that close to it.
      const glm::vec2 piece_end = fill.points[side == 1 ? e - 1 : b];
      for (size_t c = 0; c < contours.strokeCount(); ++c) {
        if (contours.kinds[c] != LineKind::kContour || contours.offsets[c + 1] - contours.offsets[c] < 2) continue;
        for (uint32_t end : {contours.offsets[c], contours.offsets[c + 1] - 1}) {
          if (glm::length(contours.points[end] - piece_end) > reach_px + radius_px) continue;
          const EndHit h = nearestNearEnd(fill, r, side == 1, reach_px, contours.points[end]);
          if (h.distance <= radius_px && h.distance < hits[2 * r + side].distance)
            hits[2 * r + side] = h, meets[2 * r + side] = end;
        }
      }
    }
  }
  // Across a gap: only contour ends no piece meets yet, each once.
  std::vector<uint32_t> taken(meets);
  std::sort(taken.begin(), taken.end());
  // The direction from the point `arc_px` of arc inside a polyline's end to that end.
  auto outward = [](const std::vector<glm::vec2>& pts, uint32_t b, uint32_t e, bool at_end, float arc_px) {
    const glm::vec2 end = pts[at_end ? e - 1 : b];
    glm::vec2 inner = end;
    float walked = 0.0f;
    for (uint32_t k = 1; k < e - b && walked < arc_px; ++k) {
      const glm::vec2 q = pts[at_end ? e - 1 - k : b + k];
      walked += glm::length(q - inner);
      inner = q;
    }
    const glm::vec2 d = end - inner;
    const float len = glm::length(d);
    return len > 0.0f ? d / len : glm::vec2(0.0f);
  };
  for (size_t r = 0; r < n && gap_px > 0.0f; ++r) {
    const uint32_t b = fill.offsets[r], e = fill.offsets[r + 1];
    for (int side = 0; side < 2 && e - b >= 2; ++side) {
      if (meets[2 * r + side] != UINT32_MAX) continue;
      const glm::vec2 piece_end = fill.points[side == 1 ? e - 1 : b];
      const glm::vec2 piece_dir = outward(fill.points, b, e, side == 1, 3.0f);
      uint32_t best = UINT32_MAX;
      float best_d = gap_px;
      for (size_t c = 0; c < contours.strokeCount(); ++c) {
        const uint32_t cb = contours.offsets[c], ce = contours.offsets[c + 1];
        if (contours.kinds[c] != LineKind::kContour || ce - cb < 2) continue;
        for (uint32_t end : {cb, ce - 1}) {
          const glm::vec2 gap = contours.points[end] - piece_end;
          const float d = glm::length(gap);
          if (!(d > 0.0f) || d > best_d || std::binary_search(taken.begin(), taken.end(), end)) continue;
          const glm::vec2 g = gap / d;
          if (glm::dot(piece_dir, g) < 0.5f) continue;  // the piece would turn more than 60°
          if (glm::dot(outward(contours.points, cb, ce, end == ce - 1, 6.0f), -g) < 0.0f) continue;
          bool along = true;
          const int steps = static_cast<int>(std::ceil(d));
          for (int k = 0; k <= steps && along; ++k)
            along = near(outline, piece_end + (static_cast<float>(k) / static_cast<float>(steps)) * gap, 2);
          if (along) best = end, best_d = d;
        }
      }
      if (best == UINT32_MAX) continue;
      meets[2 * r + side] = best;
      hits[2 * r + side] = {side == 1 ? e - 1 : b, best_d};
      taken.insert(std::upper_bound(taken.begin(), taken.end(), best), best);
    }
  }
  for (size_t r = 0; r < n; ++r) {
    const uint32_t b = fill.offsets[r], e = fill.offsets[r + 1];
    uint32_t m0 = meets[2 * r], m1 = meets[2 * r + 1];
    // The piece's points between its (possibly new) ends.
    uint32_t first = b, last = e - 1;
    if (m0 != UINT32_MAX) first = hits[2 * r].inner;
    if (m1 != UINT32_MAX) last = hits[2 * r + 1].inner;
    // Kept as it is: a piece whose two ends meet the same contour end, or that would lose
    // all its points to one end.
    const bool both = m0 != UINT32_MAX && m1 != UINT32_MAX;
    if ((both && m0 == m1) || (!both && first > last)) {
      first = b, last = e - 1, m0 = m1 = UINT32_MAX;
    }
    auto push = [&](glm::vec2 px, glm::vec3 p, float alpha) {
      out.points.push_back(px);
      out.positions.push_back(p);
      out.alpha.push_back(alpha);
    };
    const size_t start = out.points.size();
    if (m0 != UINT32_MAX) push(contours.points[m0], contours.positions[m0], fill.alpha[first]);
    for (uint32_t i = first; i <= last && i < e; ++i) push(fill.points[i], fill.positions[i], fill.alpha[i]);
    if (m1 != UINT32_MAX) push(contours.points[m1], contours.positions[m1], fill.alpha[last]);
    float length = 0.0f;
    for (size_t i = start + 1; i < out.points.size(); ++i) length += glm::length(out.points[i] - out.points[i - 1]);
    out.offsets.push_back(static_cast<uint32_t>(out.points.size()));
    out.kinds.push_back(fill.kinds[r]);
    out.strokes.push_back(fill.strokes[r]);
    out.opacity.push_back(fill.opacity[r]);
    out.length_px.push_back(length);
  }
}

}  // namespace

double completeOutline(const StrokeSet& silhouette, const Camera& camera, const DepthImage& depth,
                       const VisibilityParams& visibility, const OutlineParams& params, StrokeRuns& visible,
                       OutlineScratch& scratch, OutlineHistory* history) {
  if (visible.offsets.empty()) visible.offsets.push_back(0);
  if (silhouette.strokeCount() == 0) {
    if (history) {
      history->fill.clear();
      history->view_proj = glm::mat4(0.0f);
      ++history->frames;
    }
    return 0.0;
  }
  const int W = depth.width, H = depth.height;
  const PixelProjector proj(camera, W, H);
  StrokeRuns& sil = scratch.silhouette;
  // Every visible bit of the silhouette, however short: a bit between hidden stretches can
  // be where the outline turns the corner of an occluder (VisibilityParams).
  VisibilityParams sil_visibility = visibility;
  sil_visibility.min_visible_between_hidden_px = 0.0f;
  splitStrokes(silhouette, camera, depth, sil_visibility, &sil, nullptr);
  std::vector<Sample> samples;

  // 1. The outline: visible silhouette samples on a depth discontinuity.
  clearMask(scratch.outline, W, H);
  for (size_t r = 0; r < sil.strokeCount(); ++r) {
    sampleRun(sil, r, proj, samples);
    for (const Sample& s : samples)
      if (onDiscontinuity(depth, proj, s.px, s.eye_depth, params)) mark(scratch.outline, s.px);
  }
  // 2. Where the visible contour is.
  clearMask(scratch.contours, W, H);
  auto& csamples = scratch.contour_samples;
  csamples.clear();
  scratch.run_samples.assign(visible.strokeCount(), 0);
  scratch.run_first.assign(visible.strokeCount(), 0);
  scratch.run_px.clear();
  const bool splicing = params.splice_radius_px > 0.0f;
  for (size_t r = 0; r < visible.strokeCount(); ++r) {
    if (visible.kinds[r] != LineKind::kContour) continue;
    sampleRun(visible, r, proj, samples);
    scratch.run_samples[r] = static_cast<uint32_t>(samples.size());
    scratch.run_first[r] = static_cast<uint32_t>(scratch.run_px.size());
    for (size_t i = 0; i < samples.size(); ++i) {
      const glm::vec2 px = samples[i].px;
      if (splicing) scratch.run_px.push_back(px);
      mark(scratch.contours, px);
      uint32_t key;
      if (splicing && pixelKey(px, W, H, key))
        csamples.push_back({key, static_cast<uint32_t>(r), static_cast<uint32_t>(i), px});
    }
  }
  sortByPixel(csamples);
  // The contour sample nearest to `q` within the splice radius, if any.
  const int splice_r = static_cast<int>(std::ceil(params.splice_radius_px));
  auto nearestContour = [&](glm::vec2 q) -> const OutlineScratch::ContourSample* {
    const OutlineScratch::ContourSample* best = nullptr;
    float best_d = params.splice_radius_px;
    anyNear(csamples, q, splice_r, W, H, [&](const OutlineScratch::ContourSample& c) {
      const float d = glm::length(c.px - q);
      if (d <= best_d) best = &c, best_d = d;
      return false;
    });
    return best;
  };
  // 3. Outline samples with no contour near: the completing pieces, grown along the
  //    silhouette so they meet the contour's ends. A piece continuing one of the previous
  //    frame's (projected by this camera) is kept whatever its length.
  clearMask(scratch.previous, W, H);
  const glm::mat4 view_proj = camera.projection(static_cast<float>(W) / static_cast<float>(H)) * camera.view();
  // A sequence whose camera has not moved (a viewer at rest) is drawn like a still, and so is
  // its first frame unless the sequence starts in motion (a capture).
  const bool in_sequence =
      history && (history->frames > 0 || history->starts_in_motion) && view_proj != history->view_proj;
  if (in_sequence)
    for (const glm::vec3& p : history->fill) {
      glm::vec2 px;
      float z;
      if (proj.project(p, px, z)) mark(scratch.previous, px);
    }
  StrokeRuns fill;
  fill.offsets.push_back(0);
  std::vector<Splice> splices;
  double spliced_px = 0.0;
  scratch.fill_samples.clear();
  clearMask(scratch.fill, W, H);
  clearMask(scratch.skipped, W, H);
  clearMask(scratch.spliced, W, H);
  const int extend = std::max(0, static_cast<int>(std::lround(params.extend_px)));
  // Per silhouette sample, whether it is missing (on the outline, no contour near), flat over
  // the runs; and, for the spurs' test that a free end is beside no other missing stretch of
  // the silhouette, every missing sample by pixel.
  auto& missing = scratch.missing;
  missing.clear();
  scratch.sil_flags.clear();
  scratch.sil_first.assign(sil.strokeCount(), 0);
  for (size_t r = 0; r < sil.strokeCount(); ++r) {
    sampleRun(sil, r, proj, samples);
    scratch.sil_first[r] = static_cast<uint32_t>(scratch.sil_flags.size());
    for (size_t i = 0; i < samples.size(); ++i) {
      const bool m =
          near(scratch.outline, samples[i].px, 0) && !near(scratch.contours, samples[i].px, params.contour_radius_px);
      scratch.sil_flags.push_back(m);
      uint32_t key;
      if (m && splicing && pixelKey(samples[i].px, W, H, key))
        missing.push_back({key, static_cast<uint32_t>(r), static_cast<uint32_t>(i)});
    }
  }
  sortByPixel(missing);
  // A missing sample within the splice radius of `q` outside samples [i, j) of silhouette run r.
  auto otherMissingNear = [&](glm::vec2 q, uint32_t r, size_t i, size_t j) {
    return anyNear(missing, q, splice_r, W, H, [&](const OutlineScratch::MissingSample& m) {
      return m.run != r || m.index < i || m.index >= j;
    });
  };
  // What becomes of the piece [i, j) of silhouette run r (docs/visibility.md, step 2):
  // - skipped when the contour runs within covered_px of all of it (a silhouette that
  //   zigzags about the contour by a pixel or two: drawn, each tooth was a tick), or when it
  //   is a short spur, one end beside the middle of a contour run and the other beside no
  //   line;
  // - spliced into the contour run that both its ends lie beside, when short enough, the
  //   run's stretch between them lies beside it and no earlier splice took that stretch (a
  //   polygon corner the contour cuts);
  // - drawn as a piece of its own otherwise.
  auto classify = [&](uint32_t r, size_t i, size_t j) -> PieceRole {
    if (!splicing) return {};
    float deviation = 0.0f;
    for (size_t k = i; k < j && deviation <= params.covered_px; ++k) {
      const auto* c = nearestContour(samples[k].px);
      deviation = std::max(deviation, c ? glm::length(c->px - samples[k].px) : std::numeric_limits<float>::infinity());
    }
    if (deviation <= params.covered_px) return {PieceRole::kSkip};
    const auto* a = nearestContour(samples[i].px);
    const auto* b = nearestContour(samples[j - 1].px);
    float length = 0.0f;
    for (size_t k = i + 1; k < j; ++k) length += glm::length(samples[k].px - samples[k - 1].px);
    if ((a == nullptr) != (b == nullptr) && length <= params.spur_max_px) {
      const auto* held = a ? a : b;
      const bool from_middle =
          held->index >= kRunEndSamples && held->index + kRunEndSamples < scratch.run_samples[held->run];
      const size_t free_end = a ? j - 1 : i;
      if (from_middle && !otherMissingNear(samples[free_end].px, r, i, j)) return {PieceRole::kSkip};
    }
    if (!a || !b || a->run != b->run || !(length <= params.splice_max_px)) return {};
    const uint32_t lo = std::min(a->index, b->index), hi = std::max(a->index, b->index);
    if (hi - lo > 2 * (j - i) + 4) return {};  // the run goes elsewhere between the two ends
    // The run's stretch must lie beside the piece: its middle within twice the radius.
    const glm::vec2 mid = scratch.run_px[scratch.run_first[a->run] + (lo + hi) / 2];
    float to_piece = std::numeric_limits<float>::infinity();
    for (size_t k = i; k < j; ++k) to_piece = std::min(to_piece, glm::length(samples[k].px - mid));
    if (!(to_piece <= 2.0f * params.splice_radius_px)) return {};
    for (const Splice& sp : splices)
      if (sp.run == a->run && lo <= sp.hi && hi >= sp.lo) return {};  // taken: drawn instead
    return {PieceRole::kSplice, a->run, a->index, b->index};
  };
  for (size_t r = 0; r < sil.strokeCount(); ++r) {
    sampleRun(sil, r, proj, samples);
    const auto first = scratch.sil_flags.begin() + scratch.sil_first[r];
    scratch.flags.assign(first, first + static_cast<std::ptrdiff_t>(samples.size()));
    scratch.grown.assign(samples.size(), 0);
    for (size_t i = 0; i < samples.size(); ++i) {
      if (!scratch.flags[i]) continue;
      const size_t lo = i >= static_cast<size_t>(extend) ? i - extend : 0;
      const size_t hi = std::min(samples.size() - 1, i + extend);
      for (size_t j = lo; j <= hi; ++j) scratch.grown[j] = 1;
    }
    for (size_t i = 0; i < samples.size();) {
      if (!scratch.grown[i]) {
        ++i;
        continue;
      }
      size_t j = i;
      bool continues = false;
      for (; j < samples.size() && scratch.grown[j]; ++j)
        continues = continues || (in_sequence && near(scratch.previous, samples[j].px, params.follow_radius_px));
      if (j - i >= 2 && (!in_sequence || continues || static_cast<float>(j - i) >= params.min_length_px)) {
        for (size_t k = i; k < j; ++k) samples[k].alpha = 1.0f;
        const PieceRole role = classify(static_cast<uint32_t>(r), i, j);
        auto remember = [&](size_t a, size_t b) {
          if (history)
            for (size_t k = a; k < b; ++k) scratch.fill_samples.push_back(samples[k].p);
        };
        if (role.kind == PieceRole::kSkip) {
          for (size_t k = i; k < j; ++k) mark(scratch.skipped, samples[k].px);
        } else if (role.kind == PieceRole::kSplice) {
          Splice sp{role.run, std::min(role.a, role.b), std::max(role.a, role.b), {}};
          sp.samples.assign(samples.begin() + static_cast<ptrdiff_t>(i), samples.begin() + static_cast<ptrdiff_t>(j));
          if (role.a > role.b) std::reverse(sp.samples.begin(), sp.samples.end());
          for (size_t k = i; k < j; ++k) mark(scratch.spliced, samples[k].px);
          remember(i, j);
          splices.push_back(std::move(sp));
        } else {
          // A fold of a coarse mesh lays two or three silhouette edges over one another
          // within a pixel or two: only the stretches that no earlier piece draws yet (of 3
          // samples or more: shorter ones would be dots beside the earlier piece).
          const int dup_r = static_cast<int>(std::floor(params.covered_px));
          scratch.dup.assign(j - i, 0);
          for (size_t k = i; k < j; ++k)
            scratch.dup[k - i] =
                dup_r > 0 && (near(scratch.fill, samples[k].px, dup_r) || near(scratch.spliced, samples[k].px, dup_r));
          for (size_t a = i; a < j;) {
            if (scratch.dup[a - i]) {
              ++a;
              continue;
            }
            size_t b = a;
            while (b < j && !scratch.dup[b - i]) ++b;
            if (b - a >= 3 || (a == i && b == j && b - a >= 2)) {
              for (size_t k = a; k < b; ++k) mark(scratch.fill, samples[k].px);
              remember(a, b);
              emitRun(samples, a, b, LineKind::kContour, sil.strokes[r], fill);
            }
            a = b;
          }
        }
      }
      i = j;
    }
  }
  if (history) {
    history->fill.swap(scratch.fill_samples);
    history->view_proj = view_proj;
    ++history->frames;
  }
  if (fill.strokeCount() == 0 && splices.empty()) return 0.0;
  // 4. Contour pieces beside a completing piece but off the outline would draw it twice.
  //    Each run also takes its splices (in run order; they do not overlap, step 3), and
  //    keeps the samples beside the pieces left out for it (dropped, neither would draw).
  std::sort(splices.begin(), splices.end(), [](const Splice& x, const Splice& y) {
    return x.run != y.run ? x.run < y.run : (x.lo != y.lo ? x.lo < y.lo : x.hi < y.hi);
  });
  size_t next_splice = 0;
  std::vector<Sample> merged;
  std::vector<uint8_t> merged_flags;
  const int covered = static_cast<int>(std::floor(params.covered_px));
  StrokeRuns& out = scratch.rebuilt;
  out.clear();
  out.offsets.push_back(0);
  for (size_t r = 0; r < visible.strokeCount(); ++r) {
    if (visible.kinds[r] != LineKind::kContour) {
      copyRun(visible, r, out);
      continue;
    }
    while (next_splice < splices.size() && splices[next_splice].run < r) ++next_splice;
    const size_t first_splice = next_splice;
    while (next_splice < splices.size() && splices[next_splice].run == r) ++next_splice;
    const bool has_splice = next_splice > first_splice;
    sampleRun(visible, r, proj, samples);
    scratch.flags.assign(samples.size(), 1);
    bool dropped = has_splice;
    // Samples beside a piece left out for this contour stay, unless a drawn piece runs within
    // covered_px of them (it draws that outline): dropped, neither would draw it.
    const int keep_r = std::max(covered, 1);
    auto keeps = [&](const Sample& q) {
      return splicing && near(scratch.skipped, q.px, keep_r) && !(covered > 0 && near(scratch.fill, q.px, covered));
    };
    for (size_t i = 0; i < samples.size(); ++i)
      if (near(scratch.fill, samples[i].px, params.double_radius_px) &&
          !near(scratch.outline, samples[i].px, params.contour_radius_px) && !keeps(samples[i])) {
        scratch.flags[i] = 0;
        dropped = true;
      }
    // Drops shorter than min_drop_px inside a run are noise (a sample or two a pixel off the
    // outline): cutting there would leave a notch in the line, not remove a second one. At a
    // run's end the run only gets shorter: a short end (or a whole short run) is a burr.
    for (size_t i = 0; dropped && i < samples.size();) {
      if (scratch.flags[i]) {
        ++i;
        continue;
      }
      size_t j = i;
      while (j < samples.size() && !scratch.flags[j]) ++j;
      if (i > 0 && j < samples.size() && static_cast<float>(j - i) < params.min_drop_px)
        for (size_t k = i; k < j; ++k) scratch.flags[k] = 1;
      i = j;
    }
    // A whole run within covered_px of the pieces (a dash of contour beside the silhouette
    // of a fold): the pieces draw it.
    if (!has_splice && covered > 0 && !samples.empty() && std::all_of(samples.begin(), samples.end(), [&](const Sample& q) {
          return near(scratch.fill, q.px, covered) && !keeps(q);
        }))
      continue;
    if (!has_splice &&
        (!dropped || std::all_of(scratch.flags.begin(), scratch.flags.end(), [](uint8_t f) { return f != 0; }))) {
      copyRun(visible, r, out);
      continue;
    }
    // The run's samples with each splice's stretch [lo, hi] replaced by its piece.
    merged.clear();
    merged_flags.clear();
    size_t s_at = first_splice;
    for (size_t i = 0; i < samples.size();) {
      while (s_at < next_splice && splices[s_at].lo < i) ++s_at;  // none do (step 3): defensive
      if (s_at < next_splice && splices[s_at].lo == i) {
        const Splice& sp = splices[s_at++];
        const size_t from = merged.size();
        blendSplice(sp, samples, params.splice_ramp_px, merged);
        for (size_t k = from + 1; k < merged.size(); ++k) spliced_px += glm::length(merged[k].px - merged[k - 1].px);
        merged_flags.resize(merged.size(), 1);
        i = std::min<size_t>(samples.size(), static_cast<size_t>(sp.hi) + 1);
        continue;
      }
      merged.push_back(samples[i]);
      merged_flags.push_back(scratch.flags[i]);
      ++i;
    }
    for (size_t i = 0; i < merged.size();) {
      if (!merged_flags[i]) {
        ++i;
        continue;
      }
      size_t j = i;
      while (j < merged.size() && merged_flags[j]) ++j;
      if (j - i >= 2) emitRun(merged, i, j, LineKind::kContour, visible.strokes[r], out);
      i = j;
    }
  }
  // 5. Pieces end where the contour they meet ends, so that the two join into one stroke;
  //    first, a piece's end that runs beside a contour run's end takes that stretch over.
  StrokeRuns* contours_now = &out;
  if (params.overlap_radius_px > 0.0f) {
    takeOverContourEnds(out, fill, params, scratch.taken);
    contours_now = &scratch.taken;
  }
  stitchToContourEnds(*contours_now, fill, stitchReach(params), stitchRadius(params), params.corner_gap_px, scratch.outline,
                      scratch.stitched);
  appendStrokes(scratch.stitched, *contours_now);
  std::swap(visible, *contours_now);
  return scratch.stitched.totalLength() + spliced_px;
}

}  // namespace lodline
