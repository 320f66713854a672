#include "app/viewer_session.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "core/timer.h"
#include "io/atomic_file.h"
#include "lines/strokes.h"

namespace lodline {
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

std::string relativeTo(const std::filesystem::path& file, const std::filesystem::path& base_dir) {
  std::error_code ec;
  const auto abs_file = std::filesystem::absolute(file, ec);
  const auto abs_base = std::filesystem::absolute(base_dir.empty() ? "." : base_dir, ec);
  auto rel = abs_file.lexically_relative(abs_base);
  return rel.empty() ? abs_file.string() : rel.string();
}

}  // namespace

nlohmann::json settingsOf(const RenderParams& params, const ResolvedDetail& detail, const LineParams& lines,
                          const std::filesystem::path& base_dir) {
  nlohmann::json s;
  s["size"] = std::to_string(params.width) + "x" + std::to_string(params.height);
  s["style"] = styleName(params.style);
  s["background"] = hexColour(params.background);
  s["msaa"] = params.msaa;
  std::string kinds;
  nlohmann::json line_styles = nlohmann::json::array();
  for (int k = 0; k < kLineKindCount; ++k) {
    const LineStyle& ls = params.lines.kinds[k];
    const char* name = lineKindName(static_cast<LineKind>(k));
    if (ls.enabled) kinds += (kinds.empty() ? "" : ",") + std::string(name);
    line_styles.push_back(std::string(name) + "=" + hexColour(ls.color) + ":" + exact(ls.width_px));
  }
  s["lines"] = kinds.empty() ? "none" : kinds;
  s["line-style"] = line_styles;
  const ChamferParams& ch = params.chamfer;
  s["chamfer"] = !ch.enabled ? "off" : ch.over_toon ? "on" : "auto";
  s["chamfer-radius"] = exact(ch.radius);
  s["chamfer-k"] = exact(ch.k);
  s["chamfer-angle"] = exact(ch.threshold_deg);
  s["chamfer-shininess"] = exact(ch.shininess);
  s["chamfer-compose"] = ch.compose == ChamferCompose::kAlpha ? "alpha" : "replace";
  s["suggestive-threshold"] = exact(lines.suggestive_threshold);
  s["suggestive-fade"] = exact(lines.suggestive_fade);
  s["crease-angle"] = exact(lines.crease_angle_deg);

  const DetailParams& d = detail.params;
  s["lod"] = detail.mode == LodMode::kPm ? "pm" : detail.mode == LodMode::kCluster ? "cluster" : "none";
  s["pixel-error"] = exact(detail.cluster.pixel_error);
  s["target-area"] = exact(d.target_area);
  s["t-collapse"] = exact(d.t_c);
  s["t-split"] = exact(d.t_s);
  if (!detail.detail_map_file.empty()) s["detail-map"] = relativeTo(detail.detail_map_file, base_dir);
  s["detail-map-scale"] = exact(detail.detail_map_scale);
  s["depth-falloff"] = exact(d.depth_falloff);
  s["foveation"] = exact(d.foveation);
  if (d.focus_px.x >= 0.0f && d.focus_px.y >= 0.0f) s["focus"] = exact(d.focus_px.x) + "," + exact(d.focus_px.y);
  s["object-factor"] = exact(d.object_factor);
  s["geomorphs"] = d.geomorphs ? "on" : "off";
  s["morph-time"] = exact(d.morph_time);
  s["smoothing"] = detail.smoothing.enabled ? "on" : "off";
  s["smoothing-alpha"] = exact(detail.smoothing.alpha);
  s["smoothing-time"] = exact(detail.smoothing.seconds);
  s["max-adapt-frames"] = detail.max_adapt_frames;
  return s;
}

Result<std::unique_ptr<ViewerSession>> ViewerSession::create(std::unique_ptr<LoadedScene> loaded,
                                                             const ViewOptions& options) {
  std::unique_ptr<ViewerSession> s(new ViewerSession());
  s->options_ = options;
  auto renderer = Renderer::create();
  if (!renderer) return renderer.error();
  s->renderer_ = std::make_unique<Renderer>(std::move(renderer.value()));
  if (Status st = s->renderer_->setObjectCount(loaded->drawing.size()); !st) return st.error();
  s->fov_deg_ = loaded->view.fov_deg;
  s->loaded_ = std::move(loaded);
  const Bounds& b = s->loaded_->drawing.bounds();
  const float r = std::max(b.radius, 1e-6f);
  const auto& cam = s->loaded_->camera;
  if (cam && cam->explicit_pose) {
    // An explicit pose becomes an orbit around its target (the up vector is +Y again).
    const glm::vec3 d = cam->eye - cam->target;
    const float len = glm::length(d);
    s->orbit_.azimuth_deg = glm::degrees(std::atan2(d.x, d.z));
    s->orbit_.elevation_deg = glm::degrees(std::asin(std::clamp(d.y / len, -1.0f, 1.0f)));
    s->orbit_.distance = len / r;
    s->pan_ = cam->target - b.center;
  } else {
    s->orbit_ = s->loaded_->view.orbit;
    if (s->orbit_.distance <= 0.0f) {
      const RenderParams& rp = s->loaded_->view.render;
      const Camera c = orbitCamera(b, s->orbit_, s->fov_deg_, static_cast<float>(rp.width) / static_cast<float>(rp.height));
      s->orbit_.distance = glm::length(c.eye - c.target) / r;
    }
    if (cam && cam->path) {
      auto path = scenePath(*s->loaded_, "", false, cam->duration.value_or(8.0),
                            static_cast<float>(s->loaded_->view.render.width) / static_cast<float>(s->loaded_->view.render.height));
      if (!path) return path.error();
      s->path_ = std::move(path.value());
    }
  }
  s->initial_orbit_ = s->orbit_;
  s->initial_pan_ = s->pan_;
  return s;
}

Camera ViewerSession::camera(int width, int height) const {
  const Bounds& bounds = loaded_->drawing.bounds();
  const float aspect = static_cast<float>(width) / static_cast<float>(std::max(height, 1));
  if (path_) {
    const double t0 = path_->keys().front().time;
    const double duration = std::max(path_->duration(), 1e-3);
    return path_->at(t0 + std::fmod(play_time_, duration), bounds);
  }
  Bounds shifted = bounds;
  shifted.center += pan_;
  Camera cam = orbitCamera(shifted, orbit_, fov_deg_, aspect);
  fitClipPlanes(cam, bounds);
  return cam;
}

Status ViewerSession::frame(int width, int height, float dt) {
  SceneDrawing& scene = loaded_->drawing;
  const Camera cam = camera(width, height);
  const ResolvedDetail& detail = loaded_->detail;
  bool mesh_all = false;
  if (first_) {
    auto steps = scene.converge(cam, width, height, detail.params, 1.0f / 30.0f, detail.max_adapt_frames);
    if (!steps) return steps.error();
    first_ = false;
    mesh_all = true;
  } else if (dirty_ || scene.detailControlled()) {
    // Smoothing at the measured frame rate (Jeong §3.3), from a running mean of dt.
    mean_dt_ = 0.9f * mean_dt_ + 0.1f * std::max(dt, 1e-3f);
    const float w = detail.smoothing.enabled ? smoothingWeight(detail.smoothing.alpha, detail.smoothing.seconds, 1.0f / mean_dt_)
                                             : 1.0f;
    if (Status s = scene.frame(cam, width, height, detail.params, dt, w); !s) return s;
  } else {
    return {};
  }
  dirty_ = false;
  Stopwatch sw;
  ViewerStats st;
  for (size_t i = 0; i < scene.size(); ++i) {
    const LodDrawing& d = *scene[i].drawing;
    const LineDrawing& ld = d.drawing();
    if (mesh_all || d.meshChanged())
      renderer_->setMesh(i, ld.mesh().positions, ld.normals(), ld.mesh().faces, ld.mesh().marked_edges);
    renderer_->setLines(i, ld.lines());
    st.active_faces += ld.mesh().faceCount();
    if (const AdaptiveMesh* lod = d.lod()) {
      st.visible_faces += lod->stats().visible_faces;
      st.splits += lod->stats().splits;
      st.collapses += lod->stats().collapses;
      st.morphing += lod->stats().morphing;
    }
    st.strokes += ld.strokes().strokeCount();
    measureStrokeLengths(ld.strokes(), [&](glm::vec3 p) { return projectToPixels(cam, p, width, height); },
                         stroke_lengths_);
    st.specks += countSpecks(stroke_lengths_);
  }
  const CpuTimings t = scene.timings();
  st.adapt_ms = scene.adaptMs();
  st.shape_ms = t.shape;
  st.view_ms = t.view;
  st.extract_ms = t.extract;
  st.chain_ms = t.chain;
  st.upload_ms = sw.lap();
  st.draw_ms = stats_.draw_ms;
  stats_ = st;
  return {};
}

void ViewerSession::draw(int width, int height) {
  Stopwatch sw;
  const SceneDrawing& scene = loaded_->drawing;
  styles_.clear();
  for (const auto& o : scene.objects()) styles_.push_back(o.style);
  RenderParams frame = loaded_->view.render;
  frame.width = width;
  frame.height = height;
  renderer_->draw(camera(width, height), frame, styles_, width, height);
  stats_.draw_ms = sw.lap();
}

void ViewerSession::orbit(float d_azimuth_deg, float d_elevation_deg) {
  orbit_.azimuth_deg += d_azimuth_deg;
  orbit_.elevation_deg = std::clamp(orbit_.elevation_deg + d_elevation_deg, -89.0f, 89.0f);
  dirty_ = true;
}

void ViewerSession::pan(float dx_px, float dy_px, int width, int height) {
  const Camera cam = camera(width, height);
  const glm::vec3 fwd = cam.forward();
  const glm::vec3 right = glm::normalize(glm::cross(fwd, cam.up));
  const glm::vec3 up = glm::cross(right, fwd);
  // One pixel moves the target by the size of a pixel at the target's distance.
  const float dist = glm::length(cam.target - cam.eye);
  const float px = 2.0f * dist * std::tan(glm::radians(fov_deg_) * 0.5f) / static_cast<float>(std::max(height, 1));
  pan_ += (-dx_px * right + dy_px * up) * px;
  dirty_ = true;
}

void ViewerSession::zoom(float factor) {
  orbit_.distance = std::clamp(orbit_.distance * factor, 0.05f, 200.0f);
  dirty_ = true;
}

void ViewerSession::resetView() {
  orbit_ = initial_orbit_;
  pan_ = initial_pan_;
  dirty_ = true;
}

void ViewerSession::play(std::optional<CameraPath> path) {
  path_ = std::move(path);
  play_time_ = 0.0;
  dirty_ = true;
}

void ViewerSession::setLineParams(const LineParams& p) {
  loaded_->view.line_params = p;
  for (auto& o : loaded_->drawing.objects()) o.drawing->setLineParams(p);
  dirty_ = true;
}

Status ViewerSession::setDetailMap(const std::string& path, float scale) {
  ResolvedDetail& d = loaded_->detail;
  if (!(scale > 0.0f && std::isfinite(scale))) return Error::usage("detail-map scale must be > 0");
  if (path.empty()) {
    d.params.detail_map.reset();
    d.detail_map_file.clear();
  } else {
    auto map = readDetailMap(path, scale);
    if (!map) return map.error();
    d.params.detail_map = std::move(map.value());
    d.detail_map_file = path;
  }
  d.detail_map_scale = scale;
  dirty_ = true;
  return {};
}

void ViewerSession::setStyleAll(Style style) {
  loaded_->view.render.style = style;
  for (auto& o : loaded_->drawing.objects()) o.style.style = style;
  for (auto& o : loaded_->scene.objects) o.style.erase("style");  // the frame's style now holds for all
  dirty_ = true;
}

Status ViewerSession::saveView(const std::filesystem::path& path, int width, int height) const {
  const std::filesystem::path dir = path.parent_path();
  RenderParams frame = loaded_->view.render;
  frame.width = width;
  frame.height = height;
  nlohmann::json j;
  j["lodline"] = 1;
  j["description"] = "view saved by lodline view from " + loaded_->view.model.filename().string();
  j["settings"] = settingsOf(frame, loaded_->detail, loaded_->view.line_params, dir);
  const Camera cam = camera(width, height);
  j["camera"] = {{"eye", {cam.eye.x, cam.eye.y, cam.eye.z}},
                 {"target", {cam.target.x, cam.target.y, cam.target.z}},
                 {"up", {cam.up.x, cam.up.y, cam.up.z}},
                 {"fov", cam.fov_deg}};
  if (loaded_->scene.light_dir_eye) {
    const glm::vec3 l = *loaded_->scene.light_dir_eye;
    j["light"] = {{"direction", {l.x, l.y, l.z}}};
  }
  nlohmann::json objects = nlohmann::json::array();
  const SceneDrawing& scene = loaded_->drawing;
  for (size_t i = 0; i < loaded_->scene.objects.size(); ++i) {
    const SceneObject& so = loaded_->scene.objects[i];
    nlohmann::json o;
    o["name"] = so.name;
    o["mesh"] = relativeTo(so.mesh, dir);
    if (so.gltf_node >= 0) o["gltf_node"] = so.gltf_node;
    if (so.placement != glm::mat4(1.0f)) o["matrix"] = matrixJson(so.placement);
    o["detail_factor"] = scene[i].detail_factor;
    for (const auto& [key, value] : so.style.items()) {
      std::string k = key;
      std::replace(k.begin(), k.end(), '-', '_');
      o[k] = value;
    }
    if (scene[i].style.style != frame.style) o["style"] = styleName(scene[i].style.style);
    objects.push_back(o);
  }
  j["objects"] = objects;
  const std::string text = j.dump(2) + "\n";
  return writeFileAtomically(path, [&](std::ostream& out) -> Status {
    out << text;
    return {};
  });
}

}  // namespace lodline
