#include "present/stroke_parameterization.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

namespace lodline {
namespace {

constexpr float kCell = 3.0f;  // grid cell of the current segments, px

float median(std::vector<float>& v) {
  const size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid), v.end());
  return v[mid];
}

}  // namespace

void StrokeParameterizer::reset() {
  prev_positions_.clear();
  prev_u_.clear();
  prev_kinds_.clear();
  prev_runs_.clear();
  prev_fraction_.clear();
  prev_seams_.clear();
  prev_seam_kinds_.clear();
  prev_run_count_ = 0;
}

void StrokeParameterizer::update(StrokeRuns& runs, const Camera& camera, int width, int height, bool coherent,
                                 const StrokeParameterizationParams& params) {
  const size_t nr = runs.strokeCount();
  const size_t np = runs.points.size();
  closed_.assign(nr, 0);
  for (size_t r = 0; r < nr; ++r) {
    const uint32_t b = runs.offsets[r], e = runs.offsets[r + 1];
    closed_[r] = e - b >= 4 && glm::length(runs.points[b] - runs.points[e - 1]) < 0.5f;
  }
  // Closed runs start where a closed run of their kind started before (the seam stays put).
  if (coherent && !prev_seams_.empty() && runs.positions.size() == np && width > 0 && height > 0) {
    const PixelProjector projector(camera, width, height);
    seam_px_.clear();
    for (const glm::vec3& p : prev_seams_) {
      glm::vec2 px;
      float depth = 0.0f;
      seam_px_.push_back(projector.project(p, px, depth) ? px : glm::vec2(-1e9f));
    }
    const bool has_alpha = runs.alpha.size() == np;
    for (size_t r = 0; r < nr; ++r) {
      if (!closed_[r]) continue;
      const uint32_t b = runs.offsets[r], e = runs.offsets[r + 1];
      float best = params.match_px;
      uint32_t start = b;
      glm::vec2 lo = runs.points[b], hi = runs.points[b];
      for (uint32_t i = b + 1; i < e; ++i) lo = glm::min(lo, runs.points[i]), hi = glm::max(hi, runs.points[i]);
      lo -= params.match_px, hi += params.match_px;
      for (size_t k = 0; k < seam_px_.size(); ++k) {
        if (prev_seam_kinds_[k] != runs.kinds[r]) continue;
        const glm::vec2 q = seam_px_[k];
        if (q.x < lo.x || q.y < lo.y || q.x > hi.x || q.y > hi.y) continue;  // too far from this loop
        for (uint32_t i = b; i + 1 < e; ++i) {
          const float d = glm::length(runs.points[i] - seam_px_[k]);
          if (d < best) best = d, start = i;
        }
      }
      if (start == b) continue;
      // The loop without its repeated last point, rotated, then closed again.
      auto rotate = [&](auto& v) {
        std::rotate(v.begin() + b, v.begin() + start, v.begin() + (e - 1));
        v[e - 1] = v[b];
      };
      rotate(runs.points);
      rotate(runs.positions);
      if (has_alpha) rotate(runs.alpha);
    }
  }
  persisting_ = 0;
  drift_sum_ = 0.0;
  arc_.assign(np, 0.0f);
  point_run_.assign(np, 0);
  for (size_t r = 0; r < nr; ++r)
    for (uint32_t i = runs.offsets[r]; i < runs.offsets[r + 1]; ++i) {
      point_run_[i] = static_cast<uint32_t>(r);
      if (i > runs.offsets[r]) arc_[i] = arc_[i - 1] + glm::length(runs.points[i] - runs.points[i - 1]);
    }

  // Where the previous samples land: the nearest segment of a current run of their kind.
  landings_.clear();
  if (!prev_positions_.empty() && width > 0 && height > 0) {
    const int gw = static_cast<int>(std::ceil(static_cast<float>(width) / kCell)) + 1;
    const int gh = static_cast<int>(std::ceil(static_cast<float>(height) / kCell)) + 1;
    auto inImage = [&](glm::vec2 p) {
      return std::isfinite(p.x) && std::isfinite(p.y) && p.x > -kCell && p.y > -kCell && p.x < width + kCell &&
             p.y < height + kCell;
    };
    grid_.build(runs, glm::vec2(0.0f), kCell, gw, gh, inImage);

    const PixelProjector projector(camera, width, height);
    const bool has_positions = runs.positions.size() == np && params.surface_px > 0.0f;
    const bool ortho = camera.orthographic;
    // Model units per pixel: at unit eye depth (perspective), or everywhere (orthographic).
    const float world_per_px = (ortho ? camera.ortho_height : 2.0f * std::tan(glm::radians(camera.fov_deg) * 0.5f)) /
                               static_cast<float>(height);
    // Every run of the sample's kind within match_px: the nearest point of each.
    candidates_.clear();
    for (size_t j = 0; j < prev_positions_.size(); ++j) {
      glm::vec2 px;
      float depth = 0.0f;
      if (!projector.project(prev_positions_[j], px, depth) || !inImage(px)) continue;
      // The segments near the sample (in the 2 × 2 cells at most that the disc of radius
      // match_px touches, match_px being under half a cell).
      const size_t first = candidates_.size();
      grid_.forEachNear(px, params.match_px, [&](uint32_t i) {
        const uint32_t r = point_run_[i];
        if (runs.kinds[r] != prev_kinds_[j]) return;
        const glm::vec2 a = runs.points[i], ab = runs.points[i + 1] - a;
        const float t = nearestOnSegment(px, a, ab);
        const float d = glm::length(px - (a + t * ab));
        if (d > params.match_px) return;
        // And on the surface: the run's own point there must be the sample's, within
        // surface_px pixels' worth at its depth (else another piece of line lies over it
        // in the image, e.g. the other sheet of a fold: the sample did not persist).
        if (has_positions) {
          const glm::vec3 q = runs.positions[i] + t * (runs.positions[i + 1] - runs.positions[i]);
          if (glm::length(q - prev_positions_[j]) > params.surface_px * world_per_px * (ortho ? 1.0f : depth)) return;
        }
        const float s_here = arc_[i] + t * (arc_[i + 1] - arc_[i]);
        auto same = std::find_if(candidates_.begin() + static_cast<std::ptrdiff_t>(first), candidates_.end(),
                                 [r](const Candidate& c) { return c.run == r; });
        if (same == candidates_.end()) {
          candidates_.push_back({static_cast<uint32_t>(j), r, s_here, d});
          return;
        }
        // Near both ends of a closed run: the end the sample was nearer to on its loop.
        const float length = arc_[runs.offsets[r + 1] - 1];
        if (closed_[r] && prev_fraction_[j] >= 0.0f && std::abs(s_here - same->s) > 0.5f * length) {
          if (std::abs(s_here / length - prev_fraction_[j]) < std::abs(same->s / length - prev_fraction_[j]))
            *same = {static_cast<uint32_t>(j), r, s_here, d};
        } else if (d < same->d) {
          *same = {static_cast<uint32_t>(j), r, s_here, d};
        }
      });
    }
    // Where a sample could land on several runs (a junction, strokes side by side), it lands
    // on the run that most samples of its previous run landed on nearest (its successor).
    successor_keys_.clear();
    for (size_t g0 = 0; g0 < candidates_.size();) {
      size_t g1 = g0, nearest = g0;
      while (g1 < candidates_.size() && candidates_[g1].sample == candidates_[g0].sample) {
        if (candidates_[g1].d < candidates_[nearest].d) nearest = g1;
        ++g1;
      }
      successor_keys_.push_back((uint64_t(prev_runs_[candidates_[g0].sample]) << 32) | candidates_[nearest].run);
      g0 = g1;
    }
    std::sort(successor_keys_.begin(), successor_keys_.end());
    successor_.assign(prev_run_count_, UINT32_MAX);
    successor_votes_.assign(prev_run_count_, 0);
    auto& best_count = successor_votes_;
    for (size_t k0 = 0; k0 < successor_keys_.size();) {
      size_t k1 = k0;
      while (k1 < successor_keys_.size() && successor_keys_[k1] == successor_keys_[k0]) ++k1;
      const uint32_t from = static_cast<uint32_t>(successor_keys_[k0] >> 32);
      if (k1 - k0 > best_count[from]) {
        best_count[from] = static_cast<uint32_t>(k1 - k0);
        successor_[from] = static_cast<uint32_t>(successor_keys_[k0] & 0xffffffffu);
      }
      k0 = k1;
    }
    for (size_t g0 = 0; g0 < candidates_.size();) {
      size_t g1 = g0, chosen = g0;
      const uint32_t want = successor_[prev_runs_[candidates_[g0].sample]];
      bool found = false;
      while (g1 < candidates_.size() && candidates_[g1].sample == candidates_[g0].sample) {
        if (candidates_[g1].run == want) chosen = g1, found = true;
        else if (!found && candidates_[g1].d < candidates_[chosen].d) chosen = g1;
        ++g1;
      }
      const Candidate& c = candidates_[chosen];
      landings_.push_back({c.run, c.s, prev_u_[c.sample]});
      g0 = g1;
    }
  }
  std::sort(landings_.begin(), landings_.end(), [](const Landing& a, const Landing& b) { return a.run < b.run; });

  // u = s until a run's votes say otherwise.
  u_ = arc_;
  if (coherent)
    for (size_t g0 = 0; g0 < landings_.size();) {
      size_t g1 = g0;
      while (g1 < landings_.size() && landings_[g1].run == landings_[g0].run) ++g1;
      const uint32_t r = landings_[g0].run;
      if (static_cast<int>(g1 - g0) >= params.min_votes) {
        // The direction most votes agree with.
        float sign = 1.0f;
        size_t best_inliers = 0;
        for (float dir : {1.0f, -1.0f}) {
          votes_.clear();
          for (size_t k = g0; k < g1; ++k) votes_.push_back(landings_[k].u - dir * landings_[k].s);
          const float offset = median(votes_);
          size_t inliers = 0;
          for (size_t k = g0; k < g1; ++k)
            inliers += std::abs(landings_[k].u - dir * landings_[k].s - offset) < params.inlier_px;
          if (inliers > best_inliers) best_inliers = inliers, sign = dir;
        }
        // Votes by arc length, then each point's offset: the median of the votes within the
        // window, else the nearest vote's.
        std::sort(landings_.begin() + static_cast<std::ptrdiff_t>(g0), landings_.begin() + static_cast<std::ptrdiff_t>(g1),
                  [](const Landing& a, const Landing& b) { return a.s < b.s; });
        size_t lo = g0, hi = g0;
        for (uint32_t i = runs.offsets[r]; i < runs.offsets[r + 1]; ++i) {
          const float s = arc_[i];
          while (lo < g1 && landings_[lo].s < s - params.window_px) ++lo;
          if (hi < lo) hi = lo;
          while (hi < g1 && landings_[hi].s <= s + params.window_px) ++hi;
          // Widen the window to the nearest `min_window_votes` votes where it holds fewer
          // (sparse runs, the ends): one parent's texture wins on each part.
          size_t a = lo, c = hi;
          while (c - a < std::min<size_t>(params.min_window_votes, g1 - g0)) {
            const bool left = a > g0, right = c < g1;
            if (left && (!right || s - landings_[a - 1].s <= landings_[c].s - s)) --a;
            else ++c;
          }
          window_.clear();
          for (size_t k = a; k < c; ++k) window_.push_back(landings_[k].u - sign * landings_[k].s);
          float offset = median(window_);
          // Where the window holds two sides of a seam (two parents' textures), the point
          // takes its nearest vote's side, moved toward the window's median by at most
          // heal_px: a seam stays where it was on the surface and closes a little every
          // frame, instead of jumping by a sample or two with the median (docs/strokes.md).
          if (c > a && params.heal_px < std::numeric_limits<float>::infinity()) {
            size_t nearest = a;
            for (size_t k = a + 1; k < c; ++k)
              if (std::abs(landings_[k].s - s) < std::abs(landings_[nearest].s - s)) nearest = k;
            const float o_n = landings_[nearest].u - sign * landings_[nearest].s;
            votes_.clear();
            for (size_t k = a; k < c; ++k) {
              const float o = landings_[k].u - sign * landings_[k].s;
              if (std::abs(o - o_n) < params.inlier_px) votes_.push_back(o);
            }
            const float side = median(votes_);
            offset = side + std::clamp(offset - side, -params.heal_px, params.heal_px);
          }
          u_[i] = offset + sign * s;
        }
      }
      g0 = g1;
    }

  // The texture drift of persisting samples: where each landed, this frame's parameter
  // (between the run's points) against the one it carried.
  for (const Landing& l : landings_) {
    const uint32_t b = runs.offsets[l.run], e = runs.offsets[l.run + 1];
    if (e - b < 2) {
      drift_sum_ += std::abs(u_[b] - l.u);
      continue;
    }
    const auto it = std::upper_bound(arc_.begin() + b, arc_.begin() + e, l.s);
    const uint32_t i1 = std::clamp<uint32_t>(static_cast<uint32_t>(it - arc_.begin()), b + 1, e - 1), i0 = i1 - 1;
    const float span = arc_[i1] - arc_[i0];
    const float t = span > 0.0f ? std::clamp((l.s - arc_[i0]) / span, 0.0f, 1.0f) : 0.0f;
    drift_sum_ += std::abs(u_[i0] + t * (u_[i1] - u_[i0]) - l.u);
  }
  persisting_ = landings_.size();

  // This frame's samples, for the next.
  prev_positions_.clear();
  prev_u_.clear();
  prev_kinds_.clear();
  prev_runs_.clear();
  prev_fraction_.clear();
  prev_seams_.clear();
  prev_seam_kinds_.clear();
  prev_run_count_ = nr;
  if (runs.positions.size() == np)
    for (size_t r = 0; r < nr; ++r) {
      const float length = arc_[runs.offsets[r + 1] - 1];
      const bool loop = closed_[r] && length > 0.0f;
      if (loop) {
        prev_seams_.push_back(runs.positions[runs.offsets[r]]);
        prev_seam_kinds_.push_back(runs.kinds[r]);
      }
      for (uint32_t i = runs.offsets[r]; i < runs.offsets[r + 1]; ++i) {
        prev_fraction_.push_back(loop ? arc_[i] / length : -1.0f);
        prev_positions_.push_back(runs.positions[i]);
        prev_u_.push_back(u_[i]);
        prev_kinds_.push_back(runs.kinds[r]);
        prev_runs_.push_back(static_cast<uint32_t>(r));
      }
    }
}

}  // namespace lodline
