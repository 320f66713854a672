// Headless rendering through the GL presenter: EGL surfaceless (and OSMesa) on Mesa, no
// display, no GPU.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <set>

#include <glad/gl.h>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "gl/context.h"
#include "io/generate.h"
#include "io/load_mesh.h"
#include "present_test_util.h"

namespace lodline {
namespace {

struct Rendered {
  Image image;
  Camera camera;
  size_t segments = 0;
};

using test::Look;

// Renders `mesh` with the given look through `backend`; empty image if no context.
Rendered renderMesh(TriMesh mesh, ContextBackend backend, const Look& look, OrbitView orbit,
                    std::string* error = nullptr) {
  Rendered out;
  SceneDrawing scene = test::sceneOf(std::move(mesh), look.style);
  out.camera = orbitCamera(scene.bounds(), orbit, 35.0f, look.frame.aspect());
  test::Presented p = test::presentScene(scene, out.camera, look.frame, PresenterBackend::kGl, backend);
  if (!p) {
    if (error) *error = p.error;
    return out;
  }
  out.image = std::move(p.image);
  out.segments = p.presenter->segmentsDrawn(0);
  return out;
}

bool isDark(const uint8_t* p) { return p[0] < 100 && p[1] < 100 && p[2] < 100; }

Look linesOnly(int w, int h) {
  Look l;
  l.frame.width = w;
  l.frame.height = h;
  l.frame.msaa = 1;
  l.style.style = Style::kLines;
  l.style.lines[LineKind::kContour].width_px = 1.0f;
  return l;
}

// The current context is OpenGL ≥ 3 core.
void expectCurrentCoreProfile() {
  GLint major = 0, mask = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &mask);
  EXPECT_GE(major, 3);
  EXPECT_TRUE(mask & GL_CONTEXT_CORE_PROFILE_BIT);
}

TEST(HeadlessRender, EglContextIsCoreProfile) {
  auto ctx = createHeadlessContext(ContextBackend::kEgl);
  ASSERT_TRUE(ctx.ok()) << ctx.error().message;
  expectCurrentCoreProfile();
  EXPECT_FALSE((*ctx)->description().empty());
}

// The EGL device platform (what NVIDIA's driver offers without a display) gives the same kind
// of context; Mesa offers a software device, so it is tested here on llvmpipe.
TEST(HeadlessRender, EglDevicePlatformGivesACoreContext) {
  auto ctx = createEglContext(EglPlatform::kDevice);
  if (!ctx.ok() && ctx.error().message.find("EGL_EXT_platform_device is not supported") != std::string::npos)
    GTEST_SKIP() << ctx.error().message;
  ASSERT_TRUE(ctx.ok()) << ctx.error().message;
  expectCurrentCoreProfile();
  std::printf("EGL device context: %s\n", (*ctx)->description().c_str());
}

// The silhouette of a sphere is a closed ring of the radius the projection predicts.
TEST(HeadlessRender, SphereSilhouetteIsRingOfExpectedRadius) {
  const int w = 480, h = 360;
  const float dist = 4.0f;  // bounding radii
  Rendered r = renderMesh(makeIcoSphere(1.0f, 5), ContextBackend::kEgl, linesOnly(w, h),
                          {20.0f, 10.0f, dist});
  ASSERT_EQ(r.image.width, w);
  ASSERT_EQ(r.image.height, h);
  EXPECT_GT(r.segments, 50u);
  // Angular radius asin(r/d) seen through focal length f = (h/2)/tan(fov/2).
  const float f = 0.5f * h / std::tan(glm::radians(35.0f) * 0.5f);
  const float expected = f * std::tan(std::asin(1.0f / dist));
  const float cx = 0.5f * w, cy = 0.5f * h;
  std::array<int, 72> hits{};
  int dark = 0, off_ring = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!isDark(r.image.pixel(x, y))) continue;
      ++dark;
      const float dx = x + 0.5f - cx, dy = y + 0.5f - cy;
      const float rad = std::sqrt(dx * dx + dy * dy);
      if (std::abs(rad - expected) > 2.0f) {
        ++off_ring;
        continue;
      }
      const double a = std::atan2(dy, dx) + std::numbers::pi;
      hits[static_cast<size_t>(a / (2 * std::numbers::pi) * 72) % 72]++;
    }
  EXPECT_GT(dark, 100);
  EXPECT_EQ(off_ring, 0) << "dark pixels away from the predicted silhouette radius " << expected;
  for (size_t i = 0; i < hits.size(); ++i) EXPECT_GT(hits[i], 0) << "gap in the ring at bin " << i;
  // Background stays background: corners and centre (inside the sphere, no lines) are white.
  for (auto [x, y] : {std::pair{0, 0}, {w - 1, 0}, {0, h - 1}, {w - 1, h - 1}, {w / 2, h / 2}}) {
    const uint8_t* p = r.image.pixel(x, y);
    EXPECT_EQ(p[0], 255);
    EXPECT_EQ(p[1], 255);
    EXPECT_EQ(p[2], 255);
  }
}

// Lines hidden behind the surface are not drawn: a small sphere right behind a big one
// (seen along +Z) has a contour, but none of it may show inside the big sphere's disk.
TEST(HeadlessRender, HiddenLinesRemoved) {
  TriMesh scene = makeIcoSphere(1.0f, 4);
  TriMesh back = makeIcoSphere(0.4f, 3);
  const uint32_t base = static_cast<uint32_t>(scene.positions.size());
  for (auto p : back.positions) scene.positions.push_back(p + glm::vec3(0.0f, 0.0f, -2.5f));
  for (auto f : back.faces) scene.faces.push_back({f[0] + base, f[1] + base, f[2] + base});
  const int w = 320, h = 240;
  Rendered r = renderMesh(scene, ContextBackend::kEgl, linesOnly(w, h), {0.0f, 0.0f, 3.0f});
  // The front sphere's contour ring was drawn (simplified to a polygon of a few dozen sides)...
  EXPECT_GT(r.segments, 30u);
  // ...but inside the big sphere's projected disk (minus a 3 px rim) every pixel is white.
  const glm::vec2 c = projectToPixels(r.camera, glm::vec3(0.0f), w, h);
  const glm::vec2 edge = projectToPixels(r.camera, glm::vec3(1.0f, 0.0f, 0.0f), w, h);
  const float disk = glm::length(edge - c) * 0.9f;  // a point on the sphere's equator is inside
  int dark_inside = 0, inside = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (glm::length(glm::vec2(x + 0.5f, y + 0.5f) - c) < disk - 3.0f) {
        ++inside;
        dark_inside += isDark(r.image.pixel(x, y));
      }
  EXPECT_GT(inside, 1000);
  EXPECT_EQ(dark_inside, 0);
}

TEST(HeadlessRender, ToonShadesTheSurface) {
  Look rp;
  rp.frame.width = 200;
  rp.frame.height = 160;
  rp.frame.msaa = 1;
  Rendered r = renderMesh(makeIcoSphere(1.0f, 4), ContextBackend::kEgl, rp, {0.0f, 0.0f, 4.0f});
  // The centre is lit with one of the ramp's tones times the base colour: not background.
  const uint8_t* c = r.image.pixel(100, 80);
  EXPECT_LT(c[2], 250);
  EXPECT_GT(c[0], 100);
  // At least two distinct tones appear on the sphere (the ramp has three bands).
  std::set<int> tones;
  for (int x = 60; x < 140; ++x) tones.insert(r.image.pixel(x, 80)[0] / 8);
  EXPECT_GE(tones.size(), 2u);
}

// EGL and OSMesa must draw the same image (both are Mesa's llvmpipe here).
TEST(HeadlessRender, BackendsAgree) {
  Look rp;
  rp.frame.width = 240;
  rp.frame.height = 180;
  rp.frame.msaa = 1;
  std::string err;
  Rendered a = renderMesh(makeTorus(1.0f, 0.35f, 64, 32), ContextBackend::kEgl, rp, {30, 25, 0}, &err);
  ASSERT_FALSE(a.image.rgba.empty()) << err;
  Rendered b = renderMesh(makeTorus(1.0f, 0.35f, 64, 32), ContextBackend::kOsMesa, rp, {30, 25, 0}, &err);
  if (b.image.rgba.empty()) GTEST_SKIP() << "OSMesa unavailable: " << err;
  size_t differing = 0;
  for (size_t i = 0; i < a.image.rgba.size(); i += 4) {
    int d = 0;
    for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(a.image.rgba[i + c] - b.image.rgba[i + c]));
    if (d > 8) ++differing;
  }
  EXPECT_LT(differing, a.image.rgba.size() / 4 / 200) << "more than 0.5% of pixels differ";
}

TEST(HeadlessRender, CgalMeshRenders) {
  const auto p = test::dataMesh("bunny00.off");
  if (p.empty()) GTEST_SKIP() << "data/meshes/bunny00.off missing (run scripts/setup.sh)";
  auto mesh = loadMesh(p);
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  Rendered r = renderMesh(std::move(mesh.value()), ContextBackend::kEgl, linesOnly(320, 240), {});
  EXPECT_GT(r.segments, 100u);
  int dark = 0;
  for (int y = 0; y < 240; ++y)
    for (int x = 0; x < 320; ++x) dark += isDark(r.image.pixel(x, y));
  EXPECT_GT(dark, 300);
}

}  // namespace
}  // namespace lodline
