#include "export/contact_sheet.h"

#include <algorithm>
#include <cmath>

namespace lodline {
namespace {

// Box-filter weights of one axis: output pixel i covers input [i·s, (i+1)·s), s = in/out;
// each input pixel j it touches weighs |[j, j+1) ∩ that interval| / s.
struct AxisWeights {
  std::vector<int> first;      // first input pixel of each output pixel
  std::vector<int> count;      // input pixels it covers
  std::vector<float> weights;  // concatenated, count[i] per output pixel
  std::vector<size_t> offset;  // start of output pixel i's weights
};

AxisWeights boxWeights(int in, int out) {
  AxisWeights w;
  const double s = static_cast<double>(in) / static_cast<double>(out);
  for (int i = 0; i < out; ++i) {
    const double a = i * s, b = (i + 1) * s;
    const int j0 = std::clamp(static_cast<int>(std::floor(a)), 0, in - 1);
    const int j1 = std::clamp(static_cast<int>(std::ceil(b)) - 1, j0, in - 1);
    w.first.push_back(j0);
    w.count.push_back(j1 - j0 + 1);
    w.offset.push_back(w.weights.size());
    double total = 0.0;
    const size_t start = w.weights.size();
    for (int j = j0; j <= j1; ++j) {
      const double overlap = std::max(0.0, std::min<double>(j + 1, b) - std::max<double>(j, a));
      w.weights.push_back(static_cast<float>(overlap));
      total += overlap;
    }
    for (size_t k = start; k < w.weights.size(); ++k)
      w.weights[k] = total > 0.0 ? static_cast<float>(w.weights[k] / total) : 0.0f;
  }
  return w;
}

int lineHeight(const Font& font, float px) { return static_cast<int>(std::ceil(font.ascent(px) + font.descent(px))); }

// `text`, shortened with a trailing ellipsis to at most `max_width` px (unchanged if it fits).
std::string ellipsize(const Font& font, const std::string& text, float px, int max_width) {
  if (font.measure(text, px) <= static_cast<float>(max_width)) return text;
  std::string s = text;
  while (!s.empty()) {
    // Drop one whole UTF-8 code point (its continuation bytes are 10xxxxxx).
    do s.pop_back();
    while (!s.empty() && (static_cast<uint8_t>(s.back()) & 0xc0) == 0x80);
    if (font.measure(s + "\u2026", px) <= static_cast<float>(max_width)) return s + "\u2026";
  }
  return s;
}

PixelRect textRect(const Font& font, const std::string& text, float px, int x, int y) {
  return {x, y, static_cast<int>(std::ceil(font.measure(text, px))), lineHeight(font, px)};
}

void drawText(Image& image, const Font& font, const PixelRect& r, const std::string& text, float px, Rgba8 colour) {
  font.draw(image, static_cast<float>(r.x), static_cast<float>(r.y) + font.ascent(px), text, px, colour);
}

void fill(Image& image, const PixelRect& r, Rgba8 colour) {
  for (int y = std::max(0, r.y); y < std::min(image.height, r.y + r.height); ++y)
    for (int x = std::max(0, r.x); x < std::min(image.width, r.x + r.width); ++x)
      std::copy(colour.begin(), colour.end(), image.pixel(x, y));
}

// Size of `w`×`h` scaled down to fit `max_w`×`max_h` with its aspect kept (never up).
std::pair<int, int> fittedSize(int w, int h, int max_w, int max_h) {
  const double s = std::min({1.0, static_cast<double>(max_w) / w, static_cast<double>(max_h) / h});
  return {std::max(1, static_cast<int>(std::lround(w * s))), std::max(1, static_cast<int>(std::lround(h * s)))};
}

}  // namespace

Image resizeBox(const Image& image, int width, int height) {
  const AxisWeights wx = boxWeights(image.width, width), wy = boxWeights(image.height, height);
  // Premultiplied alpha, so transparent pixels do not bleed their colour into the average.
  std::vector<float> rows(static_cast<size_t>(width) * image.height * 4);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < width; ++x) {
      float acc[4] = {0, 0, 0, 0};
      for (int k = 0; k < wx.count[x]; ++k) {
        const uint8_t* p = image.pixel(wx.first[x] + k, y);
        const float w = wx.weights[wx.offset[x] + k], a = static_cast<float>(p[3]) / 255.0f;
        for (int c = 0; c < 3; ++c) acc[c] += w * a * static_cast<float>(p[c]);
        acc[3] += w * static_cast<float>(p[3]);
      }
      std::copy(acc, acc + 4, &rows[(static_cast<size_t>(y) * width + x) * 4]);
    }
  Image out(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float acc[4] = {0, 0, 0, 0};
      for (int k = 0; k < wy.count[y]; ++k) {
        const float* p = &rows[(static_cast<size_t>(wy.first[y] + k) * width + x) * 4];
        const float w = wy.weights[wy.offset[y] + k];
        for (int c = 0; c < 4; ++c) acc[c] += w * p[c];
      }
      uint8_t* q = out.pixel(x, y);
      const float a = acc[3] / 255.0f;
      for (int c = 0; c < 3; ++c)
        q[c] = a > 0.0f ? static_cast<uint8_t>(std::clamp(std::lround(acc[c] / a), 0l, 255l)) : 0;
      q[3] = static_cast<uint8_t>(std::clamp(std::lround(acc[3]), 0l, 255l));
    }
  return out;
}

Image fitImage(const Image& image, int max_width, int max_height) {
  const auto [w, h] = fittedSize(image.width, image.height, max_width, max_height);
  if (w == image.width && h == image.height) return image;
  return resizeBox(image, w, h);
}

ContactSheetLayout layoutContactSheet(const ContactSheet& sheet, const Font& font, const ContactSheetParams& p) {
  ContactSheetLayout l;
  const int cell_w = std::max(1, p.cell_width);
  int cell_h = p.cell_height;
  if (cell_h <= 0) {
    cell_h = cell_w * 3 / 4;
    for (const auto& c : sheet.cells)
      if (c.image.width > 0 && c.image.height > 0) {
        cell_h = std::max(1, static_cast<int>(std::lround(static_cast<double>(cell_w) * c.image.height / c.image.width)));
        break;
      }
  }
  size_t caption_lines = 0;
  for (const auto& c : sheet.cells) caption_lines = std::max(caption_lines, c.caption.size());
  const int caption_lh = lineHeight(font, p.caption_px), label_lh = lineHeight(font, p.label_px);
  const int caption_h = caption_lines ? static_cast<int>(caption_lines) * caption_lh + p.gap / 2 : 0;

  // Width of the row-label column (right-aligned labels, the axis name on top).
  int label_col = 0;
  if (!sheet.row_labels.empty()) {
    float w = font.measure(sheet.row_axis, p.label_px);
    for (const auto& s : sheet.row_labels) w = std::max(w, font.measure(s, p.label_px));
    label_col = static_cast<int>(std::ceil(w)) + p.gap;
  }
  const int grid_x = p.margin + label_col;
  const int grid_w = sheet.columns * cell_w + std::max(0, sheet.columns - 1) * p.gap;
  int width = grid_x + grid_w + p.margin;

  int y = p.margin;
  for (const auto& line : sheet.title) {
    l.title.push_back(textRect(font, line, p.title_px, p.margin, y));
    width = std::max(width, 2 * p.margin + l.title.back().width);
    y += lineHeight(font, p.title_px) + 2;
  }
  if (!sheet.title.empty()) y += p.gap;
  const bool column_header = !sheet.column_labels.empty();
  if (column_header && !sheet.column_axis.empty()) {
    l.column_axis = textRect(font, sheet.column_axis, p.label_px, 0, y);
    l.column_axis.x = grid_x + (grid_w - l.column_axis.width) / 2;
    y += label_lh + p.gap / 2;
  }
  // The line just above the grid: column values, and the row axis name over its labels.
  const bool header_line = column_header || (!sheet.row_labels.empty() && !sheet.row_axis.empty());
  if (!sheet.row_labels.empty() && !sheet.row_axis.empty()) {
    l.row_axis = textRect(font, sheet.row_axis, p.label_px, 0, y);
    l.row_axis.x = grid_x - p.gap - l.row_axis.width;
  }
  for (int c = 0; c < static_cast<int>(sheet.column_labels.size()); ++c) {
    PixelRect r = textRect(font, ellipsize(font, sheet.column_labels[c], p.label_px, cell_w), p.label_px, 0, y);
    r.x = grid_x + c * (cell_w + p.gap) + (cell_w - r.width) / 2;
    l.column_labels.push_back(r);
  }
  if (header_line) y += label_lh + p.gap / 2;

  const int grid_y = y;
  const int pitch_y = cell_h + caption_h + p.gap;
  for (int r = 0; r < static_cast<int>(sheet.row_labels.size()); ++r) {
    PixelRect t = textRect(font, sheet.row_labels[r], p.label_px, 0, 0);
    t.x = grid_x - p.gap - t.width;
    t.y = grid_y + r * pitch_y + (cell_h - t.height) / 2;
    l.row_labels.push_back(t);
  }
  const size_t n = static_cast<size_t>(sheet.rows) * static_cast<size_t>(sheet.columns);
  for (size_t i = 0; i < n; ++i) {
    const int r = static_cast<int>(i) / sheet.columns, c = static_cast<int>(i) % sheet.columns;
    const PixelRect cell{grid_x + c * (cell_w + p.gap), grid_y + r * pitch_y, cell_w, cell_h};
    l.cells.push_back(cell);
    l.captions.push_back({cell.x, cell.y + cell_h, cell_w, caption_h});
    PixelRect img;
    if (i < sheet.cells.size() && sheet.cells[i].image.width > 0 && sheet.cells[i].image.height > 0) {
      const auto [w, h] = fittedSize(sheet.cells[i].image.width, sheet.cells[i].image.height, cell_w, cell_h);
      img = {cell.x + (cell_w - w) / 2, cell.y + (cell_h - h) / 2, w, h};
    }
    l.images.push_back(img);
  }
  l.width = width;
  l.height = grid_y + sheet.rows * pitch_y - (sheet.rows > 0 ? p.gap : 0) + p.margin;
  return l;
}

Image drawContactSheet(const ContactSheet& sheet, const Font& font, const ContactSheetParams& p,
                       ContactSheetLayout* layout_out) {
  const ContactSheetLayout l = layoutContactSheet(sheet, font, p);
  Image out(std::max(1, l.width), std::max(1, l.height));
  fill(out, {0, 0, out.width, out.height}, p.background);
  for (size_t i = 0; i < sheet.title.size(); ++i) drawText(out, font, l.title[i], sheet.title[i], p.title_px, p.text);
  if (l.column_axis.width > 0) drawText(out, font, l.column_axis, sheet.column_axis, p.label_px, p.text);
  if (l.row_axis.width > 0) drawText(out, font, l.row_axis, sheet.row_axis, p.label_px, p.text);
  for (size_t i = 0; i < l.column_labels.size(); ++i)
    drawText(out, font, l.column_labels[i], ellipsize(font, sheet.column_labels[i], p.label_px, p.cell_width),
             p.label_px, p.text);
  for (size_t i = 0; i < l.row_labels.size(); ++i)
    drawText(out, font, l.row_labels[i], sheet.row_labels[i], p.label_px, p.text);

  for (size_t i = 0; i < l.cells.size(); ++i) {
    const PixelRect& cell = l.cells[i];
    fill(out, {cell.x - 1, cell.y - 1, cell.width + 2, cell.height + 2}, p.frame);
    fill(out, cell, p.background);
    const ContactSheetCell* c = i < sheet.cells.size() ? &sheet.cells[i] : nullptr;
    const PixelRect& img = l.images[i];
    if (c && img.width > 0) {
      const Image fitted = fitImage(c->image, img.width, img.height);
      for (int y = 0; y < fitted.height; ++y)
        for (int x = 0; x < fitted.width; ++x) {
          const uint8_t* s = fitted.pixel(x, y);
          uint8_t* d = out.pixel(img.x + x, img.y + y);
          const float a = static_cast<float>(s[3]) / 255.0f;
          for (int k = 0; k < 3; ++k)
            d[k] = static_cast<uint8_t>(std::lround(static_cast<float>(s[k]) * a + static_cast<float>(d[k]) * (1.0f - a)));
          d[3] = 255;
        }
    } else {
      fill(out, cell, p.empty_cell);
      if (c && !c->note.empty()) {
        PixelRect t = textRect(font, c->note, p.label_px, 0, 0);
        t.x = cell.x + (cell.width - t.width) / 2;
        t.y = cell.y + (cell.height - t.height) / 2;
        drawText(out, font, t, c->note, p.label_px, p.note);
      }
    }
    if (c) {
      const int lh = lineHeight(font, p.caption_px);
      for (size_t k = 0; k < c->caption.size(); ++k) {
        const std::string line = ellipsize(font, c->caption[k], p.caption_px, cell.width);
        PixelRect t = textRect(font, line, p.caption_px, 0, 0);
        t.x = cell.x + (cell.width - t.width) / 2;
        t.y = l.captions[i].y + p.gap / 4 + static_cast<int>(k) * lh;
        drawText(out, font, t, line, p.caption_px, p.text);
      }
    }
  }
  if (layout_out) *layout_out = l;
  return out;
}

}  // namespace lodline
