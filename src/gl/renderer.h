// The OpenGL stage (docs/design.md §1: gl): toon-shaded, Blinn–Phong-shaded (or
// background-coloured) faces drawn first with a polygon offset, then the chamfer highlights
// of sharp edges (ChamferLayer, Wei, Shi, Yong 2014) blended over them (drawSurfaces()); then,
// once the presenter has read the depth back and split the strokes into visible and hidden
// runs, the lines in pixels with no depth test (drawLines()). The renderer only consumes
// arrays; it never computes geometry.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "core/camera.h"
#include "core/line_buffer.h"
#include "core/render_params.h"
#include "core/image.h"
#include "core/result.h"
#include "gl/chamfer_layer.h"
#include "gl/gl_objects.h"

namespace lodline {

class Renderer {
 public:
  /// Compiles the shaders; needs a current context. Holds one object until setObjectCount().
  static Result<Renderer> create();

  /// Number of objects (a mesh with its lines and chamfer layer each) the renderer holds;
  /// objects beyond `n` are released, new ones start empty. Errors: shader compilation of a
  /// new object's chamfer layer.
  Status setObjectCount(size_t n);
  size_t objectCount() const { return objects_.size(); }

  /// Uploads the surface of `object`: `positions` and `normals` hold one entry per vertex,
  /// `faces` indexes them. Buffers are reused when the sizes fit. `marked_edges` (vertex
  /// index pairs, e.g. TriMesh::marked_edges) always get chamfer highlights; other sharp
  /// edges are found by dihedral angle (ChamferParams::threshold_deg) at the first draw that
  /// needs them.
  void setMesh(size_t object, std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
               std::span<const std::array<uint32_t, 3>> faces, std::span<const EdgeKey> marked_edges = {});
  /// Lets drawSurfaces() cull `object`'s back faces while the eye is outside the sphere
  /// (`center`, `radius`): for a closed surface seen from outside (LodDrawing::backFacesHidden)
  /// they are hidden anyway, and culling them halves the triangles rasterised. Off by default.
  void setBackFaceCulling(size_t object, bool closed, const glm::vec3& center, float radius);
  /// Uploads the lines of `object`: stroke geometry in pixels, visible per kind, then hidden.
  void setLines(size_t object, const ScreenLines& lines);

  /// Draws every object's surface into the currently bound framebuffer of frame.width ×
  /// frame.height px (cleared first to `frame.background`), lit by frame.light_dir_eye: all
  /// faces, each object in its own `styles[i]` (style, toon, chamfer; the array holds
  /// objectCount() entries), then the chamfer highlights. The depth buffer then holds every
  /// object's faces.
  void drawSurfaces(const Camera& camera, const FrameParams& frame, std::span<const ObjectStyle> styles);
  /// Draws every object's lines over the bound framebuffer (after drawSurfaces()), blended,
  /// no depth test, antialiased by coverage: hidden lines in styles[i].hidden's colour (when
  /// enabled), then visible lines in their kind's colour (widths are in the geometry).
  void drawLines(const FrameParams& frame, std::span<const ObjectStyle> styles);

  /// Faces uploaded of one object.
  size_t faceCount(size_t object) const { return objects_[object].face_count; }
  /// Segments drawn by the last drawLines() (enabled kinds, hidden lines included), over
  /// all objects / of one.
  size_t segmentsDrawn() const;
  size_t segmentsDrawn(size_t object) const { return objects_[object].segments_drawn; }
  /// Sharp edges highlighted by the last drawSurfaces() (0 when the chamfer layer was off).
  size_t chamferEdgesDrawn() const;
  /// The surface pass of the coherence measure: every object's faces into the bound
  /// framebuffer (a SurfaceTarget), each pixel the world position of the nearest surface and
  /// the object's index + 1.
  void drawSurface(const Camera& camera, int width, int height);

  /// The chamfer layer of `object` (per-vertex radii: chamfer(i).setMesh(...) after setMesh()).
  ChamferLayer& chamfer(size_t object = 0) { return objects_[object].chamfer; }

 private:
  struct Object {
    GlVertexArray mesh_vao, line_vao;
    GlBuffer positions, normals, indices, line_vertices;
    ChamferLayer chamfer;
    size_t face_count = 0, segments_drawn = 0, chamfer_drawn = 0;
    std::array<uint32_t, kLineKindCount> first{}, count{}, segments{};
    uint32_t hidden_first = 0, hidden_count = 0, hidden_segments = 0;
    bool closed = false;  // setBackFaceCulling
    glm::vec3 center{0.0f};
    float radius = 0.0f;
  };
  Renderer() = default;
  Result<Object> makeObject() const;
  void drawFaces(Object& o, const Camera& camera, const ObjectStyle& style, const FrameParams& frame);
  void drawChamfer(Object& o, const Camera& camera, const ObjectStyle& style, const FrameParams& frame);
  void drawObjectLines(Object& o, const ObjectStyle& style);
  /// The texture of a stroke style's brush (uploaded at its first use).
  unsigned brushTexture(const std::shared_ptr<const Image>& brush);
  struct BrushTexture {
    std::shared_ptr<const Image> image;
    GlTexture texture;
  };
  std::vector<BrushTexture> brushes_;
  GlProgram toon_, depth_only_, line_, surface_;
  GlTexture ramp_;
  std::vector<Object> objects_;
  std::array<float, 5> ramp_key_{};  // tones + thresholds the ramp texture was built from
};

/// A single-sample RGBA32F framebuffer with depth for Renderer::drawSurface(), read back as a
/// SurfaceImage (core/image.h).
class SurfaceTarget {
 public:
  static Result<SurfaceTarget> create(int width, int height);
  /// Binds and clears it (to background: all zero).
  void bindAndClear() const;
  /// Reads it back, top row first, into `out` (resized).
  void readback(SurfaceImage& out) const;

 private:
  SurfaceTarget() = default;
  int width_ = 0, height_ = 0;
  GlFramebuffer fbo_;
  GlRenderbuffer color_, depth_;
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
  /// Reads the depth buffer (one sample per pixel), top row first, values in [0, 1], into
  /// `out` (resized).
  void readDepth(DepthImage& out) const;
  /// Resolves the multisampled image and copies it into the currently bound draw
  /// framebuffer's lower left `width()`×`height()` pixels (a window's back buffer).
  void blitToBound() const;
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
