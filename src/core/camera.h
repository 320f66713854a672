// Camera maths shared by every stage: view/projection matrices, the orbit
// placement used by --view, and the image-space area factor of docs/design.md
// §2.1 (Jeong et al. 2005 §3.1: A_img = k·A/d² in perspective, k·A in orthographic).
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/mesh.h"

namespace lodline {

/// Where the camera is and how it projects. Distances in model units.
struct Camera {
  glm::vec3 eye{0.0f, 0.0f, 3.0f};
  glm::vec3 target{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fov_deg = 35.0f;      ///< vertical field of view, degrees (perspective)
  bool orthographic = false;  ///< orthographic: `ortho_height` model units fill the image height
  float ortho_height = 2.0f;
  float near_plane = 0.01f;   ///< set by fitClipPlanes()
  float far_plane = 100.0f;

  glm::mat4 view() const;
  /// Projection for an image of aspect `width/height` (OpenGL clip conventions).
  glm::mat4 projection(float aspect) const;
  glm::vec3 forward() const;
};

/// Orbit placement used by `--view AZ,EL,DIST`: azimuth about +Y from +Z (degrees),
/// elevation above the XZ plane (degrees), distance in bounding-sphere radii.
struct OrbitView {
  float azimuth_deg = 35.0f;   ///< default: a 3/4 view
  float elevation_deg = 20.0f;
  float distance = 0.0f;       ///< 0: frame the whole model for the field of view
};

/// Camera looking at `bounds.center` from the orbit `v`. With distance 0 the sphere
/// fits the vertical and horizontal field of view with a small margin.
Camera orbitCamera(const Bounds& bounds, const OrbitView& v, float fov_deg, float aspect);

/// A perspective camera whose eye lies outside the sphere (`center`, `radius`): a closed
/// surface inside it then shows only its front faces (the renderers cull the back ones).
bool eyeOutsideSphere(const Camera& camera, const glm::vec3& center, float radius);

/// Sets near/far planes to enclose the bounding sphere (near ≥ 1e-3 of far).
void fitClipPlanes(Camera& cam, const Bounds& bounds);

/// Image-space area factor k: a triangle of area A (model units²) facing the camera at
/// distance d covers k·A/d² pixels² (perspective) or k·A (orthographic).
float pixelAreaFactor(const Camera& cam, int image_height);

/// The one projector from model space to pixels of a `width`×`height` image (origin
/// top-left, y down), with eye-space depth (the distance along the view direction), and the
/// inverse of OpenGL's window-depth mapping for reading depth buffers.
class PixelProjector {
 public:
  PixelProjector(const Camera& cam, int width, int height);
  /// Pixel position and eye depth of `p`; false behind the eye (or on its plane).
  bool project(glm::vec3 p, glm::vec2& px, float& eye_depth) const;
  /// Eye depth of `p`.
  float eyeDepth(glm::vec3 p) const;
  /// Eye depth of a window depth in [0, 1] (OpenGL's default depth range).
  float eyeDepthOfWindow(float window_depth) const;
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  glm::mat4 view_, view_proj_;
  int width_, height_;
  float near_, far_;
  bool ortho_;
};

/// Projects a model-space point to pixel coordinates (origin top-left, y down); `depth`
/// receives the eye-space distance along the view direction (PixelProjector, once).
glm::vec2 projectToPixels(const Camera& cam, glm::vec3 p, int width, int height,
                          float* depth = nullptr);

}  // namespace lodline
