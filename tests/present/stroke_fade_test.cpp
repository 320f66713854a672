// Lines that appear fade in (present/stroke_fade.h): the first frame of a sequence is drawn
// at full opacity, a line that continues one of the previous frame (through its surface
// point or in the image) keeps its opacity, a new one starts at one step and gains a step per
// frame, and with no step nothing changes.
#include <gtest/gtest.h>

#include "export/coherence.h"
#include "present/stroke_fade.h"

namespace lodline {
namespace {

constexpr int kW = 200, kH = 150;

Camera camera() {
  Camera c;
  c.eye = {0.0f, 0.0f, 5.0f};
  c.target = {0.0f, 0.0f, 0.0f};
  return c;
}

// A run along the model-space segment a→b (z = 0), sampled ~1 px apart, projected by `cam`.
void addRun(StrokeRuns& runs, const Camera& cam, glm::vec3 a, glm::vec3 b) {
  const PixelProjector proj(cam, kW, kH);
  if (runs.offsets.empty()) runs.offsets.push_back(0);
  for (int i = 0; i <= 40; ++i) {
    const glm::vec3 p = a + (b - a) * (static_cast<float>(i) / 40.0f);
    glm::vec2 px;
    float depth = 0.0f;
    ASSERT_TRUE(proj.project(p, px, depth));
    runs.points.push_back(px);
    runs.positions.push_back(p);
    runs.alpha.push_back(1.0f);
  }
  runs.offsets.push_back(static_cast<uint32_t>(runs.points.size()));
  runs.kinds.push_back(LineKind::kContour);
  runs.opacity.push_back(1.0f);
  runs.length_px.push_back(40.0f);
}

TEST(StrokeFade, NewLinesFadeInAndContinuingOnesKeepTheirOpacity) {
  const Camera cam = camera();
  StrokeFader fader;
  StrokeFadeParams params;
  params.step = 0.25f;
  StrokeRuns first;
  addRun(first, cam, {-1.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f});
  fader.update(first, cam, kW, kH, params);
  for (float a : first.alpha) EXPECT_EQ(a, 1.0f);  // a sequence's first frame: as a still
  EXPECT_EQ(fader.fading(), 0u);
  // Frame 2: the same line, and a new one far from it.
  float expected = 0.25f;
  for (int frame = 2; frame <= 6; ++frame) {
    StrokeRuns runs;
    addRun(runs, cam, {-1.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f});
    addRun(runs, cam, {-1.0f, 1.0f, 0.0f}, {1.0f, 1.0f, 0.0f});
    fader.update(runs, cam, kW, kH, params);
    for (uint32_t i = runs.offsets[0]; i < runs.offsets[1]; ++i) EXPECT_EQ(runs.alpha[i], 1.0f) << frame;
    for (uint32_t i = runs.offsets[1]; i < runs.offsets[2]; ++i) EXPECT_FLOAT_EQ(runs.alpha[i], expected) << frame;
    EXPECT_EQ(fader.fading(), expected < 1.0f ? 41u : 0u);
    expected = std::min(1.0f, expected + 0.25f);
  }
  // A line whose samples all moved by a pixel in the image continues (no dip).
  StrokeRuns moved;
  addRun(moved, cam, {-1.0f, 0.02f, 0.0f}, {1.0f, 0.02f, 0.0f});
  fader.update(moved, cam, kW, kH, params);
  for (float a : moved.alpha) EXPECT_EQ(a, 1.0f);
  // The ramp multiplies the line's own alpha (a faded suggestive contour stays fainter).
  StrokeRuns faint;
  addRun(faint, cam, {-1.0f, -1.0f, 0.0f}, {1.0f, -1.0f, 0.0f});
  for (float& a : faint.alpha) a = 0.5f;
  fader.update(faint, cam, kW, kH, params);
  for (float a : faint.alpha) EXPECT_FLOAT_EQ(a, 0.125f);
  // And the line mask of the coherence measure sees it at that opacity.
  LineMask mask;
  rasterizeStrokes(faint, kW, kH, mask);
  EXPECT_NEAR(mask.weight() / static_cast<double>(mask.count()), 0.125, 0.005);
}

TEST(StrokeFade, NoStepOrANewSequenceDrawsAtFullOpacity) {
  const Camera cam = camera();
  StrokeFader fader;
  StrokeRuns a, b;
  addRun(a, cam, {-1.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f});
  addRun(b, cam, {-1.0f, 1.0f, 0.0f}, {1.0f, 1.0f, 0.0f});
  fader.update(a, cam, kW, kH, {});
  fader.update(b, cam, kW, kH, {});  // step 0: off
  for (float v : b.alpha) EXPECT_EQ(v, 1.0f);
  StrokeFadeParams params;
  params.step = 0.5f;
  fader.reset();
  StrokeRuns c;
  addRun(c, cam, {-1.0f, 1.0f, 0.0f}, {1.0f, 1.0f, 0.0f});
  fader.update(c, cam, kW, kH, params);  // first frame after reset
  for (float v : c.alpha) EXPECT_EQ(v, 1.0f);
}

}  // namespace
}  // namespace lodline
