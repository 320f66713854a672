// Text rendering with stb_truetype: loading errors, metrics, where glyph pixels land, UTF-8.
#include <gtest/gtest.h>

#include <fstream>

#include "export/text.h"
#include "test_util.h"

namespace lodline {
namespace {

class Text : public ::testing::Test {
 protected:
  void SetUp() override {
    auto f = Font::load(kDefaultFontPath);
    if (!f) GTEST_SKIP() << f.error().message << " (scripts/setup.sh installs fonts-dejavu-core)";
    font_.emplace(std::move(f.value()));
  }
  std::optional<Font> font_;
};

// Bounding box of the pixels darker than the white page.
struct Ink {
  int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1, count = 0;
};
Ink inkOf(const Image& im) {
  Ink ink;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x)
      if (im.pixel(x, y)[0] < 160) {
        ink.x0 = std::min(ink.x0, x);
        ink.y0 = std::min(ink.y0, y);
        ink.x1 = std::max(ink.x1, x);
        ink.y1 = std::max(ink.y1, y);
        ++ink.count;
      }
  return ink;
}

Image white(int w, int h) {
  Image im(w, h);
  std::fill(im.rgba.begin(), im.rgba.end(), uint8_t{255});
  return im;
}

TEST(TextFont, MissingOrInvalidFileIsAnErrorNamingIt) {
  auto missing = Font::load("/nonexistent/font.ttf");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find("/nonexistent/font.ttf"), std::string::npos);
  test::TempDir dir;
  std::ofstream(dir / "fake.ttf") << "this is not a font, just some text long enough";
  auto fake = Font::load(dir / "fake.ttf");
  ASSERT_FALSE(fake.ok());
  EXPECT_NE(fake.error().message.find("not a TrueType font"), std::string::npos) << fake.error().message;
}

TEST_F(Text, MetricsScaleWithSize) {
  EXPECT_EQ(font_->measure("", 20.0f), 0.0f);
  EXPECT_LT(font_->measure("iii", 20.0f), font_->measure("WWW", 20.0f));
  const float w20 = font_->measure("target-area", 20.0f), w40 = font_->measure("target-area", 40.0f);
  EXPECT_GT(w20, 40.0f);
  EXPECT_NEAR(w40 / w20, 2.0f, 0.01f);
  // Ascender + descender = the pixel height.
  EXPECT_NEAR(font_->ascent(20.0f) + font_->descent(20.0f), 20.0f, 0.01f);
  EXPECT_GT(font_->descent(20.0f), 0.0f);
}

TEST_F(Text, GlyphsLandBetweenPenAndAdvanceAboveTheBaseline) {
  Image im = white(200, 60);
  const float px = 24.0f, x = 20.0f, baseline = 40.0f;
  font_->draw(im, x, baseline, "HIH", px, {0, 0, 0, 255});
  const Ink ink = inkOf(im);
  ASSERT_GT(ink.count, 50);
  const float width = font_->measure("HIH", px);
  EXPECT_GE(ink.x0, static_cast<int>(x));
  EXPECT_LE(ink.x1, static_cast<int>(x + width) + 1);
  EXPECT_GT(ink.x1, static_cast<int>(x + 0.8f * width));
  // Capitals sit on the baseline and reach most of the ascender.
  EXPECT_LE(ink.y1, static_cast<int>(baseline));
  EXPECT_GE(ink.y1, static_cast<int>(baseline) - 2);
  EXPECT_LE(ink.y0, static_cast<int>(baseline - 0.6f * font_->ascent(px)));
  EXPECT_GE(ink.y0, static_cast<int>(baseline - font_->ascent(px)) - 1);
  // Colour and alpha: red text is red; a transparent colour draws nothing.
  Image red = white(200, 60);
  font_->draw(red, x, baseline, "HIH", px, {255, 0, 0, 255});
  int reds = 0;
  for (int y = 0; y < red.height; ++y)
    for (int xx = 0; xx < red.width; ++xx) reds += red.pixel(xx, y)[0] > 200 && red.pixel(xx, y)[1] < 60;
  EXPECT_GT(reds, 50);
  Image none = white(200, 60);
  font_->draw(none, x, baseline, "HIH", px, {0, 0, 0, 0});
  EXPECT_EQ(inkOf(none).count, 0);
}

TEST_F(Text, ClipsAtTheImageEdges) {
  Image im = white(30, 20);
  font_->draw(im, -15.0f, 10.0f, "Wide text past both edges", 30.0f, {0, 0, 0, 255});
  font_->draw(im, 10.0f, 60.0f, "below", 30.0f, {0, 0, 0, 255});
  EXPECT_GT(inkOf(im).count, 0);
}

TEST(TextUtf8, DecodesAndSkipsInvalidBytes) {
  const std::string s = "a\xc2\xb2\xe2\x82\xac\xf0\x9f\x98\x80";  // a ² € 😀
  size_t pos = 0;
  EXPECT_EQ(nextCodepoint(s, pos), 'a');
  EXPECT_EQ(nextCodepoint(s, pos), 0xb2);
  EXPECT_EQ(nextCodepoint(s, pos), 0x20ac);
  EXPECT_EQ(nextCodepoint(s, pos), 0x1f600);
  EXPECT_EQ(pos, s.size());
  for (const std::string bad : {"\xff", "\xc2", "\xc0\xaf", "\xed\xa0\x80", "\xe2\x28\xa1"}) {
    size_t p = 0;
    EXPECT_EQ(nextCodepoint(bad, p), -1) << bad.size();
    EXPECT_EQ(p, 1u);
  }
}

}  // namespace
}  // namespace lodline
