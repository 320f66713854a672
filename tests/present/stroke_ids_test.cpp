// Stable stroke ids on known answers: runs that move a pixel keep their ids, a run that
// splits keeps its id on its longer part, new runs get new ids, and ids are never reused.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include <glm/geometric.hpp>

#include "present/stroke_ids.h"

namespace lodline {
namespace {

constexpr int kSize = 200;  // an orthographic camera, 50 px per model unit, centred

Camera camera() {
  Camera c;
  c.eye = {0.0f, 0.0f, 3.0f};
  c.orthographic = true;
  c.ortho_height = 4.0f;
  c.near_plane = 1.0f;
  c.far_plane = 5.0f;
  return c;
}

// Appends a straight run from pixel a to pixel b (points every 4 px, as stroke points are).
void addRun(StrokeRuns& runs, glm::vec2 a, glm::vec2 b) {
  if (runs.offsets.empty()) runs.offsets.push_back(0);
  const int n = std::max(1, static_cast<int>(glm::length(b - a) / 4.0f));
  for (int i = 0; i <= n; ++i) {
    const glm::vec2 px = a + (b - a) * (static_cast<float>(i) / static_cast<float>(n));
    runs.points.push_back(px);
    runs.positions.push_back({(px.x - 100.0f) / 50.0f, (100.0f - px.y) / 50.0f, 0.0f});
    runs.alpha.push_back(1.0f);
  }
  runs.offsets.push_back(static_cast<uint32_t>(runs.points.size()));
  runs.kinds.push_back(LineKind::kContour);
  runs.strokes.push_back(0);
  runs.opacity.push_back(1.0f);
  runs.length_px.push_back(glm::length(b - a));
}

TEST(StrokeIds, RunsKeepTheirIdsWhileTheyPersist) {
  StrokeIdTracker tracker;
  std::vector<StrokeRuns> frame(1);
  addRun(frame[0], {20, 50}, {120, 50});   // A
  addRun(frame[0], {150, 20}, {150, 180});  // B
  tracker.update(frame, camera(), kSize, kSize);
  const uint64_t a = tracker.ids()[0][0], b = tracker.ids()[0][1];
  EXPECT_NE(a, b);

  // Both move a pixel: same ids.
  frame.assign(1, {});
  addRun(frame[0], {150, 21}, {151, 181});  // B, listed first now
  addRun(frame[0], {21, 51}, {121, 51});    // A
  tracker.update(frame, camera(), kSize, kSize);
  EXPECT_EQ(tracker.ids()[0][0], b);
  EXPECT_EQ(tracker.ids()[0][1], a);

  // A splits: its longer part keeps the id, the shorter one is new; B is gone and a new run
  // appears far from everything.
  frame.assign(1, {});
  addRun(frame[0], {21, 51}, {91, 51});   // 70 px of A
  addRun(frame[0], {96, 51}, {121, 51});  // 25 px of A
  addRun(frame[0], {30, 150}, {90, 150});
  tracker.update(frame, camera(), kSize, kSize);
  const auto& ids = tracker.ids()[0];
  EXPECT_EQ(ids[0], a);
  EXPECT_GT(ids[1], std::max(a, b));
  EXPECT_GT(ids[2], std::max(a, b));
  EXPECT_NE(ids[1], ids[2]);

  // B comes back where it was: it is a new stroke (two frames later), not B again.
  const uint64_t highest = std::max(ids[1], ids[2]);
  frame.assign(1, {});
  addRun(frame[0], {150, 21}, {151, 181});
  tracker.update(frame, camera(), kSize, kSize);
  EXPECT_GT(tracker.ids()[0][0], highest);
}

TEST(StrokeIds, IdsFollowTheSurfaceWhenTheCameraMoves) {
  // The same model-space run seen by a camera moved sideways by 10 px: it keeps its id
  // (the previous frame's samples are projected by the new camera).
  StrokeIdTracker tracker;
  std::vector<StrokeRuns> frame(1);
  addRun(frame[0], {20, 50}, {120, 50});
  tracker.update(frame, camera(), kSize, kSize);
  const uint64_t a = tracker.ids()[0][0];
  Camera moved = camera();
  moved.eye.x = moved.target.x = 0.2f;  // the image shifts 10 px left
  for (glm::vec2& p : frame[0].points) p.x -= 10.0f;
  tracker.update(frame, moved, kSize, kSize);
  EXPECT_EQ(tracker.ids()[0][0], a);
}

}  // namespace
}  // namespace lodline
