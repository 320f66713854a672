// Contact sheets: box-filter downscaling, grid layout, and where images and labels land.
#include <gtest/gtest.h>

#include <optional>

#include "export/contact_sheet.h"

namespace lodline {
namespace {

Image solid(int w, int h, Rgba8 c) {
  Image im(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) std::copy(c.begin(), c.end(), im.pixel(x, y));
  return im;
}

TEST(ResizeBox, AveragesTheCoveredArea) {
  // Vertical stripes one pixel wide, black and white: halving the width gives mid grey.
  Image stripes(8, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) {
      uint8_t* p = stripes.pixel(x, y);
      p[0] = p[1] = p[2] = x % 2 ? 255 : 0;
      p[3] = 255;
    }
  const Image half = resizeBox(stripes, 4, 2);
  ASSERT_EQ(half.width, 4);
  ASSERT_EQ(half.height, 2);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) {
      EXPECT_NEAR(half.pixel(x, y)[0], 127.5, 1.0);
      EXPECT_EQ(half.pixel(x, y)[3], 255);
    }
  // A non-integer factor (8 -> 3): each output pixel covers 8/3 inputs; the middle one covers
  // 1/3 of pixel 2 (black), all of 3 (white), all of 4 (black) and 1/3 of 5 (white).
  const Image third = resizeBox(stripes, 3, 4);
  EXPECT_NEAR(third.pixel(1, 0)[0], 255.0 * (1.0 + 1.0 / 3.0) / (8.0 / 3.0), 1.0);
}

TEST(ResizeBox, TransparentPixelsDoNotBleedTheirColour) {
  Image im(2, 1);
  const uint8_t a[4] = {255, 0, 0, 255}, b[4] = {0, 0, 255, 0};  // red, transparent "blue"
  std::copy(a, a + 4, im.pixel(0, 0));
  std::copy(b, b + 4, im.pixel(1, 0));
  const Image one = resizeBox(im, 1, 1);
  EXPECT_EQ(one.pixel(0, 0)[0], 255);
  EXPECT_EQ(one.pixel(0, 0)[2], 0);
  EXPECT_NEAR(one.pixel(0, 0)[3], 128, 1);
}

TEST(FitImage, KeepsTheAspectAndNeverEnlarges) {
  const Image wide = solid(400, 100, {0, 0, 0, 255});
  const Image fitted = fitImage(wide, 200, 200);
  EXPECT_EQ(fitted.width, 200);
  EXPECT_EQ(fitted.height, 50);
  const Image small = fitImage(solid(30, 20, {0, 0, 0, 255}), 200, 200);
  EXPECT_EQ(small.width, 30);
  EXPECT_EQ(small.height, 20);
}

class Sheet : public ::testing::Test {
 protected:
  void SetUp() override {
    auto f = Font::load(kDefaultFontPath);
    if (!f) GTEST_SKIP() << f.error().message << " (scripts/setup.sh installs fonts-dejavu-core)";
    font_.emplace(std::move(f.value()));
  }
  // 2 rows × 3 columns of solid renders (colour per cell), one cell failed.
  ContactSheet grid() const {
    ContactSheet s;
    s.title = {"bunny: rows T, columns distance"};
    s.rows = 2;
    s.columns = 3;
    s.row_axis = "target-area";
    s.column_axis = "view.dist";
    s.row_labels = {"4", "16"};
    s.column_labels = {"2.5", "5", "10"};
    for (int i = 0; i < 6; ++i) {
      ContactSheetCell c;
      if (i == 4) {
        c.note = "failed";
      } else {
        c.image = solid(160, 120, colours[i]);
      }
      c.caption = {"faces " + std::to_string(1000 * (i + 1))};
      s.cells.push_back(std::move(c));
    }
    return s;
  }
  static constexpr Rgba8 colours[6] = {Rgba8{255, 0, 0, 255}, Rgba8{0, 255, 0, 255}, Rgba8{0, 0, 255, 255},
                                       Rgba8{255, 255, 0, 255}, Rgba8{0, 0, 0, 0}, Rgba8{0, 255, 255, 255}};
  std::optional<Font> font_;
};

bool inside(const PixelRect& inner, int w, int h) {
  return inner.x >= 0 && inner.y >= 0 && inner.x + inner.width <= w && inner.y + inner.height <= h;
}
bool overlap(const PixelRect& a, const PixelRect& b) {
  return a.x < b.x + b.width && b.x < a.x + a.width && a.y < b.y + b.height && b.y < a.y + a.height;
}
int darkPixels(const Image& im, const PixelRect& r) {
  int n = 0;
  for (int y = r.y; y < r.y + r.height; ++y)
    for (int x = r.x; x < r.x + r.width; ++x) n += im.pixel(x, y)[0] < 128 && im.pixel(x, y)[1] < 128;
  return n;
}

TEST_F(Sheet, CellsFormAGridWithLabelsBesideThem) {
  ContactSheetParams p;
  p.cell_width = 80;
  const ContactSheet s = grid();
  const ContactSheetLayout l = layoutContactSheet(s, *font_, p);
  ASSERT_EQ(l.cells.size(), 6u);
  ASSERT_EQ(l.row_labels.size(), 2u);
  ASSERT_EQ(l.column_labels.size(), 3u);
  for (int i = 0; i < 6; ++i) {
    const PixelRect& c = l.cells[i];
    EXPECT_EQ(c.width, 80);
    EXPECT_EQ(c.height, 60);  // the images' 4:3 aspect
    EXPECT_TRUE(inside(c, l.width, l.height));
    const int r = i / 3, col = i % 3;
    EXPECT_EQ(c.x, l.cells[col].x) << "columns line up";
    EXPECT_EQ(c.y, l.cells[3 * r].y) << "rows line up";
    if (col > 0) {
      EXPECT_EQ(c.x, l.cells[i - 1].x + 80 + p.gap);
    }
    if (r > 0) {
      EXPECT_GT(c.y, l.cells[i - 3].y + 60) << "room for the caption";
    }
    for (int j = 0; j < i; ++j) EXPECT_FALSE(overlap(c, l.cells[j]));
    // The image fills the cell (same aspect), the caption sits under it.
    EXPECT_EQ(l.images[i].width, i == 4 ? 0 : 80);
    EXPECT_EQ(l.captions[i].y, c.y + c.height);
  }
  for (int col = 0; col < 3; ++col) {
    const PixelRect& t = l.column_labels[col];
    const int centre = t.x + t.width / 2;
    EXPECT_NEAR(centre, l.cells[col].x + 40, 2) << "column label centred over its column";
    EXPECT_LT(t.y + t.height, l.cells[0].y + 1) << "above the grid";
  }
  for (int r = 0; r < 2; ++r) {
    const PixelRect& t = l.row_labels[r];
    EXPECT_LT(t.x + t.width, l.cells[0].x) << "left of the grid";
    EXPECT_GE(t.y, l.cells[3 * r].y);
    EXPECT_LE(t.y + t.height, l.cells[3 * r].y + 60);
  }
  EXPECT_LT(l.column_axis.y + l.column_axis.height, l.column_labels[0].y + 1);
  EXPECT_LT(l.row_axis.x + l.row_axis.width, l.cells[0].x);
  ASSERT_EQ(l.title.size(), 1u);
  EXPECT_LT(l.title[0].y + l.title[0].height, l.column_axis.y);
  for (const auto* group : {&l.row_labels, &l.column_labels, &l.title})
    for (const auto& t : *group) EXPECT_TRUE(inside(t, l.width, l.height));
}

TEST_F(Sheet, ImagesAndLabelsAreDrawnWhereTheLayoutSays) {
  ContactSheetParams p;
  p.cell_width = 80;
  const ContactSheet s = grid();
  ContactSheetLayout l;
  const Image im = drawContactSheet(s, *font_, p, &l);
  ASSERT_EQ(im.width, l.width);
  ASSERT_EQ(im.height, l.height);
  for (int i = 0; i < 6; ++i) {
    const PixelRect& c = l.cells[i];
    const uint8_t* centre = im.pixel(c.x + c.width / 2, c.y + c.height / 2);
    if (i == 4) {
      // The failed cell: grey fill and its note in the note colour.
      EXPECT_EQ(centre[3], 255);
      int notes = 0;
      for (int y = c.y; y < c.y + c.height; ++y)
        for (int x = c.x; x < c.x + c.width; ++x) notes += im.pixel(x, y)[0] > 120 && im.pixel(x, y)[1] < 90;
      EXPECT_GT(notes, 10);
      EXPECT_EQ(im.pixel(c.x + 2, c.y + 2)[0], p.empty_cell[0]);
      continue;
    }
    for (int k = 0; k < 3; ++k) EXPECT_EQ(centre[k], colours[i][k]) << "cell " << i;
    // Captions are drawn in text colour under the cell.
    EXPECT_GT(darkPixels(im, l.captions[i]), 10) << "caption of cell " << i;
  }
  for (const auto& t : l.column_labels) EXPECT_GT(darkPixels(im, t), 5);
  for (const auto& t : l.row_labels) EXPECT_GT(darkPixels(im, t), 5);
  EXPECT_GT(darkPixels(im, l.title[0]), 50);
  EXPECT_GT(darkPixels(im, l.row_axis), 20);
  EXPECT_GT(darkPixels(im, l.column_axis), 20);
  // The gap between two cells (outside their 1-px frames) is the page background.
  const PixelRect& a = l.cells[0];
  const uint8_t* gap = im.pixel(a.x + a.width + p.gap / 2, a.y + a.height / 2);
  EXPECT_EQ(gap[0], 255);
  EXPECT_EQ(gap[1], 255);
}

TEST_F(Sheet, WideRendersAreFittedAndCentredInTheirCell) {
  ContactSheet s;
  s.rows = 1;
  s.columns = 2;
  s.cells.resize(2);
  s.cells[0].image = solid(200, 150, {255, 0, 0, 255});
  s.cells[1].image = solid(400, 100, {0, 0, 255, 255});  // another size: letterboxed
  ContactSheetParams p;
  p.cell_width = 100;
  ContactSheetLayout l;
  const Image im = drawContactSheet(s, *font_, p, &l);
  EXPECT_EQ(l.cells[1].height, 75);
  EXPECT_EQ(l.images[1].width, 100);
  EXPECT_EQ(l.images[1].height, 25);
  EXPECT_EQ(l.images[1].y, l.cells[1].y + 25);
  EXPECT_EQ(im.pixel(l.cells[1].x + 50, l.cells[1].y + 5)[2], 255);  // above the image: background (white)
  EXPECT_EQ(im.pixel(l.cells[1].x + 50, l.cells[1].y + 5)[0], 255);
  EXPECT_EQ(im.pixel(l.cells[1].x + 50, l.cells[1].y + 37)[0], 0);   // the image: blue
  EXPECT_TRUE(l.row_labels.empty());
  EXPECT_EQ(l.row_axis.width, 0);
}

}  // namespace
}  // namespace lodline
