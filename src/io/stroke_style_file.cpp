#include "io/stroke_style_file.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/hash.h"
#include "io/atomic_file.h"
#include "io/image.h"
#include "core/printable.h"
#include "io/input_check.h"

namespace lodline {
namespace {

// A hash of integer lattice points to [0, 1): the brushes' noise.
float lattice(uint32_t seed, int x, int y) {
  return unitNoise((static_cast<uint64_t>(seed) << 42) ^ (static_cast<uint64_t>(static_cast<uint32_t>(x)) << 21) ^
                   static_cast<uint64_t>(static_cast<uint32_t>(y)));
}

// Value noise with cells of cx × cy px, periodic in x with period `wrap` px (a multiple of
// cx), smooth (cubic) between lattice points. In [0, 1).
float valueNoise(uint32_t seed, float x, float y, int cx, int cy, int wrap) {
  const float gx = x / static_cast<float>(cx), gy = y / static_cast<float>(cy);
  const int x0 = static_cast<int>(std::floor(gx)), y0 = static_cast<int>(std::floor(gy));
  const float fx = gx - static_cast<float>(x0), fy = gy - static_cast<float>(y0);
  const int cells = std::max(1, wrap / cx);
  auto at = [&](int i, int j) { return lattice(seed, ((i % cells) + cells) % cells, j); };
  const float sx = fx * fx * (3.0f - 2.0f * fx), sy = fy * fy * (3.0f - 2.0f * fy);
  const float top = at(x0, y0) + sx * (at(x0 + 1, y0) - at(x0, y0));
  const float bottom = at(x0, y0 + 1) + sx * (at(x0 + 1, y0 + 1) - at(x0, y0 + 1));
  return top + sy * (bottom - top);
}

uint8_t toByte(float v) { return static_cast<uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); }

// Every kind drawn with `s`; with a colour and a width scale when a preset sets them.
std::array<KindStrokeStyle, kLineKindCount> allKinds(const StrokeStyle& s) {
  std::array<KindStrokeStyle, kLineKindCount> kinds;
  for (KindStrokeStyle& k : kinds) k.stroke = s;
  return kinds;
}
std::array<KindStrokeStyle, kLineKindCount> allKinds(const StrokeStyle& s, glm::vec4 color, float width_scale) {
  std::array<KindStrokeStyle, kLineKindCount> kinds = allKinds(s);
  for (KindStrokeStyle& k : kinds) {
    k.set_color = true;
    k.color = color;
    k.width_scale = width_scale;
  }
  return kinds;
}

std::shared_ptr<const Image> builtinBrush(BrushKind kind) { return std::make_shared<const Image>(makeBrush(kind)); }

NamedStrokeStyle preset(const std::string& name) {
  NamedStrokeStyle out;
  out.name = name;
  StrokeStyle s;
  if (name == "ink") {
    // Brush pen: tapered ends, thick where near and where it bends, thin where weak.
    s.taper_in_px = 10.0f;
    s.taper_out_px = 14.0f;
    s.taper_min = 0.15f;
    s.depth_thickness = 0.35f;
    s.strength_thickness = 0.6f;
    s.curvature_thickness = 0.6f;
    s.strength_opacity = 0.4f;
    s.min_length_px = 3.0f;
    out.kinds = allKinds(s, {0.06f, 0.05f, 0.05f, 1.0f}, 1.3f);
  } else if (name == "pencil") {
    // Graphite: grainy, a little unsteady, lighter with distance, soft ends.
    s.taper_in_px = 6.0f;
    s.taper_out_px = 6.0f;
    s.taper_min = 0.4f;
    s.depth_opacity = 0.25f;
    s.strength_opacity = 0.6f;
    s.jitter_px = 0.35f;
    s.jitter_period_px = 30.0f;
    s.brush = builtinBrush(BrushKind::kPencil);
    s.brush_path = "pencil";
    s.brush_period_px = 48.0f;
    out.kinds = allKinds(s, {0.16f, 0.16f, 0.19f, 1.0f}, 1.15f);
  } else if (name == "marker") {
    // Felt marker: broad, translucent, streaky, square-ish ends.
    s.cap = StrokeCap::kSquare;
    s.strength_thickness = 0.3f;
    s.brush = builtinBrush(BrushKind::kMarker);
    s.brush_path = "marker";
    s.brush_period_px = 96.0f;
    out.kinds = allKinds(s, {0.16f, 0.22f, 0.30f, 0.8f}, 1.6f);
  } else {
    out.kinds = allKinds(s);  // plain
  }
  return out;
}

// Reads one kind's (or "all"'s) fields from `j` into `k`; `where` names the file and key.
Status readKind(const nlohmann::json& j, const std::filesystem::path& base, const std::string& where,
                KindStrokeStyle& k) {
  if (!j.is_object()) return Error::runtime(where + ": expected an object");
  auto number = [&](const std::string& key, const nlohmann::json& v, float lo, float hi, float& out) -> Status {
    if (!v.is_number() || !(v.get<double>() >= lo && v.get<double>() <= hi))
      return Error::runtime(where + "." + key + ": expected a number in [" + std::to_string(lo).substr(0, 6) + ", " +
                            std::to_string(hi).substr(0, 7) + "]");
    out = static_cast<float>(v.get<double>());
    return {};
  };
  StrokeStyle& s = k.stroke;
  for (const auto& [key, v] : j.items()) {
    Status st;
    if (key == "cap") {
      const std::string c = v.is_string() ? v.get<std::string>() : "";
      if (c == "butt") s.cap = StrokeCap::kButt;
      else if (c == "round") s.cap = StrokeCap::kRound;
      else if (c == "square") s.cap = StrokeCap::kSquare;
      else return Error::runtime(where + ".cap: expected \"butt\", \"round\" or \"square\"");
    } else if (key == "taper_in") st = number(key, v, 0, 1e4f, s.taper_in_px);
    else if (key == "taper_out") st = number(key, v, 0, 1e4f, s.taper_out_px);
    else if (key == "taper_min") st = number(key, v, 0, 1, s.taper_min);
    else if (key == "depth_thickness") st = number(key, v, -1, 1, s.depth_thickness);
    else if (key == "strength_thickness") st = number(key, v, 0, 1, s.strength_thickness);
    else if (key == "curvature_thickness") st = number(key, v, -1, 4, s.curvature_thickness);
    else if (key == "depth_opacity") st = number(key, v, 0, 1, s.depth_opacity);
    else if (key == "strength_opacity") st = number(key, v, 0, 1, s.strength_opacity);
    else if (key == "curvature_opacity") st = number(key, v, 0, 1, s.curvature_opacity);
    else if (key == "dash") {
      if (!v.is_array() || v.size() != 2) return Error::runtime(where + ".dash: expected [ON, OFF] in pixels");
      if (st = number("dash[0]", v[0], 0, 1e4f, s.dash_on); !st) return st;
      st = number("dash[1]", v[1], 0, 1e4f, s.dash_off);
    } else if (key == "jitter") st = number(key, v, 0, 64, s.jitter_px);
    else if (key == "jitter_period") st = number(key, v, 1, 1e4f, s.jitter_period_px);
    else if (key == "seed") {
      if (!v.is_number_unsigned() || v.get<uint64_t>() > 0xffffffffull)
        return Error::runtime(where + ".seed: expected an integer in [0, 4294967295]");
      s.seed = static_cast<uint32_t>(v.get<uint64_t>());
    } else if (key == "min_length") st = number(key, v, 0, 1e5f, s.min_length_px);
    else if (key == "smoothing") st = number(key, v, 0, 16, s.smoothing_px);
    else if (key == "brush_period") st = number(key, v, 4, 1024, s.brush_period_px);
    else if (key == "brush") {
      if (!v.is_string()) return Error::runtime(where + ".brush: expected a PNG path, \"pencil\", \"marker\" or \"none\"");
      const std::string b = v.get<std::string>();
      if (b == "none") {
        s.brush.reset();
        s.brush_path.clear();
      } else if (auto kind = parseBrushKind(b)) {
        s.brush = builtinBrush(*kind);
        s.brush_path = b;
      } else {
        const std::filesystem::path p = std::filesystem::path(b).is_absolute() ? std::filesystem::path(b) : base / b;
        auto img = readPng(p);
        if (!img) return Error::runtime(where + ".brush: " + printableText(img.error().message, 300));
        s.brush = std::make_shared<const Image>(std::move(img.value()));
        s.brush_path = p.string();
      }
    } else if (key == "color") {
      auto c = v.is_string() ? parseColor(v.get<std::string>()) : Result<glm::vec4>(Error::runtime("expected a string"));
      if (!c) return Error::runtime(where + ".color: " + c.error().message);
      k.set_color = true;
      k.color = *c;
    } else if (key == "width_scale") st = number(key, v, 0.05f, 16, k.width_scale);
    else return Error::runtime(where + ": unknown key \"" + printableText(key, 80) + "\"");
    if (!st) return st;
  }
  return {};
}

// `brush` resampled to one period of arc length by 8 px across, the size it is drawn at.
std::shared_ptr<const Image> periodBrush(const Image& brush, float period_px) {
  const int period = static_cast<int>(std::lround(std::clamp(period_px, 4.0f, 1024.0f)));
  return std::make_shared<const Image>(resampleBrush(brush, period, 8));
}

// The shortest decimal that reads back as `v` (0.15, not 0.15000000596046448).
double shortest(float v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof(buf) - 1, v);
  *r.ptr = '\0';
  return std::strtod(buf, nullptr);
}

}  // namespace

Image makeBrush(BrushKind kind) {
  constexpr int W = 256, H = 32;
  Image img(W, H);
  for (int y = 0; y < H; ++y) {
    const float t = (static_cast<float>(y) + 0.5f) / H;  // across, 0..1
    const float edge = std::abs(2.0f * t - 1.0f);         // 0 centre, 1 rim
    for (int x = 0; x < W; ++x) {
      const float fx = static_cast<float>(x) + 0.5f, fy = static_cast<float>(y) + 0.5f;
      float ink;
      if (kind == BrushKind::kPencil) {
        // Graphite on paper grain: fine speckle over a medium tooth, lighter at the rims.
        const float tooth = valueNoise(11, fx, fy, 4, 3, W);
        const float speck = lattice(12, x, y);
        const float streak = valueNoise(13, fx, fy, 32, 8, W);
        ink = 0.55f + 0.45f * tooth + 0.2f * streak - 0.45f * speck * speck;
        ink *= 1.0f - 0.45f * edge * edge * edge;
      } else {
        // Felt tip: streaks along the stroke (noise across, slow along), ink pooling at the rims.
        const float streaks = valueNoise(21, fx, fy, 128, 3, W);
        const float slow = valueNoise(22, fx, fy, 64, 32, W);
        ink = 0.74f + 0.2f * streaks + 0.08f * slow + 0.12f * std::pow(edge, 6.0f);
      }
      uint8_t* p = img.pixel(x, y);
      p[0] = p[1] = p[2] = toByte(ink);
      p[3] = 255;
    }
  }
  return img;
}

Result<BrushKind> parseBrushKind(const std::string& name) {
  if (name == "pencil") return BrushKind::kPencil;
  if (name == "marker") return BrushKind::kMarker;
  return Error::usage("unknown brush '" + name + "' (expected pencil or marker)");
}

Image resampleBrush(const Image& brush, int width, int height) {
  Image out(width, height);
  if (brush.width <= 0 || brush.height <= 0) return out;
  const float sx = static_cast<float>(brush.width) / width, sy = static_cast<float>(brush.height) / height;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      // The source pixels whose centres fall in the output pixel's footprint (at least the
      // nearest one).
      const int x0 = static_cast<int>(std::floor(x * sx)), x1 = std::max(x0 + 1, static_cast<int>(std::floor((x + 1) * sx)));
      const int y0 = static_cast<int>(std::floor(y * sy)), y1 = std::max(y0 + 1, static_cast<int>(std::floor((y + 1) * sy)));
      float sum[4] = {0, 0, 0, 0};
      int n = 0;
      for (int j = y0; j < std::min(y1, brush.height); ++j)
        for (int i = x0; i < std::min(x1, brush.width); ++i) {
          const uint8_t* p = brush.pixel(i, j);
          for (int c = 0; c < 4; ++c) sum[c] += p[c];
          ++n;
        }
      uint8_t* q = out.pixel(x, y);
      for (int c = 0; c < 4; ++c) q[c] = static_cast<uint8_t>(std::lround(sum[c] / std::max(n, 1)));
    }
  return out;
}

std::string strokeStylePresetList() { return "plain, ink, pencil, marker"; }

Result<NamedStrokeStyle> loadStrokeStyle(const std::string& name_or_path) {
  if (name_or_path == "plain" || name_or_path == "ink" || name_or_path == "pencil" || name_or_path == "marker")
    return preset(name_or_path);
  const std::filesystem::path path(name_or_path);
  if (path.extension() != ".json")
    return Error::usage("--stroke-style: expected " + strokeStylePresetList() + " or a .json file, got '" +
                        name_or_path + "'");
  if (Status s = checkInputFile(path, "stroke style file"); !s) return s.error();
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) return Error::runtime(path.string() + ": cannot read (" + ec.message() + ")");
  if (size > (1u << 20)) return Error::runtime(path.string() + ": stroke style file larger than 1 MB");
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text.str());
  } catch (const std::exception& e) {  // parse_error, and out_of_range for numbers past double
    std::string what = e.what();
    if (const auto p = what.find("] "); p != std::string::npos) what = what.substr(p + 2);
    return Error::runtime(path.string() + ": not valid JSON (" + printableText(what, 300) + ")");
  }
  if (!j.is_object()) return Error::runtime(path.string() + ": expected an object of line kinds");
  NamedStrokeStyle out = preset("plain");
  out.name = name_or_path;
  const std::filesystem::path base = path.parent_path();
  if (j.contains("all")) {
    KindStrokeStyle all;
    if (Status s = readKind(j["all"], base, path.string() + ": all", all); !s) return s.error();
    out.kinds.fill(all);
  }
  for (const auto& [key, v] : j.items()) {
    if (key == "all") continue;
    const auto kind = parseLineKind(key);
    if (!kind)
      return Error::runtime(path.string() + ": unknown key \"" + printableText(key, 80) +
                            "\" (expected all or a line kind: " + lineKindList() + ")");
    if (Status s = readKind(v, base, path.string() + ": " + key, out.kinds[static_cast<int>(*kind)]); !s)
      return s.error();
  }
  return out;
}

void applyStrokeStyle(const NamedStrokeStyle& style, LineStyles& lines) {
  for (int k = 0; k < kLineKindCount; ++k) {
    const KindStrokeStyle& ks = style.kinds[k];
    LineStyle& ls = lines.kinds[k];
    ls.stroke = ks.stroke;
    if (ks.stroke.brush) ls.stroke.brush = periodBrush(*ks.stroke.brush, ks.stroke.brush_period_px);
    if (ks.set_color) ls.color = ks.color;
    ls.width_px *= ks.width_scale;
  }
}

Status prepareBrush(StrokeStyle& s) {
  if (s.brush_path.empty()) {
    s.brush.reset();
    return {};
  }
  if (auto kind = parseBrushKind(s.brush_path)) {
    s.brush = periodBrush(makeBrush(*kind), s.brush_period_px);
    return {};
  }
  auto img = readPng(s.brush_path);
  if (!img) return img.error();
  s.brush = periodBrush(*img, s.brush_period_px);
  return {};
}

nlohmann::json strokeStyleJson(const LineStyles& lines, const std::filesystem::path& base_dir) {
  static constexpr const char* kCaps[] = {"butt", "round", "square"};
  nlohmann::json j = nlohmann::json::object();
  for (int k = 0; k < kLineKindCount; ++k) {
    const StrokeStyle& s = lines.kinds[k].stroke;
    nlohmann::json o;
    o["cap"] = kCaps[static_cast<int>(s.cap)];
    o["taper_in"] = shortest(s.taper_in_px);
    o["taper_out"] = shortest(s.taper_out_px);
    o["taper_min"] = shortest(s.taper_min);
    o["depth_thickness"] = shortest(s.depth_thickness);
    o["strength_thickness"] = shortest(s.strength_thickness);
    o["curvature_thickness"] = shortest(s.curvature_thickness);
    o["depth_opacity"] = shortest(s.depth_opacity);
    o["strength_opacity"] = shortest(s.strength_opacity);
    o["curvature_opacity"] = shortest(s.curvature_opacity);
    o["dash"] = {shortest(s.dash_on), shortest(s.dash_off)};
    o["jitter"] = shortest(s.jitter_px);
    o["jitter_period"] = shortest(s.jitter_period_px);
    o["seed"] = s.seed;
    o["min_length"] = shortest(s.min_length_px);
    o["smoothing"] = shortest(s.smoothing_px);
    std::string brush = "none";
    if (!s.brush_path.empty())
      brush = parseBrushKind(s.brush_path) ? s.brush_path
                                           : std::filesystem::absolute(s.brush_path)
                                                 .lexically_relative(std::filesystem::absolute(base_dir))
                                                 .generic_string();
    o["brush"] = brush;
    o["brush_period"] = shortest(s.brush_period_px);
    j[lineKindName(static_cast<LineKind>(k))] = std::move(o);
  }
  return j;
}

Status writeStrokeStyleFile(const std::filesystem::path& path, const LineStyles& lines) {
  const nlohmann::json j = strokeStyleJson(lines, path.parent_path());
  return writeFileAtomically(path, [&](std::ostream& out) -> Status {
    out << j.dump(2) << "\n";
    return {};
  });
}

}  // namespace lodline
