// The viewer without a window (EGL surfaceless): its first frame is the picture `render`
// writes, a saved view renders back to the same picture, and the panel's T slider, dragged
// with real ImGui mouse input, changes the active face count.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include <glad/gl.h>
#include <glm/trigonometric.hpp>
#include <nlohmann/json.hpp>

#include "app/model.h"
#include "app/viewer_session.h"
#include "gl/context.h"
#include "gl/renderer.h"
#include "io/generate.h"
#include "io/image.h"
#include "io/load_mesh.h"
#include "io/stroke_style_file.h"
#include "test_util.h"

#ifdef LODLINE_HAVE_VIEWER
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include "app/viewer_panel.h"
#endif

namespace lodline {
namespace {

class Viewer : public ::testing::Test {
 protected:
  void SetUp() override {
    setenv("XDG_CACHE_HOME", (dir_ / "cache").c_str(), 1);
    ASSERT_TRUE(saveOff(dir_ / "sphere.off", makeIcoSphere(1.0f, 4)).ok());
    ASSERT_TRUE(saveOff(dir_ / "knot.off", makeTorusKnot(2, 3, 1.0f, 0.3f, 300, 24, 0.0f)).ok());
    const nlohmann::json scene = {
        {"settings", {{"size", "320x240"}, {"msaa", 1}}},
        {"objects",
         {{{"name", "knot"}, {"mesh", "knot.off"}, {"rotate", {10, 0, 0}}},
          {{"name", "ball"}, {"mesh", "sphere.off"}, {"translate", {1.5, 0.4, -2.5}}, {"scale", 0.8},
           {"detail_factor", 3}, {"style", "lines"}}}}};
    std::ofstream(dir_ / "scene.json") << scene.dump(1);
    auto ctx = createHeadlessContext(ContextBackend::kEgl);
    if (!ctx) GTEST_SKIP() << ctx.error().message;
    ctx_ = std::move(ctx.value());
  }

  // Loads `args` as `lodline view` would and opens a session on it.
  std::unique_ptr<ViewerSession> open(const std::vector<std::string>& args) {
    CLI::App app;
    ViewOptions view;
    DetailOptions detail;
    addViewOptions(app, view);
    addDetailOptions(app, detail);
    std::vector<std::string> rev(args.rbegin(), args.rend());
    app.parse(rev);
    auto loaded = loadInput(app, view, detail);
    EXPECT_TRUE(loaded) << (loaded ? "" : loaded.error().message);
    if (!loaded) return nullptr;
    auto s = ViewerSession::create(std::move(loaded.value()), view);
    EXPECT_TRUE(s) << (s ? "" : s.error().message);
    return s ? std::move(s.value()) : nullptr;
  }

  // The session's current frame copied into a w×h offscreen target, as into a window.
  Image draw(ViewerSession& s, int w, int h) {
    auto target = OffscreenTarget::create(w, h, 1);
    EXPECT_TRUE(target);
    target->bind();
    s.draw();
    glFinish();
    return target->readback();
  }

  // Pixels whose channels differ by more than `levels` (of 255).
  static size_t differing(const Image& a, const Image& b, int levels = 0) {
    if (a.width != b.width || a.height != b.height) return SIZE_MAX;
    size_t n = 0;
    for (size_t i = 0; i < a.rgba.size(); i += 4) {
      int d = 0;
      for (int k = 0; k < 4; ++k) d = std::max(d, std::abs(int(a.rgba[i + k]) - int(b.rgba[i + k])));
      n += d > levels;
    }
    return n;
  }

  test::TempDir dir_;
  std::unique_ptr<GlContext> ctx_;
};

TEST_F(Viewer, FirstFrameIsWhatRenderWrites) {
  const std::string scene = (dir_ / "scene.json").string();
  auto s = open({scene});
  ASSERT_TRUE(s);
  ASSERT_EQ(s->scene().size(), 2u);
  ASSERT_TRUE(s->frame(320, 240, 1.0f / 30.0f).ok());
  const Image viewer = draw(*s, 320, 240);
  ASSERT_EQ(test::runLodline("render " + scene + " -o " + (dir_ / "render.png").string()), 0);
  auto rendered = readPng(dir_ / "render.png");
  ASSERT_TRUE(rendered);
  EXPECT_EQ(differing(viewer, *rendered), 0u);
  // And the picture is not empty: both objects drew lines.
  EXPECT_GT(s->presenter().segmentsDrawn(0), 50u);
  EXPECT_GT(s->presenter().segmentsDrawn(1), 20u);
}

TEST_F(Viewer, ASavedViewRendersToTheSamePicture) {
  auto s = open({(dir_ / "scene.json").string(), "--msaa", "1"});
  ASSERT_TRUE(s);
  ASSERT_TRUE(s->frame(320, 240, 1.0f / 30.0f).ok());
  // Change what the panel and the mouse change: camera, T, a factor, line kinds and styles.
  s->orbit(40.0f, -15.0f);
  s->zoom(0.8f);
  s->pan(12.0f, -7.0f, 320, 240);
  s->detail().target_area = 9.0f;
  s->scene()[1].detail_factor = 1.5f;
  s->defaultStyle().lines.kinds[1].enabled = false;
  for (auto& o : s->scene().objects()) o.style.lines.kinds[1].enabled = false;
  LineParams lp = s->lineParams();
  lp.crease_angle_deg = 45.0f;
  s->setLineParams(lp);
  s->setStyleAll(Style::kShaded);
  const auto saved = dir_ / "views" / "saved.json";
  std::filesystem::create_directories(saved.parent_path());
  ASSERT_TRUE(s->saveView(saved, 300, 200).ok());
  // A fresh session on the saved file converges to that camera and those parameters...
  auto t = open({saved.string()});
  ASSERT_TRUE(t);
  EXPECT_FLOAT_EQ(t->detail().target_area, 9.0f);
  EXPECT_FLOAT_EQ(t->scene()[1].detail_factor, 1.5f);
  EXPECT_FALSE(t->scene()[0].style.lines.kinds[1].enabled);
  EXPECT_EQ(t->scene()[0].style.style, Style::kShaded);
  EXPECT_FLOAT_EQ(t->lineParams().crease_angle_deg, 45.0f);
  const Camera a = s->camera(300, 200), b = t->camera(300, 200);
  EXPECT_LT(glm::length(a.eye - b.eye), 1e-4f * glm::length(a.eye));
  ASSERT_TRUE(t->frame(300, 200, 1.0f / 30.0f).ok());
  const Image viewer = draw(*t, 300, 200);
  // ...and `render` of the saved file writes exactly that picture.
  ASSERT_EQ(test::runLodline("render " + saved.string() + " -o " + (dir_ / "saved.png").string()), 0);
  auto rendered = readPng(dir_ / "saved.png");
  ASSERT_TRUE(rendered);
  EXPECT_EQ(rendered->width, 300);
  // Up to one level of 255: a stroke's coverage turns a last-bit difference of its position
  // (the saved camera read back in another process) into a level in a few fringe pixels.
  EXPECT_EQ(differing(viewer, *rendered, 1), 0u);
}

// With the panel covering the window's left, the scene is framed in the part it leaves free:
// its centre at that part's centre, its bounding box inside it; a saved view keeps the
// framing without the panel's shift (render centres the scene).
TEST_F(Viewer, TheSceneIsFramedBesideThePanel) {
  auto s = open({(dir_ / "scene.json").string(), "--msaa", "1"});
  ASSERT_TRUE(s);
  const int w = 480, h = 240, inset = 200;
  s->setInset(inset);
  ASSERT_TRUE(s->frame(w, h, 1.0f / 30.0f).ok());
  const Bounds& b = s->scene().bounds();
  const Camera cam = s->camera(w, h);
  const PixelProjector proj(cam, w, h);
  glm::vec2 c;
  float depth = 0.0f;
  ASSERT_TRUE(proj.project(b.center, c, depth));
  EXPECT_NEAR(c.x, inset + 0.5f * (w - inset), 1.0f);
  EXPECT_NEAR(c.y, 0.5f * h, 1.0f);
  // The scene's box lies in the free part.
  for (int k = 0; k < 8; ++k) {
    const glm::vec3 p((k & 1) ? b.max.x : b.min.x, (k & 2) ? b.max.y : b.min.y, (k & 4) ? b.max.z : b.min.z);
    glm::vec2 px;
    ASSERT_TRUE(proj.project(p, px, depth));
    EXPECT_GE(px.x, inset - 1.0f) << "corner " << k;
    EXPECT_LE(px.x, w + 1.0f) << "corner " << k;
  }
  // Without the panel the same session frames the scene in the whole window again.
  s->setInset(0);
  ASSERT_TRUE(s->frame(w, h, 1.0f / 30.0f).ok());
  const PixelProjector whole(s->camera(w, h), w, h);
  ASSERT_TRUE(whole.project(b.center, c, depth));
  EXPECT_NEAR(c.x, 0.5f * w, 1.0f);
  // The saved view looks at the scene's centre: no sideways shift.
  s->setInset(inset);
  ASSERT_TRUE(s->frame(w, h, 1.0f / 30.0f).ok());
  const auto saved = dir_ / "framed.json";
  ASSERT_TRUE(s->saveView(saved, w, h).ok());
  auto t = open({saved.string()});
  ASSERT_TRUE(t);
  const Camera back = t->camera(w, h);
  EXPECT_LT(glm::length(back.target - b.center), 1e-3f * b.radius);
}

// Stroke fields edited in the panel (one kind, then all of them) are saved as a style file
// beside the view; a fresh session on it has the same fields and `render` draws the same.
TEST_F(Viewer, EditedStrokeFieldsAreSavedWithTheView) {
  auto s = open({(dir_ / "scene.json").string(), "--msaa", "1", "--stroke-style", "pencil"});
  ASSERT_TRUE(s);
  StrokeStyle all = s->defaultStyle().lines.kinds[0].stroke;
  all.taper_in_px = 9.0f;
  all.dash_on = 12.0f;
  all.dash_off = 5.0f;
  all.cap = StrokeCap::kButt;
  s->setStrokeStyle(-1, all);
  StrokeStyle suggestive = all;
  suggestive.brush_path = "marker";
  suggestive.brush_period_px = 40.0f;
  suggestive.jitter_px = 1.5f;
  ASSERT_TRUE(prepareBrush(suggestive).ok());
  s->setStrokeStyle(static_cast<int>(LineKind::kSuggestive), suggestive);
  EXPECT_EQ(s->scene()[1].style.lines[LineKind::kContour].stroke.dash_on, 12.0f);  // every object
  ASSERT_TRUE(s->frame(320, 240, 1.0f / 30.0f).ok());
  const auto saved = dir_ / "views" / "styled.json";
  std::filesystem::create_directories(saved.parent_path());
  ASSERT_TRUE(s->saveView(saved, 320, 240).ok());
  ASSERT_TRUE(std::filesystem::exists(dir_ / "views" / "styled.strokes.json"));
  auto t = open({saved.string()});
  ASSERT_TRUE(t);
  for (size_t i = 0; i < t->scene().size(); ++i) {
    const LineStyles& l = t->scene()[i].style.lines;
    EXPECT_EQ(l[LineKind::kContour].stroke.taper_in_px, 9.0f);
    EXPECT_EQ(l[LineKind::kContour].stroke.dash_off, 5.0f);
    EXPECT_EQ(l[LineKind::kContour].stroke.cap, StrokeCap::kButt);
    EXPECT_EQ(l[LineKind::kContour].stroke.brush_path, "pencil");
    EXPECT_EQ(l[LineKind::kSuggestive].stroke.brush_path, "marker");
    EXPECT_EQ(l[LineKind::kSuggestive].stroke.jitter_px, 1.5f);
    ASSERT_TRUE(l[LineKind::kSuggestive].stroke.brush);
    EXPECT_EQ(l[LineKind::kSuggestive].stroke.brush->width, 40);
    // The preset's colours and widths came back through the view's line-style.
    EXPECT_EQ(l[LineKind::kContour].width_px, s->scene()[i].style.lines[LineKind::kContour].width_px);
  }
  ASSERT_TRUE(t->frame(320, 240, 1.0f / 30.0f).ok());
  const Image viewer = draw(*t, 320, 240);
  ASSERT_EQ(test::runLodline("render " + saved.string() + " -o " + (dir_ / "styled.png").string()), 0);
  auto rendered = readPng(dir_ / "styled.png");
  ASSERT_TRUE(rendered);
  EXPECT_EQ(differing(viewer, *rendered, 1), 0u);
  // And the edit shows: the dashed, butt-capped picture is not the preset's.
  ASSERT_EQ(test::runLodline("render " + (dir_ / "scene.json").string() + " --stroke-style pencil -o " +
                             (dir_ / "preset.png").string()),
            0);
  auto preset = readPng(dir_ / "preset.png");
  ASSERT_TRUE(preset);
  EXPECT_GT(differing(*preset, *rendered, 8), 200u);
}

// One frame, three readers: the viewer's panel (the session's report), `render --stats` and
// the first row of `capture --metrics` count it the same way (one definition of each count).
TEST_F(Viewer, PanelStatsAndMetricsCountTheSameFrame) {
  auto s = open({(dir_ / "scene.json").string()});
  ASSERT_TRUE(s);
  ASSERT_TRUE(s->frame(320, 240, 1.0f / 30.0f).ok());
  s->orbit(25.0f, 10.0f);
  const auto view = dir_ / "view.json";
  ASSERT_TRUE(s->saveView(view, 320, 240).ok());
  // The panel of a session opened on the saved view: its first frame.
  auto t = open({view.string()});
  ASSERT_TRUE(t);
  ASSERT_TRUE(t->frame(320, 240, 1.0f / 30.0f).ok());
  const ObjectReport& panel = t->report().total;
  // --stats of `render` of the same view.
  ASSERT_EQ(test::runLodline("render " + view.string() + " -o " + (dir_ / "v.png").string() + " --stats " +
                             (dir_ / "v.json").string()),
            0);
  const nlohmann::json stats = nlohmann::json::parse(std::ifstream(dir_ / "v.json"));
  // --metrics of a capture whose first frame has that camera.
  const Camera cam = t->camera(320, 240);
  auto key = [&](double time) {
    return nlohmann::json{{"time", time},
                          {"eye", {cam.eye.x, cam.eye.y, cam.eye.z}},
                          {"target", {cam.target.x, cam.target.y, cam.target.z}},
                          {"up", {cam.up.x, cam.up.y, cam.up.z}},
                          {"fov", cam.fov_deg}};
  };
  std::ofstream(dir_ / "still.json") << nlohmann::json{{"keys", {key(0.0), key(1.0)}}}.dump();
  ASSERT_EQ(test::runLodline("capture " + view.string() + " --path " + (dir_ / "still.json").string() +
                             " --frames 1 -o " + (dir_ / "frames").string() + "/ --metrics " + (dir_ / "m.csv").string()),
            0);
  std::ifstream csv(dir_ / "m.csv");
  std::string header, row;
  std::getline(csv, header);
  std::getline(csv, row);
  std::map<std::string, double> metrics;
  {
    std::stringstream h(header), r(row);
    std::string name, value;
    while (std::getline(h, name, ',') && std::getline(r, value, ',')) metrics[name] = std::stod(value);
  }
  EXPECT_GT(panel.strokes, 5u);
  EXPECT_GT(panel.line_pixels, 100u);
  EXPECT_EQ(panel.strokes, stats["strokes"].get<uint64_t>());
  EXPECT_EQ(panel.specks, stats["specks"].get<uint64_t>());
  EXPECT_EQ(panel.line_pixels, stats["line_pixels"].get<uint64_t>());
  EXPECT_EQ(panel.active_faces, stats["active_faces"].get<uint64_t>());
  EXPECT_EQ(static_cast<double>(panel.strokes), metrics["strokes"]);
  EXPECT_EQ(static_cast<double>(panel.specks), metrics["specks"]);
  EXPECT_EQ(static_cast<double>(panel.line_pixels), metrics["line_pixels"]);
  EXPECT_EQ(static_cast<double>(panel.active_faces), metrics["active_faces"]);
}

#ifdef LODLINE_HAVE_VIEWER
TEST_F(Viewer, DraggingThePanelsTargetAreaSliderChangesTheActiveFaces) {
  auto s = open({(dir_ / "scene.json").string(), "--geomorphs", "off"});
  ASSERT_TRUE(s);
  const int w = 900, h = 760;
  ASSERT_TRUE(s->frame(w, h, 1.0f / 30.0f).ok());
  const size_t faces_before = s->report().total.active_faces;
  const float t_before = s->detail().target_area;
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;
  io.DisplaySize = ImVec2(static_cast<float>(w), static_cast<float>(h));
  io.DeltaTime = 1.0f / 30.0f;
  ASSERT_TRUE(ImGui_ImplOpenGL3_Init("#version 330 core"));
  PanelState panel;
  initPanel(*s, panel);
  auto target = OffscreenTarget::create(w, h, 1);
  ASSERT_TRUE(target);
  // One viewer frame with the panel; the mouse as given.
  auto frame = [&](ImVec2 mouse, bool down) {
    io.MousePos = mouse;
    io.MouseDown[0] = down;
    ASSERT_TRUE(s->frame(w, h, 1.0f / 30.0f).ok());
    target->bind();
    s->draw();
    ImGui_ImplOpenGL3_NewFrame();
    ImGui::NewFrame();
    drawPanel(*s, panel, w, h);
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  };
  frame(ImVec2(-100, -100), false);
  frame(ImVec2(-100, -100), false);
  const auto r = panel.target_area_slider;
  ASSERT_GT(r[2] - r[0], 50.0f) << "the T slider was not laid out";
  const float y = 0.5f * (r[1] + r[3]);
  frame(ImVec2(r[0] + 0.5f * (r[2] - r[0]), y), false);  // hover
  frame(ImVec2(r[0] + 0.5f * (r[2] - r[0]), y), true);   // press
  frame(ImVec2(r[2] - 1.0f, y), true);                   // drag to the coarse end
  frame(ImVec2(r[2] - 1.0f, y), false);                  // release
  for (int i = 0; i < 4; ++i) frame(ImVec2(-100, -100), false);  // adapt (no geomorphs: at once)
  EXPECT_GT(s->detail().target_area, 8.0f * t_before);
  EXPECT_LT(s->report().total.active_faces, faces_before / 2);
  // The panel was drawn over the picture: its pixels differ from the bare drawing.
  const Image with_panel = target->readback();
  target->bind();
  s->draw();
  glFinish();
  EXPECT_GT(differing(with_panel, target->readback()), 20000u);
  ImGui_ImplOpenGL3_Shutdown();
  ImGui::DestroyContext();
}
#endif

}  // namespace
}  // namespace lodline
