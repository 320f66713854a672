// The toon style drawn in software, with no OpenGL context (`lodline render --backend soft`):
// the same picture as src/gl/renderer.cpp + shaders/toon.frag — faces shaded by a ramp of
// flat tones indexed by max(n·l, 0) (Lake et al. 2000) with the light in eye space, drawn
// with a polygon offset, then lines depth-tested (LEQUAL, no depth writes) and blended.
// Faces go through the constant-depth-scanline rasteriser (raster.h; Han & Wang 2011,
// J. CAD & CG 23(6)), which interpolates the eye-space normal and, when a texture is set,
// its coordinates; the texture (e.g. a detail map or a checker) modulates the base colour.
// The depth image it leaves is what export/visibility.h needs for SVG hidden-line removal.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core/camera.h"
#include "core/line_buffer.h"
#include "core/render_params.h"
#include "export/visibility.h"
#include "io/image.h"
#include "raster/raster.h"

namespace lodline {

enum class TextureFilter { kNearest, kBilinear };

/// Samples the RGBA8 `image` at texture coordinates (u, v) ∈ [0, 1)² with repeat wrapping
/// (u = 0 at the left column, v = 0 at the top row). Returns RGBA in [0, 1]. `image` must
/// not be empty.
glm::vec4 sampleTexture(const Image& image, float u, float v, TextureFilter filter);

/// Draws `vertices` (pairs = segments, model space) as aliased wide lines like OpenGL's
/// GL_LINES with glLineWidth: per column (x-major) or row (y-major) a run of
/// round(width) pixels centred on the segment, half-open along the major axis so chained
/// segments neither overlap nor leave gaps. A fragment is kept when its window depth is ≤
/// `depth` (depth LEQUAL, no writes) and blended (src alpha = style alpha × vertex alpha)
/// into `image`, which must be depth.width × depth.height. Segments are clipped to the
/// near and far planes. Work is split into `threads` bands of rows. Returns segments drawn.
size_t drawWideLines(std::span<const LineVertex> vertices, const glm::mat4& view_projection,
                     const LineStyle& style, const DepthImage& depth, Image& image, int threads);

/// Milliseconds per stage of the last SoftRenderer::draw().
struct SoftTimes {
  double transform = 0.0;  ///< vertices to clip space, normals to eye space
  double setup = 0.0;      ///< triangle setup + binning (raster.h)
  double raster = 0.0;     ///< tile traversal with attribute interpolation
  double shade = 0.0;      ///< toon ramp (+ texture) per pixel
  double lines = 0.0;      ///< wide lines
};

class SoftRenderer {
 public:
  /// `params` selects the interpolation mode and threads; polygon offset and culling are
  /// set by draw() to match the GL renderer.
  explicit SoftRenderer(const RasterParams& params = {}) : params_(params) {}
  void setRasterParams(const RasterParams& params) { params_ = params; }

  /// Copies the surface: one position and normal per vertex, faces index them.
  void setMesh(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
               std::span<const std::array<uint32_t, 3>> faces);
  /// A texture modulating the toon colour, sampled bilinearly at `uvs` (one per vertex,
  /// perspective-correctly interpolated). An empty texture removes it.
  void setTexture(Image texture, std::span<const glm::vec2> uvs);
  /// Copies the lines, grouped by kind.
  void setLines(const LineBuffer& lines);

  /// Draws a params.width × params.height frame from `camera` into image() and depth().
  void draw(const Camera& camera, const RenderParams& params);

  const Image& image() const { return image_; }
  /// Window depth of the faces (with the polygon offset, like GL's depth buffer).
  const DepthImage& depth() const { return target_.depth; }
  const RasterTarget& target() const { return target_; }
  size_t faceCount() const { return faces_.size(); }
  size_t segmentsDrawn() const { return segments_drawn_; }
  const SoftTimes& times() const { return times_; }
  const RasterStats& rasterStats() const { return rasterizer_.stats(); }

 private:
  RasterParams params_;
  SoftRasterizer rasterizer_;
  RasterTarget target_;
  Image image_;
  std::vector<glm::vec3> positions_, normals_;
  std::vector<std::array<uint32_t, 3>> faces_;
  Image texture_;
  std::vector<glm::vec2> uvs_;
  LineBuffer lines_;
  std::vector<glm::vec4> clip_;     // per-frame scratch, reused
  std::vector<float> attributes_;   // per-frame scratch, reused
  size_t segments_drawn_ = 0;
  SoftTimes times_;
};

}  // namespace lodline
