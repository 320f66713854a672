#include "export/coherence.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

namespace lodline {
namespace {

// Pixels of `a` with no pixel of `b` within `r` (Chebyshev distance).
uint64_t unmatched(const LineMask& a, const LineMask& b, int r) {
  uint64_t n = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      if (!a.at(x, y)) continue;
      bool found = false;
      for (int yy = std::max(0, y - r); yy <= std::min(b.height - 1, y + r) && !found; ++yy)
        for (int xx = std::max(0, x - r); xx <= std::min(b.width - 1, x + r) && !found; ++xx)
          found = b.at(xx, yy);
      n += !found;
    }
  return n;
}

// A line pixel of one frame moved into the other, with its opacity (0–255) and where it was.
struct MovedPixel {
  int x, y;
  uint8_t opacity;
  int from_x, from_y;
};

// Moves every line pixel of `from` (frame A) to frame B by its surface point's image motion;
// `out` gets the moved pixel of each kept line pixel; returns the number dropped.
uint64_t moveLinePixels(const LineMask& from, const SurfaceImage& surf_a, const PixelProjector& proj_a,
                        const SurfaceImage& surf_b, const PixelProjector& proj_b, const CompensationParams& params,
                        std::vector<MovedPixel>& out) {
  out.clear();
  uint64_t dropped = 0;
  const int w = from.width, h = from.height, r = params.search_radius;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!from.at(x, y)) continue;
      // The surface point under the pixel, else the nearest covered pixel's.
      const glm::vec4* t = &surf_a.at(x, y);
      if (t->w <= 0.0f) {
        t = nullptr;
        int best = INT32_MAX;
        for (int yy = std::max(0, y - r); yy <= std::min(h - 1, y + r); ++yy)
          for (int xx = std::max(0, x - r); xx <= std::min(w - 1, x + r); ++xx) {
            const glm::vec4& c = surf_a.at(xx, yy);
            const int d = (xx - x) * (xx - x) + (yy - y) * (yy - y);
            if (c.w > 0.0f && d < best) {
              best = d;
              t = &c;
            }
          }
      }
      if (!t) {
        ++dropped;
        continue;
      }
      const glm::vec3 p(*t);
      glm::vec2 pa, pb;
      float da = 0.0f, db = 0.0f;
      if (!proj_a.project(p, pa, da) || !proj_b.project(p, pb, db)) {
        ++dropped;
        continue;
      }
      const glm::vec2 moved = glm::vec2(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f) + (pb - pa);
      const int mx = static_cast<int>(std::floor(moved.x)), my = static_cast<int>(std::floor(moved.y));
      if (mx < 0 || my < 0 || mx >= w || my >= h) {
        ++dropped;
        continue;
      }
      // Hidden in B: the surface around where the point now projects is nearer than the
      // point. The farthest surface over a 3×3 neighbourhood is taken (background counts as
      // infinitely far), so a contour point on the rim is not hidden by its own faces, as in
      // the hidden-line test of the strokes (export/visibility.h).
      const int sx = static_cast<int>(std::floor(pb.x)), sy = static_cast<int>(std::floor(pb.y));
      float farthest = 0.0f;
      bool open = false;
      for (int yy = std::max(0, sy - 1); yy <= std::min(h - 1, sy + 1) && !open; ++yy)
        for (int xx = std::max(0, sx - 1); xx <= std::min(w - 1, sx + 1) && !open; ++xx) {
          const glm::vec4& s = surf_b.at(xx, yy);
          if (s.w <= 0.0f) open = true;
          else farthest = std::max(farthest, proj_b.eyeDepth(glm::vec3(s)));
        }
      if (!open && farthest < db * (1.0f - params.depth_tolerance)) {
        ++dropped;
        continue;
      }
      out.push_back({mx, my, from.on[static_cast<size_t>(y) * w + x], x, y});
    }
  return dropped;
}

// Moved pixels with no pixel of `target` within Chebyshev distance r (the count), and the sum
// of how much more opaque each moved pixel is than the most opaque one of `target` within r.
// With `zones`, the unmatched pixels in each zone are added to near_ops / near_morphs, each
// looked up where it was (`at_source`: a pixel of the zones' frame) or where it moved to.
void unmatchedMoved(const std::vector<MovedPixel>& moved, const LineMask& target, int r, uint64_t& count,
                    double& weight, const ChangeZones* zones, bool at_source, uint64_t& near_ops,
                    uint64_t& near_morphs, uint8_t* pops) {
  count = 0;
  uint64_t excess = 0;
  for (const MovedPixel& p : moved) {
    uint8_t best = 0;
    for (int yy = std::max(0, p.y - r); yy <= std::min(target.height - 1, p.y + r) && best < p.opacity; ++yy)
      for (int xx = std::max(0, p.x - r); xx <= std::min(target.width - 1, p.x + r); ++xx)
        best = std::max(best, target.on[static_cast<size_t>(yy) * target.width + xx]);
    count += best == 0;
    excess += p.opacity > best ? p.opacity - best : 0;
    if (pops && p.opacity > best) {  // where the pixel is in the current frame
      uint8_t& v = pops[at_source ? static_cast<size_t>(p.from_y) * target.width + p.from_x
                                  : static_cast<size_t>(p.y) * target.width + p.x];
      v = std::max<uint8_t>(v, static_cast<uint8_t>(p.opacity - best));
    }
    if (zones && best == 0) {
      const uint8_t z = at_source ? zones->at(p.from_x, p.from_y) : zones->at(p.x, p.y);
      near_ops += (z & ChangeZones::kNearOps) != 0;
      near_morphs += (z & ChangeZones::kNearMorph) != 0;
    }
  }
  weight = static_cast<double>(excess) / 255.0;
}

}  // namespace

void PopMap::reset(int w, int h) {
  width = std::max(w, 0);
  height = std::max(h, 0);
  appeared.assign(static_cast<size_t>(width) * height, 0);
  vanished.assign(static_cast<size_t>(width) * height, 0);
}

Image popImage(const Image& frame, const PopMap& pops) {
  Image out = frame;
  const size_t n = static_cast<size_t>(frame.width) * frame.height;
  const bool with_pops = pops.width == frame.width && pops.height == frame.height && pops.appeared.size() == n &&
                         pops.vanished.size() == n && frame.rgba.size() == 4 * n;
  for (size_t i = 0; i < n && 4 * i + 3 < out.rgba.size(); ++i) {
    uint8_t* px = &out.rgba[4 * i];
    float c[3];
    for (int k = 0; k < 3; ++k) c[k] = 255.0f - (255.0f - px[k]) / 3.0f;
    auto over = [&](uint8_t a, float r, float g, float b) {
      const float t = a / 255.0f;
      c[0] += (r - c[0]) * t;
      c[1] += (g - c[1]) * t;
      c[2] += (b - c[2]) * t;
    };
    if (with_pops) {
      over(pops.vanished[i], 220.0f, 0.0f, 0.0f);
      over(pops.appeared[i], 0.0f, 170.0f, 0.0f);
    }
    for (int k = 0; k < 3; ++k) px[k] = static_cast<uint8_t>(std::lround(std::clamp(c[k], 0.0f, 255.0f)));
    px[3] = 255;
  }
  return out;
}

void ChangeZones::reset(int w, int h) {
  width = std::max(w, 0);
  height = std::max(h, 0);
  bits.assign(static_cast<size_t>(width) * height, 0);
}

void ChangeZones::mark(glm::vec2 px, int radius, uint8_t bit) {
  if (!(std::isfinite(px.x) && std::isfinite(px.y))) return;
  const int cx = static_cast<int>(std::floor(std::clamp(px.x, -1e6f, 1e6f)));
  const int cy = static_cast<int>(std::floor(std::clamp(px.y, -1e6f, 1e6f)));
  for (int y = std::max(0, cy - radius); y <= std::min(height - 1, cy + radius); ++y)
    for (int x = std::max(0, cx - radius); x <= std::min(width - 1, cx + radius); ++x)
      bits[static_cast<size_t>(y) * width + x] |= bit;
}

uint64_t LineMask::count() const {
  uint64_t n = 0;
  for (uint8_t v : on) n += v != 0;
  return n;
}

double LineMask::weight() const {
  uint64_t n = 0;
  for (uint8_t v : on) n += v;
  return static_cast<double>(n) / 255.0;
}

CompensatedChange compareMasksCompensated(const LineMask& previous, const SurfaceImage& previous_surface,
                                          const Camera& previous_camera, const LineMask& current,
                                          const SurfaceImage& current_surface, const Camera& current_camera,
                                          const CompensationParams& params) {
  CompensatedChange c;
  c.line_pixels = current.count();
  c.line_weight = current.weight();
  const int w = current.width, h = current.height;
  auto same = [&](int ow, int oh) { return ow == w && oh == h; };
  if (!same(previous.width, previous.height) || !same(previous_surface.width, previous_surface.height) ||
      !same(current_surface.width, current_surface.height)) {
    c.appeared = c.line_pixels;  // no comparable previous frame: everything is new
    c.appeared_weight = c.line_weight;
    if (params.pops) {
      params.pops->reset(w, h);
      if (current.on.size() == params.pops->appeared.size()) params.pops->appeared = current.on;
    }
    return c;
  }
  const PixelProjector prev_proj(previous_camera, w, h), cur_proj(current_camera, w, h);
  const ChangeZones* zones = params.zones && same(params.zones->width, params.zones->height) &&
                                     params.zones->bits.size() == static_cast<size_t>(w) * h
                                 ? params.zones
                                 : nullptr;
  if (params.pops) params.pops->reset(w, h);
  std::vector<MovedPixel> moved;
  // Forward: does each previous line pixel still have a line where its point went?
  c.dropped += moveLinePixels(previous, previous_surface, prev_proj, current_surface, cur_proj, params, moved);
  unmatchedMoved(moved, current, params.tolerance, c.vanished, c.vanished_weight, zones, false, c.popped_near_ops,
                 c.popped_near_morphs, params.pops ? params.pops->vanished.data() : nullptr);
  // Backward: was there a line where each current line pixel's point was before?
  c.dropped += moveLinePixels(current, current_surface, cur_proj, previous_surface, prev_proj, params, moved);
  unmatchedMoved(moved, previous, params.tolerance, c.appeared, c.appeared_weight, zones, true, c.popped_near_ops,
                 c.popped_near_morphs, params.pops ? params.pops->appeared.data() : nullptr);
  if (zones)
    for (size_t i = 0; i < current.on.size(); ++i) {
      if (!current.on[i]) continue;
      c.lines_near_ops += (zones->bits[i] & ChangeZones::kNearOps) != 0;
      c.lines_near_morphs += (zones->bits[i] & ChangeZones::kNearMorph) != 0;
    }
  return c;
}

void rasterizeStrokes(const StrokeRuns& strokes, int width, int height, LineMask& out) {
  out.width = width;
  out.height = height;
  out.on.assign(static_cast<size_t>(width) * height, 0);
  const bool has_alpha = strokes.alpha.size() == strokes.points.size();
  auto mark = [&](glm::vec2 p, float alpha) {
    const int x = static_cast<int>(std::floor(p.x)), y = static_cast<int>(std::floor(p.y));
    if (x < 0 || y < 0 || x >= width || y >= height) return;
    const uint8_t a = static_cast<uint8_t>(std::clamp(std::lround(alpha * 255.0f), 1L, 255L));
    uint8_t& v = out.on[static_cast<size_t>(y) * width + x];
    v = std::max(v, a);
  };
  for (size_t s = 0; s < strokes.strokeCount(); ++s)
    for (uint32_t i = strokes.offsets[s]; i < strokes.offsets[s + 1]; ++i) {
      const glm::vec2 p = strokes.points[i];
      const float ap = has_alpha ? strokes.alpha[i] : 1.0f;
      mark(p, ap);
      if (i + 1 < strokes.offsets[s + 1]) {
        const glm::vec2 q = strokes.points[i + 1];
        const float aq = has_alpha ? strokes.alpha[i + 1] : 1.0f;
        const int steps = std::min(4096, static_cast<int>(std::ceil(std::max(std::abs(q.x - p.x), std::abs(q.y - p.y)) * 2.0f)));
        for (int k = 1; k < steps; ++k) {
          const float t = static_cast<float>(k) / static_cast<float>(steps);
          mark(p + (q - p) * t, ap + (aq - ap) * t);
        }
      }
    }
}

MaskChange compareMasks(const LineMask& previous, const LineMask& current, int tolerance) {
  MaskChange c;
  c.line_pixels = current.count();
  if (previous.width != current.width || previous.height != current.height) {
    c.appeared = c.line_pixels;  // no comparable previous frame: everything is new
    return c;
  }
  c.appeared = unmatched(current, previous, tolerance);
  c.vanished = unmatched(previous, current, tolerance);
  return c;
}

FrameCoherence CoherenceMeter::measure(LineMask& mask, SurfaceImage& surface, const Camera& camera,
                                       const CompensationParams& params) {
  FrameCoherence f;
  if (have_previous_) {
    f.raw = compareMasks(previous_mask_, mask, params.tolerance);
    f.compensated = compareMasksCompensated(previous_mask_, previous_surface_, previous_camera_, mask, surface, camera,
                                            params);
    f.compared = true;
  } else {
    f.raw.line_pixels = mask.count();
    f.compensated.line_pixels = f.raw.line_pixels;
    f.compensated.line_weight = mask.weight();
  }
  std::swap(previous_mask_, mask);
  std::swap(previous_surface_, surface);
  previous_camera_ = camera;
  have_previous_ = true;
  return f;
}

}  // namespace lodline
