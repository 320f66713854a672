#include "export/svg.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <ostream>

#include "io/atomic_file.h"

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

// Polylines of one layer's strokes, grouped by type.
void writeStrokes(std::ostream& os, const SvgStrokes& strokes, const SvgStyle& style, int decimals) {
  const size_t ns = strokes.kinds.size();
  for (int type = 0; type < kLineKindCount; ++type) {
    const SvgLineStyle& ls = style.lines[type];
    bool open = false;
    for (size_t s = 0; s < ns; ++s) {
      if (static_cast<int>(strokes.kinds[s]) != type) continue;
      const uint32_t begin = strokes.offsets[s], end = strokes.offsets[s + 1];
      if (end - begin < 2) continue;
      if (!open) {
        os << "<g class=\"" << lineKindName(static_cast<LineKind>(type))
           << "\" fill=\"none\" stroke=\"" << sanitizeColour(ls.colour) << "\" stroke-width=\"";
        writeNumber(os, ls.width, 3);
        os << "\" stroke-linecap=\"round\" stroke-linejoin=\"round\">\n";
        open = true;
      }
      os << "<polyline";
      float op = ls.opacity * (strokes.opacity.empty() ? 1.0f : strokes.opacity[s]);
      if (!std::isfinite(op)) op = 1.0f;
      op = std::clamp(op, 0.0f, 1.0f);
      if (op < 1.0f) {
        os << " stroke-opacity=\"";
        writeNumber(os, op, 3);
        os << '"';
      }
      os << " points=\"";
      for (uint32_t i = begin; i < end; ++i) {
        glm::vec2 p = strokes.points[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y)) p = glm::vec2(0.0f);
        if (i > begin) os << ' ';
        writeNumber(os, p.x, decimals);
        os << ',';
        writeNumber(os, p.y, decimals);
      }
      os << "\"/>\n";
    }
    if (open) os << "</g>\n";
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

Status writeSvgLayers(const std::filesystem::path& path, int width, int height, std::span<const SvgLayer> layers,
                      const SvgStyle& page) {
  const std::string name = path.string();
  if (width <= 0 || height <= 0)
    return Error::runtime(name + ": invalid SVG size " + std::to_string(width) + "x" +
                          std::to_string(height));
  for (const SvgLayer& layer : layers) {
    const SvgStrokes& strokes = layer.strokes;
    const size_t ns = strokes.kinds.size();
    if (ns > 0 && strokes.offsets.size() != ns + 1)
      return Error::runtime(name + ": stroke offsets (" + std::to_string(strokes.offsets.size()) +
                            ") do not match stroke count (" + std::to_string(ns) + ")");
    if (!strokes.opacity.empty() && strokes.opacity.size() != ns)
      return Error::runtime(name + ": stroke opacities do not match stroke count");
    for (size_t s = 0; s < ns; ++s)
      if (strokes.offsets[s] > strokes.offsets[s + 1] || strokes.offsets[s + 1] > strokes.points.size())
        return Error::runtime(name + ": stroke " + std::to_string(s) + " is out of range");
  }

  return writeFileAtomically(path, [&](std::ostream& os) -> Status {
    os << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
       << "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" << width
       << "\" height=\"" << height << "\" viewBox=\"0 0 " << width << ' ' << height << "\">\n";
    if (page.background)
      os << "<rect x=\"0\" y=\"0\" width=\"" << width << "\" height=\"" << height
         << "\" fill=\"" << sanitizeColour(page.background_colour) << "\"/>\n";
    for (const SvgLayer& layer : layers) {
      const bool group = layers.size() > 1;
      if (group) os << "<g id=\"" << sanitizeId(layer.name) << "\">\n";
      writeStrokes(os, layer.strokes, layer.style, std::clamp(layer.style.decimals, 0, 6));
      if (group) os << "</g>\n";
    }
    os << "</svg>\n";
    return {};
  });
}

}  // namespace lodline
