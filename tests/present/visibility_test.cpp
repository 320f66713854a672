// Per-sample visibility against exact visibility: the runs the presenter draws (visible) and
// those it hides are compared, sample by sample, with ray casting against the meshes on two
// analytic scenes (a sphere behind a sphere; a torus seen edge-on). Rays ignore the surface
// within two edge lengths (or 3 px) of the sample itself (a contour point lies on faces that
// graze the ray), so what is tested is occlusion by other parts and other objects. The
// mismatching length must stay under 1% of the line length (docs/visibility.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "io/generate.h"
#include "present/gl_presenter.h"
#include "present_test_util.h"

namespace lodline {
namespace {

// Nearest hit of the ray o + t·d (t > 0) with a triangle of `meshes` farther than `skip`
// from `p` (world units) and before `t_max`; false when none.
bool occluded(const std::vector<const TriMesh*>& meshes, glm::vec3 o, glm::vec3 p, float skip) {
  const glm::vec3 d = p - o;  // t in (0, 1) reaches p at t = 1
  for (const TriMesh* m : meshes)
    for (const auto& f : m->faces) {
      const glm::vec3 a = m->positions[f[0]], b = m->positions[f[1]], c = m->positions[f[2]];
      // Möller–Trumbore.
      const glm::vec3 e1 = b - a, e2 = c - a, q = glm::cross(d, e2);
      const float det = glm::dot(e1, q);
      if (std::abs(det) < 1e-12f) continue;
      const float inv = 1.0f / det;
      const glm::vec3 s = o - a;
      const float u = glm::dot(s, q) * inv;
      if (u < 0.0f || u > 1.0f) continue;
      const glm::vec3 r = glm::cross(s, e1);
      const float v = glm::dot(d, r) * inv;
      if (v < 0.0f || u + v > 1.0f) continue;
      const float t = glm::dot(e2, r) * inv;
      if (t <= 1e-4f || t >= 1.0f) continue;
      if (glm::length(o + t * d - p) > skip) return true;
    }
  return false;
}

struct Comparison {
  double length = 0.0;    // drawn (visible) plus hidden run length, px
  double mismatch = 0.0;  // of that, classified otherwise by ray casting, px
  double visible = 0.0, hidden = 0.0;
  double drawn_but_occluded = 0.0, hidden_but_clear = 0.0;
};

// Longest edge of the meshes: a contour point lies on faces that graze the ray to it, and
// those can be an edge or two away.
float longestEdge(const std::vector<const TriMesh*>& meshes) {
  float len = 0.0f;
  for (const TriMesh* m : meshes)
    for (const auto& f : m->faces)
      for (int k = 0; k < 3; ++k) len = std::max(len, glm::length(m->positions[f[k]] - m->positions[f[(k + 1) % 3]]));
  return len;
}

// Resamples every run of `runs` at ≤ 1 px (positions perspective-correct) and compares the
// class of each piece (`drawn`) with ray casting.
void compare(const StrokeRuns& runs, bool drawn, const Camera& cam, const FrameParams& frame,
             const std::vector<const TriMesh*>& meshes, Comparison& c) {
  const float edge = longestEdge(meshes);
  const PixelProjector proj(cam, frame.width, frame.height);
  const float px_world = 2.0f * std::tan(glm::radians(cam.fov_deg) * 0.5f) / static_cast<float>(frame.height);
  for (size_t r = 0; r < runs.strokeCount(); ++r)
    for (uint32_t i = runs.offsets[r]; i + 1 < runs.offsets[r + 1]; ++i) {
      const glm::vec2 a = runs.points[i], b = runs.points[i + 1];
      const glm::vec3 pa = runs.positions[i], pb = runs.positions[i + 1];
      const float za = proj.eyeDepth(pa), zb = proj.eyeDepth(pb);
      const float len = glm::length(b - a);
      const int steps = std::max(1, static_cast<int>(std::ceil(len)));
      for (int k = 0; k < steps; ++k) {
        const float s = (static_cast<float>(k) + 0.5f) / static_cast<float>(steps);
        const float t = (s / zb) / ((1.0f - s) / za + s / zb);
        const glm::vec3 p = pa + t * (pb - pa);
        const float piece = len / static_cast<float>(steps);
        const float skip = std::max(3.0f * px_world * proj.eyeDepth(p), 2.0f * edge);
        const bool exact_visible = !occluded(meshes, cam.eye, p, skip);
        c.length += piece;
        (drawn ? c.visible : c.hidden) += piece;
        if (exact_visible != drawn) {
          c.mismatch += piece;
          (drawn ? c.drawn_but_occluded : c.hidden_but_clear) += piece;
        }
      }
    }
}

Comparison checkScene(std::vector<TriMesh> meshes, const Camera& cam, const char* name) {
  Comparison c;
  auto gl = GlPresenter::createHeadless(ContextBackend::kEgl, FrameParams{});
  if (!gl) return c;
  SceneDrawing scene;
  std::vector<const TriMesh*> world;
  ObjectStyle style;
  style.style = Style::kLines;
  for (int k = 1; k < kLineKindCount; ++k) style.lines.kinds[k].enabled = false;  // contours only
  for (size_t i = 0; i < meshes.size(); ++i) {
    SceneDrawing::Object o;
    o.name = "o" + std::to_string(i);
    o.style = style;
    o.drawing = std::make_unique<LodDrawing>(meshes[i]);
    scene.add(std::move(o));
  }
  for (const TriMesh& m : meshes) world.push_back(&m);
  FrameParams frame;
  frame.width = 640;
  frame.height = 480;
  frame.msaa = 1;
  EXPECT_TRUE(scene.frame(cam, frame.width, frame.height, DetailParams{}, 1.0f / 30.0f).ok());
  EXPECT_TRUE((*gl)->present(scene, cam, frame, true).ok());
  for (size_t i = 0; i < scene.size(); ++i) {
    compare((*gl)->visible()[i], true, cam, frame, world, c);
    compare((*gl)->hidden()[i], false, cam, frame, world, c);
  }
  std::printf("%s: line length %.0f px (visible %.0f, hidden %.0f), mismatching %.1f px (%.3f%%: drawn but "
              "occluded %.1f, hidden but clear %.1f)\n",
              name, c.length, c.visible, c.hidden, c.mismatch, 100.0 * c.mismatch / std::max(c.length, 1.0),
              c.drawn_but_occluded, c.hidden_but_clear);
  return c;
}

TEST(ExactVisibility, ASphereBehindASphere) {
  TriMesh front = makeIcoSphere(1.0f, 4), back = makeIcoSphere(1.0f, 4);
  for (auto& p : front.positions) p += glm::vec3(0.0f, 0.0f, 1.5f);
  for (auto& p : back.positions) p += glm::vec3(0.9f, 0.3f, -1.0f);
  Camera cam;
  cam.eye = {0.0f, 0.0f, 9.0f};
  cam.target = {0.0f, 0.0f, 0.0f};
  cam.fov_deg = 35.0f;
  fitClipPlanes(cam, unionBounds(computeBounds(front.positions), computeBounds(back.positions)));
  const Comparison c = checkScene({front, back}, cam, "sphere behind sphere");
  if (c.length == 0.0) GTEST_SKIP() << "no EGL context";
  EXPECT_GT(c.visible, 500.0);
  EXPECT_GT(c.hidden, 100.0);  // the back sphere's contour behind the front one
  EXPECT_LT(c.mismatch, 0.01 * c.length);
}

TEST(ExactVisibility, ATorusSeenEdgeOn) {
  TriMesh torus = makeTorus(1.0f, 0.35f, 96, 48);
  Camera cam;
  cam.eye = {0.0f, 0.8f, 5.0f};  // 9 degrees above the plane of the torus: the hole half hidden
  cam.target = {0.0f, 0.0f, 0.0f};
  cam.fov_deg = 35.0f;
  fitClipPlanes(cam, computeBounds(torus.positions));
  const Comparison c = checkScene({torus}, cam, "torus edge-on");
  if (c.length == 0.0) GTEST_SKIP() << "no EGL context";
  EXPECT_GT(c.visible, 500.0);
  EXPECT_GT(c.hidden, 100.0);  // the far side of the hole, behind the near tube
  EXPECT_LT(c.mismatch, 0.01 * c.length);
}

}  // namespace
}  // namespace lodline
