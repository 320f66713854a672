// Line charts as SVG: well-formed, one point per value, gaps, escaping, scales.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>

#include "export/chart.h"
#include "test_util.h"

namespace lodline {
namespace {

size_t countOf(const std::string& s, const std::string& what) {
  size_t n = 0;
  for (size_t pos = s.find(what); pos != std::string::npos; pos = s.find(what, pos + 1)) ++n;
  return n;
}

// Well-formedness: tags nest and close in order, attribute values are quoted, text has no
// raw '<' or '&' outside entities.
bool wellFormed(const std::string& s) {
  std::vector<std::string> stack;
  const std::regex tag(R"(<(/?)([A-Za-z?][A-Za-z0-9_:-]*)((?:\s+[A-Za-z_:][A-Za-z0-9_:.-]*="[^"<]*")*)\s*(/?\??)>)");
  size_t last = 0;
  for (auto it = std::sregex_iterator(s.begin(), s.end(), tag); it != std::sregex_iterator(); ++it) {
    const std::string between = s.substr(last, static_cast<size_t>(it->position()) - last);
    if (between.find('<') != std::string::npos) return false;  // a tag the regex did not accept
    for (size_t a = between.find('&'); a != std::string::npos; a = between.find('&', a + 1))
      if (!std::regex_search(between.substr(a), std::regex("^&(amp|lt|gt|quot|apos);"))) return false;
    last = static_cast<size_t>(it->position() + it->length());
    const std::string name = (*it)[2];
    if (name[0] == '?') continue;
    if ((*it)[4] == "/") continue;
    if ((*it)[1] == "/") {
      if (stack.empty() || stack.back() != name) return false;
      stack.pop_back();
    } else {
      stack.push_back(name);
    }
  }
  return stack.empty() && s.find('<', last) == std::string::npos;
}

std::vector<double> attributeValues(const std::string& s, const std::string& element, const std::string& attr) {
  std::vector<double> out;
  const std::regex re("<" + element + "[^>]*\\s" + attr + "=\"([-0-9.]+)\"");
  for (auto it = std::sregex_iterator(s.begin(), s.end(), re); it != std::sregex_iterator(); ++it)
    out.push_back(std::stod((*it)[1]));
  return out;
}

LineChart sample() {
  LineChart c;
  c.title = "bunny: active_faces against target-area";
  c.x_label = "target-area";
  c.y_label = "active_faces";
  c.x_ticks = {"4", "8", "16", "32"};
  c.x = {4, 8, 16, 32};
  c.x_scale = autoScale(c.x);
  c.series = {{"view.dist = 2.5", {4000, 2900, 1800, 1100}},
              {"view.dist = 5", {1800, 1100, std::numeric_limits<double>::quiet_NaN(), 300}},
              {"view.dist = 10", {560, 300, 140, 60}}};
  return c;
}

TEST(Chart, WellFormedWithOnePointPerValue) {
  const std::string svg = lineChartSvg(sample());
  EXPECT_TRUE(wellFormed(svg)) << svg;
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_EQ(countOf(svg, "<circle class=\"point\""), 11u);  // 12 values, one missing
  // The missing value breaks its line: the second series' line joins its first two values
  // only (the last one stands alone, a circle without a line).
  std::vector<size_t> points_per_line;
  const std::regex line("<polyline fill=\"none\" stroke-width=\"2\"[^>]* points=\"([^\"]*)\"");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), line); it != std::sregex_iterator(); ++it)
    points_per_line.push_back(countOf((*it)[1], ",") );
  EXPECT_EQ(points_per_line, (std::vector<size_t>{4, 2, 4}));
  EXPECT_EQ(countOf(svg, "<g class=\"legend\">"), 1u);
  for (const char* label : {"view.dist = 2.5", "view.dist = 10", "target-area (log scale)", "active_faces"})
    EXPECT_NE(svg.find(label), std::string::npos) << label;
  // Ticks at the x values, in order.
  for (const char* t : {">4<", ">8<", ">16<", ">32<"}) EXPECT_NE(svg.find(t), std::string::npos) << t;
}

TEST(Chart, LogScaleSpacesDoublingsEvenly) {
  const std::string svg = lineChartSvg(sample());
  const std::vector<double> cx = attributeValues(svg, "circle", "cx");
  ASSERT_GE(cx.size(), 4u);
  // First series: x = 4, 8, 16, 32 at equal steps on a log axis.
  EXPECT_NEAR(cx[1] - cx[0], cx[2] - cx[1], 0.02);
  EXPECT_NEAR(cx[2] - cx[1], cx[3] - cx[2], 0.02);
  EXPECT_GT(cx[1], cx[0]);
  // Larger values are higher up (smaller y).
  const std::vector<double> cy = attributeValues(svg, "circle", "cy");
  EXPECT_LT(cy[0], cy[1]);
  EXPECT_LT(cy[1], cy[2]);

  LineChart lin = sample();
  lin.x_scale = AxisScale::kLinear;
  const std::vector<double> lx = attributeValues(lineChartSvg(lin), "circle", "cx");
  EXPECT_NEAR((lx[2] - lx[1]) / (lx[1] - lx[0]), 2.0, 0.01);  // 8 -> 16 is twice 4 -> 8
}

TEST(Chart, AutoScale) {
  EXPECT_EQ(autoScale({4, 8, 16, 32}), AxisScale::kLog);
  EXPECT_EQ(autoScale({2.5, 5, 10, 20}), AxisScale::kLog);
  EXPECT_EQ(autoScale({1, 2, 3}), AxisScale::kLinear);
  EXPECT_EQ(autoScale({0, 10, 100}), AxisScale::kLinear);
  EXPECT_EQ(autoScale({}), AxisScale::kLinear);
}

TEST(Chart, CategoriesAndEscapedText) {
  LineChart c;
  c.title = "a <b> & \"c\"";
  c.x_label = "lod";
  c.y_label = "ms_total";
  c.x_ticks = {"pm", "cluster", "none"};
  c.series = {{"T < 8 & d > 2", {10, 20, 30}}};
  const std::string svg = lineChartSvg(c);
  EXPECT_TRUE(wellFormed(svg)) << svg;
  EXPECT_NE(svg.find("a &lt;b&gt; &amp; &quot;c&quot;"), std::string::npos);
  EXPECT_NE(svg.find("T &lt; 8 &amp; d &gt; 2"), std::string::npos);
  const std::vector<double> cx = attributeValues(svg, "circle", "cx");
  ASSERT_EQ(cx.size(), 3u);
  EXPECT_NEAR(cx[1] - cx[0], cx[2] - cx[1], 0.02);  // categories evenly spaced
}

TEST(Chart, NoDataStillDrawsAxes) {
  LineChart c;
  c.x_ticks = {"1", "2"};
  c.x = {1, 2};
  c.series = {{"", {std::nan(""), std::nan("")}}};
  const std::string svg = lineChartSvg(c);
  EXPECT_TRUE(wellFormed(svg));
  EXPECT_EQ(countOf(svg, "<circle"), 0u);
}

TEST(Chart, WrittenAtomicallyAndRenderable) {
  test::TempDir dir;
  const auto path = dir / "chart.svg";
  ASSERT_TRUE(writeLineChartSvg(path, sample()).ok());
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_EQ(ss.str(), lineChartSvg(sample()));
  EXPECT_FALSE(writeLineChartSvg("/nonexistent-dir/c.svg", sample()).ok());
  // A real SVG renderer accepts it (librsvg, installed by scripts/setup.sh).
  if (std::system("command -v rsvg-convert >/dev/null 2>&1") != 0) GTEST_SKIP() << "rsvg-convert not installed";
  EXPECT_EQ(std::system(("rsvg-convert " + path.string() + " -o " + (dir / "c.png").string()).c_str()), 0);
  EXPECT_TRUE(std::filesystem::exists(dir / "c.png"));
}

}  // namespace
}  // namespace lodline
