#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include <sys/stat.h>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

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

// The built-in paths start from --view: its azimuth, elevation and distance (in bounding
// radii); the default start is the default framing (35°, 20°, framed).
TEST(CameraPath, BuiltInPathsStartFromTheGivenView) {
  const Bounds b = unitBounds();
  const OrbitView start{100.0f, -15.0f, 10.0f};
  const Camera expected = orbitCamera(b, start, 35.0f, 1.5f);
  for (const char* name : {"orbit", "zoom-out", "dolly"}) {
    SCOPED_TRACE(name);
    auto p = builtinPath(name, b, 35.0f, 1.5f, 4.0, start);
    ASSERT_TRUE(p.ok());
    const Camera c = p->at(0.0, b);
    const glm::vec3 dir = glm::normalize(c.eye - c.target), want = glm::normalize(expected.eye - expected.target);
    EXPECT_GT(glm::dot(dir, want), 0.99999f);
    const float dist = glm::length(c.eye - c.target), want_dist = glm::length(expected.eye - expected.target);
    EXPECT_NEAR(dist, std::string(name) == "dolly" ? 3.0f * want_dist : want_dist, 1e-3f * want_dist);
  }
  // The orbit keeps the elevation and distance all the way round.
  auto orbit = builtinPath("orbit", b, 35.0f, 1.5f, 4.0, start);
  for (double t = 0.0; t <= 4.0; t += 0.5) {
    const Camera c = orbit->at(t, b);
    EXPECT_NEAR(glm::normalize(c.eye - c.target).y, std::sin(glm::radians(-15.0f)), 1e-3f) << t;
  }
  // Default start: the default framing.
  auto plain = builtinPath("orbit", b, 35.0f, 1.5f, 4.0);
  auto framed = builtinPath("orbit", b, 35.0f, 1.5f, 4.0, OrbitView{35.0f, 20.0f, 0.0f});
  EXPECT_EQ(plain->at(1.3, b).eye, framed->at(1.3, b).eye);
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

// Found by fuzzing (tests/fuzz/fuzz_camera_path.cpp): values a path may not hold, each refused
// with one printable line naming the file and what is wrong.
TEST(CameraPath, HostileValuesAreRefused) {
  test::TempDir dir;
  const std::pair<const char*, const char*> cases[] = {
      // A value beyond float's range was narrowed (undefined behaviour).
      {"coordinate", "{\"keys\": [{\"time\": 0, \"eye\": [1e300, 0, 5], \"target\": [0, 0, 0]}]}"},
      {"fov", "{\"keys\": [{\"time\": 0, \"eye\": [0, 0, 5], \"target\": [0, 0, 0], \"fov\": 1e300}]}"},
      // Finite keys whose spline overflows to infinity between them.
      {"within", "{\"keys\": [{\"time\": 0, \"eye\": [3e38, 0, 5], \"target\": [0, 0, 0]}, "
                 "{\"time\": 1, \"eye\": [-3e38, 0, 5], \"target\": [0, 0, 0]}]}"},
      // A duration of infinity made the frame count undefined.
      {"time", "{\"keys\": [{\"time\": -1e308, \"eye\": [0, 0, 5], \"target\": [0, 0, 0]}, "
               "{\"time\": 1e308, \"eye\": [0, 1, 5], \"target\": [0, 0, 0]}]}"},
      // lookAt with up along the view direction gives a NaN view matrix.
      {"parallel", "{\"keys\": [{\"time\": 0, \"eye\": [0, 5, 0], \"target\": [0, 0, 0], \"up\": [0, 2, 0]}]}"},
  };
  const std::pair<const char*, const char*> expected[] = {
      {"coordinate", "within +-1e15"}, {"fov", "fov must be 1-170"}, {"within", "within +-1e15"},
      {"time", "within +-1e9 seconds"}, {"parallel", "parallel to the view direction"}};
  for (size_t i = 0; i < std::size(cases); ++i) {
    const std::string name = std::string(cases[i].first) + ".json";
    std::ofstream(dir / name) << cases[i].second;
    auto r = loadCameraPath(dir / name);
    ASSERT_FALSE(r.ok()) << name;
    EXPECT_NE(r.error().message.find(name), std::string::npos) << r.error().message;
    EXPECT_NE(r.error().message.find(expected[i].second), std::string::npos) << r.error().message;
  }
  // The JSON parser's message quotes the file: its control characters are not passed on.
  std::ofstream(dir / "ctl.json", std::ios::binary) << "{\"keys\": [{\"time\": 0, \"\x01\x1b[31m\": [";
  auto r = loadCameraPath(dir / "ctl.json");
  ASSERT_FALSE(r.ok());
  for (unsigned char c : r.error().message) EXPECT_TRUE(c >= 0x20 && c < 0x7f) << int(c) << ": " << r.error().message;
  // Not regular files: a FIFO would block the reader.
  ASSERT_EQ(mkfifo((dir / "fifo.json").c_str(), 0600), 0);
  auto fifo = loadCameraPath(dir / "fifo.json");
  ASSERT_FALSE(fifo.ok());
  EXPECT_NE(fifo.error().message.find("not a regular file"), std::string::npos) << fifo.error().message;
  std::filesystem::create_directory(dir / "d.json");
  EXPECT_FALSE(loadCameraPath(dir / "d.json").ok());
}

// Valid keys whose splines bring the eye onto the target, or the view direction onto up,
// between keys: every sample still has a finite view matrix.
TEST(CameraPath, InterpolatedDegeneraciesStayDefined) {
  std::vector<CameraKey> keys(2);
  keys[0].time = 0.0;
  keys[0].eye = {-1, 0, 0};
  keys[0].target = {1, 0, 0};
  keys[1].time = 1.0;
  keys[1].eye = {1, 0, 0};
  keys[1].target = {-1, 0, 0};  // eye and target cross at t = 0.5
  CameraPath crossing(keys);
  keys[0].eye = {0, 0, 5};
  keys[0].target = {0, 0, 0};
  keys[1].eye = {5, 0, 0};
  keys[1].target = {0, 0, 0};
  keys[0].up = {-1, 1, -1};
  keys[1].up = {-1, -1, -1};  // at t = 0.5 the interpolated up is (-1, 0, -1), the view direction
  CameraPath turning(keys);
  for (const CameraPath* p : {&crossing, &turning}) {
    ASSERT_EQ(p->validate(), "");
    for (int k = 0; k <= 200; ++k) {
      const glm::mat4 v = p->at(k / 200.0, unitBounds()).view();
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) ASSERT_TRUE(std::isfinite(v[i][j])) << "sample " << k;
    }
  }
}

}  // namespace
}  // namespace lodline
