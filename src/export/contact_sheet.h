// Contact sheets: a grid of downscaled renders with the varied parameter values as row and
// column labels and a title, for comparing the runs of a parameter sweep (`lodline sweep`,
// docs/experiments.md) at a glance.
#pragma once

#include <string>
#include <vector>

#include "export/text.h"
#include "io/image.h"

namespace lodline {

/// Resizes `image` to `width`×`height` with a box filter (each output pixel is the
/// area-weighted mean of the input pixels it covers), averaging premultiplied alpha in sRGB
/// values, which keeps thin dark lines visible. Both sizes > 0.
Image resizeBox(const Image& image, int width, int height);

/// `image` scaled down by resizeBox() to fit in `max_width`×`max_height` with its aspect
/// kept (at least 1 px each way); an image that fits already is returned unchanged.
Image fitImage(const Image& image, int max_width, int max_height);

struct ContactSheetParams {
  int cell_width = 256;        ///< px, width of a cell's image area; renders are fitted into it
  int cell_height = 0;         ///< px; 0 = cell_width × the aspect of the first cell's image (3:4 without one)
  int gap = 8;                 ///< px between cells and between a label and what it labels
  int margin = 16;             ///< px around everything
  float title_px = 20.0f;      ///< text height (ascender to descender) of the title lines
  float label_px = 15.0f;      ///< text height of axis names and values
  float caption_px = 13.0f;    ///< text height of per-cell captions
  Rgba8 background{255, 255, 255, 255};
  Rgba8 frame{200, 200, 200, 255};            ///< 1-px frame around every cell
  Rgba8 empty_cell{232, 232, 232, 255};       ///< fill of a cell without an image
  Rgba8 text{0, 0, 0, 255};
  Rgba8 note{176, 0, 0, 255};                 ///< colour of an empty cell's note ("failed")
};

struct ContactSheetCell {
  Image image;                       ///< the render (any size; fitted into the cell); empty = none
  std::vector<std::string> caption;  ///< lines under the image (e.g. the run's values or stats)
  std::string note;                  ///< centred in a cell without an image, e.g. "failed"
};

/// A `rows`×`columns` grid. Row labels go left of the rows, column labels above the columns,
/// each axis name above its labels; empty label lists leave that header out (a sheet of
/// paired runs labels its cells with captions instead).
struct ContactSheet {
  std::vector<std::string> title;          ///< lines at the top
  int rows = 0;
  int columns = 0;
  std::string row_axis;                    ///< name of the row parameter ("" = none)
  std::string column_axis;                 ///< name of the column parameter ("" = none)
  std::vector<std::string> row_labels;     ///< `rows` entries, or empty
  std::vector<std::string> column_labels;  ///< `columns` entries, or empty
  std::vector<ContactSheetCell> cells;     ///< rows·columns, row-major (missing ones are empty)
};

struct PixelRect {
  int x = 0, y = 0, width = 0, height = 0;  ///< top-left corner and size, px (y down)
  bool contains(int px, int py) const { return px >= x && py >= y && px < x + width && py < y + height; }
};

/// Where everything of a sheet goes. Text rectangles span the text's advance width and
/// its ascender-to-descender height.
struct ContactSheetLayout {
  int width = 0, height = 0;
  std::vector<PixelRect> title;          ///< one per title line
  PixelRect row_axis, column_axis;       ///< axis names (zero size when absent)
  std::vector<PixelRect> row_labels;     ///< one per row label
  std::vector<PixelRect> column_labels;  ///< one per column label
  std::vector<PixelRect> cells;          ///< image area of every cell, row-major
  std::vector<PixelRect> images;         ///< the fitted image inside each cell (zero size when none)
  std::vector<PixelRect> captions;       ///< caption area under each cell
};

/// Computes the layout of `sheet` (no drawing).
ContactSheetLayout layoutContactSheet(const ContactSheet& sheet, const Font& font, const ContactSheetParams& params);

/// Draws `sheet` into a new opaque image; `layout` (optional) receives where things went.
Image drawContactSheet(const ContactSheet& sheet, const Font& font, const ContactSheetParams& params,
                       ContactSheetLayout* layout = nullptr);

}  // namespace lodline
