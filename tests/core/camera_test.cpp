#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/trigonometric.hpp>

#include "core/camera.h"
#include "core/render_params.h"
#include "io/generate.h"

namespace lodline {
namespace {

TEST(Camera, OrbitFramesTheSphere) {
  Bounds b;
  b.center = {1, 2, 3};
  b.radius = 2.0f;
  const Camera cam = orbitCamera(b, {30.0f, 20.0f, 0.0f}, 35.0f, 16.0f / 9.0f);
  // The sphere's silhouette must fit in the vertical field of view.
  const float d = glm::length(cam.eye - b.center);
  const float half_angle = std::asin(b.radius / d);
  EXPECT_LT(half_angle, glm::radians(35.0f) * 0.5f);
  EXPECT_GT(half_angle, glm::radians(35.0f) * 0.5f * 0.85f);  // and fill most of it
  EXPECT_LT(cam.near_plane, d - b.radius);
  EXPECT_GT(cam.far_plane, d + b.radius);
}

// Found by fuzzing camera paths: with the eye 2.3e11 units from a unit model, d - 1.05 r and
// d + 1.05 r are the same float, and the empty depth range made the projection divide by zero.
TEST(Camera, ClipPlanesStayOrderedFarFromTheModel) {
  Bounds b;
  b.min = glm::vec3(-1.0f);
  b.max = glm::vec3(1.0f);
  b.radius = std::sqrt(3.0f);
  for (float dist : {3.0f, 1e6f, 2.3e11f, 1e15f}) {
    Camera cam;
    cam.eye = {dist, 16.5f, 37.2f};
    cam.target = {0.0f, 0.0f, 0.0f};
    fitClipPlanes(cam, b);
    EXPECT_GT(cam.near_plane, 0.0f) << dist;
    EXPECT_LT(cam.near_plane, cam.far_plane) << dist;
    const glm::mat4 p = cam.projection(1.5f);
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) EXPECT_TRUE(std::isfinite(p[i][j])) << dist;
  }
}

TEST(Camera, OrbitAzimuthElevation) {
  Bounds b;
  b.radius = 1.0f;
  const Camera cam = orbitCamera(b, {90.0f, 0.0f, 5.0f}, 35.0f, 1.0f);
  EXPECT_NEAR(cam.eye.x, 5.0f, 1e-5f);  // azimuth 90° from +Z is +X
  EXPECT_NEAR(cam.eye.y, 0.0f, 1e-5f);
  const Camera top = orbitCamera(b, {0.0f, 60.0f, 2.0f}, 35.0f, 1.0f);
  EXPECT_NEAR(top.eye.y, 2.0f * std::sin(glm::radians(60.0f)), 1e-5f);
}

TEST(Camera, ProjectCentreAndEdge) {
  Camera cam;
  cam.eye = {0, 0, 10};
  cam.target = {0, 0, 0};
  cam.fov_deg = 90.0f;
  cam.near_plane = 0.1f;
  cam.far_plane = 100.0f;
  float depth = 0.0f;
  const glm::vec2 c = projectToPixels(cam, {0, 0, 0}, 200, 100, &depth);
  EXPECT_NEAR(c.x, 100.0f, 1e-3f);
  EXPECT_NEAR(c.y, 50.0f, 1e-3f);
  EXPECT_NEAR(depth, 10.0f, 1e-4f);
  // fov 90°: at distance 10 the half height is 10 units = 50 px; +y goes up in the image.
  const glm::vec2 top = projectToPixels(cam, {0, 5, 0}, 200, 100);
  EXPECT_NEAR(top.y, 25.0f, 1e-3f);
}

TEST(Camera, PixelAreaFactor) {
  Camera cam;
  cam.fov_deg = 90.0f;
  // f = (H/2)/tan(45°) = H/2 px: a unit square at distance 1 covers (H/2)² px².
  EXPECT_NEAR(pixelAreaFactor(cam, 720), 360.0f * 360.0f, 1e-2f);
  cam.orthographic = true;
  cam.ortho_height = 4.0f;
  EXPECT_NEAR(pixelAreaFactor(cam, 720), 180.0f * 180.0f, 1e-2f);
}

TEST(RenderParams, ParseSizeColorStyle) {
  EXPECT_EQ(*parseSize("640x480"), (std::array<int, 2>{640, 480}));
  EXPECT_FALSE(parseSize("640").ok());
  EXPECT_FALSE(parseSize("0x480").ok());
  EXPECT_FALSE(parseSize("64x48junk").ok());
  EXPECT_EQ(parseSize("x").error().exitCode(), 2);
  EXPECT_NEAR(parseColor("#ff8000")->y, 128.0f / 255.0f, 1e-6f);
  EXPECT_EQ(parseColor("transparent")->w, 0.0f);
  EXPECT_EQ(parseColor("#fff")->x, 1.0f);
  EXPECT_FALSE(parseColor("#12345").ok());
  EXPECT_FALSE(parseColor("mauve-ish").ok());
  // A rejected value is echoed in the error, but never a control byte (a fuzz finding: a DEL
  // inside a stroke style's colour reached the terminal).
  const Result<glm::vec4> bad = parseColor(std::string("#12\x7f\x1b[2J") + std::string(200, 'f'));
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().message.find_first_of("\x7f\x1b"), std::string::npos) << bad.error().message;
  EXPECT_NE(bad.error().message.find("#12??[2J"), std::string::npos) << bad.error().message;
  EXPECT_LT(bad.error().message.size(), 200u);
  EXPECT_EQ(*parseStyle("lines"), Style::kLines);
  EXPECT_FALSE(parseStyle("sketchy").ok());
}

// Generators must produce closed, outward-oriented surfaces (positive signed volume).
double signedVolume(const TriMesh& m) {
  double v = 0.0;
  for (const auto& f : m.faces)
    v += glm::dot(glm::dvec3(m.positions[f[0]]),
                  glm::cross(glm::dvec3(m.positions[f[1]]), glm::dvec3(m.positions[f[2]]))) / 6.0;
  return v;
}

TEST(Generate, ClosedSurfacesPointOutward) {
  const double pi = 3.14159265358979;
  EXPECT_NEAR(signedVolume(makeIcoSphere(1.0f, 4)), 4.0 / 3.0 * pi, 0.02);
  EXPECT_NEAR(signedVolume(makeUvSphere(1.0f, 64, 32)), 4.0 / 3.0 * pi, 0.03);
  EXPECT_NEAR(signedVolume(makeTorus(1.0f, 0.3f, 96, 48)), 2.0 * pi * pi * 1.0 * 0.09, 0.01);
  EXPECT_NEAR(signedVolume(makeEllipsoid(1.0f, 0.5f, 0.25f, 4)), 4.0 / 3.0 * pi * 0.125, 0.01);
  EXPECT_GT(signedVolume(makeTorusKnot(2, 3, 1.0f, 0.15f, 240, 16, 0.0f)), 0.0);
}

TEST(Generate, OpenCylinderPointsAwayFromAxis) {
  const TriMesh c = makeCylinder(1.0f, 2.0f, 16, 4);
  std::vector<glm::vec3> n;
  computeFaceNormals(c, n);
  for (size_t f = 0; f < c.faceCount(); ++f) {
    const glm::vec3 centre = (c.positions[c.faces[f][0]] + c.positions[c.faces[f][1]] +
                              c.positions[c.faces[f][2]]) / 3.0f;
    EXPECT_GT(glm::dot(n[f], glm::vec3(centre.x, 0.0f, centre.z)), 0.0f);
  }
}

TEST(Generate, Counts) {
  EXPECT_EQ(makeIcoSphere(1.0f, 3).faceCount(), 20u * 64u);
  EXPECT_EQ(makeTorus(1.0f, 0.3f, 10, 6).faceCount(), 120u);
  EXPECT_EQ(makeCylinder(1.0f, 1.0f, 10, 4).faceCount(), 80u);
  EXPECT_EQ(makeGrid(1.0f, 4).faceCount(), 32u);
  const TriMesh uv = makeUvSphere(1.0f, 8, 4);
  EXPECT_EQ(uv.faceCount(), 8u * 2u + 8u * 2u * 2u);
}

}  // namespace
}  // namespace lodline
