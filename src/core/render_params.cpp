#include "core/render_params.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/printable.h"

namespace lodline {

void LineStyles::scaleWidths(float s) {
  for (auto& k : kinds) k.width_px *= s;
}

std::array<bool, kLineKindCount> ObjectStyle::enabledKinds() const {
  std::array<bool, kLineKindCount> enabled{};
  for (int k = 0; k < kLineKindCount; ++k) enabled[k] = lines.kinds[k].enabled;
  return enabled;
}

std::array<float, 256> toonRamp(const ToonParams& t) {
  std::array<float, 256> ramp;
  for (int i = 0; i < 256; ++i) {
    const float x = (static_cast<float>(i) + 0.5f) / 256.0f;
    ramp[i] = x < t.thresholds[0] ? t.tones[0] : x < t.thresholds[1] ? t.tones[1] : t.tones[2];
  }
  return ramp;
}

Result<Style> parseStyle(const std::string& s) {
  if (s == "toon") return Style::kToon;
  if (s == "lines") return Style::kLines;
  if (s == "shaded") return Style::kShaded;
  return Error::usage("--style: unknown style '" + s + "' (expected lines, toon or shaded)");
}

const char* styleName(Style s) {
  switch (s) {
    case Style::kLines: return "lines";
    case Style::kToon: return "toon";
    case Style::kShaded: return "shaded";
  }
  return "?";
}

Result<glm::vec4> parseColor(const std::string& s) {
  std::string t = s;
  std::transform(t.begin(), t.end(), t.begin(), [](unsigned char c) { return std::tolower(c); });
  if (t == "white") return glm::vec4(1, 1, 1, 1);
  if (t == "black") return glm::vec4(0, 0, 0, 1);
  if (t == "paper") return glm::vec4(0.98f, 0.96f, 0.91f, 1);
  if (t == "grey" || t == "gray") return glm::vec4(0.5f, 0.5f, 0.5f, 1);
  if (t == "red") return glm::vec4(0.8f, 0.1f, 0.1f, 1);
  if (t == "green") return glm::vec4(0.1f, 0.6f, 0.2f, 1);
  if (t == "blue") return glm::vec4(0.1f, 0.25f, 0.8f, 1);
  if (t == "transparent") return glm::vec4(1, 1, 1, 0);
  const auto bad = Error::usage("invalid colour '" + printableText(s, 80) +
                                "' (expected #rrggbb, #rrggbbaa, #rgb, transparent or a name)");
  if (t.size() < 2 || t[0] != '#') return bad;
  std::string hex = t.substr(1);
  if (hex.size() == 3) hex = {hex[0], hex[0], hex[1], hex[1], hex[2], hex[2]};
  if (hex.size() == 6) hex += "ff";
  if (hex.size() != 8) return bad;
  glm::vec4 c;
  for (int i = 0; i < 4; ++i) {
    unsigned v = 0;
    const char* b = hex.data() + 2 * i;
    auto [p, ec] = std::from_chars(b, b + 2, v, 16);
    if (ec != std::errc() || p != b + 2) return bad;
    c[i] = static_cast<float>(v) / 255.0f;
  }
  return c;
}

Result<HiddenLineStyle> parseHiddenLines(const std::string& s) {
  HiddenLineStyle h;
  if (s == "off") return h;
  const auto bad = Error::usage("--hidden-lines: invalid value '" + s +
                                "' (expected off or COLOUR[:WIDTH][:dash=ON,OFF], e.g. grey:1:dash=4,3)");
  h.enabled = true;
  std::vector<std::string> parts;
  size_t start = 0;
  while (true) {
    const size_t colon = s.find(':', start);
    parts.push_back(s.substr(start, colon == std::string::npos ? std::string::npos : colon - start));
    if (colon == std::string::npos) break;
    start = colon + 1;
  }
  auto c = parseColor(parts[0]);
  if (!c) return bad;
  h.color = *c;
  auto number = [](const std::string& t, float& out) {
    auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), out);
    return ec == std::errc() && p == t.data() + t.size() && std::isfinite(out);
  };
  for (size_t i = 1; i < parts.size(); ++i) {
    const std::string& part = parts[i];
    if (part.rfind("dash=", 0) == 0) {
      const std::string v = part.substr(5);
      const size_t comma = v.find(',');
      if (comma == std::string::npos || !number(v.substr(0, comma), h.dash_on) ||
          !number(v.substr(comma + 1), h.dash_off) || h.dash_on <= 0.0f || h.dash_off < 0.0f ||
          h.dash_on > 1000.0f || h.dash_off > 1000.0f)
        return bad;
    } else if (i == 1) {
      if (!number(part, h.width_px) || !(h.width_px > 0.0f && h.width_px <= 64.0f)) return bad;
    } else {
      return bad;
    }
  }
  return h;
}

std::string formatHiddenLines(const HiddenLineStyle& h) {
  if (!h.enabled) return "off";
  char buf[96];
  auto byte = [](float v) { return static_cast<int>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
  std::snprintf(buf, sizeof(buf), "#%02x%02x%02x%02x:%.9g:dash=%.9g,%.9g", byte(h.color.r), byte(h.color.g),
                byte(h.color.b), byte(h.color.a), static_cast<double>(h.width_px), static_cast<double>(h.dash_on),
                static_cast<double>(h.dash_off));
  return buf;
}

Result<std::array<int, 2>> parseSize(const std::string& s) {
  const auto bad = Error::usage("--size: invalid size '" + s + "' (expected WxH, e.g. 1280x720, each 16..16384)");
  const auto x = s.find_first_of("xX");
  if (x == std::string::npos) return bad;
  int w = 0, h = 0;
  auto r1 = std::from_chars(s.data(), s.data() + x, w);
  auto r2 = std::from_chars(s.data() + x + 1, s.data() + s.size(), h);
  if (r1.ec != std::errc() || r1.ptr != s.data() + x || r2.ec != std::errc() ||
      r2.ptr != s.data() + s.size())
    return bad;
  if (w < 16 || h < 16 || w > 16384 || h > 16384) return bad;
  return std::array<int, 2>{w, h};
}

}  // namespace lodline
