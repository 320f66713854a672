// The software presenter (raster/, Han & Wang 2011 constant-depth scanlines) against the
// OpenGL one: the toon image agrees within a tolerance, and the visibility of lines from the
// soft depth buffer agrees with the GL depth buffer.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <glm/geometric.hpp>

#include "export/visibility.h"
#include "io/generate.h"
#include "io/image.h"
#include "io/load_mesh.h"
#include "present_test_util.h"

namespace lodline {
namespace {

struct Frame {
  Image image;
  DepthImage depth;
};

using test::Look;

Frame render(TriMesh mesh, const Look& look, OrbitView orbit, PresenterBackend backend, Camera* camera = nullptr,
             StrokeSet* strokes = nullptr) {
  Frame f;
  SceneDrawing scene = test::sceneOf(std::move(mesh), look.style);
  const Camera cam = orbitCamera(scene.bounds(), orbit, 35.0f, look.frame.aspect());
  test::Presented p = test::presentScene(scene, cam, look.frame, backend);
  if (!p) return f;
  f.image = std::move(p.image);
  f.depth = p.presenter->depth();
  if (camera) *camera = cam;
  if (strokes) *strokes = scene[0].drawing->drawing().strokes();
  return f;
}

// Fraction of pixels whose colours differ by more than `tol` in some channel.
double differingFraction(const Image& a, const Image& b, int tol) {
  size_t n = 0;
  for (size_t i = 0; i < a.rgba.size(); i += 4) {
    int d = 0;
    for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(a.rgba[i + c] - b.rgba[i + c]));
    n += d > tol;
  }
  return static_cast<double>(n) / static_cast<double>(a.rgba.size() / 4);
}

// Fraction of differing pixels that have no matching pixel within 1 px in the other image
// (i.e. not just a line or tone boundary shifted by a pixel).
double unmatchedFraction(const Image& a, const Image& b, int tol) {
  size_t n = 0;
  auto close = [&](int x, int y, int xx, int yy) {
    const uint8_t *p = a.pixel(x, y), *q = b.pixel(xx, yy);
    for (int c = 0; c < 3; ++c)
      if (std::abs(p[c] - q[c]) > tol) return false;
    return true;
  };
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      bool found = false;
      for (int yy = std::max(0, y - 1); yy <= std::min(a.height - 1, y + 1) && !found; ++yy)
        for (int xx = std::max(0, x - 1); xx <= std::min(a.width - 1, x + 1) && !found; ++xx)
          found = close(x, y, xx, yy);
      n += !found;
    }
  return static_cast<double>(n) / (static_cast<double>(a.width) * a.height);
}

Look params(int w, int h) {
  Look rp;
  rp.frame.width = w;
  rp.frame.height = h;
  rp.frame.msaa = 1;  // the software renderer does not antialias
  return rp;
}

void checkToonAgrees(TriMesh mesh, OrbitView view, const char* name) {
  const Look rp = params(400, 300);
  const Frame gl = render(mesh, rp, view, PresenterBackend::kGl);
  if (gl.image.rgba.empty()) GTEST_SKIP() << "no EGL context";
  const Frame soft = render(std::move(mesh), rp, view, PresenterBackend::kSoft);
  const double diff = differingFraction(gl.image, soft.image, 8);
  const double unmatched = unmatchedFraction(gl.image, soft.image, 8);
  std::printf("%s: %.2f%% of pixels differ, %.3f%% without a match within 1 px\n", name, 100 * diff, 100 * unmatched);
  if (const char* dir = std::getenv("LODLINE_SOFT_DUMP")) {  // for looking at the images
    Image d = gl.image;
    for (size_t i = 0; i < d.rgba.size(); i += 4) {
      int m = 0;
      for (int c = 0; c < 3; ++c) m = std::max(m, std::abs(gl.image.rgba[i + c] - soft.image.rgba[i + c]));
      if (m > 8) d.rgba[i] = 255, d.rgba[i + 1] = 0, d.rgba[i + 2] = 0;
    }
    const std::string base = std::string(dir) + "/" + name;
    (void)writePng(base + "-gl.png", gl.image);
    (void)writePng(base + "-soft.png", soft.image);
    (void)writePng(base + "-diff.png", d);
  }
  EXPECT_LT(diff, 0.03) << name;        // tone-band borders and line pixels only
  EXPECT_LT(unmatched, 0.01) << name;  // almost all differences are one-pixel shifts
  // Depth buffers agree where both have a surface.
  size_t both = 0, coverage_differs = 0, far_off = 0;
  for (size_t i = 0; i < gl.depth.depth.size(); ++i) {
    const bool a = gl.depth.depth[i] < 1.0f, b = soft.depth.depth[i] < 1.0f;
    coverage_differs += a != b;
    if (a && b) {
      ++both;
      far_off += std::abs(gl.depth.depth[i] - soft.depth.depth[i]) > 1e-3f;
    }
  }
  EXPECT_GT(both, 1000u);
  EXPECT_LT(static_cast<double>(coverage_differs) / gl.depth.depth.size(), 0.003) << name;
  EXPECT_LT(static_cast<double>(far_off) / both, 0.003) << name;
}

TEST(SoftVsGl, ToonTorusAgrees) { checkToonAgrees(makeTorus(1.0f, 0.35f, 64, 32), {30, 25, 0}, "torus"); }

TEST(SoftVsGl, ToonSphereAgrees) { checkToonAgrees(makeIcoSphere(1.0f, 4), {20, 10, 0}, "sphere"); }

TEST(SoftVsGl, ToonArmadilloAgrees) {
  const auto p = test::dataMesh("armadillo.off");
  if (p.empty()) GTEST_SKIP() << "data/meshes/armadillo.off missing";
  auto mesh = loadMesh(p);
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  checkToonAgrees(std::move(mesh.value()), {200, 10, 2.9f}, "armadillo");
}

// Hidden-line removal for SVG: every stroke sample classified visible/hidden against the
// soft depth buffer and against the GL depth buffer.
void checkVisibilityAgrees(TriMesh mesh, OrbitView view, const char* name) {
  Look rp = params(400, 300);
  rp.style.style = Style::kLines;
  Camera camera;
  StrokeSet strokes;
  const Frame gl = render(mesh, rp, view, PresenterBackend::kGl, &camera, &strokes);
  if (gl.image.rgba.empty()) GTEST_SKIP() << "no EGL context";
  const Frame soft = render(std::move(mesh), rp, view, PresenterBackend::kSoft);
  size_t total = 0, agree = 0, visible_gl = 0, visible_soft = 0;
  for (size_t k = 0; k < strokes.points.size(); ++k) {
    const bool a = isPointVisible(camera, gl.depth, strokes.points[k]);
    const bool b = isPointVisible(camera, soft.depth, strokes.points[k]);
    ++total;
    agree += a == b;
    visible_gl += a;
    visible_soft += b;
  }
  StrokeRuns vg, vs;
  visibleStrokes(strokes, camera, gl.depth, {}, vg);
  visibleStrokes(strokes, camera, soft.depth, {}, vs);
  double len_gl = 0, len_soft = 0;
  for (float l : vg.length_px) len_gl += l;
  for (float l : vs.length_px) len_soft += l;
  std::printf("%s: %zu stroke points, %.2f%% agree (visible: gl %zu, soft %zu); visible length gl %.0f px, soft %.0f px\n",
              name, total, 100.0 * agree / total, visible_gl, visible_soft, len_gl, len_soft);
  ASSERT_GT(total, 100u);
  EXPECT_GT(visible_gl, total / 5);
  EXPECT_LT(visible_gl, total);  // some lines are hidden: the test means something
  EXPECT_GT(static_cast<double>(agree) / total, 0.99) << name;
  EXPECT_NEAR(len_soft, len_gl, 0.02 * len_gl) << name;
}

TEST(SoftVsGl, SvgVisibilitySphereScene) {
  // A big sphere with a small one behind it, partly hidden.
  TriMesh scene = makeIcoSphere(1.0f, 4);
  TriMesh back = makeIcoSphere(0.5f, 3);
  const uint32_t base = static_cast<uint32_t>(scene.positions.size());
  for (auto p : back.positions) scene.positions.push_back(p + glm::vec3(0.9f, 0.3f, -1.8f));
  for (auto f : back.faces) scene.faces.push_back({f[0] + base, f[1] + base, f[2] + base});
  checkVisibilityAgrees(std::move(scene), {15, 10, 3.0f}, "spheres");
}

TEST(SoftVsGl, SvgVisibilityArmadillo) {
  const auto p = test::dataMesh("armadillo.off");
  if (p.empty()) GTEST_SKIP() << "data/meshes/armadillo.off missing";
  auto mesh = loadMesh(p);
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  checkVisibilityAgrees(std::move(mesh.value()), {200, 10, 2.9f}, "armadillo");
}

}  // namespace
}  // namespace lodline
