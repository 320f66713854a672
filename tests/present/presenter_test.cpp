// The last stage of a frame (present/): the GL and software presenters draw, read back and
// count the same scene alike; the frame report's totals are the sums of its objects; the
// software presenter refuses what it cannot draw.
#include <gtest/gtest.h>

#if defined(__linux__)
#include <sys/resource.h>
#include <unistd.h>
#endif

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "frame/scene_drawing.h"
#include "io/generate.h"
#include "pm/progressive_mesh.h"
#include "present/frame_report.h"
#include "present/gl_presenter.h"
#include "present/soft_presenter.h"
#include "test_util.h"

namespace lodline {
namespace {

// Two spheres seen from +Z, the front one toon-shaded, the back one in the lines style and
// partly hidden by the front one.
SceneDrawing twoSpheres() {
  SceneDrawing scene;
  auto pool = std::make_shared<WorkerPool>(2);
  const glm::vec3 offsets[2] = {{0.0f, 0.0f, 1.5f}, {0.9f, 0.3f, -1.0f}};
  for (int i = 0; i < 2; ++i) {
    TriMesh m = makeIcoSphere(1.0f, 4);
    for (glm::vec3& p : m.positions) p += offsets[i];
    SceneDrawing::Object o;
    o.name = i == 0 ? "front" : "back";
    o.style.style = i == 0 ? Style::kToon : Style::kLines;
    o.input_faces = m.faceCount();
    o.input_vertices = m.vertexCount();
    o.drawing = std::make_unique<LodDrawing>(std::move(m), LineParams{}, pool);
    scene.add(std::move(o));
  }
  return scene;
}

Camera frontCamera() {
  Camera cam;
  cam.eye = {0.0f, 0.0f, 9.0f};
  cam.target = {0.0f, 0.0f, 0.0f};
  cam.fov_deg = 35.0f;
  return cam;
}

FrameParams smallFrame() {
  FrameParams f;
  f.width = 320;
  f.height = 240;
  f.msaa = 1;
  return f;
}

// The two spheres through a headless GL presenter: the scene's lines computed, presented.
struct GlFixture : ::testing::Test {
  void SetUp() override {
    auto p = GlPresenter::createHeadless(ContextBackend::kEgl, frame);
    if (!p) GTEST_SKIP() << p.error().message;
    gl = std::move(p.value());
    ASSERT_TRUE(scene.frame(camera, frame.width, frame.height, DetailParams{}, 1.0f / 30.0f).ok());
    ASSERT_TRUE(gl->present(scene, camera, frame, true).ok());
  }
  const FrameParams frame = smallFrame();
  const Camera camera = frontCamera();
  SceneDrawing scene = twoSpheres();
  std::unique_ptr<GlPresenter> gl;
};

double visibleLength(const StrokeRuns& v) {
  double len = 0.0;
  for (float l : v.length_px) len += l;
  return len;
}

using Presenter = GlFixture;

TEST_F(Presenter, GlAndSoftDrawAndCountTheSameScene) {
  SoftPresenter soft;
  ASSERT_TRUE(soft.present(scene, camera, frame, true).ok());
  const FrameReport a = reportFrame(scene, *gl), b = reportFrame(scene, soft);
  ASSERT_EQ(a.objects.size(), 2u);
  ASSERT_EQ(b.objects.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(a.objects[i].faces_drawn, b.objects[i].faces_drawn);
    EXPECT_EQ(a.objects[i].line_segments, b.objects[i].line_segments);
    EXPECT_EQ(a.objects[i].lines_extracted, b.objects[i].lines_extracted);
    const double la = visibleLength(gl->visible()[i]), lb = visibleLength(soft.visible()[i]);
    EXPECT_GT(la, 100.0) << i;
    EXPECT_NEAR(la, lb, 0.02 * la) << "visible stroke length of object " << i;
  }
  // The back sphere's contour is partly hidden by the front sphere.
  const double hidden_len = visibleLength(gl->visible()[1]);
  EXPECT_LT(a.objects[1].lines[0], a.objects[1].lines_extracted[0]);
  EXPECT_GT(hidden_len, 0.0);
  // Surfaces agree: where both saw a surface, the same point and object.
  SurfaceImage sa, sb;
  ASSERT_TRUE(gl->readSurface(sa).ok());
  ASSERT_TRUE(soft.readSurface(sb).ok());
  ASSERT_EQ(sa.texels.size(), sb.texels.size());
  size_t both = 0, same_object = 0, close = 0, coverage_differs = 0;
  for (size_t i = 0; i < sa.texels.size(); ++i) {
    const glm::vec4 &p = sa.texels[i], &q = sb.texels[i];
    coverage_differs += (p.w > 0.0f) != (q.w > 0.0f);
    if (p.w > 0.0f && q.w > 0.0f) {
      ++both;
      same_object += p.w == q.w;
      close += glm::length(glm::vec3(p) - glm::vec3(q)) < 0.01f;
    }
  }
  EXPECT_GT(both, 5000u);
  EXPECT_GT(static_cast<double>(same_object) / both, 0.995);
  EXPECT_GT(static_cast<double>(close) / both, 0.995);
  EXPECT_LT(static_cast<double>(coverage_differs) / sa.texels.size(), 0.005);
}

TEST_F(Presenter, ReportTotalsAreTheSumsOfTheObjects) {
  LineMask mask;
  const FrameReport r = reportFrame(scene, *gl, &mask);
  uint64_t faces = 0, strokes = 0, specks = 0, pixels = 0, segments = 0;
  for (const ObjectReport& o : r.objects) {
    faces += o.active_faces;
    strokes += o.strokes;
    specks += o.specks;
    pixels += o.line_pixels;
    segments += o.line_segments;
    EXPECT_LE(o.strokes, o.strokes_extracted + o.strokes_extracted);  // splits at hidden parts at most double
    EXPECT_EQ(o.active_faces, o.faces_drawn);
  }
  EXPECT_EQ(r.total.active_faces, faces);
  EXPECT_EQ(r.total.strokes, strokes);
  EXPECT_EQ(r.total.specks, specks);
  EXPECT_EQ(r.total.line_segments, segments);
  // A pixel both objects' lines cross counts once in the total.
  EXPECT_LE(r.total.line_pixels, pixels);
  EXPECT_GT(r.total.line_pixels, pixels / 2);
  EXPECT_EQ(mask.count(), r.total.line_pixels);
  // The stats JSON carries the same numbers.
  const nlohmann::json j = frameStatsJson(r);
  EXPECT_EQ(j["strokes"].get<uint64_t>(), r.total.strokes);
  EXPECT_EQ(j["objects"][1]["name"], "back");
  EXPECT_EQ(j["objects"][1]["style"], "lines");
}

// Frames in a pipeline: frame i + 1's stages run (present()'s `overlap`) while frame i is
// drawn. The frames must be the ones drawn one after the other: same images, same strokes.
TEST(PresenterPipeline, OverlappedStagesGiveTheFramesDrawnInTurn) {
  const FrameParams frame = smallFrame();
  const TriMesh knot = makeTorusKnot(2, 3, 1.0f, 0.3f, 240, 24, 0.25f);
  auto pm = buildProgressiveMesh(knot);
  ASSERT_TRUE(pm.ok());
  const auto shared = std::make_shared<const ProgressiveMesh>(std::move(pm.value()));
  auto sceneOfKnot = [&] {
    SceneDrawing scene;
    SceneDrawing::Object o;
    o.name = "knot";
    o.style.style = Style::kLines;
    o.input_faces = knot.faceCount();
    o.input_vertices = knot.vertexCount();
    o.drawing = std::make_unique<LodDrawing>(knot, shared);
    scene.add(std::move(o));
    return scene;
  };
  SceneDrawing in_turn = sceneOfKnot(), pipelined = sceneOfKnot();
  auto a = GlPresenter::createHeadless(ContextBackend::kEgl, frame);
  if (!a) GTEST_SKIP() << a.error().message;
  auto b = GlPresenter::createHeadless(ContextBackend::kEgl, frame);
  ASSERT_TRUE(b.ok());
  auto camera = [&](int i) {
    Camera cam = frontCamera();
    const float az = glm::radians(4.0f * static_cast<float>(i));
    cam.eye = glm::vec3(5.0f * std::sin(az), 1.5f, 5.0f * std::cos(az));
    return cam;
  };
  const float dt = 1.0f / 30.0f;
  ASSERT_TRUE(pipelined.frame(camera(0), frame.width, frame.height, DetailParams{}, dt).ok());
  int overlaps = 0, differing = 0;
  int overlap_nice = 0;
  for (int i = 0; i < 8; ++i) {
    ASSERT_TRUE(in_turn.frame(camera(i), frame.width, frame.height, DetailParams{}, dt).ok());
    ASSERT_TRUE((*a)->present(in_turn, camera(i), frame, i == 0).ok());
    ASSERT_TRUE((*b)->present(pipelined, camera(i), frame, i == 0, [&] {
                   (void)pipelined.frameWhileDrawing(camera(i + 1), frame.width, frame.height, DetailParams{}, dt);
#if defined(__linux__)
                   overlap_nice = getpriority(PRIO_PROCESS, static_cast<id_t>(gettid()));
#endif
                   ++overlaps;
                 }).ok());
    const Image ia = (*a)->readImage(), ib = (*b)->readImage();
    differing += ia.rgba != ib.rgba;
    EXPECT_EQ((*a)->visible()[0].strokeCount(), (*b)->visible()[0].strokeCount()) << "frame " << i;
    EXPECT_EQ((*a)->visible()[0].points.size(), (*b)->visible()[0].points.size()) << "frame " << i;
  }
  EXPECT_EQ(overlaps, 8);
  EXPECT_EQ(differing, 0);
#if defined(__linux__)
  // The overlapped stages yield to the drawing: their thread runs at a higher nice value than
  // the caller's (which stays as it was).
  const int caller_nice = getpriority(PRIO_PROCESS, static_cast<id_t>(gettid()));
  if (caller_nice < 19) {
    EXPECT_GT(overlap_nice, caller_nice);
  }
#endif
  // The camera moved and detail changed: the frames were not all alike.
  EXPECT_GT((*a)->visible()[0].strokeCount(), 0u);
}

TEST(SoftPresenter, RefusesTheShadedStyleAndChamferHighlights) {
  SceneDrawing scene = twoSpheres();
  SoftPresenter soft;
  EXPECT_TRUE(soft.check(scene).ok());
  scene[1].style.style = Style::kShaded;
  Status s = soft.check(scene);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().kind, Error::Kind::kUsage);
  EXPECT_NE(s.error().message.find("'back'"), std::string::npos) << s.error().message;
  // present() refuses too, before drawing anything.
  EXPECT_FALSE(soft.present(scene, frontCamera(), smallFrame(), true).ok());
  scene[1].style.style = Style::kToon;
  scene[1].style.chamfer.over_toon = true;
  EXPECT_FALSE(soft.check(scene).ok());
}

}  // namespace
}  // namespace lodline
