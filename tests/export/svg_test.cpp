// SVG export: structure of the written file (parsed back), styles, atomic failure.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "export/svg.h"
#include "test_util.h"

namespace lodline {
namespace {

std::string readFile(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

size_t countOf(const std::string& s, const std::string& what) {
  size_t n = 0;
  for (size_t pos = s.find(what); pos != std::string::npos; pos = s.find(what, pos + 1)) ++n;
  return n;
}

// Minimal well-formedness check: every tag opened is closed in order (no attributes with
// '<' or '>' inside, which the writer never produces).
bool tagsBalanced(const std::string& s) {
  std::vector<std::string> stack;
  const std::regex tag(R"(<(/?)([A-Za-z?][A-Za-z0-9_:-]*)[^>]*?(/?)>)");
  for (auto it = std::sregex_iterator(s.begin(), s.end(), tag); it != std::sregex_iterator(); ++it) {
    const std::string name = (*it)[2];
    if (name[0] == '?') continue;  // XML declaration
    if ((*it)[3] == "/") continue;   // self-closing
    if ((*it)[1] == "/") {
      if (stack.empty() || stack.back() != name) return false;
      stack.pop_back();
    } else {
      stack.push_back(name);
    }
  }
  return stack.empty();
}

TEST(Svg, WritesOnePathPerStrokeWithViewBox) {
  test::TempDir dir;
  const auto path = dir / "drawing.svg";
  const std::vector<glm::vec2> points = {{10, 10}, {20, 15}, {30, 10},  // contour
                                         {5, 5},   {6, 6},               // crease
                                         {1, 1},                         // 1 point: skipped
                                         {40, 40}, {50, 45}, {60, 40}, {40, 40}};  // closed suggestive
  const std::vector<uint32_t> offsets = {0, 3, 5, 6, 10};
  const std::vector<LineKind> kinds = {LineKind::kContour, LineKind::kCrease,
                                       LineKind::kBoundary, LineKind::kSuggestive};
  const std::vector<float> opacity = {1.0f, 1.0f, 1.0f, 0.25f};
  SvgStrokes strokes{points, offsets, kinds, opacity};
  const Status s = writeSvg(path, 640, 480, strokes);
  ASSERT_TRUE(s.ok()) << s.error().message;
  const std::string svg = readFile(path);
  EXPECT_TRUE(tagsBalanced(svg)) << svg;
  EXPECT_NE(svg.find("viewBox=\"0 0 640 480\""), std::string::npos);
  EXPECT_NE(svg.find("width=\"640\" height=\"480\""), std::string::npos);
  EXPECT_EQ(countOf(svg, "<path"), 3u);
  EXPECT_EQ(countOf(svg, "<polyline"), 0u);
  EXPECT_EQ(countOf(svg, "<rect"), 1u);  // background
  // The contour's path: its corner kept, its two straight pieces written as lines.
  EXPECT_NE(svg.find("d=\"M10.00,10.00L20.00,15.00L30.00,10.00\""), std::string::npos) << svg;
  EXPECT_NE(svg.find("class=\"suggestive\""), std::string::npos);
  EXPECT_NE(svg.find("stroke-opacity=\"0.250\""), std::string::npos);
  EXPECT_EQ(svg.find("class=\"boundary\""), std::string::npos);  // its only stroke had 1 point
  // No temporary files left beside it.
  size_t files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 1u);
  // With curves off, the stroke's points as they are.
  SvgStyle plain;
  plain.curves = false;
  ASSERT_TRUE(writeSvg(path, 640, 480, strokes, plain).ok());
  const std::string poly = readFile(path);
  EXPECT_EQ(countOf(poly, "<polyline"), 3u);
  EXPECT_NE(poly.find("points=\"10.00,10.00 20.00,15.00 30.00,10.00\""), std::string::npos);
}

TEST(Svg, StyleAndNoBackground) {
  test::TempDir dir;
  const auto path = dir / "styled.svg";
  const std::vector<glm::vec2> points = {{0, 0}, {1, 1}};
  const std::vector<uint32_t> offsets = {0, 2};
  const std::vector<LineKind> kinds = {LineKind::kContour};
  SvgStyle style;
  style.background = false;
  style.lines[0].colour = "#ff0000\"><script>";  // hostile: sanitised
  style.lines[0].width = 3.0f;
  ASSERT_TRUE(writeSvg(path, 10, 10, SvgStrokes{points, offsets, kinds, {}}, style).ok());
  const std::string svg = readFile(path);
  EXPECT_TRUE(tagsBalanced(svg));
  EXPECT_EQ(countOf(svg, "<rect"), 0u);
  EXPECT_EQ(svg.find("<script"), std::string::npos);
  EXPECT_NE(svg.find("stroke-width=\"3.000\""), std::string::npos);
  // An empty drawing is still a valid document.
  ASSERT_TRUE(writeSvg(path, 10, 10, SvgStrokes{}).ok());
  const std::string empty = readFile(path);
  EXPECT_TRUE(tagsBalanced(empty));
  EXPECT_EQ(countOf(empty, "<polyline"), 0u);
}

TEST(Svg, ErrorsNameTheFileAndLeaveNothing) {
  test::TempDir dir;
  const auto missing_dir = dir / "no_such_dir" / "out.svg";
  const std::vector<glm::vec2> points = {{0, 0}, {1, 1}};
  const std::vector<uint32_t> offsets = {0, 2};
  const std::vector<LineKind> kinds = {LineKind::kContour};
  const SvgStrokes strokes{points, offsets, kinds, {}};
  Status s = writeSvg(missing_dir, 100, 100, strokes);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("out.svg"), std::string::npos) << s.error().message;
  EXPECT_FALSE(std::filesystem::exists(missing_dir));
  // Bad size and inconsistent arrays are errors too, and write nothing.
  const auto path = dir / "bad.svg";
  s = writeSvg(path, 0, 100, strokes);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("bad.svg"), std::string::npos);
  const std::vector<uint32_t> bad_offsets = {0, 7};
  s = writeSvg(path, 100, 100, SvgStrokes{points, bad_offsets, kinds, {}});
  EXPECT_FALSE(s.ok());
  EXPECT_FALSE(std::filesystem::exists(path));
  // A directory in the way of the target.
  std::filesystem::create_directory(dir / "taken.svg");
  s = writeSvg(dir / "taken.svg", 100, 100, strokes);
  EXPECT_FALSE(s.ok());
  size_t files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 1u);  // only the directory we made
}

}  // namespace
}  // namespace lodline
