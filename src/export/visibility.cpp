#include "export/visibility.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

namespace lodline {
namespace {

// Projection of model points to pixel position + eye depth, and the inverse of the depth
// mapping for the buffer's values, for one camera and image size.
class Projector {
 public:
  Projector(const Camera& cam, int width, int height)
      : width_(width), height_(height), near_(cam.near_plane), far_(cam.far_plane),
        ortho_(cam.orthographic) {
    view_proj_ = cam.projection(static_cast<float>(width) / static_cast<float>(height)) * cam.view();
  }

  /// Pixel position (x right, y down) and eye-space depth; false behind the eye.
  bool project(glm::vec3 p, glm::vec2& px, float& eye_depth) const {
    const glm::vec4 c = view_proj_ * glm::vec4(p, 1.0f);
    if (c.w <= 1e-12f) return false;
    const glm::vec3 ndc = glm::vec3(c) / c.w;
    px = {(ndc.x * 0.5f + 0.5f) * static_cast<float>(width_), (0.5f - ndc.y * 0.5f) * static_cast<float>(height_)};
    eye_depth = eyeDepth(ndc.z * 0.5f + 0.5f);
    return true;
  }

  /// Eye-space depth of a window depth in [0, 1] (OpenGL's default depth range).
  float eyeDepth(float window_depth) const {
    if (ortho_) return near_ + window_depth * (far_ - near_);
    const float ndc_z = 2.0f * window_depth - 1.0f;
    return 2.0f * near_ * far_ / (far_ + near_ - ndc_z * (far_ - near_));
  }

  int width() const { return width_; }
  int height() const { return height_; }

 private:
  glm::mat4 view_proj_;
  int width_, height_;
  float near_, far_;
  bool ortho_;
};

bool visibleAt(const Projector& proj, const DepthImage& depth, glm::vec2 px, float eye_depth,
               const VisibilityParams& params) {
  const int x = static_cast<int>(std::floor(px.x)), y = static_cast<int>(std::floor(px.y));
  if (x < 0 || y < 0 || x >= depth.width || y >= depth.height) return false;
  float farthest = 0.0f;
  const int r = params.neighbourhood;
  for (int yy = std::max(0, y - r); yy <= std::min(depth.height - 1, y + r); ++yy)
    for (int xx = std::max(0, x - r); xx <= std::min(depth.width - 1, x + r); ++xx)
      farthest = std::max(farthest, depth.at(xx, yy));
  if (farthest >= 1.0f) return true;  // background next to the sample: nothing in front
  const float surface = proj.eyeDepth(farthest);
  return eye_depth <= surface * (1.0f + params.relative_tolerance);
}

}  // namespace

void VisibleStrokes::clear() {
  points.clear();
  offsets.clear();
  kinds.clear();
  opacity.clear();
  length_px.clear();
}

void appendStrokes(const VisibleStrokes& from, VisibleStrokes& to) {
  if (from.strokeCount() == 0) return;
  const uint32_t base = static_cast<uint32_t>(to.points.size());
  if (to.offsets.empty()) to.offsets.push_back(0);
  to.points.insert(to.points.end(), from.points.begin(), from.points.end());
  for (size_t s = 0; s < from.strokeCount(); ++s) to.offsets.push_back(base + from.offsets[s + 1]);
  to.kinds.insert(to.kinds.end(), from.kinds.begin(), from.kinds.end());
  to.opacity.insert(to.opacity.end(), from.opacity.begin(), from.opacity.end());
  to.length_px.insert(to.length_px.end(), from.length_px.begin(), from.length_px.end());
}

bool isPointVisible(const Camera& camera, const DepthImage& depth, glm::vec3 p,
                    const VisibilityParams& params) {
  const Projector proj(camera, depth.width, depth.height);
  glm::vec2 px;
  float z = 0.0f;
  return proj.project(p, px, z) && visibleAt(proj, depth, px, z, params);
}

void visibleStrokes(const StrokeSet& strokes, const Camera& camera, const DepthImage& depth,
                    const VisibilityParams& params, VisibleStrokes& out) {
  out.clear();
  const Projector proj(camera, depth.width, depth.height);
  out.offsets.push_back(0);
  const float spacing = std::max(params.sample_spacing_px, 0.05f);
  for (size_t s = 0; s < strokes.strokeCount(); ++s) {
    const uint32_t begin = strokes.offsets[s], end = strokes.offsets[s + 1];
    bool open_run = false;
    float alpha_sum = 0.0f;
    uint32_t alpha_n = 0;
    float length = 0.0f;
    auto close_run = [&]() {
      if (!open_run) return;
      open_run = false;
      const uint32_t first = out.offsets.back();
      if (out.points.size() - first >= 2) {
        out.offsets.push_back(static_cast<uint32_t>(out.points.size()));
        out.kinds.push_back(strokes.kinds[s]);
        out.opacity.push_back(alpha_n ? alpha_sum / static_cast<float>(alpha_n) : 1.0f);
        out.length_px.push_back(length);
      } else {
        out.points.resize(first);  // a single visible sample is no stroke
      }
      alpha_sum = 0.0f;
      alpha_n = 0;
      length = 0.0f;
    };
    auto add_sample = [&](glm::vec3 p, float alpha) {
      glm::vec2 px;
      float z = 0.0f;
      const bool vis = proj.project(p, px, z) && visibleAt(proj, depth, px, z, params);
      if (!vis) {
        close_run();
        return;
      }
      if (open_run) length += glm::length(px - out.points.back());
      open_run = true;
      out.points.push_back(px);
      alpha_sum += alpha;
      ++alpha_n;
    };
    for (uint32_t i = begin; i + 1 < end; ++i) {
      const glm::vec3 a = strokes.points[i], b = strokes.points[i + 1];
      glm::vec2 pa, pb;
      float za = 0.0f, zb = 0.0f;
      int steps = 1;
      if (proj.project(a, pa, za) && proj.project(b, pb, zb))
        steps = std::clamp(static_cast<int>(std::ceil(glm::length(pb - pa) / spacing)), 1, 4096);
      for (int k = 0; k < steps; ++k) {
        const float t = static_cast<float>(k) / static_cast<float>(steps);
        add_sample(a + t * (b - a), strokes.alpha[i] + t * (strokes.alpha[i + 1] - strokes.alpha[i]));
      }
    }
    if (end > begin) add_sample(strokes.points[end - 1], strokes.alpha[end - 1]);
    close_run();
  }
}

std::array<uint32_t, kLineKindCount> countVisibleSegments(const LineSet& lines, const Camera& camera,
                                                          const DepthImage& depth,
                                                          const VisibilityParams& params) {
  std::array<uint32_t, kLineKindCount> counts{};
  const Projector proj(camera, depth.width, depth.height);
  for (size_t s = 0; s < lines.segmentCount(); ++s) {
    const glm::vec3 mid = 0.5f * (lines.points[2 * s] + lines.points[2 * s + 1]);
    glm::vec2 px;
    float z = 0.0f;
    if (proj.project(mid, px, z) && visibleAt(proj, depth, px, z, params))
      ++counts[static_cast<int>(lines.kinds[s])];
  }
  return counts;
}

}  // namespace lodline
