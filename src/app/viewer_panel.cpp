#include "app/viewer_panel.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "io/stroke_style_file.h"

namespace lodline {
namespace {

void copyText(std::array<char, 1024>& dst, const std::string& src) {
  const size_t n = std::min(src.size(), dst.size() - 1);
  std::memcpy(dst.data(), src.data(), n);
  dst[n] = '\0';
}

// Colours are kept on the 8-bit grid a saved view writes, so `render` of a saved view draws
// the same colours.
void quantize(glm::vec4& c) {
  for (int i = 0; i < 4; ++i) c[i] = std::round(std::clamp(c[i], 0.0f, 1.0f) * 255.0f) / 255.0f;
}

// Applies `edit` to the frame's parameters and to every object's style (the panel's style
// controls act on the whole scene); object-specific keys `keys` of the scene file no longer
// hold once the panel sets them.
template <class Edit>
void editAllStyles(ViewerSession& s, std::initializer_list<const char*> keys, Edit&& edit) {
  edit(s.defaultStyle());
  for (auto& o : s.scene().objects()) edit(o.style);
  auto& objects = s.description().objects;
  for (auto& o : objects)
    for (const char* k : keys) o.style.erase(k);
  s.touch();
}

const char* kStyles[] = {"lines", "toon", "shaded"};

void detailSection(ViewerSession& s, PanelState& st) {
  if (!ImGui::CollapsingHeader("Detail control", ImGuiTreeNodeFlags_DefaultOpen)) return;
  DetailParams& d = s.detail();
  const char* mode = std::holds_alternative<ProgressiveDetail>(s.lod())  ? "progressive mesh"
                     : std::holds_alternative<ClusteredDetail>(s.lod()) ? "vertex clustering"
                                                                         : "none (full detail)";
  ImGui::Text("Level of detail: %s", mode);
  ImGui::SliderFloat("T (px^2)", &d.target_area, 0.25f, 4096.0f, "%.3g", ImGuiSliderFlags_Logarithmic);
  {
    const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
    st.target_area_slider = {a.x, a.y, b.x, b.y};
  }
  float tc = d.t_c, ts = d.t_s;
  const bool tc_changed = ImGui::SliderFloat("t_c (collapse)", &tc, 0.05f, 1.5f, "%.3f");
  const bool ts_changed = ImGui::SliderFloat("t_s (split)", &ts, 0.2f, 4.0f, "%.3f");
  if (tc_changed || ts_changed) {
    if (tc > 0.0f && 2.0f * tc < ts) {
      d.t_c = tc;
      d.t_s = ts;
    } else {
      st.message = "t_c/t_s need 0 < 2*t_c < t_s";
    }
  }
  ImGui::Checkbox("Geomorphs", &d.geomorphs);
  ImGui::SliderFloat("Morph time (s)", &d.morph_time, 0.05f, 5.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
  ImGui::SliderFloat("Adapt budget (ms, 0 = none)", &d.max_adapt_ms, 0.0f, 50.0f, "%.1f");
  ImGui::SliderFloat("Shortest suggestive (x sqrt T)", &d.min_suggestive_length, 0.0f, 4.0f, "%.2f");
  ImGui::InputText("Detail map", st.detail_map.data(), st.detail_map.size());
  ImGui::SliderFloat("Map scale", &st.detail_map_scale, 0.25f, 64.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
  if (ImGui::Button("Load map")) {
    if (Status r = s.setDetailMap(st.detail_map.data(), st.detail_map_scale); !r) st.message = r.error().message;
    else st.message = st.detail_map[0] ? std::string("detail map loaded") : std::string("detail map cleared");
  }
  ImGui::SameLine();
  if (ImGui::Button("No map")) {
    st.detail_map[0] = '\0';
    (void)s.setDetailMap("", st.detail_map_scale);
    st.message = "detail map cleared";
  }
}

void objectsSection(ViewerSession& s) {
  if (!ImGui::CollapsingHeader("Objects", s.scene().size() > 1 ? ImGuiTreeNodeFlags_DefaultOpen : 0)) return;
  auto& objects = s.description().objects;
  for (size_t i = 0; i < s.scene().size(); ++i) {
    SceneDrawing::Object& o = s.scene()[i];
    ImGui::PushID(static_cast<int>(i));
    ImGui::Text("%s", o.name.c_str());
    ImGui::SliderFloat("factor on T", &o.detail_factor, 0.1f, 64.0f, "%.3g", ImGuiSliderFlags_Logarithmic);
    int style = static_cast<int>(o.style.style);
    if (ImGui::Combo("style", &style, kStyles, 3)) {
      o.style.style = static_cast<Style>(style);
      if (i < objects.size()) objects[i].style["style"] = kStyles[style];
      s.touch();
    }
    if (ImGui::Checkbox("hidden lines", &o.style.hidden.enabled)) {
      if (i < objects.size()) objects[i].style["hidden-lines"] = formatHiddenLines(o.style.hidden);
      s.touch();
    }
    ImGui::PopID();
  }
}

void smoothingSection(ViewerSession& s) {
  if (!ImGui::CollapsingHeader("Temporal smoothing")) return;
  SmoothingParams& p = s.smoothing();
  ImGui::Checkbox("Smooth normals, kr, Dw kr", &p.enabled);
  ImGui::SliderFloat("alpha", &p.alpha, 0.05f, 0.99f, "%.3f");
  ImGui::SliderFloat("within (s)", &p.seconds, 0.05f, 5.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
}

const char* kStrokeStyles[] = {"plain", "ink", "pencil", "marker"};

// The stroke style: a preset for every kind, as --stroke-style sets it (the preset's colours
// and widths replace the current ones), so that a saved view names it and renders the same.
void strokeStyleSection(ViewerSession& s) {
  int current = -1;
  for (int i = 0; i < 4; ++i)
    if (s.defaultStyle().stroke_style == kStrokeStyles[i]) current = i;
  // The preview names an edited style or a style file too.
  const std::string shown = std::filesystem::path(s.defaultStyle().stroke_style).filename().string();
  if (ImGui::BeginCombo("Stroke style", shown.c_str())) {
    for (int i = 0; i < 4; ++i)
      if (ImGui::Selectable(kStrokeStyles[i], i == current)) current = i + 4;  // + 4: picked now
    ImGui::EndCombo();
  }
  if (current >= 4) {
    auto preset = loadStrokeStyle(kStrokeStyles[current - 4]);
    if (preset)
      editAllStyles(s, {"stroke-style", "line-style", "line-width"}, [&](ObjectStyle& p) {
        LineStyles fresh;
        for (int k = 0; k < kLineKindCount; ++k) fresh.kinds[k].enabled = p.lines.kinds[k].enabled;
        applyStrokeStyle(*preset, fresh);
        p.lines = fresh;
        p.stroke_style = preset->name;
      });
  }
}

// Every field of the stroke style (docs/strokes.md's table), for one line kind or all of
// them; an edit makes the style an edited one, which "save view" writes as a style file.
void strokeFieldsSection(ViewerSession& s, PanelState& st) {
  if (!ImGui::TreeNode("Stroke fields")) return;
  std::string kinds = std::string("all kinds") + '\0';
  for (int k = 0; k < kLineKindCount; ++k) kinds += std::string(lineKindName(static_cast<LineKind>(k))) + '\0';
  int which = st.stroke_kind + 1;
  if (ImGui::Combo("edit", &which, kinds.c_str())) st.stroke_kind = which - 1;
  StrokeStyle f = s.defaultStyle().lines.kinds[std::max(st.stroke_kind, 0)].stroke;
  bool changed = false;
  int cap = static_cast<int>(f.cap);
  const char* caps[] = {"butt", "round", "square"};
  if (ImGui::Combo("cap", &cap, caps, 3)) {
    f.cap = static_cast<StrokeCap>(cap);
    changed = true;
  }
  changed |= ImGui::SliderFloat("taper in (px)", &f.taper_in_px, 0.0f, 64.0f, "%.1f");
  changed |= ImGui::SliderFloat("taper out (px)", &f.taper_out_px, 0.0f, 64.0f, "%.1f");
  changed |= ImGui::SliderFloat("taper min", &f.taper_min, 0.0f, 1.0f, "%.2f");
  changed |= ImGui::SliderFloat("thickness by depth", &f.depth_thickness, -1.0f, 1.0f, "%.2f");
  changed |= ImGui::SliderFloat("thickness by strength", &f.strength_thickness, 0.0f, 1.0f, "%.2f");
  changed |= ImGui::SliderFloat("thickness by bend", &f.curvature_thickness, -1.0f, 4.0f, "%.2f");
  changed |= ImGui::SliderFloat("opacity by depth", &f.depth_opacity, 0.0f, 1.0f, "%.2f");
  changed |= ImGui::SliderFloat("opacity by strength", &f.strength_opacity, 0.0f, 1.0f, "%.2f");
  changed |= ImGui::SliderFloat("opacity by bend", &f.curvature_opacity, 0.0f, 1.0f, "%.2f");
  changed |= ImGui::SliderFloat("dash on (px)", &f.dash_on, 0.0f, 64.0f, "%.1f");
  changed |= ImGui::SliderFloat("dash off (px, 0 = solid)", &f.dash_off, 0.0f, 64.0f, "%.1f");
  changed |= ImGui::SliderFloat("jitter (px)", &f.jitter_px, 0.0f, 8.0f, "%.2f");
  changed |= ImGui::SliderFloat("jitter period (px)", &f.jitter_period_px, 1.0f, 256.0f, "%.1f",
                                ImGuiSliderFlags_Logarithmic);
  changed |= ImGui::InputScalar("seed", ImGuiDataType_U32, &f.seed);
  changed |= ImGui::SliderFloat("min length (px)", &f.min_length_px, 0.0f, 64.0f, "%.1f");
  changed |= ImGui::SliderFloat("smoothing (px)", &f.smoothing_px, 0.0f, 16.0f, "%.1f");
  // The brush: none or a built-in one; a brush read from a file is kept until another is
  // picked.
  const bool from_file = !f.brush_path.empty() && !parseBrushKind(f.brush_path);
  const std::string brush_name = f.brush_path.empty() ? "none" : std::filesystem::path(f.brush_path).filename().string();
  bool brush_changed = false;
  if (ImGui::BeginCombo("brush", brush_name.c_str())) {
    for (const char* b : {"none", "pencil", "marker"})
      if (ImGui::Selectable(b, !from_file && brush_name == b)) {
        f.brush_path = std::string(b) == "none" ? "" : b;
        brush_changed = true;
      }
    ImGui::EndCombo();
  }
  brush_changed |= ImGui::SliderFloat("brush period (px)", &f.brush_period_px, 4.0f, 1024.0f, "%.0f",
                                      ImGuiSliderFlags_Logarithmic);
  if (brush_changed) {
    if (Status r = prepareBrush(f); !r) st.message = r.error().message;
    changed = true;
  }
  if (changed) s.setStrokeStyle(st.stroke_kind, f);
  ImGui::TreePop();
}

void linesSection(ViewerSession& s, PanelState& st) {
  if (!ImGui::CollapsingHeader("Lines")) return;
  strokeStyleSection(s);
  strokeFieldsSection(s, st);
  for (int k = 0; k < kLineKindCount; ++k) {
    ImGui::PushID(k);
    LineStyle ls = s.defaultStyle().lines.kinds[k];
    bool changed = ImGui::Checkbox(lineKindName(static_cast<LineKind>(k)), &ls.enabled);
    ImGui::SameLine(140.0f);
    if (ImGui::ColorEdit4("colour", &ls.color.r, ImGuiColorEditFlags_NoInputs | ImGuiColorEditFlags_NoLabel)) {
      quantize(ls.color);
      changed = true;
    }
    ImGui::SameLine();
    ImGui::SetNextItemWidth(110.0f);
    changed |= ImGui::SliderFloat("width", &ls.width_px, 0.5f, 8.0f, "%.2f px");
    if (changed)
      editAllStyles(s, {"lines", "line-style", "line-width"}, [&](ObjectStyle& p) { p.lines.kinds[k] = ls; });
    ImGui::PopID();
  }
  if (s.defaultStyle().lines[LineKind::kIntersection].enabled && !s.hasIntersectionLines())
    ImGui::TextDisabled("(no intersection lines: found when loading with the kind enabled)");
  // Hidden lines: every kind's hidden parts in one style.
  HiddenLineStyle h = s.defaultStyle().hidden;
  bool hidden_changed = ImGui::Checkbox("hidden lines", &h.enabled);
  ImGui::SameLine(140.0f);
  if (ImGui::ColorEdit4("hidden colour", &h.color.r, ImGuiColorEditFlags_NoInputs | ImGuiColorEditFlags_NoLabel)) {
    quantize(h.color);
    hidden_changed = true;
  }
  ImGui::SameLine();
  ImGui::SetNextItemWidth(110.0f);
  hidden_changed |= ImGui::SliderFloat("hidden width", &h.width_px, 0.5f, 8.0f, "%.2f px");
  hidden_changed |= ImGui::SliderFloat("Dash on (px)", &h.dash_on, 0.5f, 32.0f, "%.1f");
  hidden_changed |= ImGui::SliderFloat("Dash off (px, 0 = solid)", &h.dash_off, 0.0f, 32.0f, "%.1f");
  if (hidden_changed) editAllStyles(s, {"hidden-lines"}, [&](ObjectStyle& p) { p.hidden = h; });
  LineParams lp = s.lineParams();
  bool changed = ImGui::Checkbox("Complete the outline (mesh silhouette where the contour leaves it)", &lp.complete_outline);
  changed |= ImGui::Checkbox("Contour along silhouette creases", &lp.contours_follow_creases);
  changed |= ImGui::Checkbox("No suggestive lines at creases", &lp.suggestive_off_creases);
  changed |= ImGui::SliderFloat("Suggestive threshold", &lp.suggestive_threshold, 0.0f, 0.2f, "%.4f");
  changed |= ImGui::SliderFloat("Suggestive fade", &lp.suggestive_fade, 0.0f, 0.2f, "%.4f");
  changed |= ImGui::SliderFloat("Motion fade from (px/s)", &lp.suggestive_motion_fade_start, 0.0f, 200.0f, "%.1f");
  changed |= ImGui::SliderFloat("Motion fade to (px/s, 0 = off)", &lp.suggestive_motion_fade_end, 0.0f, 400.0f, "%.1f");
  changed |= ImGui::SliderFloat("Crease angle (deg)", &lp.crease_angle_deg, 1.0f, 179.0f, "%.1f");
  changed |= ImGui::SliderFloat("Isophote spacing (n.l)", &lp.isophote_spacing, 0.05f, 1.0f, "%.3f");
  changed |= ImGui::SliderFloat("Topo spacing (of diagonal)", &lp.topo_spacing, 0.005f, 0.25f, "%.4f",
                                ImGuiSliderFlags_Logarithmic);
  changed |= ImGui::SliderFloat("Parabolic threshold", &lp.parabolic_threshold, 0.0f, 1.0f, "%.3f");
  changed |= ImGui::SliderFloat("Ridge/valley threshold", &lp.ridge_threshold, 0.005f, 2.0f, "%.3f",
                                ImGuiSliderFlags_Logarithmic);
  {
    int estimator = static_cast<int>(lp.ridge_estimator);
    changed |= ImGui::Combo("Ridge/valley derivatives", &estimator, "per-face tensor\0fitted jet (slower)\0");
    lp.ridge_estimator = static_cast<RidgeEstimator>(estimator);
  }
  changed |= ImGui::SliderFloat("Apparent-ridge threshold", &lp.apparent_ridge_threshold, 0.005f, 2.0f, "%.3f",
                                ImGuiSliderFlags_Logarithmic);
  changed |= ImGui::SliderFloat("Principal-highlight threshold", &lp.principal_highlight_threshold, 0.001f, 1.0f,
                                "%.3f", ImGuiSliderFlags_Logarithmic);
  if (changed) s.setLineParams(lp);
}

void styleSection(ViewerSession& s) {
  if (!ImGui::CollapsingHeader("Style")) return;
  int style = static_cast<int>(s.defaultStyle().style);
  if (ImGui::Combo("Style (all objects)", &style, kStyles, 3)) s.setStyleAll(static_cast<Style>(style));
  ChamferParams ch = s.defaultStyle().chamfer;
  int mode = !ch.enabled ? 2 : ch.over_toon ? 1 : 0;
  const char* modes[] = {"auto (shaded style)", "on (also over toon)", "off"};
  bool changed = ImGui::Combo("Chamfer", &mode, modes, 3);
  ch.enabled = mode != 2;
  ch.over_toon = mode == 1;
  changed |= ImGui::InputFloat("Radius r_e (0 = auto)", &ch.radius, 0.0f, 0.0f, "%.5g");
  changed |= ImGui::InputFloat("K (0 = auto)", &ch.k, 0.0f, 0.0f, "%.5g");
  changed |= ImGui::SliderFloat("Sharp angle (deg)", &ch.threshold_deg, 1.0f, 180.0f, "%.1f");
  changed |= ImGui::SliderFloat("Shininess", &ch.shininess, 1.0f, 127.0f, "%.0f");
  int compose = ch.compose == ChamferCompose::kAlpha ? 1 : 0;
  const char* composes[] = {"replace", "alpha (paper)"};
  if (ImGui::Combo("Compose", &compose, composes, 2)) {
    ch.compose = compose == 1 ? ChamferCompose::kAlpha : ChamferCompose::kReplace;
    changed = true;
  }
  if (changed) {
    ch.radius = std::isfinite(ch.radius) ? std::max(ch.radius, 0.0f) : 0.0f;
    ch.k = std::isfinite(ch.k) ? std::max(ch.k, 0.0f) : 0.0f;
    editAllStyles(s, {"chamfer", "chamfer-radius"}, [&](ObjectStyle& p) { p.chamfer = ch; });
  }
}

void statsSection(const ViewerSession& s, const PanelState& st) {
  if (!ImGui::CollapsingHeader("Frame statistics", ImGuiTreeNodeFlags_DefaultOpen)) return;
  const FrameReport& r = s.report();
  const ObjectReport& t = r.total;
  ImGui::Text("%.1f fps", static_cast<double>(st.fps));
  if (ImGui::BeginTable("ms", 4)) {
    auto cell = [](const char* name, double ms) {
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(name);
      ImGui::TableNextColumn();
      ImGui::Text("%.2f ms", ms);
    };
    cell("adapt", r.ms.adapt);
    cell("shape", r.ms.shape);
    cell("view", r.ms.view);
    cell("extract", r.ms.extract);
    cell("chain", r.ms.chain);
    cell("upload", r.ms.upload);
    cell("draw", r.ms.render);
    cell("visibility", r.ms.visibility);
    cell("strokes", r.ms.strokes);
    ImGui::EndTable();
  }
  const auto u = [](uint64_t v) { return static_cast<unsigned long long>(v); };
  ImGui::Text("active faces %llu, visible %llu", u(t.active_faces), u(t.lod ? t.lod->visible_faces : 0));
  if (t.lod) ImGui::Text("splits %llu, collapses %llu, morphing %llu", u(t.lod->splits), u(t.lod->collapses), u(t.lod->morphing));
  ImGui::Text("strokes %llu visible (%llu extracted), specks %llu", u(t.strokes), u(t.strokes_extracted), u(t.specks));
  ImGui::Text("line pixels %llu", u(t.line_pixels));
}

}  // namespace

void initPanel(const ViewerSession& session, PanelState& state) {
  copyText(state.detail_map, session.detailMapFile());
  state.detail_map_scale = session.detailMapScale();
  copyText(state.save_path, "lodline-view.json");
}

void drawPanel(ViewerSession& session, PanelState& state, int width, int height) {
  if (!state.visible) return;
  ImGui::SetNextWindowPos(ImVec2(8.0f, 8.0f), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(420.0f, std::min(static_cast<float>(height) - 16.0f, 820.0f)), ImGuiCond_FirstUseEver);
  ImGui::Begin("lodline");
  ImGui::PushItemWidth(-170.0f);  // room for the labels
  ImGui::TextWrapped("%s (%zu object%s)", session.loaded().view.model.filename().string().c_str(), session.scene().size(),
                     session.scene().size() == 1 ? "" : "s");
  statsSection(session, state);
  detailSection(session, state);
  objectsSection(session);
  linesSection(session, state);
  smoothingSection(session);
  styleSection(session);
  if (ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) {
    if (ImGui::Button("Reset view")) session.resetView();
    ImGui::InputText("Scene file", state.save_path.data(), state.save_path.size());
    if (ImGui::Button("Save view")) {
      if (Status r = session.saveView(state.save_path.data(), width, height); !r) state.message = r.error().message;
      else state.message = std::string("saved ") + state.save_path.data() + " (lodline render reproduces it)";
    }
  }
  if (!state.message.empty()) ImGui::TextWrapped("%s", state.message.c_str());
  ImGui::PopItemWidth();
  const float scale = ImGui::GetIO().DisplayFramebufferScale.x;
  // Moved to the right half, the panel no longer narrows the view from the left.
  const bool left = ImGui::GetWindowPos().x < 0.5f * ImGui::GetIO().DisplaySize.x;
  state.right_px = left ? (ImGui::GetWindowPos().x + ImGui::GetWindowSize().x + 8.0f) * (scale > 0.0f ? scale : 1.0f) : 0.0f;
  ImGui::End();
}

}  // namespace lodline
