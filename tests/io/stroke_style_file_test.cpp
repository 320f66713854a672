// Stroke styles by name and from files (io/stroke_style_file.h): the presets, the brushes
// (deterministic, and the committed copies are the generator's output), style files with
// their errors naming the file and the key, and brush resampling.
#include <gtest/gtest.h>

#include <fstream>

#include "io/image.h"
#include "io/stroke_style_file.h"
#include "test_util.h"

namespace lodline {
namespace {

void writeText(const std::filesystem::path& p, const std::string& text) { std::ofstream(p) << text; }

double meanRed(const Image& img) {
  double s = 0.0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) s += img.pixel(x, y)[0];
  return s / (static_cast<double>(img.width) * img.height);
}

TEST(StrokeStyleFile, PresetsAreWhatTheDocsSay) {
  auto plain = loadStrokeStyle("plain");
  ASSERT_TRUE(plain);
  LineStyles lines;
  const LineStyles before = lines;
  applyStrokeStyle(*plain, lines);
  for (int k = 0; k < kLineKindCount; ++k) {  // today's look: nothing changes
    EXPECT_EQ(lines.kinds[k].width_px, before.kinds[k].width_px);
    EXPECT_EQ(lines.kinds[k].color, before.kinds[k].color);
    EXPECT_EQ(lines.kinds[k].stroke.cap, StrokeCap::kRound);
    EXPECT_EQ(lines.kinds[k].stroke.taper_in_px, 0.0f);
    EXPECT_EQ(lines.kinds[k].stroke.strength_opacity, 1.0f);
    EXPECT_FALSE(lines.kinds[k].stroke.brush);
  }
  auto ink = loadStrokeStyle("ink");
  ASSERT_TRUE(ink);
  EXPECT_GT(ink->kinds[0].stroke.taper_in_px, 0.0f);
  EXPECT_GT(ink->kinds[0].stroke.strength_thickness, 0.0f);
  for (const char* name : {"pencil", "marker"}) {
    auto p = loadStrokeStyle(name);
    ASSERT_TRUE(p) << name;
    ASSERT_TRUE(p->kinds[0].stroke.brush) << name;
    LineStyles l;
    applyStrokeStyle(*p, l);
    // Resampled to one period of arc length by 8 px across.
    EXPECT_EQ(l.kinds[0].stroke.brush->width, static_cast<int>(p->kinds[0].stroke.brush_period_px)) << name;
    EXPECT_EQ(l.kinds[0].stroke.brush->height, 8) << name;
  }
  auto bad = loadStrokeStyle("crayon");
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("plain, ink, pencil, marker"), std::string::npos);
}

TEST(StrokeStyleFile, BrushesAreDeterministicAndCommitted) {
  for (auto [kind, file] : {std::pair{BrushKind::kPencil, "pencil.png"}, std::pair{BrushKind::kMarker, "marker.png"}}) {
    const Image a = makeBrush(kind), b = makeBrush(kind);
    EXPECT_EQ(a.rgba, b.rgba);
    EXPECT_GT(meanRed(a), 100.0);  // mostly ink, with texture
    auto committed = readPng(std::filesystem::path(LODLINE_SOURCE_DIR) / "models" / "brushes" / file);
    ASSERT_TRUE(committed) << committed.error().message;
    EXPECT_EQ(committed->rgba, a.rgba) << file << " differs from `lodline generate brush-...`";
  }
}

TEST(StrokeStyleFile, FilesSetKindsAfterAll) {
  test::TempDir dir;
  Image brush(4, 2);
  std::fill(brush.rgba.begin(), brush.rgba.end(), 200);
  ASSERT_TRUE(writePng(dir / "b.png", brush));
  writeText(dir / "s.json", R"({"all": {"cap": "butt", "taper_in": 5, "color": "#ff0000", "width_scale": 2},
                               "suggestive": {"dash": [4, 2], "brush": "b.png", "brush_period": 16, "seed": 7}})");
  auto s = loadStrokeStyle((dir / "s.json").string());
  ASSERT_TRUE(s) << s.error().message;
  LineStyles lines;
  const float contour_width = lines[LineKind::kContour].width_px;
  applyStrokeStyle(*s, lines);
  EXPECT_EQ(lines[LineKind::kContour].stroke.cap, StrokeCap::kButt);
  EXPECT_EQ(lines[LineKind::kContour].stroke.taper_in_px, 5.0f);
  EXPECT_EQ(lines[LineKind::kContour].width_px, 2.0f * contour_width);
  EXPECT_EQ(lines[LineKind::kContour].color, glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));
  const StrokeStyle& sg = lines[LineKind::kSuggestive].stroke;
  EXPECT_EQ(sg.cap, StrokeCap::kButt);  // from "all"
  EXPECT_EQ(sg.dash_on, 4.0f);
  EXPECT_EQ(sg.dash_off, 2.0f);
  EXPECT_EQ(sg.seed, 7u);
  ASSERT_TRUE(sg.brush);
  EXPECT_EQ(sg.brush->width, 16);
  EXPECT_NEAR(meanRed(*sg.brush), 200.0, 0.5);  // resampling keeps a flat brush flat
  EXPECT_FALSE(lines[LineKind::kContour].stroke.brush);
}

TEST(StrokeStyleFile, ErrorsNameTheFileAndTheKey) {
  test::TempDir dir;
  const auto cases = {std::pair{R"({"contour": {"cap": "pointy"}})", "contour.cap"},
                      std::pair{R"({"all": {"taper_min": 2}})", "taper_min"},
                      std::pair{R"({"contour": {"wobble": 1}})", "wobble"},
                      std::pair{R"({"silhouette": {}})", "silhouette"},
                      std::pair{R"({"contour": {"brush": "missing.png"}})", "missing.png"},
                      std::pair{R"({"contour": {"dash": [1]}})", "dash"},
                      std::pair{R"({"contour": [1, 2]})", "contour"},
                      std::pair{R"({"contour": )", "not valid JSON"}};
  for (const auto& [text, key] : cases) {
    writeText(dir / "bad.json", text);
    auto s = loadStrokeStyle((dir / "bad.json").string());
    ASSERT_FALSE(s) << text;
    EXPECT_NE(s.error().message.find("bad.json"), std::string::npos) << s.error().message;
    EXPECT_NE(s.error().message.find(key), std::string::npos) << s.error().message;
  }
  auto missing = loadStrokeStyle((dir / "nope.json").string());
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("nope.json"), std::string::npos);
}

// What the viewer's "save view" writes for a style edited in the panel reads back field for
// field, brushes (built-in and from a file, relative to the style file) included.
TEST(StrokeStyleFile, WrittenFilesReadBackTheSameFields) {
  test::TempDir dir;
  std::filesystem::create_directories(dir / "brushes");
  Image brush(8, 4);
  for (size_t i = 0; i < brush.rgba.size(); ++i) brush.rgba[i] = static_cast<uint8_t>(i * 7);
  ASSERT_TRUE(writePng(dir / "brushes" / "mine.png", brush));
  LineStyles lines;
  for (int k = 0; k < kLineKindCount; ++k) {
    StrokeStyle& s = lines.kinds[k].stroke;
    s.cap = static_cast<StrokeCap>(k % 3);
    s.taper_in_px = 1.5f + k;
    s.taper_out_px = 0.1f * k;
    s.taper_min = 0.15f;
    s.depth_thickness = -0.35f;
    s.strength_thickness = 0.6f;
    s.curvature_thickness = 3.3f;
    s.depth_opacity = 0.25f;
    s.strength_opacity = 0.4f;
    s.curvature_opacity = 0.7f;
    s.dash_on = 4.2f;
    s.dash_off = k == 0 ? 0.0f : 2.5f;
    s.jitter_px = 0.35f;
    s.jitter_period_px = 30.0f;
    s.seed = 4000000000u - k;
    s.min_length_px = 3.0f;
    s.brush_period_px = 48.0f + k;
    s.brush_path = k == 1 ? "pencil" : k == 2 ? (dir / "brushes" / "mine.png").string() : "";
    ASSERT_TRUE(prepareBrush(s).ok());
  }
  std::filesystem::create_directories(dir / "views");
  const auto path = dir / "views" / "v.strokes.json";
  ASSERT_TRUE(writeStrokeStyleFile(path, lines).ok());
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\"../brushes/mine.png\""), std::string::npos) << text;  // relative to the file
  EXPECT_NE(text.find("0.15,"), std::string::npos) << "floats written short: " << text;
  auto loaded = loadStrokeStyle(path.string());
  ASSERT_TRUE(loaded) << loaded.error().message;
  LineStyles back;
  applyStrokeStyle(*loaded, back);
  for (int k = 0; k < kLineKindCount; ++k) {
    const StrokeStyle &a = lines.kinds[k].stroke, &b = back.kinds[k].stroke;
    EXPECT_EQ(a.cap, b.cap) << k;
    EXPECT_EQ(a.taper_in_px, b.taper_in_px) << k;
    EXPECT_EQ(a.taper_out_px, b.taper_out_px) << k;
    EXPECT_EQ(a.taper_min, b.taper_min) << k;
    EXPECT_EQ(a.depth_thickness, b.depth_thickness) << k;
    EXPECT_EQ(a.strength_thickness, b.strength_thickness) << k;
    EXPECT_EQ(a.curvature_thickness, b.curvature_thickness) << k;
    EXPECT_EQ(a.depth_opacity, b.depth_opacity) << k;
    EXPECT_EQ(a.strength_opacity, b.strength_opacity) << k;
    EXPECT_EQ(a.curvature_opacity, b.curvature_opacity) << k;
    EXPECT_EQ(a.dash_on, b.dash_on) << k;
    EXPECT_EQ(a.dash_off, b.dash_off) << k;
    EXPECT_EQ(a.jitter_px, b.jitter_px) << k;
    EXPECT_EQ(a.jitter_period_px, b.jitter_period_px) << k;
    EXPECT_EQ(a.seed, b.seed) << k;
    EXPECT_EQ(a.min_length_px, b.min_length_px) << k;
    EXPECT_EQ(a.brush_period_px, b.brush_period_px) << k;
    ASSERT_EQ(static_cast<bool>(a.brush), static_cast<bool>(b.brush)) << k;
    if (a.brush) {
      EXPECT_EQ(a.brush->rgba, b.brush->rgba) << k;
    }
    // Colours and widths are not the style file's: the scene's line-style keeps them.
    EXPECT_EQ(back.kinds[k].color, LineStyles().kinds[k].color) << k;
    EXPECT_EQ(back.kinds[k].width_px, LineStyles().kinds[k].width_px) << k;
  }
  EXPECT_TRUE(lines.kinds[1].stroke.brush);
  EXPECT_EQ(lines.kinds[2].stroke.brush->width, 50);  // resampled to the period
  StrokeStyle missing;
  missing.brush_path = (dir / "nope.png").string();
  const Status st = prepareBrush(missing);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.error().message.find("nope.png"), std::string::npos);
}

}  // namespace
}  // namespace lodline
