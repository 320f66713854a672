// Software triangle rasteriser with constant-depth scanlines (docs/design.md §2.3):
// Han, Wang, "Linear texture coordinate interpolation in rasterization", J. CAD & CG 23(6),
// 2011 — §2 (lines of constant depth are parallel in screen space and perspective-correct
// attributes are linear along them), §3 (per-triangle arrays of start value and step for each
// constant-depth line, traversal in columns or rows with an index offset per column), §4
// (error correction: denser lines, linear interpolation between the two nearest lines).
//
// Coverage is exact: vertices are snapped to 1/256 px, edge functions are evaluated in 64-bit
// integers and a top-left rule decides pixel centres on an edge, so triangles sharing an edge
// cover each pixel along it exactly once. Triangles are clipped against the near and far
// planes (and a guard band) in clip space. Output planes: window depth in [0, 1] (like
// OpenGL's default depth range, so export/visibility.h works unchanged), face ID, facing,
// and the interpolated attributes of the nearest fragment per pixel (a G-buffer; shading is
// a separate pass, see soft_renderer.h).
//
// Multithreaded by screen tiles on a WorkerPool (core/worker_pool.h): each thread's slot sets
// up and bins a contiguous range of faces, then threads take tiles and draw each tile's
// triangles in face order, so the result does not depend on the thread count. Setup records,
// bins and line arrays are kept and reused.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/vec4.hpp>

#include "core/worker_pool.h"

#include "core/image.h"

namespace lodline {

/// How attributes are interpolated inside a triangle. All modes share the same setup,
/// coverage and traversal; they differ only in the per-pixel attribute evaluation.
enum class Interpolation {
  /// Han & Wang 2011: values read from per-triangle constant-depth line arrays, no per-pixel
  /// division (RasterParams::line_density, RasterParams::linear_correction).
  kConstantDepth,
  /// Reference: exact perspective-correct interpolation, one division per pixel.
  kExact,
  /// Reference: affine (screen-linear, no perspective correction), as in early hardware.
  kAffine,
};

/// "constant-depth", "exact" or "affine".
const char* interpolationName(Interpolation m);

/// Rasteriser settings; defaults give the paper's recommended configuration.
struct RasterParams {
  Interpolation interpolation = Interpolation::kConstantDepth;
  /// Constant-depth lines per pixel of the traversal's minor axis: 1, 2 or 4 (Han & Wang
  /// §4, "denser lines"). Default 1.
  int line_density = 1;
  /// Interpolate linearly between the two nearest constant-depth lines instead of taking the
  /// nearest one (Han & Wang §4). Default on: the paper's best accuracy/time trade-off.
  bool linear_correction = true;
  /// Threads of the rasteriser's own WorkerPool (the caller included); 0 = one per core (at
  /// most 8). Ignored while a pool is given by SoftRasterizer::setWorkerPool(). Default 0.
  int threads = 0;
  /// Screen tiles are tile_size × tile_size pixels (16..1024). Default 64.
  int tile_size = 64;
  /// Depth test GL_LESS with depth writes. Off: every fragment overwrites. Default on.
  bool depth_test = true;
  /// Skip triangles that are back-facing (clockwise in OpenGL window coordinates). Default off.
  bool cull_back_faces = false;
  /// glPolygonOffset(factor, units): depth += factor·max|∂z/∂x|,|∂z/∂y| + units·2⁻²⁴.
  /// Default 0, 0.
  float depth_offset_factor = 0.0f;
  float depth_offset_units = 0.0f;
  /// kExact only: evaluate the planes and the division in double precision (a ground truth
  /// for error measurements; the timed reference is single precision). Default off.
  bool double_precision = false;
  /// Count every fragment (before the depth test) in RasterTarget::fragments. Default off.
  bool count_fragments = false;
};

inline constexpr int kMaxAttributes = 8;
inline constexpr uint32_t kNoFace = 0xffffffffu;

/// What to draw. All spans are caller-owned and must stay valid during draw().
struct RasterInput {
  /// One clip-space position per vertex (OpenGL conventions: visible when −w ≤ x,y,z ≤ w).
  std::span<const glm::vec4> clip;
  /// attribute_count floats per vertex, interleaved (vertex v's attribute a at
  /// [v·attribute_count + a]); may be empty when attribute_count is 0.
  std::span<const float> attributes;
  int attribute_count = 0;  ///< 0..kMaxAttributes
  /// Vertex indices per triangle; the face ID written for a triangle is its index here.
  std::span<const std::array<uint32_t, 3>> faces;
  /// Optional, one byte per face: a non-zero face is culled when back-facing, as
  /// RasterParams::cull_back_faces culls every face (e.g. only the closed objects of a scene).
  std::span<const uint8_t> cull;
};

/// Caller-owned output planes, row 0 = top of the image.
struct RasterTarget {
  int width = 0;
  int height = 0;
  int attribute_count = 0;
  DepthImage depth;                   ///< width·height window depths in [0, 1]; 1 = empty
  std::vector<uint32_t> face_id;      ///< width·height face indices, kNoFace where empty
  std::vector<uint8_t> front_facing;  ///< width·height: 1 where the face is front-facing
  /// attribute_count planes of width·height floats (plane a starts at a·width·height).
  std::vector<float> attributes;
  /// width·height fragment counts (only with RasterParams::count_fragments).
  std::vector<uint32_t> fragments;

  /// Sets the size (allocating only when it grows) and clears.
  void resize(int w, int h, int attributes_per_pixel);
  /// Depth 1, no face, attributes 0, fragment counts 0.
  void clear();
  size_t index(int x, int y) const { return static_cast<size_t>(y) * width + x; }
  float attribute(int a, int x, int y) const {
    return attributes[static_cast<size_t>(a) * width * height + index(x, y)];
  }
};

/// Counters and timings of the last draw().
struct RasterStats {
  size_t triangles_in = 0;     ///< faces submitted
  size_t triangles_drawn = 0;  ///< screen triangles set up (after clipping and culling)
  size_t clipped = 0;          ///< faces that needed clipping
  size_t fragments = 0;        ///< fragments that passed coverage (before the depth test)
  size_t lines = 0;            ///< constant-depth line entries computed (paper's arrays)
  double ms_setup = 0.0;       ///< setup + binning, wall clock
  double ms_raster = 0.0;      ///< tile traversal, wall clock
};

/// Slope of the constant-depth lines of a screen triangle (Han & Wang §2). The three
/// clip-space vertices are projected to a `width`×`height` image (y down). When
/// `rows` is false the lines are y = g·x + c with |g| ≤ 1 and pixels are walked in columns;
/// when true they are x = g·y + c with |g| < 1 and pixels are walked in rows.
struct ConstantDepthSlope {
  float g = 0.0f;
  bool rows = false;
};
ConstantDepthSlope constantDepthSlope(const glm::vec4& c0, const glm::vec4& c1, const glm::vec4& c2,
                                      int width, int height);

/// A reusable rasteriser: keeps its per-thread setup records, tile bins and line arrays
/// between frames, so repeated draws allocate nothing once they have warmed up.
class SoftRasterizer {
 public:
  SoftRasterizer();
  ~SoftRasterizer();
  SoftRasterizer(SoftRasterizer&&) noexcept;
  SoftRasterizer& operator=(SoftRasterizer&&) noexcept;

  /// Draws `input` into `target` (which keeps what was drawn before: call target.clear()
  /// for a new frame). target.attribute_count must be ≥ input.attribute_count.
  void draw(const RasterInput& input, const RasterParams& params, RasterTarget& target);
  const RasterStats& stats() const { return stats_; }
  /// Runs the data-parallel loops on `pool` (shared with the caller's other loops) from now
  /// on; RasterParams::threads no longer applies.
  void setWorkerPool(std::shared_ptr<WorkerPool> pool);
  /// The pool draw() uses: the one given, else one of RasterParams::threads threads.
  WorkerPool& workerPool(int threads);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;  // pimpl keeps the setup structures out of the header
  RasterStats stats_;
};

/// One-shot form of SoftRasterizer::draw.
void rasterize(const RasterInput& input, const RasterParams& params, RasterTarget& target);

}  // namespace lodline
