#include "export/chart.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "io/atomic_file.h"

namespace lodline {
namespace {

// Series colours (distinct on white, readable in grey) and dash patterns for series beyond them.
constexpr const char* kColours[] = {"#1b5fa8", "#d0490c", "#25803a", "#7a2a96",
                                    "#b8860b", "#0f8b8d", "#c2185b", "#555555"};
constexpr const char* kDashes[] = {"", "6,3", "2,3", "8,3,2,3"};

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.2f", v);
  return buf;
}

// Tick label: up to 6 significant digits, no trailing zeros ("0.25", "1500", "1e+06").
std::string tickLabel(double v) {
  if (std::abs(v) < 1e-12) v = 0.0;
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.6g", v);
  return buf;
}

// 1, 2 or 5 times a power of ten, the smallest not below `raw`.
double niceStep(double raw) {
  if (!(raw > 0.0)) return 1.0;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= raw * (1.0 - 1e-9)) return m * p;
  return 10.0 * p;
}

// Rough advance width of `text` in a sans-serif font of size `px` (SVG has no text metrics).
double textWidth(const std::string& text, double px) {
  size_t chars = 0;
  for (unsigned char c : text) chars += (c & 0xc0) != 0x80;
  return 0.6 * px * static_cast<double>(chars);
}

}  // namespace

std::string escapeXml(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default:
        // Control characters are not allowed in XML 1.0 text.
        if (static_cast<unsigned char>(c) >= 0x20 || c == '\t' || c == '\n') out += c;
    }
  }
  return out;
}

AxisScale autoScale(const std::vector<double>& x) {
  if (x.empty()) return AxisScale::kLinear;
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  return *lo > 0.0 && std::isfinite(*hi) && *hi / *lo >= 8.0 ? AxisScale::kLog : AxisScale::kLinear;
}

std::string lineChartSvg(const LineChart& chart, const ChartParams& params) {
  const double W = params.width, H = params.height, fs = params.font_px;
  const size_t n = chart.x_ticks.size();
  const bool numeric = chart.x.size() == n && n > 0;
  const bool log_x = numeric && chart.x_scale == AxisScale::kLog &&
                     std::all_of(chart.x.begin(), chart.x.end(), [](double v) { return v > 0.0; });

  // Legend on the right, as wide as its longest label.
  double legend_w = 0.0;
  for (const auto& s : chart.series) legend_w = std::max(legend_w, textWidth(s.label, fs));
  if (chart.series.size() > 1 || (chart.series.size() == 1 && !chart.series[0].label.empty())) legend_w += 44.0;
  else legend_w = 0.0;
  const double left = 16.0 + 1.4 * fs + 7.0 * 0.6 * fs, right = W - 16.0 - legend_w;
  const double top = 20.0 + 1.6 * fs, bottom = H - (20.0 + 2.6 * fs);

  // x positions in [left, right], with half a step of padding for categories.
  std::vector<double> px(n);
  if (numeric) {
    std::vector<double> t(n);
    for (size_t i = 0; i < n; ++i) t[i] = log_x ? std::log(chart.x[i]) : chart.x[i];
    const auto [lo, hi] = std::minmax_element(t.begin(), t.end());
    const double span = *hi - *lo, pad = 0.05 * (right - left);
    for (size_t i = 0; i < n; ++i)
      px[i] = span > 0.0 ? left + pad + (t[i] - *lo) / span * (right - left - 2.0 * pad) : 0.5 * (left + right);
  } else {
    for (size_t i = 0; i < n; ++i) px[i] = left + (static_cast<double>(i) + 0.5) / static_cast<double>(n) * (right - left);
  }

  // y range: the data rounded out to nice ticks; from 0 when the data is positive and spans
  // more than a third of its maximum.
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& s : chart.series)
    for (double v : s.y)
      if (std::isfinite(v)) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
  if (!std::isfinite(lo)) lo = 0.0, hi = 1.0;
  if (lo >= 0.0 && lo < hi * (2.0 / 3.0)) lo = 0.0;
  if (hi - lo < 1e-12 * std::max(1.0, std::abs(hi))) {
    const double d = std::abs(hi) > 0.0 ? 0.1 * std::abs(hi) : 1.0;
    lo -= d;
    hi += d;
  }
  const double step = niceStep((hi - lo) / 5.0);
  const double y0 = std::floor(lo / step + 1e-9) * step, y1 = std::ceil(hi / step - 1e-9) * step;
  auto py = [&](double v) { return bottom - (v - y0) / (y1 - y0) * (bottom - top); };

  std::ostringstream os;
  os << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
     << "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" << params.width << "\" height=\""
     << params.height << "\" viewBox=\"0 0 " << params.width << ' ' << params.height
     << "\" font-family=\"DejaVu Sans, Verdana, sans-serif\" font-size=\"" << num(fs) << "\">\n"
     << "<rect x=\"0\" y=\"0\" width=\"" << params.width << "\" height=\"" << params.height << "\" fill=\"white\"/>\n";
  if (!chart.title.empty())
    os << "<text class=\"title\" x=\"" << num(W / 2) << "\" y=\"" << num(8.0 + 1.2 * fs)
       << "\" text-anchor=\"middle\" font-size=\"" << num(1.2 * fs) << "\">" << escapeXml(chart.title) << "</text>\n";

  // Grid, y ticks and labels.
  os << "<g class=\"y-axis\">\n";
  for (int k = 0; y0 + k * step <= y1 + 0.5 * step; ++k) {
    const double v = y0 + k * step, y = py(v);
    os << "<line x1=\"" << num(left) << "\" y1=\"" << num(y) << "\" x2=\"" << num(right) << "\" y2=\"" << num(y)
       << "\" stroke=\"#e0e0e0\"/>\n"
       << "<line x1=\"" << num(left - 5) << "\" y1=\"" << num(y) << "\" x2=\"" << num(left) << "\" y2=\"" << num(y)
       << "\" stroke=\"black\"/>\n"
       << "<text x=\"" << num(left - 8) << "\" y=\"" << num(y + 0.35 * fs) << "\" text-anchor=\"end\">"
       << tickLabel(v) << "</text>\n";
  }
  os << "</g>\n<g class=\"x-axis\">\n";
  for (size_t i = 0; i < n; ++i)
    os << "<line x1=\"" << num(px[i]) << "\" y1=\"" << num(bottom) << "\" x2=\"" << num(px[i]) << "\" y2=\""
       << num(bottom + 5) << "\" stroke=\"black\"/>\n"
       << "<text x=\"" << num(px[i]) << "\" y=\"" << num(bottom + 8 + fs) << "\" text-anchor=\"middle\">"
       << escapeXml(chart.x_ticks[i]) << "</text>\n";
  os << "</g>\n"
     << "<polyline class=\"frame\" fill=\"none\" stroke=\"black\" points=\"" << num(left) << ',' << num(top) << ' '
     << num(left) << ',' << num(bottom) << ' ' << num(right) << ',' << num(bottom) << "\"/>\n";
  if (!chart.x_label.empty())
    os << "<text class=\"x-label\" x=\"" << num((left + right) / 2) << "\" y=\"" << num(H - 10) << "\" text-anchor=\"middle\" "
       << "font-size=\"" << num(1.1 * fs) << "\">" << escapeXml(chart.x_label + (log_x ? " (log scale)" : ""))
       << "</text>\n";
  if (!chart.y_label.empty())
    os << "<text class=\"y-label\" x=\"0\" y=\"0\" transform=\"translate(" << num(10.0 + 1.1 * fs) << ','
       << num((top + bottom) / 2) << ") rotate(-90)\" text-anchor=\"middle\" font-size=\"" << num(1.1 * fs) << "\">"
       << escapeXml(chart.y_label) << "</text>\n";

  // Series: polylines broken at missing values, a circle per value.
  for (size_t s = 0; s < chart.series.size(); ++s) {
    const ChartSeries& series = chart.series[s];
    const char* colour = kColours[s % std::size(kColours)];
    const char* dash = kDashes[(s / std::size(kColours)) % std::size(kDashes)];
    os << "<g class=\"series\" stroke=\"" << colour << "\" fill=\"" << colour << "\">\n";
    std::string points;
    auto flush = [&] {
      if (points.find(' ') != std::string::npos)
        os << "<polyline fill=\"none\" stroke-width=\"2\"" << (*dash ? std::string(" stroke-dasharray=\"") + dash + "\"" : "")
           << " points=\"" << points << "\"/>\n";
      points.clear();
    };
    for (size_t i = 0; i < n; ++i) {
      const double v = i < series.y.size() ? series.y[i] : std::numeric_limits<double>::quiet_NaN();
      if (!std::isfinite(v)) {
        flush();
        continue;
      }
      if (!points.empty()) points += ' ';
      points += num(px[i]) + ',' + num(py(v));
    }
    flush();
    for (size_t i = 0; i < n && i < series.y.size(); ++i)
      if (std::isfinite(series.y[i]))
        os << "<circle class=\"point\" cx=\"" << num(px[i]) << "\" cy=\"" << num(py(series.y[i])) << "\" r=\"3\"/>\n";
    os << "</g>\n";
  }

  if (legend_w > 0.0) {
    const double lx = right + 16.0;
    os << "<g class=\"legend\">\n";
    for (size_t s = 0; s < chart.series.size(); ++s) {
      const char* colour = kColours[s % std::size(kColours)];
      const char* dash = kDashes[(s / std::size(kColours)) % std::size(kDashes)];
      const double y = top + 4.0 + static_cast<double>(s) * 1.6 * fs;
      os << "<line x1=\"" << num(lx) << "\" y1=\"" << num(y) << "\" x2=\"" << num(lx + 22) << "\" y2=\"" << num(y)
         << "\" stroke=\"" << colour << "\" stroke-width=\"2\""
         << (*dash ? std::string(" stroke-dasharray=\"") + dash + "\"" : "") << "/>\n"
         << "<text x=\"" << num(lx + 28) << "\" y=\"" << num(y + 0.35 * fs) << "\">" << escapeXml(chart.series[s].label)
         << "</text>\n";
    }
    os << "</g>\n";
  }
  os << "</svg>\n";
  return os.str();
}

Status writeLineChartSvg(const std::filesystem::path& path, const LineChart& chart, const ChartParams& params) {
  const std::string text = lineChartSvg(chart, params);
  return writeFileAtomically(path, [&](std::ostream& out) -> Status {
    out << text;
    return {};
  });
}

}  // namespace lodline
