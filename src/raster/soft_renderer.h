// The lines and toon styles drawn in software, with no OpenGL context (`lodline render
// --backend soft`): the same picture as src/gl/renderer.cpp + shaders/toon.frag — faces
// shaded by a ramp of flat tones indexed by max(n·l, 0) (Lake et al. 2000) with the frame's
// light in eye space (or in the background colour for the lines style), drawn with a polygon
// offset, then lines in pixels (visible and hidden runs the presenter found) blended over
// them. The shaded style and chamfer highlights need OpenGL (supports() says so).
// Faces go through the constant-depth-scanline rasteriser (raster.h; Han & Wang 2011,
// J. CAD & CG 23(6)), which interpolates the eye-space normal and, when a texture is set,
// its coordinates; the texture (e.g. a detail map or a checker) modulates the base colour.
// The depth image it leaves is what export/visibility.h needs for hidden-line removal.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core/camera.h"
#include "core/line_buffer.h"
#include "core/render_params.h"
#include "core/image.h"
#include "core/result.h"
#include "core/worker_pool.h"
#include "raster/raster.h"

namespace lodline {

enum class TextureFilter { kNearest, kBilinear };

/// Samples the RGBA8 `image` at texture coordinates (u, v) ∈ [0, 1)² with repeat wrapping
/// (u = 0 at the left column, v = 0 at the top row). Returns RGBA in [0, 1]. `image` must
/// not be empty.
glm::vec4 sampleTexture(const Image& image, float u, float v, TextureFilter filter);

/// Draws stroke geometry (`vertices`: triangles in pixels, present/stroke_geometry.h) as
/// OpenGL draws it with shaders/stroke.frag: pixel centres inside each triangle (top-left
/// fill rule, so the triangles of one band never cover a pixel twice) get the interpolated
/// offsets, strokeCoverage() of them × vertex alpha × colour alpha is blended into `image`
/// with no depth test. With a `brush` (one period, its width in pixels of arc length), the
/// coverage is also × its red channel at brushCoordinates(), bilinear, repeating along and
/// clamped across like the GL texture. Bands of rows run on `pool`. Returns triangles drawn.
size_t drawStrokeTriangles(std::span<const StrokeVertex> vertices, const glm::vec4& colour, const Image* brush,
                           Image& image, WorkerPool& pool);

/// Milliseconds per stage of the last drawSurfaces() and drawLines().
struct SoftTimes {
  double transform = 0.0;  ///< vertices to clip space, normals to eye space
  double setup = 0.0;      ///< triangle setup + binning (raster.h)
  double raster = 0.0;     ///< tile traversal with attribute interpolation
  double shade = 0.0;      ///< toon ramp (+ texture) per pixel
  double lines = 0.0;      ///< stroke geometry (drawLines)
};

/// The scene drawn in software, like gl/renderer.h: every object's faces (each in its own
/// style), then every object's lines, so an object hides the lines of those behind it.
class SoftRenderer {
 public:
  /// `params` selects the interpolation mode and threads; polygon offset and culling are
  /// set by draw() to match the GL renderer. Holds one object until setObjectCount().
  explicit SoftRenderer(const RasterParams& params = {});
  /// Runs the rasteriser, shading and lines on `pool` (e.g. the scene's).
  void setWorkerPool(std::shared_ptr<WorkerPool> pool);

  /// Number of objects; objects beyond `n` are released, new ones start empty.
  void setObjectCount(size_t n);
  size_t objectCount() const { return objects_.size(); }

  /// Copies the surface of `object`: one position and normal per vertex, faces index them.
  void setMesh(size_t object, std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
               std::span<const std::array<uint32_t, 3>> faces);
  /// A texture modulating the toon colour of `object`, sampled bilinearly at `uvs` (one per
  /// vertex, perspective-correctly interpolated). An empty texture removes it.
  void setTexture(size_t object, Image texture, std::span<const glm::vec2> uvs);
  /// As Renderer::setBackFaceCulling: drawSurfaces() leaves out `object`'s back faces while
  /// the eye is outside the sphere (`center`, `radius`), so both backends fill the same depth.
  void setBackFaceCulling(size_t object, bool closed, const glm::vec3& center, float radius);
  /// Copies the lines of `object` (pixels; visible per kind, then hidden).
  void setLines(size_t object, const ScreenLines& lines);

  /// Whether this renderer draws `style`: the lines and toon styles, without chamfer
  /// highlights. Errors are usage errors naming what is missing.
  static Status supports(const ObjectStyle& style);

  /// Draws the faces of a frame.width × frame.height frame from `camera` into image() and
  /// depth(): object i in styles[i] (objectCount() entries, each supported).
  void drawSurfaces(const Camera& camera, const FrameParams& frame, std::span<const ObjectStyle> styles);
  /// Draws every object's lines over image() (after drawSurfaces() of the same frame), no
  /// depth test: hidden lines in styles[i].hidden when enabled, then visible ones.
  void drawLines(const FrameParams& frame, std::span<const ObjectStyle> styles);
  /// The surface pass of the coherence measure (as the GL renderer's): each pixel's nearest
  /// world position and object index + 1, into `out` (resized to the last draw's size).
  void drawSurface(const Camera& camera, SurfaceImage& out);

  const Image& image() const { return image_; }
  /// Window depth of the faces (with the polygon offset, like GL's depth buffer).
  const DepthImage& depth() const { return target_.depth; }
  size_t faceCount(size_t object) const { return objects_[object].faces.size(); }
  size_t segmentsDrawn(size_t object) const { return objects_[object].segments_drawn; }
  const SoftTimes& times() const { return times_; }

 private:
  struct Object {
    std::vector<glm::vec3> positions, normals;
    std::vector<std::array<uint32_t, 3>> faces;
    Image texture;
    std::vector<glm::vec2> uvs;
    ScreenLines lines;
    size_t segments_drawn = 0;
    bool closed = false;  // setBackFaceCulling
    glm::vec3 center{0.0f};
    float radius = 0.0f;
  };
  bool textured(const Object& o) const { return !o.texture.rgba.empty() && o.uvs.size() == o.positions.size(); }
  // All objects' vertices to clip space (attributes: eye normal, uv) and their faces into one
  // array, face_object_ saying whose each face is. With `camera`, face_cull_ marks the faces
  // of objects set to be culled while its eye is outside their sphere (RasterInput::cull).
  void gather(const glm::mat4& view, const glm::mat4& view_proj, int attribute_count,
              const Camera* camera = nullptr);
  WorkerPool& pool() { return rasterizer_.workerPool(params_.threads); }

  RasterParams params_;
  SoftRasterizer rasterizer_;
  RasterTarget target_, surface_target_;
  Image image_;
  std::vector<Object> objects_;
  std::vector<glm::vec4> clip_;     // per-frame scratch, reused
  std::vector<float> attributes_;   // per-frame scratch, reused
  std::vector<std::array<uint32_t, 3>> faces_;
  std::vector<uint32_t> face_object_;
  std::vector<uint8_t> face_cull_;
  int width_ = 0, height_ = 0;
  SoftTimes times_;
};

}  // namespace lodline
