#include "app/options.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>

#include <glm/geometric.hpp>

#include "io/scene_file.h"
#include "io/stroke_style_file.h"

namespace lodline {

void addViewOptions(CLI::App& cmd, ViewOptions& o) {
  cmd.add_option("model", o.models,
                 "Mesh file (.off, .obj, .ply, .stl; polygons are triangulated), scene file (.json, "
                 "docs/scenes.md) or glTF 2.0 file (.gltf, .glb); default: the default model (knot.off), "
                 "found beside the program (share/lodline/models when installed, models/ in the source tree)");
  cmd.add_option("--size", o.size, "Image size WxH in pixels")->capture_default_str();
  cmd.add_option("--view", o.view,
                 "Camera as AZ,EL,DIST: azimuth and elevation in degrees, distance in "
                 "bounding-sphere radii, 0 = frame the whole model (default: 35,20,0, a 3/4 view)");
  cmd.add_option("--fov", o.fov_deg, "Vertical field of view in degrees (1-170)")->capture_default_str();
  cmd.add_option("--style", o.style,
                 "lines (lines on the background), toon (toon-shaded faces + lines) or shaded "
                 "(Blinn-Phong faces + chamfer edge highlights + lines)")
      ->capture_default_str();
  cmd.add_option("--line-width", o.line_width,
                 "Contour width in pixels; the other line kinds scale with it (default 2.5)");
  cmd.add_option("--background", o.background,
                 "Background colour: #rrggbb, #rrggbbaa, transparent or a name (white, paper, ...)")
      ->capture_default_str();
  cmd.add_option("--msaa", o.msaa, "Multisample count for antialiasing (1 = off, up to 4 on llvmpipe)")
      ->capture_default_str();
  cmd.add_option("--line-style", o.line_styles,
                 "Colour and width of one line kind, KIND=COLOUR[:WIDTH], e.g. suggestive=#804020:1.2 "
                 "(repeatable; applied after --line-width)");
  cmd.add_option("--stroke-style", o.stroke_style,
                 "How strokes are drawn: plain, ink, pencil, marker, or a style file (.json): caps, tapering, "
                 "thickness and opacity by depth, strength and bend, dashes, jitter, brush (docs/strokes.md)")
      ->capture_default_str();
  cmd.add_option("--lines", o.lines,
                 "Comma-separated line kinds to draw: contour, suggestive, crease, boundary, intersection, "
                 "isophote, topo, parabolic, ridge, valley, suggestive-highlight, apparent-ridge, principal-highlight, "
                 "material (or none; docs/lines.md)")
      ->capture_default_str();
  cmd.add_option("--hidden-lines", o.hidden_lines,
                 "Draw the hidden parts of lines too: off, or COLOUR[:WIDTH][:dash=ON,OFF] (pixels), e.g. "
                 "grey:1:dash=4,3 (docs/visibility.md)")
      ->capture_default_str();
  cmd.add_option("--outline", o.outline,
                 "complete: where the interpolated contour leaves the object's outline (coarse meshes), the "
                 "mesh's own silhouette edges draw it; contour: the interpolated contour only")
      ->capture_default_str();
  cmd.add_option("--contour-creases", o.contour_creases,
                 "on: where a crease is itself a silhouette (its two faces face opposite ways) the contour "
                 "runs along it, not across the faces beside it (CAD parts' sharp rims); off: n.v = 0 "
                 "interpolated from vertex normals everywhere, as rtsc draws it (docs/lines.md)")
      ->capture_default_str();
  cmd.add_option("--suggestive-at-creases", o.suggestive_at_creases,
                 "off: suggestive contours and highlights leave out the faces with a corner on a crease, where "
                 "curvature is undefined and its estimate draws scratches beside the edge (CAD parts); on: "
                 "drawn there too, as rtsc draws them (docs/lines.md)")
      ->capture_default_str();
  cmd.add_option("--chamfer", o.chamfer,
                 "Chamfer highlights on sharp edges: auto (with --style shaded), on (also over "
                 "toon) or off")
      ->capture_default_str();
  cmd.add_option("--chamfer-radius", o.chamfer_radius,
                 "Rounded-edge radius r_e in model units (0 = auto: 0.004 x bounding radius)")
      ->capture_default_str();
  cmd.add_option("--chamfer-k", o.chamfer_k,
                 "K of the highlight weight W = K*r_e/(d*r_max), pixels (0 = auto: focal length)")
      ->capture_default_str();
  cmd.add_option("--chamfer-angle", o.chamfer_angle,
                 "Dihedral angle in degrees from which an edge is sharp (1-180)")
      ->capture_default_str();
  cmd.add_option("--chamfer-shininess", o.chamfer_shininess,
                 "Blinn-Phong exponent of the shaded faces and highlights (1-127)")
      ->capture_default_str();
  cmd.add_option("--chamfer-compose", o.chamfer_compose,
                 "How highlights meet the faces: replace (the strip replaces the face bands it "
                 "rounds off) or alpha (the paper's blend with W = K*r_e/(d*r_max))")
      ->capture_default_str();
  cmd.add_option("--suggestive-threshold", o.suggestive_threshold,
                 "Suggestive contours where tan(theta)*Dw kr exceeds this / feature size^2 (larger: fewer)")
      ->capture_default_str();
  cmd.add_option("--suggestive-fade", o.suggestive_fade,
                 "Fade of weak suggestive contours (0 = no fading)")
      ->capture_default_str();
  cmd.add_option("--suggestive-motion-fade", o.suggestive_motion_fade,
                 "off, or START,END in px/s: in sequences (capture, view) suggestive contours that slide over "
                 "the surface faster than START fade, gone at END (DeCarlo et al. 2004; docs/temporal-coherence.md)")
      ->capture_default_str();
  cmd.add_option("--crease-angle", o.crease_angle, "Dihedral angle in degrees above which an edge is a crease line")
      ->capture_default_str();
  cmd.add_option("--isophote-spacing", o.isophote_spacing,
                 "Isophotes (--lines ...,isophote) at n.l = 0, S, 2S, ... under the frame's light")
      ->capture_default_str();
  cmd.add_option("--topo-spacing", o.topo_spacing,
                 "Topographic lines (--lines ...,topo) every S times the object's bounding-box diagonal")
      ->capture_default_str();
  cmd.add_option("--topo-axis", o.topo_axis, "X,Y,Z: the up axis of the topographic lines' heights (world)")
      ->capture_default_str();
  cmd.add_option("--parabolic-threshold", o.parabolic_threshold,
                 "Parabolic lines (--lines ...,parabolic, K = 0) only where max(|k1|,|k2|) exceeds this / feature size")
      ->capture_default_str();
  cmd.add_option("--ridge-threshold", o.ridge_threshold,
                 "Ridges and valleys (--lines ...,ridge,valley) where the dominant |k| exceeds this / feature size "
                 "(faded in up to twice it)")
      ->capture_default_str();
  cmd.add_option("--ridge-estimator", o.ridge_estimator,
                 "Ridges' and valleys' curvature derivatives: tensor (the per-face estimate every curvature kind "
                 "shares: fast, keeps features a couple of edges wide, spurious ridges where curvature is flat "
                 "across them), fit (a degree-4 jet over ~3 edges round each candidate vertex: converges on "
                 "smooth surfaces, slower, smooths narrower features away; docs/lines.md)")
      ->capture_default_str();
  cmd.add_option("--apparent-ridge-threshold", o.apparent_ridge_threshold,
                 "Apparent ridges (--lines ...,apparent-ridge) where the view-dependent curvature q1 exceeds this / "
                 "feature size (faded in up to twice it)")
      ->capture_default_str();
  cmd.add_option("--principal-highlight-threshold", o.principal_highlight_threshold,
                 "Principal highlights (--lines ...,principal-highlight) where (kd^2 - ko^2)*n.v*fs^2 exceeds this "
                 "(faded in up to twice it)")
      ->capture_default_str();
}

namespace {

// "A,B,C": three finite numbers (spaces before each allowed), or nothing.
std::optional<std::array<float, 3>> parseThreeFloats(const std::string& s) {
  std::array<float, 3> vals{};
  std::stringstream ss(s);
  std::string item;
  int n = 0;
  while (std::getline(ss, item, ',')) {
    if (n >= 3) return std::nullopt;
    const char* b = item.data();
    while (*b == ' ') ++b;
    auto [p, ec] = std::from_chars(b, item.data() + item.size(), vals[n]);
    if (ec != std::errc() || p != item.data() + item.size() || !std::isfinite(vals[n])) return std::nullopt;
    ++n;
  }
  if (n != 3) return std::nullopt;
  return vals;
}

}  // namespace

Result<OrbitView> parseOrbitView(const std::string& s) {
  const auto bad = Error::usage("--view: invalid value '" + s +
                                "' (expected AZ,EL,DIST, e.g. 30,20,3; DIST in bounding radii, 0 = frame the model)");
  OrbitView v;
  const auto parsed = parseThreeFloats(s);
  if (!parsed) return bad;
  const auto& vals = *parsed;
  if (vals[2] < 0.0f || vals[1] < -90.0f || vals[1] > 90.0f) return bad;
  v.azimuth_deg = vals[0];
  v.elevation_deg = vals[1];
  v.distance = vals[2];
  return v;
}

Result<ResolvedView> resolveViewOptions(const ViewOptions& o) {
  ResolvedView r;
  if (o.models.size() != 1)
    return Error::usage("give exactly one MODEL (a mesh, scene or glTF file; got " + std::to_string(o.models.size()) +
                        ")");
  r.model = o.models[0];
  auto size = parseSize(o.size);
  if (!size) return size.error();
  r.frame.width = (*size)[0];
  r.frame.height = (*size)[1];
  if (!o.view.empty()) {
    auto v = parseOrbitView(o.view);
    if (!v) return v.error();
    r.orbit = *v;
    r.orbit_given = true;
  }
  if (!(o.fov_deg >= 1.0f && o.fov_deg <= 170.0f))
    return Error::usage("--fov: " + std::to_string(o.fov_deg) + " is out of range (1-170 degrees)");
  r.fov_deg = o.fov_deg;
  auto style = parseStyle(o.style);
  if (!style) return style.error();
  r.style.style = *style;
  auto strokes = loadStrokeStyle(o.stroke_style);
  if (!strokes) return strokes.error();
  applyStrokeStyle(*strokes, r.style.lines);
  r.style.stroke_style = strokes->name;
  if (o.line_width != 0.0f) {
    if (!(o.line_width > 0.0f && o.line_width <= 64.0f))
      return Error::usage("--line-width: must be in (0, 64] pixels");
    r.style.lines.scaleWidths(o.line_width / r.style.lines[LineKind::kContour].width_px);
  }
  auto bg = parseColor(o.background);
  if (!bg) return Error::usage("--background: " + bg.error().message);
  r.frame.background = *bg;
  if (o.msaa < 1 || o.msaa > 16) return Error::usage("--msaa: must be 1..16");
  r.frame.msaa = o.msaa;
  ChamferParams& ch = r.style.chamfer;
  if (o.chamfer == "auto") {
    ch.enabled = true;
    ch.over_toon = false;
  } else if (o.chamfer == "on") {
    ch.enabled = true;
    ch.over_toon = true;
  } else if (o.chamfer == "off") {
    ch.enabled = false;
    ch.over_toon = false;
  } else {
    return Error::usage("--chamfer: unknown value '" + o.chamfer + "' (expected auto, on or off)");
  }
  if (!(o.chamfer_radius >= 0.0f) || !std::isfinite(o.chamfer_radius))
    return Error::usage("--chamfer-radius: must be >= 0 model units (0 = auto)");
  ch.radius = o.chamfer_radius;
  if (!(o.chamfer_k >= 0.0f) || !std::isfinite(o.chamfer_k))
    return Error::usage("--chamfer-k: must be >= 0 pixels (0 = auto)");
  ch.k = o.chamfer_k;
  if (!(o.chamfer_angle >= 1.0f && o.chamfer_angle <= 180.0f))
    return Error::usage("--chamfer-angle: must be in [1, 180] degrees");
  ch.threshold_deg = o.chamfer_angle;
  if (!(o.chamfer_shininess >= 1.0f && o.chamfer_shininess <= 127.0f))
    return Error::usage("--chamfer-shininess: must be in [1, 127]");
  ch.shininess = o.chamfer_shininess;
  if (o.chamfer_compose == "replace")
    ch.compose = ChamferCompose::kReplace;
  else if (o.chamfer_compose == "alpha")
    ch.compose = ChamferCompose::kAlpha;
  else
    return Error::usage("--chamfer-compose: unknown value '" + o.chamfer_compose +
                        "' (expected replace or alpha)");
  for (const std::string& spec : o.line_styles) {
    const auto bad = Error::usage("--line-style: invalid value '" + spec +
                                  "' (expected KIND=COLOUR[:WIDTH], KIND one of " + lineKindList() + ")");
    const auto eq = spec.find('=');
    if (eq == std::string::npos) return bad;
    const std::string kind = spec.substr(0, eq);
    std::string colour = spec.substr(eq + 1), width;
    if (const auto colon = colour.find(':'); colon != std::string::npos) {
      width = colour.substr(colon + 1);
      colour = colour.substr(0, colon);
    }
    const auto parsed_kind = parseLineKind(kind);
    if (!parsed_kind) return bad;
    const int index = static_cast<int>(*parsed_kind);
    auto c = parseColor(colour);
    if (!c) return Error::usage("--line-style: " + c.error().message);
    r.style.lines.kinds[index].color = *c;
    if (!width.empty()) {
      float w = 0.0f;
      auto [p, ec] = std::from_chars(width.data(), width.data() + width.size(), w);
      if (ec != std::errc() || p != width.data() + width.size() || !(w > 0.0f && w <= 64.0f)) return bad;
      r.style.lines.kinds[index].width_px = w;
    }
  }
  if (!(o.suggestive_threshold >= 0.0f && o.suggestive_threshold <= 100.0f))
    return Error::usage("--suggestive-threshold: must be in [0, 100]");
  if (!(o.suggestive_fade >= 0.0f && o.suggestive_fade <= 100.0f))
    return Error::usage("--suggestive-fade: must be in [0, 100]");
  if (!(o.crease_angle >= 0.0f && o.crease_angle <= 180.0f)) return Error::usage("--crease-angle: must be in [0, 180] degrees");
  r.line_params.suggestive_threshold = o.suggestive_threshold;
  r.line_params.suggestive_fade = o.suggestive_fade;
  if (o.suggestive_motion_fade == "off") {
    r.line_params.suggestive_motion_fade_end = 0.0f;
  } else {
    const auto bad = Error::usage("--suggestive-motion-fade: expected off or START,END in px/s with 0 <= START < END, got '" +
                                  o.suggestive_motion_fade + "'");
    const auto comma = o.suggestive_motion_fade.find(',');
    if (comma == std::string::npos) return bad;
    char* end = nullptr;
    const std::string a = o.suggestive_motion_fade.substr(0, comma), b = o.suggestive_motion_fade.substr(comma + 1);
    const float start = std::strtof(a.c_str(), &end);
    if (a.empty() || *end != '\0') return bad;
    const float stop = std::strtof(b.c_str(), &end);
    if (b.empty() || *end != '\0' || !(start >= 0.0f && start < stop && stop <= 1e6f)) return bad;
    r.line_params.suggestive_motion_fade_start = start;
    r.line_params.suggestive_motion_fade_end = stop;
  }
  r.line_params.crease_angle_deg = o.crease_angle;
  if (!(o.isophote_spacing >= 0.01f && o.isophote_spacing <= 1.0f))
    return Error::usage("--isophote-spacing: must be in [0.01, 1] (a step of n.l)");
  r.line_params.isophote_spacing = o.isophote_spacing;
  r.line_params.light_dir_eye = r.frame.light_dir_eye;
  if (!(o.topo_spacing >= 1e-3f && o.topo_spacing <= 1.0f))
    return Error::usage("--topo-spacing: must be in [0.001, 1] (a fraction of the bounding-box diagonal)");
  r.line_params.topo_spacing = o.topo_spacing;
  {
    const auto a = parseThreeFloats(o.topo_axis);
    if (!a || ((*a)[0] == 0.0f && (*a)[1] == 0.0f && (*a)[2] == 0.0f))
      return Error::usage("--topo-axis: expected X,Y,Z (a non-zero direction), got '" + o.topo_axis + "'");
    r.line_params.topo_axis = glm::normalize(glm::vec3((*a)[0], (*a)[1], (*a)[2]));
  }
  if (!(o.parabolic_threshold >= 0.0f && o.parabolic_threshold <= 1e3f))
    return Error::usage("--parabolic-threshold: must be in [0, 1000]");
  r.line_params.parabolic_threshold = o.parabolic_threshold;
  if (!(o.ridge_threshold > 0.0f && o.ridge_threshold <= 1e3f))
    return Error::usage("--ridge-threshold: must be in (0, 1000]");
  r.line_params.ridge_threshold = o.ridge_threshold;
  if (o.ridge_estimator == "fit") r.line_params.ridge_estimator = RidgeEstimator::kFit;
  else if (o.ridge_estimator == "tensor") r.line_params.ridge_estimator = RidgeEstimator::kTensor;
  else return Error::usage("--ridge-estimator: expected tensor or fit, got '" + o.ridge_estimator + "'");
  if (!(o.apparent_ridge_threshold > 0.0f && o.apparent_ridge_threshold <= 1e3f))
    return Error::usage("--apparent-ridge-threshold: must be in (0, 1000]");
  r.line_params.apparent_ridge_threshold = o.apparent_ridge_threshold;
  if (!(o.principal_highlight_threshold > 0.0f && o.principal_highlight_threshold <= 1e3f))
    return Error::usage("--principal-highlight-threshold: must be in (0, 1000]");
  r.line_params.principal_highlight_threshold = o.principal_highlight_threshold;
  if (o.outline != "complete" && o.outline != "contour")
    return Error::usage("--outline: expected complete or contour, got '" + o.outline + "'");
  r.line_params.complete_outline = o.outline == "complete";
  if (o.contour_creases != "on" && o.contour_creases != "off")
    return Error::usage("--contour-creases: expected on or off, got '" + o.contour_creases + "'");
  r.line_params.contours_follow_creases = o.contour_creases == "on";
  if (o.suggestive_at_creases != "on" && o.suggestive_at_creases != "off")
    return Error::usage("--suggestive-at-creases: expected on or off, got '" + o.suggestive_at_creases + "'");
  r.line_params.suggestive_off_creases = o.suggestive_at_creases == "off";
  auto hidden = parseHiddenLines(o.hidden_lines);
  if (!hidden) return hidden.error();
  r.style.hidden = *hidden;
  for (auto& k : r.style.lines.kinds) k.enabled = false;
  std::stringstream ss(o.lines);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (item == "none" || item.empty()) continue;
    const auto kind = parseLineKind(item);
    if (!kind)
      return Error::usage("--lines: unknown line kind '" + item + "' (expected " + lineKindList() + " or none)");
    r.style.lines[*kind].enabled = true;
  }
  return r;
}

Result<ObjectStyle> resolveObjectStyle(const ViewOptions& base, const nlohmann::json& style,
                                       const std::string& where) {
  ViewOptions o = base;
  o.models = {"(object)"};  // styles do not depend on the input
  auto text = [](const nlohmann::json& v) {
    if (v.is_string()) return v.get<std::string>();
    return v.dump();
  };
  auto number = [&](const nlohmann::json& v, const std::string& key, float& out) -> Status {
    // As double first: a value beyond float's range must not be narrowed (undefined).
    if (v.is_number() && std::abs(v.get<double>()) <= 1e30) {
      out = static_cast<float>(v.get<double>());
      return {};
    }
    return Error::runtime(where + "." + key + ": expected a number (|x| <= 1e30)");
  };
  for (const auto& [key, v] : style.items()) {
    if (key == "style") o.style = text(v);
    else if (key == "lines") o.lines = text(v);
    else if (key == "line-style") {
      // Object line styles come after the frame's, so they win per kind.
      if (v.is_array())
        for (const auto& e : v) o.line_styles.push_back(text(e));
      else
        o.line_styles.push_back(text(v));
    } else if (key == "line-width") {
      if (Status s = number(v, key, o.line_width); !s) return s.error();
    } else if (key == "hidden-lines") o.hidden_lines = text(v);
    else if (key == "stroke-style") o.stroke_style = text(v);
    else if (key == "chamfer") o.chamfer = text(v);
    else if (key == "chamfer-radius") {
      if (Status s = number(v, key, o.chamfer_radius); !s) return s.error();
    } else {
      return Error::runtime(where + ": unknown style key \"" + key + "\"");
    }
  }
  auto r = resolveViewOptions(o);
  if (!r) return Error::runtime(where + ": " + r.error().message);
  return r->style;
}

namespace {

std::string hexColour(const glm::vec4& c) {
  auto byte = [](float v) { return static_cast<int>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
  char buf[16];
  std::snprintf(buf, sizeof(buf), "#%02x%02x%02x%02x", byte(c.r), byte(c.g), byte(c.b), byte(c.a));
  return buf;
}

// Shortest text that reads back as the same float (so a saved view renders the same bits).
std::string exact(float v) {
  char buf[32];
  for (int digits = 6; digits <= 9; ++digits) {
    std::snprintf(buf, sizeof(buf), "%.*g", digits, static_cast<double>(v));
    if (std::strtof(buf, nullptr) == v) break;
  }
  return buf;
}

}  // namespace

nlohmann::json settingsOf(const FrameParams& frame, const ObjectStyle& style, const ResolvedDetail& detail,
                          const LineParams& lines, const std::filesystem::path& base_dir) {
  nlohmann::json s;
  s["size"] = std::to_string(frame.width) + "x" + std::to_string(frame.height);
  s["style"] = styleName(style.style);
  s["background"] = hexColour(frame.background);
  s["msaa"] = frame.msaa;
  std::string kinds;
  nlohmann::json line_styles = nlohmann::json::array();
  for (int k = 0; k < kLineKindCount; ++k) {
    const LineStyle& ls = style.lines.kinds[k];
    const char* name = lineKindName(static_cast<LineKind>(k));
    if (ls.enabled) kinds += (kinds.empty() ? "" : ",") + std::string(name);
    line_styles.push_back(std::string(name) + "=" + hexColour(ls.color) + ":" + exact(ls.width_px));
  }
  s["lines"] = kinds.empty() ? "none" : kinds;
  s["line-style"] = line_styles;
  // A style file is written relative to the saved view, like the detail map.
  s["stroke-style"] = std::filesystem::path(style.stroke_style).extension() == ".json"
                          ? pathRelativeTo(style.stroke_style, base_dir)
                          : style.stroke_style;
  const ChamferParams& ch = style.chamfer;
  s["chamfer"] = !ch.enabled ? "off" : ch.over_toon ? "on" : "auto";
  s["chamfer-radius"] = exact(ch.radius);
  s["chamfer-k"] = exact(ch.k);
  s["chamfer-angle"] = exact(ch.threshold_deg);
  s["chamfer-shininess"] = exact(ch.shininess);
  s["chamfer-compose"] = ch.compose == ChamferCompose::kAlpha ? "alpha" : "replace";
  s["suggestive-threshold"] = exact(lines.suggestive_threshold);
  s["suggestive-fade"] = exact(lines.suggestive_fade);
  s["suggestive-motion-fade"] = lines.suggestive_motion_fade_end > 0.0f
                                    ? exact(lines.suggestive_motion_fade_start) + "," + exact(lines.suggestive_motion_fade_end)
                                    : std::string("off");
  s["crease-angle"] = exact(lines.crease_angle_deg);
  s["isophote-spacing"] = exact(lines.isophote_spacing);
  s["topo-spacing"] = exact(lines.topo_spacing);
  s["topo-axis"] = exact(lines.topo_axis.x) + "," + exact(lines.topo_axis.y) + "," + exact(lines.topo_axis.z);
  s["parabolic-threshold"] = exact(lines.parabolic_threshold);
  s["ridge-threshold"] = exact(lines.ridge_threshold);
  s["ridge-estimator"] = lines.ridge_estimator == RidgeEstimator::kFit ? "fit" : "tensor";
  s["apparent-ridge-threshold"] = exact(lines.apparent_ridge_threshold);
  s["principal-highlight-threshold"] = exact(lines.principal_highlight_threshold);
  s["outline"] = lines.complete_outline ? "complete" : "contour";
  s["contour-creases"] = lines.contours_follow_creases ? "on" : "off";
  s["suggestive-at-creases"] = lines.suggestive_off_creases ? "off" : "on";
  s["hidden-lines"] = formatHiddenLines(style.hidden);

  const DetailParams& d = detail.params;
  s["lod"] = lodChoiceName(detail.lod);
  if (const auto* cluster = std::get_if<ClusteredDetail>(&detail.lod)) s["pixel-error"] = exact(cluster->params.pixel_error);
  s["target-area"] = exact(d.target_area);
  s["t-collapse"] = exact(d.t_c);
  s["t-split"] = exact(d.t_s);
  if (!detail.detail_map_file.empty()) s["detail-map"] = pathRelativeTo(detail.detail_map_file, base_dir);
  s["detail-map-scale"] = exact(detail.detail_map_scale);
  s["depth-falloff"] = exact(d.depth_falloff);
  s["foveation"] = exact(d.foveation);
  if (d.focus_px.x >= 0.0f && d.focus_px.y >= 0.0f) s["focus"] = exact(d.focus_px.x) + "," + exact(d.focus_px.y);
  s["object-factor"] = exact(d.object_factor);
  s["geomorphs"] = d.geomorphs ? "on" : "off";
  s["morph-time"] = exact(d.morph_time);
  s["adapt-budget"] = exact(d.max_adapt_ms);
  s["min-suggestive-length"] = exact(d.min_suggestive_length);
  s["smoothing"] = detail.smoothing.enabled ? "on" : "off";
  s["smoothing-alpha"] = exact(detail.smoothing.alpha);
  s["smoothing-time"] = exact(detail.smoothing.seconds);
  s["max-adapt-frames"] = detail.max_adapt_frames;
  return s;
}

void addCaptureOptions(CLI::App& cmd, CapturePathOptions& o) {
  cmd.add_option("--path", o.path,
                 "Camera path: orbit, zoom-out, dolly, flyover, or a path file (.json); default: the scene file's "
                 "camera path, else orbit")
      ->capture_default_str();
  cmd.add_option("--duration", o.duration, "Length of a built-in path in seconds")->capture_default_str();
  cmd.add_option("--frames", o.frames,
                 "N renders frames 0..N-1; A:B renders frames A..B-1 only (frame k is identical "
                 "whichever range renders it); default: the whole path");
  cmd.add_option("--fps", o.fps, "Simulated frame rate (the video's rate)")->capture_default_str();
  cmd.add_option("--stroke-coherence", o.stroke_coherence,
                 "on: brushes, dashes and jitter stay on the surface from frame to frame; off: they start at "
                 "each visible run's first point (docs/strokes.md)")
      ->capture_default_str();
  cmd.add_option("--fade-in", o.fade_in,
                 "Seconds over which a line that appears fades in (0: off); lines that continue one of the "
                 "previous frame keep their opacity (docs/temporal-coherence.md)")
      ->capture_default_str();
}

Result<FrameRange> parseFrameRange(const std::string& s, int64_t total) {
  FrameRange r{0, total};
  if (s.empty()) return r;
  const auto bad = Error::usage("--frames: invalid value '" + s + "' (expected N or A:B with 0 <= A < B)");
  auto parse = [](std::string_view v, int64_t& out) {
    auto [p, ec] = std::from_chars(v.data(), v.data() + v.size(), out);
    return ec == std::errc() && p == v.data() + v.size() && out >= 0;
  };
  const auto colon = s.find(':');
  if (colon == std::string::npos) {
    if (!parse(s, r.end) || r.end == 0) return bad;
    return r;
  }
  if (!parse(std::string_view(s).substr(0, colon), r.first) ||
      !parse(std::string_view(s).substr(colon + 1), r.end) || r.first >= r.end)
    return bad;
  return r;
}

Status resolveCaptureOptions(const CapturePathOptions& o, CameraPath path, CaptureRequest& rq) {
  if (!(o.fps > 0.0 && o.fps <= 1000.0)) return Error::usage("--fps: must be in (0, 1000]");
  auto range = parseFrameRange(o.frames, captureFrameCount(path, o.fps));
  if (!range) return range.error();
  if (o.stroke_coherence != "on" && o.stroke_coherence != "off")
    return Error::usage("--stroke-coherence: expected on or off, got '" + o.stroke_coherence + "'");
  if (!(o.fade_in >= 0.0f && o.fade_in <= 60.0f)) return Error::usage("--fade-in: must be in [0, 60] seconds");
  rq.path = std::move(path);
  rq.path_name = o.path;
  rq.fps = o.fps;
  rq.range = *range;
  rq.stroke_coherence = o.stroke_coherence == "on";
  rq.fade_in = o.fade_in;
  return {};
}

}  // namespace lodline
