// Level-set line kinds (docs/lines.md): isophotes, topographic lines and parabolic lines,
// each the zero set of a per-vertex scalar that the generic extractor (lines/lines.h) draws
// like the other kinds, on whatever mesh the frame has — the adapted mesh under detail
// control, so they inherit its scale in the image.
//
// - Isophotes: curves of constant shading n·l = c (Koenderink & van Doorn, "Photometric
//   invariants related to solid shape", 1980; rtsc's "isophotes"), at c = k·spacing, k ≥ 0.
// - Topographic lines: curves of constant height along an up axis, at multiples of a
//   spacing (rtsc's "topo lines").
// - Parabolic lines: K = k1·k2 = 0 (Koenderink, "Solid Shape", 1990, §5), between the
//   elliptic and hyperbolic parts of the surface; drawn only where the surface is curved.
//
// Several levels in one pass: the scalar is a triangle wave w(x) = |frac((x + 1.5)/2)·2 − 1|
// − 0.5 of x = quantity/spacing, zero exactly at integer x, linear between half-integers. An
// edge's crossing is interpolated on w, which equals interpolating the quantity itself when
// the edge spans less than half a spacing; an edge spanning a whole spacing or more can miss
// a level (the mesh is then too coarse for that spacing).
#pragma once

#include <glm/vec3.hpp>

#include "core/camera.h"
#include "core/worker_pool.h"
#include "lines/view_quantities.h"
#include "shape/shape_cache.h"

namespace lodline {

/// The triangle wave of the level kinds: 0 at integers, ±0.5 at half-integers, slope ±1.
float levelWave(float x);

/// What the level kinds need besides the surface fields; a kind is computed when its flag is
/// set.
struct LevelSpec {
  bool isophotes = false;
  glm::vec3 light{0.0f, 0.0f, 1.0f};  ///< unit, towards the light, the mesh's space
  float isophote_spacing = 0.25f;     ///< in n·l, > 0
  bool topo = false;
  glm::vec3 topo_origin{0.0f};        ///< height 0
  glm::vec3 topo_axis{0.0f, 1.0f, 0.0f};  ///< unit
  float topo_spacing = 1.0f;          ///< model units, > 0
  bool parabolic = false;
  float feature_size = 1.0f;          ///< model units, > 0
  float parabolic_threshold = 0.05f;  ///< on max(|k1|, |k2|)·fs
};

/// The light of `light_dir_eye` (eye space, towards the light) in the space `camera` looks
/// at, unit.
glm::vec3 lightInModelSpace(const Camera& camera, glm::vec3 light_dir_eye);

/// Fills out.isophote/isophote_test, out.topo and out.parabolic/parabolic_test (vertexCount
/// floats each) for the kinds `spec` asks for, and clears the others. Uses fields.positions,
/// normals (isophotes; temporally smoothed normals give steady isophotes), k1 and k2
/// (parabolic lines).
void computeLevelQuantities(const SurfaceFields& fields, const LevelSpec& spec, ViewQuantities& out,
                            WorkerPool* pool = nullptr);

}  // namespace lodline
