#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <unordered_map>
#include <memory>

#include <glm/geometric.hpp>

#include "frame/lod_drawing.h"
#include "frame/temporal_smoothing.h"
#include "io/generate.h"

namespace lodline {
namespace {

TEST(Smoothing, WeightFormula) {
  // Jeong §3.3: t = 0.8 s, f = 25 fps, α = 0.9 → w ≈ 0.1087.
  EXPECT_NEAR(smoothingWeight(0.9f, 0.8f, 25.0f), 0.1087f, 1e-4f);
  EXPECT_EQ(smoothingWeight(0.9f, 0.8f, 1.0f), 1.0f);  // fewer than one frame in t: no smoothing
  EXPECT_LT(smoothingWeight(0.9f, 0.8f, 60.0f), smoothingWeight(0.9f, 0.8f, 25.0f));
}

TEST(Smoothing, HeldValueReachesAlphaWithinT) {
  // A step from 0 to 1 held for n = f·t frames reaches α.
  const float f = 30.0f, t = 0.8f, alpha = 0.9f;
  const float w = smoothingWeight(alpha, t, f);
  TemporalSmoother s;
  ViewQuantities v;
  v.ndotv = {0.5f};
  v.kr = {0.0f};
  v.dwkr = {0.0f};
  v.sc_num = {0.0f};
  s.blendView(v, w, 0.0f);  // initial state 0
  const int n = static_cast<int>(std::lround(f * t));
  for (int i = 0; i < n; ++i) {
    v.kr = {1.0f};
    v.dwkr = {1.0f};
    s.blendView(v, w, 0.0f);
    if (i == n - 2) {
      EXPECT_LT(v.kr[0], alpha);
    }
  }
  EXPECT_NEAR(v.kr[0], alpha, 1e-3f);
  EXPECT_NEAR(v.dwkr[0], alpha, 1e-3f);
  // The suggestive test is recomputed from the smoothed Dw kr: sinθ·Dw kr − thr·cosθ.
  EXPECT_NEAR(v.sc_num[0], std::sqrt(1.0f - 0.25f) * v.dwkr[0], 1e-5f);
  for (int i = 0; i < 200; ++i) {
    v.kr = {1.0f};
    s.blendView(v, w, 0.0f);
  }
  EXPECT_NEAR(v.kr[0], 1.0f, 1e-4f);  // converges to a held value
}

TEST(Smoothing, NormalsStayUnitAndFollow) {
  TemporalSmoother s;
  std::vector<glm::vec3> a = {{0, 0, 1}}, b = {{1, 0, 0}};
  s.blendNormals(a, 0.2f);
  auto out = s.blendNormals(b, 0.2f);
  EXPECT_NEAR(glm::length(out[0]), 1.0f, 1e-6f);
  EXPECT_GT(out[0].z, out[0].x);  // mostly the old value after one frame
  for (int i = 0; i < 100; ++i) out = s.blendNormals(b, 0.2f);
  EXPECT_NEAR(out[0].x, 1.0f, 1e-4f);
}

// Under level of detail, vertices created by splits start from their parent's smoothed
// values: with a slow blend, smoothed normals stay close to their raw normals while the mesh
// refines and coarsens through a zoom-in and out (starting, as captures do, from the detail
// converged for the first camera). A new vertex starting from an unrelated, default or stale
// value would sit far from its raw normal for many frames. Inheriting is continuity, not
// accuracy: on a coarse tube a child's own normal can lie 90°+ from its parent's, so a few
// samples are far off for a few frames by design (Jeong §3.3); the bounds are statistical.
TEST(Smoothing, FollowsTheVertexHierarchyThroughSplitsAndCollapses) {
  TriMesh mesh = makeTorusKnot(2, 3, 1.0f, 0.2f, 240, 24, 0.0f);
  auto pm = buildProgressiveMesh(mesh);
  ASSERT_TRUE(pm.ok()) << pm.error().message;
  LodDrawing lod(mesh, std::make_shared<const ProgressiveMesh>(std::move(pm.value())));
  const float w = smoothingWeight(0.9f, 0.8f, 30.0f);
  std::array<bool, kLineKindCount> enabled{};
  enabled.fill(true);
  DetailParams detail;
  detail.geomorphs = true;
  int splits = 0, collapses = 0;
  float worst = 1.0f;
  double sum_cos = 0.0;
  size_t samples = 0, far_off = 0;
  auto camera_at = [&](int k) {
    const float phase = static_cast<float>(k) / 179.0f;
    const float dist = 1.5f + 10.5f * std::abs(2.0f * phase - 1.0f);
    return orbitCamera(lod.bounds(), {30.0f + k, 20.0f, dist}, 35.0f, 16.0f / 9.0f);
  };
  ASSERT_TRUE(lod.converge(camera_at(0), 640, 360, detail, 1.0f / 30.0f, 300, enabled).ok());
  std::unordered_map<uint32_t, glm::vec3> previous;  // PM node -> smoothed normal last frame
  size_t inherited_checked = 0, collapse_checked = 0;
  for (int k = 0; k < 180; ++k) {
    // Zoom in from 12 to 1.5 bounding radii and back out.
    const Camera cam = camera_at(k);
    ASSERT_TRUE(lod.frame(cam, 640, 360, detail, 1.0f / 30.0f, enabled, w).ok());
    splits += lod.lod()->stats().splits;
    collapses += lod.lod()->stats().collapses;
    const auto smooth = lod.drawing().normals();
    const auto raw = lod.drawing().shape().normals();
    const auto slot_nodes = lod.lod()->slotVertices();
    const ProgressiveMesh& pmesh = lod.lod()->pm();
    // Exact bookkeeping: a node that is new this frame blended its parent's last smoothed
    // normal (split) or the mean of its children's (collapse) with its raw normal.
    if (k > 0) {
      for (size_t v = 0; v < slot_nodes.size(); ++v) {
        const uint32_t node = slot_nodes[v];
        if (node == kPmNone || previous.count(node)) continue;
        glm::vec3 start;
        const uint32_t parent = pmesh.parent[node];
        if (parent != kPmNone && previous.count(parent)) {
          start = previous[parent];
          ++inherited_checked;
        } else if (!pmesh.isLeaf(node) && previous.count(pmesh.split(node).vt) && previous.count(pmesh.split(node).vu)) {
          start = glm::normalize(previous[pmesh.split(node).vt] + previous[pmesh.split(node).vu]);
          ++collapse_checked;
        } else {
          continue;  // several levels at once: starts from its own values
        }
        const glm::vec3 expect = glm::normalize((1.0f - w) * start + w * raw[v]);
        ASSERT_GT(glm::dot(expect, smooth[v]), 0.9999f)
            << "frame " << k << " slot " << v << " node " << node << " parent " << parent << " split-case "
            << (parent != kPmNone && previous.count(parent)) << " dot(smooth,raw) " << glm::dot(smooth[v], raw[v])
            << " dot(smooth,start) " << glm::dot(smooth[v], start);
      }
    }
    previous.clear();
    for (size_t v = 0; v < slot_nodes.size(); ++v)
      if (slot_nodes[v] != kPmNone) previous[slot_nodes[v]] = smooth[v];
    std::vector<std::array<uint32_t, 3>> faces = lod.drawing().mesh().faces;
    std::vector<uint8_t> used(raw.size(), 0);
    for (const auto& f : faces)
      for (uint32_t v : f) used[v] = 1;
    for (size_t v = 0; v < raw.size(); ++v)
      if (used[v]) {
        ASSERT_NEAR(glm::length(smooth[v]), 1.0f, 1e-4f);
        const float c = glm::dot(smooth[v], raw[v]);
        worst = std::min(worst, c);
        far_off += c < 0.5f;
        sum_cos += c;
        ++samples;
      }
  }
  std::cout << "[ measured ] new vertices checked: " << inherited_checked << " from a split, " << collapse_checked
            << " from a collapse\n";
  EXPECT_GT(inherited_checked, 500u);
  EXPECT_GT(collapse_checked, 500u);
  EXPECT_GT(splits, 1000);
  EXPECT_GT(collapses, 1000);
  const double mean_cos = sum_cos / static_cast<double>(samples);
  const double far_fraction = static_cast<double>(far_off) / static_cast<double>(samples);
  std::cout << "[ measured ] cos(smoothed, raw normal) over 180 frames: mean " << mean_cos << ", worst " << worst
            << ", fraction beyond 60 degrees " << far_fraction << "\n";
  // Measured: mean 0.9991, 0.02% of vertex-frames beyond 60°.
  EXPECT_GT(mean_cos, 0.998);
  EXPECT_LT(far_fraction, 1e-3);
}

}  // namespace
}  // namespace lodline

namespace lodline {
namespace {

// The other kinds' channels (docs/lines.md): a scalar is blended like kr; a direction known
// only up to sign and a value whose sign follows it are blended after agreeing with the
// smoothed direction, so a solver that flips the sign every other frame changes nothing.
TEST(TemporalSmoother, ScalarAndDirectedChannels) {
  TemporalSmoother s;
  const float w = 0.25f;
  std::vector<float> raw{1.0f, 2.0f};
  EXPECT_EQ(s.blendScalar(TemporalSmoother::kK1, raw, w)[0], 1.0f);  // the first frame as it is
  raw = {3.0f, 2.0f};
  const auto k = s.blendScalar(TemporalSmoother::kK1, raw, w);
  EXPECT_FLOAT_EQ(k[0], 0.75f * 1.0f + 0.25f * 3.0f);
  EXPECT_FLOAT_EQ(k[1], 2.0f);

  std::vector<glm::vec3> dir{{1, 0, 0}};
  std::vector<float> val{0.5f};
  s.blendDirected(TemporalSmoother::kDt1q1, dir, val, w);
  for (int frame = 0; frame < 20; ++frame) {
    const float sign = frame % 2 ? -1.0f : 1.0f;  // the raw direction flips every frame
    dir = {sign * glm::vec3(1, 0, 0)};
    val = {sign * 0.5f};
    s.blendDirected(TemporalSmoother::kDt1q1, dir, val, w);
    EXPECT_NEAR(dir[0].x, 1.0f, 1e-6f) << frame;
    EXPECT_NEAR(val[0], 0.5f, 1e-6f) << frame;
  }
  // A direction that turns is followed, renormalised.
  for (int frame = 0; frame < 60; ++frame) {
    dir = {glm::vec3(0, 1, 0)};
    val = {0.5f};
    s.blendDirected(TemporalSmoother::kDt1q1, dir, val, w);
  }
  EXPECT_NEAR(dir[0].y, 1.0f, 1e-3f);
  EXPECT_NEAR(glm::length(dir[0]), 1.0f, 1e-5f);
  s.reset();  // forgets: the next frame is taken as it is
  raw = {7.0f, 7.0f};
  EXPECT_EQ(s.blendScalar(TemporalSmoother::kK1, raw, w)[0], 7.0f);
}

// The ridges' C(e1,e1,e1) is known only where it was computed this frame (lazy derivative
// tensors): elsewhere the raw pair is left alone and the history dropped, so a vertex that
// comes back starts from its new value, not from one computed frames ago.
TEST(TemporalSmoother, DirectedChannelWithUnknownVertices) {
  TemporalSmoother s;
  const float w = 0.25f;
  std::vector<glm::vec3> dir{{1, 0, 0}, {1, 0, 0}};
  std::vector<float> val{1.0f, 1.0f};
  s.blendDirected(TemporalSmoother::kC111, dir, val, w);
  dir = {{-1, 0, 0}, {1, 0, 0}};
  val = {-3.0f, 9.0f};  // the first flipped with its direction: 3 along the smoothed one
  const std::vector<uint8_t> valid{1, 0};
  s.blendDirected(TemporalSmoother::kC111, dir, val, w, valid);
  EXPECT_NEAR(dir[0].x, 1.0f, 1e-6f);
  EXPECT_FLOAT_EQ(val[0], 0.75f * 1.0f + 0.25f * 3.0f);
  EXPECT_EQ(val[1], 9.0f);  // unknown this frame: untouched
  val = {3.0f, 5.0f};
  dir = {{1, 0, 0}, {1, 0, 0}};
  s.blendDirected(TemporalSmoother::kC111, dir, val, w);
  EXPECT_FLOAT_EQ(val[1], 5.0f);  // no history: taken as it is
  EXPECT_FLOAT_EQ(val[0], 0.75f * 1.5f + 0.25f * 3.0f);
}

}  // namespace
}  // namespace lodline
