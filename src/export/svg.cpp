#include "export/svg.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <sstream>

#include "io/atomic_file.h"
#include "lines/stroke_curve.h"

namespace lodline {
namespace {

// Colours come from user settings: keep only characters that cannot break the attribute.
std::string sanitizeColour(const std::string& c) {
  std::string out;
  for (char ch : c)
    if (std::isalnum(static_cast<unsigned char>(ch)) || ch == '#' || ch == '(' || ch == ')' ||
        ch == ',' || ch == '.' || ch == ' ' || ch == '%')
      out.push_back(ch);
  return out.empty() ? std::string("#000000") : out;
}

void writeNumber(std::ostream& os, float v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.*f", decimals, static_cast<double>(v));
  os << buf;
}

void writePoint(std::ostream& os, glm::vec2 p, int decimals) {
  writeNumber(os, p.x, decimals);
  os << ',';
  writeNumber(os, p.y, decimals);
}

// The opacity of stroke s: the style's × the stroke's own, in [0, 1] (1 when not finite).
float strokeOpacity(const SvgLineStyle& ls, const SvgStrokes& strokes, size_t s) {
  const float op = ls.opacity * (strokes.opacity.empty() ? 1.0f : strokes.opacity[s]);
  return std::isfinite(op) ? std::clamp(op, 0.0f, 1.0f) : 1.0f;
}

// The strokes of `strokes` that `select` accepts, in one group of class `cls` and style
// `ls` (dashed by `dash` when given): smooth paths of cubic Béziers (lines/stroke_curve.h),
// or polylines with curves off; nothing when none is accepted.
template <class Select>
void writeGroup(std::ostream& os, const SvgStrokes& strokes, const char* cls, const SvgLineStyle& ls,
                const std::array<float, 2>* dash, int decimals, const SvgStyle& style, StrokeCurveScratch& scratch,
                std::vector<glm::vec2>& chain, Select&& select) {
  const size_t ns = strokes.kinds.size();
  bool open = false;
  for (size_t s = 0; s < ns; ++s) {
    if (!select(s)) continue;
    const uint32_t begin = strokes.offsets[s], end = strokes.offsets[s + 1];
    if (end - begin < 2) continue;
    if (!open) {
      os << "<g class=\"" << cls << "\" fill=\"none\" stroke=\"" << sanitizeColour(ls.colour) << "\" stroke-width=\"";
      writeNumber(os, ls.width, 3);
      const std::string cap = ls.linecap == "butt" || ls.linecap == "square" ? ls.linecap : "round";
      os << "\" stroke-linecap=\"" << cap << "\" stroke-linejoin=\"round\"";
      if (!dash) dash = &ls.dash;
      if ((*dash)[1] > 0.0f) {
        os << " stroke-dasharray=\"";
        writeNumber(os, (*dash)[0], 3);
        os << ' ';
        writeNumber(os, (*dash)[1], 3);
        os << '"';
      }
      os << ">\n";
      open = true;
    }
    const float op = strokeOpacity(ls, strokes, s);
    const auto points = strokes.points.subspan(begin, end - begin);
    chain.clear();
    if (style.curves) fitStrokeCurve(points, style.curve, chain, scratch);
    os << (style.curves ? "<path" : "<polyline");
    if (!strokes.ids.empty()) os << " id=\"s" << strokes.ids[s] << '"';
    if (op < 1.0f) {
      os << " stroke-opacity=\"";
      writeNumber(os, op, 3);
      os << '"';
    }
    if (style.curves) {
      os << " d=\"";
      if (chain.empty()) {  // a stroke of no length: a dot, as the polyline would draw it
        glm::vec2 p = points.front();
        if (!std::isfinite(p.x) || !std::isfinite(p.y)) p = glm::vec2(0.0f);
        chain.assign(1, p);
      }
      os << 'M';
      writePoint(os, chain.front(), decimals);
      for (size_t i = 1; i + 2 < chain.size(); i += 3) {
        if (isStraightSegment(&chain[i - 1])) {  // one coordinate pair instead of three
          os << 'L';
          writePoint(os, chain[i + 2], decimals);
          continue;
        }
        os << 'C';
        writePoint(os, chain[i], decimals);
        os << ' ';
        writePoint(os, chain[i + 1], decimals);
        os << ' ';
        writePoint(os, chain[i + 2], decimals);
      }
      if (chain.size() == 1) os << 'z';
      os << "\"/>\n";
      continue;
    }
    os << " points=\"";
    for (uint32_t i = begin; i < end; ++i) {
      glm::vec2 p = strokes.points[i];
      if (!std::isfinite(p.x) || !std::isfinite(p.y)) p = glm::vec2(0.0f);
      if (i > begin) os << ' ';
      writePoint(os, p, decimals);
    }
    os << "\"/>\n";
  }
  if (open) os << "</g>\n";
}

// The closed outlines of `strokes` of kind `kind`, filled: one group, a path per outline.
void writeOutlines(std::ostream& os, const SvgStrokes& strokes, int kind, const SvgLineStyle& ls, int decimals) {
  bool open = false;
  for (size_t s = 0; s < strokes.kinds.size(); ++s) {
    if (static_cast<int>(strokes.kinds[s]) != kind) continue;
    const uint32_t begin = strokes.offsets[s], end = strokes.offsets[s + 1];
    if (end - begin < 3) continue;
    if (!open) {
      os << "<g class=\"" << lineKindName(static_cast<LineKind>(kind)) << " outline\" fill=\""
         << sanitizeColour(ls.colour) << "\" stroke=\"none\">\n";
      open = true;
    }
    const float op = strokeOpacity(ls, strokes, s);
    os << "<path";
    if (!strokes.ids.empty()) os << " id=\"s" << strokes.ids[s] << '"';
    if (op < 1.0f) {
      os << " fill-opacity=\"";
      writeNumber(os, op, 3);
      os << '"';
    }
    os << " d=\"M";
    for (uint32_t i = begin; i < end; ++i) {
      glm::vec2 p = strokes.points[i];
      if (!std::isfinite(p.x) || !std::isfinite(p.y)) p = glm::vec2(0.0f);
      if (i > begin) os << 'L';
      writePoint(os, p, decimals);
    }
    os << "Z\"/>\n";
  }
  if (open) os << "</g>\n";
}

// One layer: its hidden lines (when enabled) under its visible lines, grouped by kind.
void writeStrokes(std::ostream& os, const SvgLayer& layer, int decimals) {
  const SvgStyle& style = layer.style;
  StrokeCurveScratch scratch;
  std::vector<glm::vec2> chain;
  if (style.hidden_enabled)
    writeGroup(os, layer.hidden, "hidden", style.hidden, &style.hidden_dash, decimals, style, scratch, chain,
               [](size_t) { return true; });
  for (int kind = 0; kind < kLineKindCount; ++kind) {
    writeGroup(os, layer.strokes, lineKindName(static_cast<LineKind>(kind)), style.lines[kind], nullptr, decimals,
               style, scratch, chain, [&](size_t s) { return static_cast<int>(layer.strokes.kinds[s]) == kind; });
    writeOutlines(os, layer.outlines, kind, style.lines[kind], decimals);
  }
}

// Group ids: letters, digits, '-', '_' and '.', starting with a letter.
std::string sanitizeId(const std::string& name) {
  std::string out = "o-";
  for (char ch : name)
    out.push_back(std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '_' || ch == '.' ? ch : '_');
  return out;
}

}  // namespace

Status writeSvg(const std::filesystem::path& path, int width, int height,
                const SvgStrokes& strokes, const SvgStyle& style) {
  const SvgLayer layer{"", strokes, style};
  return writeSvgLayers(path, width, height, std::span<const SvgLayer>(&layer, 1), style);
}

namespace {

// Checks the layers' arrays; errors name `name` (the file, or "SVG").
Status checkLayers(const std::string& name, int width, int height, std::span<const SvgLayer> layers) {
  if (width <= 0 || height <= 0)
    return Error::runtime(name + ": invalid SVG size " + std::to_string(width) + "x" +
                          std::to_string(height));
  for (const SvgLayer& layer : layers)
    for (const SvgStrokes* strokes : {&layer.strokes, &layer.hidden, &layer.outlines}) {
      const size_t ns = strokes->kinds.size();
      if (ns > 0 && strokes->offsets.size() != ns + 1)
        return Error::runtime(name + ": stroke offsets (" + std::to_string(strokes->offsets.size()) +
                              ") do not match stroke count (" + std::to_string(ns) + ")");
      if (!strokes->opacity.empty() && strokes->opacity.size() != ns)
        return Error::runtime(name + ": stroke opacities do not match stroke count");
      if (!strokes->ids.empty() && strokes->ids.size() != ns)
        return Error::runtime(name + ": stroke ids do not match stroke count");
      for (size_t s = 0; s < ns; ++s)
        if (strokes->offsets[s] > strokes->offsets[s + 1] || strokes->offsets[s + 1] > strokes->points.size())
          return Error::runtime(name + ": stroke " + std::to_string(s) + " is out of range");
    }
  return {};
}

void writeDocument(std::ostream& os, int width, int height, std::span<const SvgLayer> layers, const SvgStyle& page) {
  os << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
     << "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" << width
     << "\" height=\"" << height << "\" viewBox=\"0 0 " << width << ' ' << height << "\">\n";
  if (page.background)
    os << "<rect x=\"0\" y=\"0\" width=\"" << width << "\" height=\"" << height
       << "\" fill=\"" << sanitizeColour(page.background_colour) << "\"/>\n";
  for (const SvgLayer& layer : layers) {
    const bool group = layers.size() > 1;
    if (group) os << "<g id=\"" << sanitizeId(layer.name) << "\">\n";
    writeStrokes(os, layer, std::clamp(layer.style.decimals, 0, 6));
    if (group) os << "</g>\n";
  }
  os << "</svg>\n";
}

}  // namespace

Status writeSvgLayers(const std::filesystem::path& path, int width, int height, std::span<const SvgLayer> layers,
                      const SvgStyle& page) {
  if (Status s = checkLayers(path.string(), width, height, layers); !s) return s;
  return writeFileAtomically(path, [&](std::ostream& os) -> Status {
    writeDocument(os, width, height, layers, page);
    return {};
  });
}

Result<std::string> svgLayersText(int width, int height, std::span<const SvgLayer> layers, const SvgStyle& page) {
  if (Status s = checkLayers("SVG", width, height, layers); !s) return s.error();
  std::ostringstream os;
  writeDocument(os, width, height, layers, page);
  return os.str();
}

}  // namespace lodline
