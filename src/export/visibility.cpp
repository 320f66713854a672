#include "export/visibility.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

namespace lodline {
namespace {

bool visibleAt(const PixelProjector& proj, const DepthImage& depth, glm::vec2 px, float eye_depth,
               const VisibilityParams& params, float slack = 0.0f) {
  const int x = static_cast<int>(std::floor(px.x)), y = static_cast<int>(std::floor(px.y));
  if (x < 0 || y < 0 || x >= depth.width || y >= depth.height) return false;
  float farthest = 0.0f;
  const int r = params.neighbourhood;
  for (int yy = std::max(0, y - r); yy <= std::min(depth.height - 1, y + r); ++yy)
    for (int xx = std::max(0, x - r); xx <= std::min(depth.width - 1, x + r); ++xx)
      farthest = std::max(farthest, depth.at(xx, yy));
  if (farthest >= 1.0f) return true;  // background next to the sample: nothing in front
  const float surface = proj.eyeDepthOfWindow(farthest);
  return eye_depth <= surface * (1.0f + params.relative_tolerance) + slack;
}

}  // namespace

void StrokeRuns::clear() {
  points.clear();
  positions.clear();
  alpha.clear();
  offsets.clear();
  kinds.clear();
  strokes.clear();
  opacity.clear();
  length_px.clear();
}

double StrokeRuns::totalLength() const {
  double len = 0.0;
  for (float l : length_px) len += l;
  return len;
}

void appendStrokes(const StrokeRuns& from, StrokeRuns& to) {
  if (from.strokeCount() == 0) return;
  const uint32_t base = static_cast<uint32_t>(to.points.size());
  if (to.offsets.empty()) to.offsets.push_back(0);
  to.points.insert(to.points.end(), from.points.begin(), from.points.end());
  to.positions.insert(to.positions.end(), from.positions.begin(), from.positions.end());
  to.alpha.insert(to.alpha.end(), from.alpha.begin(), from.alpha.end());
  for (size_t s = 0; s < from.strokeCount(); ++s) to.offsets.push_back(base + from.offsets[s + 1]);
  to.kinds.insert(to.kinds.end(), from.kinds.begin(), from.kinds.end());
  to.strokes.insert(to.strokes.end(), from.strokes.begin(), from.strokes.end());
  to.opacity.insert(to.opacity.end(), from.opacity.begin(), from.opacity.end());
  to.length_px.insert(to.length_px.end(), from.length_px.begin(), from.length_px.end());
}

bool isPointVisible(const Camera& camera, const DepthImage& depth, glm::vec3 p,
                    const VisibilityParams& params) {
  const PixelProjector proj(camera, depth.width, depth.height);
  glm::vec2 px;
  float z = 0.0f;
  return proj.project(p, px, z) && visibleAt(proj, depth, px, z, params);
}

namespace {

// Builds the runs of one output from the samples of one stroke: a run opens at a sample,
// keeps the stroke's own points (is_vertex) and the last sample before it closes.
class RunBuilder {
 public:
  RunBuilder(StrokeRuns* out, LineKind kind, uint32_t stroke) : out_(out), kind_(kind), stroke_(stroke) {
    if (out_ && out_->offsets.empty()) out_->offsets.push_back(0);
  }
  void add(glm::vec2 px, glm::vec3 p, float alpha, bool is_vertex) {
    if (!out_) return;
    if (!open_) {
      open_ = true;
      push(px, p, alpha);
      has_pending_ = false;
    } else {
      length_ += glm::length(px - last_px_);
      if (is_vertex) {
        push(px, p, alpha);
        has_pending_ = false;
      } else {
        pending_ = {px, p, alpha};
        has_pending_ = true;
      }
    }
    last_px_ = px;
    alpha_sum_ += alpha;
    ++samples_;
  }
  void close() {
    if (!out_ || !open_) return;
    open_ = false;
    if (has_pending_) push(pending_.px, pending_.p, pending_.alpha);
    has_pending_ = false;
    const uint32_t first = out_->offsets.back();
    if (samples_ >= 2 && out_->points.size() - first >= 2) {
      out_->offsets.push_back(static_cast<uint32_t>(out_->points.size()));
      out_->kinds.push_back(kind_);
      out_->strokes.push_back(stroke_);
      out_->opacity.push_back(alpha_sum_ / static_cast<float>(samples_));
      out_->length_px.push_back(length_);
    } else {  // a single sample is no stroke
      out_->points.resize(first);
      out_->positions.resize(first);
      out_->alpha.resize(first);
    }
    alpha_sum_ = 0.0f;
    samples_ = 0;
    length_ = 0.0f;
  }

 private:
  struct Sample {
    glm::vec2 px;
    glm::vec3 p;
    float alpha;
  };
  void push(glm::vec2 px, glm::vec3 p, float alpha) {
    out_->points.push_back(px);
    out_->positions.push_back(p);
    out_->alpha.push_back(alpha);
  }
  StrokeRuns* out_;
  LineKind kind_;
  uint32_t stroke_;
  bool open_ = false, has_pending_ = false;
  Sample pending_{};
  glm::vec2 last_px_{0.0f};
  float alpha_sum_ = 0.0f, length_ = 0.0f;
  uint32_t samples_ = 0;
};

// One sample of a stroke and what the depth test found there.
enum SampleState : uint8_t { kOutside, kVisible, kHidden };
struct Sample {
  glm::vec2 px;
  glm::vec3 p;
  float alpha;
  bool is_vertex;
  SampleState state;
};

// Hides every visible stretch of `samples` that has hidden samples on both sides and spans
// less than `min_px` pixels.
void hideBlips(std::vector<Sample>& samples, float min_px) {
  const size_t n = samples.size();
  size_t i = 0;
  while (i < n) {
    if (samples[i].state != kVisible) {
      ++i;
      continue;
    }
    size_t j = i + 1;
    float length = 0.0f;
    while (j < n && samples[j].state == kVisible) {
      length += glm::length(samples[j].px - samples[j - 1].px);
      ++j;
    }
    if (i > 0 && samples[i - 1].state == kHidden && j < n && samples[j].state == kHidden && length < min_px)
      for (size_t k = i; k < j; ++k) samples[k].state = kHidden;
    i = j;
  }
}

}  // namespace

void splitStrokes(const StrokeSet& strokes, const Camera& camera, const DepthImage& depth,
                  const VisibilityParams& params, StrokeRuns* visible, StrokeRuns* hidden) {
  if (visible) visible->clear();
  if (hidden) hidden->clear();
  const PixelProjector proj(camera, depth.width, depth.height);
  const float spacing = std::max(params.sample_spacing_px, 0.05f);
  std::vector<Sample> samples;
  for (size_t s = 0; s < strokes.strokeCount(); ++s) {
    const uint32_t begin = strokes.offsets[s], end = strokes.offsets[s + 1];
    RunBuilder vis(visible, strokes.kinds[s], static_cast<uint32_t>(s));
    RunBuilder hid(hidden, strokes.kinds[s], static_cast<uint32_t>(s));
    // The stroke's samples are tested first, then the short visible stretches between hidden
    // ones hidden (VisibilityParams::min_visible_between_hidden_px), then the runs built.
    samples.clear();
    float slack = 0.0f;  // of the current segment
    auto add_sample = [&](glm::vec3 p, float alpha, bool is_vertex) {
      Sample x{glm::vec2(0.0f), p, alpha, is_vertex, kOutside};
      float z = 0.0f;
      const bool inside = proj.project(p, x.px, z) && x.px.x >= 0.0f && x.px.y >= 0.0f &&
                          x.px.x < static_cast<float>(depth.width) && x.px.y < static_cast<float>(depth.height);
      if (inside) x.state = visibleAt(proj, depth, x.px, z, params, slack) ? kVisible : kHidden;
      samples.push_back(x);
    };
    for (uint32_t i = begin; i + 1 < end; ++i) {
      const glm::vec3 a = strokes.points[i], b = strokes.points[i + 1];
      glm::vec2 pa, pb;
      float za = 0.0f, zb = 0.0f;
      int steps = 1;
      if (proj.project(a, pa, za) && proj.project(b, pb, zb))
        steps = std::clamp(static_cast<int>(std::ceil(glm::length(pb - pa) / spacing)), 1, 4096);
      // Only a contour lies where its own surface turns away; the other kinds lie on faces
      // that face the eye, and the slack would let them show through near surfaces.
      slack = strokes.kinds[s] == LineKind::kContour ? params.segment_tolerance * glm::length(b - a) : 0.0f;
      if (params.segment_tolerance_cap > 0.0f)
        slack = std::min(slack, params.segment_tolerance * params.segment_tolerance_cap);
      for (int k = 0; k < steps; ++k) {
        const float t = static_cast<float>(k) / static_cast<float>(steps);
        add_sample(a + t * (b - a), strokes.alpha[i] + t * (strokes.alpha[i + 1] - strokes.alpha[i]), k == 0);
      }
    }
    if (end > begin) add_sample(strokes.points[end - 1], strokes.alpha[end - 1], true);
    if (params.min_visible_between_hidden_px > 0.0f) hideBlips(samples, params.min_visible_between_hidden_px);
    for (const Sample& x : samples) {
      if (x.state == kOutside) {
        vis.close();
        hid.close();
      } else if (x.state == kVisible) {
        hid.close();
        vis.add(x.px, x.p, x.alpha, x.is_vertex);
      } else {
        vis.close();
        hid.add(x.px, x.p, x.alpha, x.is_vertex);
      }
    }
    vis.close();
    hid.close();
  }
  // Empty outputs still have their leading offset, like filled ones.
  if (visible && visible->offsets.empty()) visible->offsets.push_back(0);
  if (hidden && hidden->offsets.empty()) hidden->offsets.push_back(0);
}

std::array<uint32_t, kLineKindCount> countVisibleSegments(const LineSet& lines, const Camera& camera,
                                                          const DepthImage& depth,
                                                          const VisibilityParams& params) {
  std::array<uint32_t, kLineKindCount> counts{};
  const PixelProjector proj(camera, depth.width, depth.height);
  for (size_t s = 0; s < lines.segmentCount(); ++s) {
    const glm::vec3 mid = 0.5f * (lines.points[2 * s] + lines.points[2 * s + 1]);
    glm::vec2 px;
    float z = 0.0f;
    if (proj.project(mid, px, z) && visibleAt(proj, depth, px, z, params))
      ++counts[static_cast<int>(lines.kinds[s])];
  }
  return counts;
}

std::array<uint32_t, kLineKindCount> countVisibleSegments(const StrokeSet& strokes, const Camera& camera,
                                                          const DepthImage& depth,
                                                          const VisibilityParams& params) {
  std::array<uint32_t, kLineKindCount> counts{};
  const PixelProjector proj(camera, depth.width, depth.height);
  for (size_t s = 0; s < strokes.strokeCount(); ++s)
    for (uint32_t i = strokes.offsets[s]; i + 1 < strokes.offsets[s + 1]; ++i) {
      const glm::vec3 mid = 0.5f * (strokes.points[i] + strokes.points[i + 1]);
      glm::vec2 px;
      float z = 0.0f;
      if (proj.project(mid, px, z) && visibleAt(proj, depth, px, z, params)) ++counts[static_cast<int>(strokes.kinds[s])];
    }
  return counts;
}

}  // namespace lodline
