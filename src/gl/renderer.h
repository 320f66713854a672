// The OpenGL stage (DESIGN.md pipeline: gl): toon-shaded, Blinn–Phong-shaded (or
// background-coloured) faces drawn first with a polygon offset, then the chamfer highlights
// of sharp edges (ChamferLayer, Wei, Shi, Yong 2014) blended over them, then lines with depth test LEQUAL and depth writes off
// so hidden parts of lines are removed and visible ones never z-fight with their faces.
// The renderer only consumes arrays; it never computes geometry.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include <glm/vec3.hpp>

#include "core/camera.h"
#include "core/line_buffer.h"
#include "core/render_params.h"
#include "core/result.h"
#include "export/visibility.h"
#include "gl/chamfer_layer.h"
#include "gl/gl_objects.h"
#include "io/image.h"

namespace lodline {

class Renderer {
 public:
  /// Compiles the shaders; needs a current context.
  static Result<Renderer> create();

  /// Uploads the surface: `positions` and `normals` hold one entry per vertex, `faces`
  /// indexes them. Buffers are reused when the sizes fit. `marked_edges` (vertex index pairs,
  /// e.g. TriMesh::marked_edges) always get chamfer highlights; other sharp edges are found
  /// by dihedral angle (ChamferParams::threshold_deg) at the first draw that needs them.
  void setMesh(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
               std::span<const std::array<uint32_t, 3>> faces,
               std::span<const EdgeKey> marked_edges = {});
  /// Uploads the lines, grouped by kind.
  void setLines(const LineBuffer& lines);

  /// Draws into the currently bound framebuffer of `width`×`height` px (clears it first).
  void draw(const Camera& camera, const RenderParams& params, int width, int height);

  size_t faceCount() const { return face_count_; }
  /// Segments drawn by the last draw() (enabled kinds only).
  size_t segmentsDrawn() const { return segments_drawn_; }
  /// Sharp edges highlighted by the last draw() (0 when the chamfer layer was off).
  size_t chamferEdgesDrawn() const { return chamfer_drawn_; }
  /// The chamfer layer (per-vertex radii: chamfer().setMesh(...) after setMesh()).
  ChamferLayer& chamfer() { return chamfer_; }

 private:
  Renderer() = default;
  GlProgram toon_, depth_only_, line_;
  GlVertexArray mesh_vao_, line_vao_;
  GlBuffer positions_, normals_, indices_, line_vertices_;
  GlTexture ramp_;
  ChamferLayer chamfer_;
  size_t face_count_ = 0, segments_drawn_ = 0, chamfer_drawn_ = 0;
  std::array<uint32_t, kLineKindCount> first_{}, count_{};
  std::array<float, 5> ramp_key_{};  // tones + thresholds the ramp texture was built from
};

/// An offscreen multisampled framebuffer (colour RGBA8 + depth 24) with a resolve step and
/// readback, for headless rendering.
class OffscreenTarget {
 public:
  /// `samples` is clamped to GL_MAX_SAMPLES (1 = no multisampling).
  static Result<OffscreenTarget> create(int width, int height, int samples);
  void bind() const;
  /// Resolves the multisampled image and reads it back, top row first.
  Image readback() const;
  /// Reads the depth buffer (one sample per pixel), top row first, values in [0, 1].
  DepthImage readDepth() const;
  int width() const { return width_; }
  int height() const { return height_; }
  int samples() const { return samples_; }

 private:
  OffscreenTarget() = default;
  int width_ = 0, height_ = 0, samples_ = 1;
  GlFramebuffer fbo_, resolve_fbo_;
  GlRenderbuffer color_, depth_, resolve_color_, resolve_depth_;
};

}  // namespace lodline
