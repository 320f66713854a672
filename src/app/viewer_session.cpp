#include "app/viewer_session.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "io/scene_file.h"
#include "io/stroke_style_file.h"

namespace lodline {

Result<std::unique_ptr<ViewerSession>> ViewerSession::create(std::unique_ptr<LoadedScene> loaded,
                                                             const ViewOptions& options) {
  std::unique_ptr<ViewerSession> s(new ViewerSession());
  s->options_ = options;
  auto presenter = GlPresenter::createOnCurrentContext();
  if (!presenter) return presenter.error();
  s->presenter_ = std::move(presenter.value());
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
      const Camera c = orbitCamera(b, s->orbit_, s->fov_deg_, s->loaded_->view.frame.aspect());
      s->orbit_.distance = glm::length(c.eye - c.target) / r;
    }
    if (cam && cam->path) {
      auto path = scenePath({"", false, cam->duration.value_or(8.0)}, b, cam, s->fov_deg_,
                            s->loaded_->view.frame.aspect());
      if (!path) return path.error();
      s->path_ = std::move(path.value());
    }
  }
  s->initial_orbit_ = s->orbit_;
  s->initial_pan_ = s->pan_;
  s->base_distance_ = s->orbit_.distance;
  s->base_aspect_ = s->loaded_->view.frame.aspect();
  return s;
}

Camera ViewerSession::camera(int width, int height) const { return cameraFor(width, height, inset_px_); }

Camera ViewerSession::cameraFor(int width, int height, int inset_px) const {
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
  if (inset_px > 0 && height > 0) {
    // Move the camera sideways so the target sits at the free part's centre: inset/2 px to
    // the right, a pixel being the image height's share of the view at the target's distance.
    const glm::vec3 fwd = cam.forward();
    const glm::vec3 right = glm::normalize(glm::cross(fwd, cam.up));
    const float dist = glm::length(cam.target - cam.eye);
    const float px = cam.orthographic ? cam.ortho_height / static_cast<float>(height)
                               : 2.0f * dist * std::tan(glm::radians(cam.fov_deg) * 0.5f) / static_cast<float>(height);
    const glm::vec3 shift = -right * (0.5f * static_cast<float>(inset_px) * px);
    cam.eye += shift;
    cam.target += shift;
  }
  fitClipPlanes(cam, bounds);
  return cam;
}

Status ViewerSession::frame(int width, int height, float dt) {
  SceneDrawing& scene = loaded_->drawing;
  // While the view is the initial framing, fit its distance to the free part of the window.
  const bool initial = orbit_.azimuth_deg == initial_orbit_.azimuth_deg &&
                       orbit_.elevation_deg == initial_orbit_.elevation_deg &&
                       orbit_.distance == initial_orbit_.distance && pan_ == initial_pan_;
  if (initial && !path_ && height > 0 && base_distance_ > 0.0f &&
      (fitted_for_[0] != width || fitted_for_[1] != height || fitted_for_[2] != inset_px_)) {
    // What the initial view shows across the whole window must fit in the free part: the
    // scene's box, seen from the initial distance, at most half the free width either side
    // of the centre (2% margin); farther by that ratio when it is wider (twice, as the
    // perspective is not linear in the distance).
    const int free_w = std::max(width - inset_px_, width / 4);
    float scale = 1.0f;
    if (inset_px_ > 0) {
      const Bounds& b = scene.bounds();
      for (int pass = 0; pass < 2; ++pass) {
        OrbitView o = orbit_;
        o.distance = base_distance_ * scale;
        Bounds shifted = b;
        shifted.center += pan_;
        const Camera c = orbitCamera(shifted, o, fov_deg_, static_cast<float>(width) / static_cast<float>(height));
        const PixelProjector proj(c, width, height);
        float half_extent = 0.0f;
        for (int k = 0; k < 8; ++k) {
          const glm::vec3 p((k & 1) ? b.max.x : b.min.x, (k & 2) ? b.max.y : b.min.y, (k & 4) ? b.max.z : b.min.z);
          glm::vec2 px;
          float depth = 0.0f;
          if (proj.project(p, px, depth)) half_extent = std::max(half_extent, std::abs(px.x - 0.5f * width));
        }
        scale *= std::max(1.0f, half_extent / (0.48f * static_cast<float>(free_w)));
      }
    }
    orbit_.distance = initial_orbit_.distance = base_distance_ * std::max(scale, 1.0f);
    fitted_for_[0] = width;
    fitted_for_[1] = height;
    fitted_for_[2] = inset_px_;
    dirty_ = true;
  }
  const Camera cam = camera(width, height);
  const ResolvedDetail& detail = loaded_->detail;
  // A new framebuffer size needs a new picture even when nothing else changed.
  if (presenter_->frame().width != width || presenter_->frame().height != height) dirty_ = true;
  bool mesh_all = false;
  if (first_) {
    auto steps = scene.converge(cam, width, height, detail.params, SceneDrawing::kConvergeStepSeconds, detail.max_adapt_frames);
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
  FrameParams frame = loaded_->view.frame;
  frame.width = width;
  frame.height = height;
  if (Status s = presenter_->present(scene, cam, frame, mesh_all); !s) return s;
  report_ = reportFrame(scene, *presenter_);
  return {};
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

bool ViewerSession::hasIntersectionLines() const {
  for (const auto& o : loaded_->drawing.objects())
    if (o.intersections.strokeCount() > 0) return true;
  return false;
}

void ViewerSession::setStyleAll(Style style) {
  loaded_->view.style.style = style;
  for (auto& o : loaded_->drawing.objects()) o.style.style = style;
  for (auto& o : loaded_->scene.objects) o.style.erase("style");  // the frame's style now holds for all
  dirty_ = true;
}

void ViewerSession::setStrokeStyle(int kind, const StrokeStyle& style) {
  auto apply = [&](ObjectStyle& p) {
    for (int k = 0; k < kLineKindCount; ++k)
      if (kind < 0 || k == kind) p.lines.kinds[k].stroke = style;
    p.stroke_style = kEditedStrokeStyle;
  };
  apply(loaded_->view.style);
  for (auto& o : loaded_->drawing.objects()) apply(o.style);
  for (auto& o : loaded_->scene.objects) o.style.erase("stroke-style");  // the panel's style now holds for all
  dirty_ = true;
}

Status ViewerSession::saveView(const std::filesystem::path& path, int width, int height) const {
  FrameParams frame = loaded_->view.frame;
  frame.width = width;
  frame.height = height;
  Scene out = loaded_->scene;
  ObjectStyle style = loaded_->view.style;
  if (style.stroke_style == kEditedStrokeStyle) {
    // Fields edited in the panel: written as a style file beside the view, which names it.
    std::filesystem::path strokes = path;
    strokes.replace_extension(".strokes.json");
    if (Status st = writeStrokeStyleFile(strokes, style.lines); !st) return st;
    style.stroke_style = strokes.string();
  }
  out.settings = settingsOf(frame, style, loaded_->detail, loaded_->view.line_params, path.parent_path());
  const Camera cam = cameraFor(width, height, 0);
  SceneCamera sc;
  sc.explicit_pose = true;
  sc.eye = cam.eye;
  sc.target = cam.target;
  sc.up = cam.up;
  sc.fov_deg = cam.fov_deg;
  out.camera = sc;
  const SceneDrawing& scene = loaded_->drawing;
  for (size_t i = 0; i < out.objects.size(); ++i) {
    SceneObject& so = out.objects[i];
    so.detail_factor = scene[i].detail_factor;
    if (scene[i].style.style != loaded_->view.style.style) so.style["style"] = styleName(scene[i].style.style);
  }
  return writeSceneFile(path, out, "view saved by lodline view from " + loaded_->view.model.filename().string());
}

}  // namespace lodline
