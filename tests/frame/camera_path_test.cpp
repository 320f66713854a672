#include <gtest/gtest.h>

#include <fstream>

#include <glm/geometric.hpp>

#include "frame/camera_path.h"
#include "test_util.h"

namespace lodline {
namespace {

Bounds unitBounds() {
  Bounds b;
  b.min = glm::vec3(-1);
  b.max = glm::vec3(1);
  b.radius = 1.0f;
  return b;
}

TEST(CameraPath, OrbitStaysOnItsCircle) {
  auto p = builtinPath("orbit", unitBounds(), 35.0f, 16.0f / 9.0f, 8.0);
  ASSERT_TRUE(p.ok());
  EXPECT_DOUBLE_EQ(p->duration(), 8.0);
  const float r0 = glm::length(p->at(0.0, unitBounds()).eye);
  for (double t = 0.0; t <= 8.0; t += 0.037) {
    const Camera c = p->at(t, unitBounds());
    EXPECT_NEAR(glm::length(c.eye), r0, r0 * 1e-3f) << t;
    EXPECT_NEAR(glm::length(c.target), 0.0f, 1e-5f);
    EXPECT_LT(c.near_plane, glm::length(c.eye) - 1.0f);
  }
  // Closed: the end is the start.
  EXPECT_NEAR(glm::length(p->at(8.0, unitBounds()).eye - p->at(0.0, unitBounds()).eye), 0.0f, 1e-4f);
}

TEST(CameraPath, ZoomOutCoversSixteenTimes) {
  auto p = builtinPath("zoom-out", unitBounds(), 35.0f, 1.0f, 4.0);
  ASSERT_TRUE(p.ok());
  const float d0 = glm::length(p->at(0.0, unitBounds()).eye), d1 = glm::length(p->at(4.0, unitBounds()).eye);
  EXPECT_NEAR(d1 / d0, 16.0f, 0.01f);
  // Monotonic.
  float prev = 0.0f;
  for (double t = 0.0; t <= 4.0; t += 0.1) {
    const float d = glm::length(p->at(t, unitBounds()).eye);
    EXPECT_GT(d, prev);
    prev = d;
  }
}

TEST(CameraPath, InterpolatesKeysAndClamps) {
  CameraKey a, b;
  a.time = 0.0;
  a.eye = {0, 0, 4};
  b.time = 2.0;
  b.eye = {0, 0, 8};
  b.fov_deg = 45.0f;
  CameraPath p({a, b});
  EXPECT_TRUE(p.validate().empty());
  EXPECT_NEAR(p.at(1.0, unitBounds()).eye.z, 6.0f, 1e-5f);
  EXPECT_NEAR(p.at(1.0, unitBounds()).fov_deg, 40.0f, 1e-5f);
  EXPECT_NEAR(p.at(-5.0, unitBounds()).eye.z, 4.0f, 1e-5f);
  EXPECT_NEAR(p.at(99.0, unitBounds()).eye.z, 8.0f, 1e-5f);
}

TEST(CameraPath, SaveLoadRoundTrip) {
  test::TempDir dir;
  auto p = builtinPath("flyover", unitBounds(), 50.0f, 1.5f, 3.0);
  ASSERT_TRUE(p.ok());
  ASSERT_TRUE(saveCameraPath(dir / "f.json", *p).ok());
  auto q = loadCameraPath(dir / "f.json");
  ASSERT_TRUE(q.ok()) << q.error().message;
  ASSERT_EQ(q->keys().size(), p->keys().size());
  for (double t : {0.0, 0.7, 1.9, 3.0})
    EXPECT_NEAR(glm::length(q->at(t, unitBounds()).eye - p->at(t, unitBounds()).eye), 0.0f, 1e-4f);
}

TEST(CameraPath, BadFilesGiveErrorsNamingTheFile) {
  test::TempDir dir;
  const std::pair<const char*, const char*> cases[] = {
      {"notjson.json", "{ this is not json"},
      {"nokeys.json", "{\"frames\": []}"},
      {"empty.json", "{\"keys\": []}"},
      {"noeye.json", "{\"keys\": [{\"time\": 0, \"target\": [0,0,0]}]}"},
      {"badvec.json", "{\"keys\": [{\"time\": 0, \"eye\": [0,0], \"target\": [0,0,0]}]}"},
      {"order.json", "{\"keys\": [{\"time\": 1, \"eye\": [0,0,3], \"target\": [0,0,0]},"
                     "{\"time\": 0, \"eye\": [0,0,4], \"target\": [0,0,0]}]}"},
      {"fov.json", "{\"keys\": [{\"time\": 0, \"eye\": [0,0,3], \"target\": [0,0,0], \"fov\": 0}]}"},
  };
  for (auto [name, text] : cases) {
    std::ofstream(dir / name) << text;
    auto r = loadCameraPath(dir / name);
    ASSERT_FALSE(r.ok()) << name;
    EXPECT_NE(r.error().message.find(name), std::string::npos) << r.error().message;
  }
  EXPECT_FALSE(loadCameraPath(dir / "missing.json").ok());
  EXPECT_FALSE(builtinPath("spiral", unitBounds(), 35.0f, 1.0f, 1.0).ok());
}

}  // namespace
}  // namespace lodline
