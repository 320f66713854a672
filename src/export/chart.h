// Line charts as SVG (plain text, viewable in any browser): one or more series of values
// against a shared x axis, with axis labels, ticks, grid lines and a legend. Used by
// `lodline sweep --chart COLUMN` to plot a result column against a varied parameter.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/result.h"

namespace lodline {

enum class AxisScale { kLinear, kLog };

struct ChartSeries {
  std::string label;      ///< legend text
  std::vector<double> y;  ///< one value per x position; NaN = missing (the line breaks there)
};

struct LineChart {
  std::string title;
  std::string x_label;
  std::string y_label;
  std::vector<std::string> x_ticks;  ///< label of each x position, as the user wrote it
  /// Numeric x of each position (same count as x_ticks), or empty for categories spaced
  /// evenly in their given order.
  std::vector<double> x;
  AxisScale x_scale = AxisScale::kLinear;  ///< kLog needs every x > 0
  std::vector<ChartSeries> series;
};

struct ChartParams {
  int width = 720;         ///< px (SVG user units)
  int height = 420;        ///< px
  float font_px = 13.0f;   ///< tick labels and legend; title and axis labels are a little larger
};

/// The log scale suits x values that are all positive and span a factor of 8 or more
/// (T = 4, 8, 16, 32 or distances 2.5 ... 20); otherwise linear.
AxisScale autoScale(const std::vector<double>& x);

/// The chart as a standalone SVG document. Every finite value is drawn as a
/// `<circle class="point">` joined to its neighbours by `<polyline>`s.
std::string lineChartSvg(const LineChart& chart, const ChartParams& params = {});

/// Writes lineChartSvg() atomically to `path`.
Status writeLineChartSvg(const std::filesystem::path& path, const LineChart& chart, const ChartParams& params = {});

/// `text` with &, <, >, " and ' replaced by XML entities.
std::string escapeXml(const std::string& text);

}  // namespace lodline
