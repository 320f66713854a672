// `lodline sweep`: results.csv, contact sheets and charts from the runs' stats (sweep.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <sstream>

#include "app/sweep.h"
#include "export/chart.h"
#include "export/contact_sheet.h"
#include "io/atomic_file.h"
#include "io/image.h"

namespace lodline::sweep {
namespace {

// Result columns read from each run's stats JSON (docs/experiments.md): JSON pointers, the
// first present one wins.
struct StatColumn {
  const char* name;
  std::vector<const char*> pointers;
};
const std::vector<StatColumn>& statColumns() {
  static const std::vector<StatColumn> columns = {
      {"faces", {"/model/faces"}},
      {"faces_drawn", {"/faces_drawn"}},
      {"active_faces", {"/lod/active_faces", "/faces_drawn"}},
      {"visible_faces", {"/lod/visible_faces"}},
      {"band_fraction", {"/lod/band_fraction"}},
      {"band_or_limit_fraction", {"/lod/band_or_limit_fraction"}},
      {"target_area", {"/lod/target_area"}},
      {"coverage_px", {"/image/coverage_px"}},
      {"line_segments", {"/line_segments"}},
      {"strokes", {"/strokes"}},
      {"specks", {"/specks"}},
      {"line_pixels", {"/line_pixels"}},
      {"ms_load", {"/ms/load"}},
      {"ms_pm", {"/ms/pm"}},
      {"ms_adapt", {"/ms/adapt"}},
      {"ms_shape", {"/ms/shape"}},
      {"ms_view", {"/ms/view"}},
      {"ms_extract", {"/ms/extract"}},
      {"ms_chain", {"/ms/chain"}},
      {"ms_setup", {"/ms/setup"}},
      {"ms_render", {"/ms/render"}},
      {"ms_readback", {"/ms/readback"}},
      {"ms_visibility", {"/ms/visibility"}},
      {"ms_total", {"/ms/total"}},
  };
  return columns;
}

const StatColumn* findStatColumn(const std::string& name) {
  for (const auto& c : statColumns())
    if (name == c.name) return &c;
  return nullptr;
}

const nlohmann::json* statValue(const nlohmann::json& stats, const StatColumn& column) {
  for (const char* p : column.pointers) {
    const nlohmann::json::json_pointer ptr(p);
    if (stats.is_object() && stats.contains(ptr) && stats.at(ptr).is_number()) return &stats.at(ptr);
  }
  return nullptr;
}

std::string formatNumber(const nlohmann::json& v) {
  if (v.is_number_integer() || v.is_number_unsigned()) return v.dump();
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.6g", v.get<double>());
  return buf;
}

double numberOr(const nlohmann::json* v, double fallback) { return v ? v->get<double>() : fallback; }

// Values as labels: file names without their directory, "(none)" for an empty value.
std::string displayValue(const std::string& value) {
  if (value.empty()) return "(none)";
  if (value.find('/') != std::string::npos) return std::filesystem::path(value).filename().string();
  return value;
}

std::string csvField(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

// Value of column `name` (a varied key, "run", or a stat column) for run `i`; "" when missing.
std::string cellValue(const Plan& plan, const std::vector<RunResult>& results, size_t i, const std::string& name) {
  if (name == "run") return plan.runs[i].name;
  for (size_t a = 0; a < plan.axes.size(); ++a)
    if (plan.axes[a].key == name) return plan.axes[a].values[plan.runs[i].index[a]];
  if (const StatColumn* c = findStatColumn(name); c && hasStats(results[i]))
    if (const nlohmann::json* v = statValue(results[i].stats, *c)) return formatNumber(*v);
  return {};
}

// One sheet per combination of the values of the third and later axes (one sheet for all
// runs otherwise): the value indices of those axes per sheet.
std::vector<std::vector<size_t>> extraCombinations(const Plan& plan) {
  std::vector<std::vector<size_t>> combos = {{}};
  if (plan.zip || plan.axes.size() <= 2) return combos;
  for (size_t a = 2; a < plan.axes.size(); ++a) {
    std::vector<std::vector<size_t>> next;
    for (const auto& c : combos)
      for (size_t v = 0; v < plan.axes[a].values.size(); ++v) {
        next.push_back(c);
        next.back().push_back(v);
      }
    combos = std::move(next);
  }
  return combos;
}

}  // namespace

std::vector<std::string> statColumnNames() {
  std::vector<std::string> names;
  for (const auto& c : statColumns()) names.push_back(c.name);
  return names;
}

bool isStatColumn(const std::string& name) { return findStatColumn(name) != nullptr; }

Status writeResultsCsv(const std::filesystem::path& path, const Plan& plan, const std::vector<RunResult>& results) {
  std::ostringstream csv;
  csv << "run";
  for (const auto& a : plan.axes) csv << ',' << csvField(a.key);
  csv << ",status,error";
  for (const auto& c : statColumns()) csv << ',' << c.name;
  csv << '\n';
  for (size_t i = 0; i < plan.runs.size(); ++i) {
    if (!hasResult(results[i])) continue;
    csv << csvField(plan.runs[i].name);
    for (size_t a = 0; a < plan.axes.size(); ++a) csv << ',' << csvField(plan.axes[a].values[plan.runs[i].index[a]]);
    csv << ',' << (hasStats(results[i]) ? "ok" : "failed") << ',' << csvField(results[i].error);
    for (const auto& c : statColumns()) csv << ',' << cellValue(plan, results, i, c.name);
    csv << '\n';
  }
  const std::string text = csv.str();
  return writeFileAtomically(path, [&](std::ostream& out) -> Status {
    out << text;
    return {};
  });
}

Result<std::vector<std::filesystem::path>> writeSheets(const Plan& plan, const std::vector<RunResult>& results,
                                                       const std::filesystem::path& dir,
                                                       const std::filesystem::path& runs_dir, const Font& font,
                                                       const SheetOptions& o) {
  std::vector<std::filesystem::path> files;
  const auto& axes = plan.axes;
  const bool zip = plan.zip;
  // "camel.off: " before titles (nothing when the model is varied: it is an axis).
  const std::string model_name =
      plan.model.empty() ? std::string() : std::filesystem::path(plan.model).filename().string() + ": ";
  std::string fixed;
  for (const auto& t : plan.fixed_given) fixed += (fixed.empty() ? "" : " ") + t;
  if (fixed.size() > 120) fixed = fixed.substr(0, 117) + "...";
  // Cell width: --cell-width, else the first render's width up to 320 px.
  ContactSheetParams params;
  params.cell_width = o.cell_width;
  for (size_t i = 0; i < results.size() && params.cell_width <= 0; ++i)
    if (hasStats(results[i]))
      params.cell_width = std::min(320, static_cast<int>(numberOr(statValue(results[i].stats, {"", {"/image/width"}}), 320)));
  if (params.cell_width <= 0) params.cell_width = 320;
  for (const auto& combo : extraCombinations(plan)) {
    ContactSheet sheet;
    std::vector<size_t> members;  // run indices, in cell order
    if (zip || axes.size() == 1) {
      for (size_t i = 0; i < plan.runs.size(); ++i) members.push_back(i);
      const int n = static_cast<int>(members.size());
      sheet.columns = !zip ? n
                      : o.columns > 0 ? std::min(o.columns, n)
                      : (n <= 5 ? n : static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n)))));
      sheet.rows = (n + sheet.columns - 1) / sheet.columns;
      if (!zip) {
        sheet.column_axis = axes[0].key;
        for (const auto& v : axes[0].values) sheet.column_labels.push_back(displayValue(v));
      }
    } else {
      sheet.rows = static_cast<int>(axes[0].values.size());
      sheet.columns = static_cast<int>(axes[1].values.size());
      sheet.row_axis = axes[0].key;
      sheet.column_axis = axes[1].key;
      for (const auto& v : axes[0].values) sheet.row_labels.push_back(displayValue(v));
      for (const auto& v : axes[1].values) sheet.column_labels.push_back(displayValue(v));
      members.assign(static_cast<size_t>(sheet.rows) * sheet.columns, 0);
      for (size_t i = 0; i < plan.runs.size(); ++i) {
        const auto& idx = plan.runs[i].index;
        if (!std::equal(combo.begin(), combo.end(), idx.begin() + 2)) continue;
        members[idx[0] * sheet.columns + idx[1]] = i;
      }
    }
    sheet.title.push_back(!o.title.empty() ? o.title
                          : zip || axes.size() == 1
                              ? model_name + std::string(zip ? "paired runs" : "sweep of " + axes[0].key)
                              : model_name + "rows " + axes[0].key + ", columns " + axes[1].key);
    std::string extra;
    for (size_t k = 0; k < combo.size(); ++k)
      extra += (extra.empty() ? "" : ", ") + axes[k + 2].key + " = " + displayValue(axes[k + 2].values[combo[k]]);
    if (!extra.empty()) sheet.title.push_back(extra);
    if (!fixed.empty()) sheet.title.push_back(fixed);

    for (size_t i : members) {
      ContactSheetCell cell;
      const RunResult& r = results[i];
      if (zip)
        for (size_t a = 0; a < axes.size(); ++a)
          cell.caption.push_back(axes[a].key + " = " + displayValue(axes[a].values[plan.runs[i].index[a]]));
      for (const auto& c : o.captions) {
        const std::string v = cellValue(plan, results, i, c);
        cell.caption.push_back(c + " " + (v.empty() ? "-" : v));
      }
      if (hasStats(r)) {
        auto img = readPng(pngOf(runs_dir, plan.runs[i]));
        if (!img) return img.error();
        cell.image = fitImage(*img, params.cell_width, params.cell_width * img->height / std::max(1, img->width) + 1);
      } else {
        cell.note = r.state == RunState::kFailed ? "failed" : "not run";
      }
      sheet.cells.push_back(std::move(cell));
    }
    std::string file = "sheet";
    for (size_t k = 0; k < combo.size(); ++k) file += "_" + namePart(axes[k + 2].key, axes[k + 2].values[combo[k]]);
    const auto path = dir / (file + ".png");
    if (Status s = writePng(path, drawContactSheet(sheet, font, params)); !s) return s.error();
    files.push_back(path);
  }
  return files;
}

Result<std::vector<std::filesystem::path>> writeCharts(const Plan& plan, const std::vector<RunResult>& results,
                                                       const std::filesystem::path& dir,
                                                       const std::vector<std::string>& columns) {
  std::vector<std::filesystem::path> files;
  const auto& axes = plan.axes;
  // "camel.off: " before titles (nothing when the model is varied: it is an axis).
  const std::string model_name =
      plan.model.empty() ? std::string() : std::filesystem::path(plan.model).filename().string() + ": ";
  for (const auto& column : columns) {
    if (!findStatColumn(column)) return Error::usage("--chart " + column + ": not a result column");
    const StatColumn& c = *findStatColumn(column);
    LineChart chart;
    chart.title = model_name + column + " against " + axes[0].key;
    chart.x_label = axes[0].key;
    chart.y_label = column;
    auto y_of = [&](size_t i) {
      return hasStats(results[i]) ? numberOr(statValue(results[i].stats, c), std::nan(""))
                                  : std::numeric_limits<double>::quiet_NaN();
    };
    std::vector<std::string> x_text;
    if (plan.zip) {
      ChartSeries s;
      for (size_t i = 0; i < plan.runs.size(); ++i) {
        x_text.push_back(axes[0].values[plan.runs[i].index[0]]);
        s.y.push_back(y_of(i));
      }
      chart.series.push_back(std::move(s));
    } else {
      x_text = axes[0].values;
      // One series per combination of the other axes' values, in plan order.
      std::map<std::vector<size_t>, size_t> series_of;
      for (size_t i = 0; i < plan.runs.size(); ++i) {
        const auto& idx = plan.runs[i].index;
        const std::vector<size_t> rest(idx.begin() + 1, idx.end());
        auto [it, added] = series_of.emplace(rest, chart.series.size());
        if (added) {
          ChartSeries s;
          for (size_t a = 1; a < axes.size(); ++a)
            s.label += (a > 1 ? ", " : "") + axes[a].key + " = " + displayValue(axes[a].values[idx[a]]);
          s.y.assign(axes[0].values.size(), std::numeric_limits<double>::quiet_NaN());
          chart.series.push_back(std::move(s));
        }
        chart.series[it->second].y[idx[0]] = y_of(i);
      }
    }
    for (const auto& t : x_text) chart.x_ticks.push_back(displayValue(t));
    std::vector<double> x;
    for (const auto& t : x_text)
      if (auto v = parseNumber(t)) x.push_back(*v);
    if (x.size() == x_text.size()) {
      chart.x = x;
      chart.x_scale = autoScale(x);
    }
    const auto path = dir / ("chart_" + column + ".svg");
    if (Status s = writeLineChartSvg(path, chart); !s) return s.error();
    files.push_back(path);
  }
  return files;
}

}  // namespace lodline::sweep
