#include "core/camera.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

namespace lodline {

glm::mat4 Camera::view() const { return glm::lookAt(eye, target, up); }

glm::mat4 Camera::projection(float aspect) const {
  if (orthographic) {
    const float h = 0.5f * ortho_height, w = h * aspect;
    return glm::ortho(-w, w, -h, h, near_plane, far_plane);
  }
  return glm::perspective(glm::radians(fov_deg), aspect, near_plane, far_plane);
}

glm::vec3 Camera::forward() const { return glm::normalize(target - eye); }

bool eyeOutsideSphere(const Camera& camera, const glm::vec3& center, float radius) {
  const glm::vec3 d = camera.eye - center;
  return !camera.orthographic && glm::dot(d, d) > radius * radius;
}

Camera orbitCamera(const Bounds& bounds, const OrbitView& v, float fov_deg, float aspect) {
  Camera cam;
  cam.fov_deg = fov_deg;
  cam.target = bounds.center;
  const float r = bounds.radius > 0.0f ? bounds.radius : 1.0f;
  float dist = v.distance * r;
  if (v.distance <= 0.0f) {
    // Fit the sphere in the narrower of the two fields of view, 8% margin.
    const float half_v = glm::radians(fov_deg) * 0.5f;
    const float half_h = std::atan(std::tan(half_v) * aspect);
    dist = 1.08f * r / std::sin(std::min(half_v, half_h));
  }
  const float az = glm::radians(v.azimuth_deg), el = glm::radians(v.elevation_deg);
  const glm::vec3 dir(std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az));
  cam.eye = cam.target + dist * dir;
  cam.ortho_height = 2.0f * 1.08f * r;
  fitClipPlanes(cam, bounds);
  return cam;
}

void fitClipPlanes(Camera& cam, const Bounds& bounds) {
  const float r = std::max(bounds.radius, 1e-6f);
  const float d = glm::dot(bounds.center - cam.eye, cam.forward());
  cam.far_plane = std::max(d + 1.05f * r, 1e-3f);
  cam.near_plane = std::max(d - 1.05f * r, cam.far_plane * 1e-3f);
  // Far enough from the model, d - 1.05 r and d + 1.05 r round to the same float: keep the
  // depth range non-empty (an empty one makes the projection divide by zero).
  if (!(cam.near_plane < cam.far_plane)) cam.near_plane = 0.5f * cam.far_plane;
}

float pixelAreaFactor(const Camera& cam, int image_height) {
  if (cam.orthographic) {
    const float px_per_unit = static_cast<float>(image_height) / cam.ortho_height;
    return px_per_unit * px_per_unit;
  }
  const float f = 0.5f * static_cast<float>(image_height) /
                  std::tan(0.5f * glm::radians(cam.fov_deg));
  return f * f;
}

PixelProjector::PixelProjector(const Camera& cam, int width, int height)
    : view_(cam.view()), width_(width), height_(height), near_(cam.near_plane), far_(cam.far_plane),
      ortho_(cam.orthographic) {
  view_proj_ = cam.projection(static_cast<float>(width) / static_cast<float>(height)) * view_;
}

bool PixelProjector::project(glm::vec3 p, glm::vec2& px, float& eye_depth) const {
  const glm::vec4 c = view_proj_ * glm::vec4(p, 1.0f);
  if (c.w <= 1e-12f) return false;
  px = {(c.x / c.w * 0.5f + 0.5f) * static_cast<float>(width_), (0.5f - c.y / c.w * 0.5f) * static_cast<float>(height_)};
  eye_depth = eyeDepth(p);
  return true;
}

float PixelProjector::eyeDepth(glm::vec3 p) const { return -(view_ * glm::vec4(p, 1.0f)).z; }

float PixelProjector::eyeDepthOfWindow(float window_depth) const {
  if (ortho_) return near_ + window_depth * (far_ - near_);
  const float ndc_z = 2.0f * window_depth - 1.0f;
  return 2.0f * near_ * far_ / (far_ + near_ - ndc_z * (far_ - near_));
}

glm::vec2 projectToPixels(const Camera& cam, glm::vec3 p, int width, int height, float* depth) {
  const PixelProjector proj(cam, width, height);
  glm::vec2 px(0.0f);
  float z = 0.0f;
  if (!proj.project(p, px, z)) {  // behind the eye: the plain perspective divide, as before
    const glm::vec4 c = cam.projection(static_cast<float>(width) / static_cast<float>(height)) * cam.view() *
                        glm::vec4(p, 1.0f);
    px = {(c.x / c.w * 0.5f + 0.5f) * static_cast<float>(width), (0.5f - c.y / c.w * 0.5f) * static_cast<float>(height)};
    z = proj.eyeDepth(p);
  }
  if (depth) *depth = z;
  return px;
}

}  // namespace lodline
