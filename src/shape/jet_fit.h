// Principal curvatures, directions and the curvature derivative tensor from a local
// polynomial fit (an osculating jet), for the lines that need third-order quantities to be
// right where they are: ridges and valleys (docs/lines.md, "Ridges from a fitted jet").
//
// Papers: F. Cazals, M. Pouget, "Estimating differential quantities using polynomial
// fitting of osculating jets" (SGP 2003, CAGD 2005), §3–5: the height function of the
// surface over its tangent plane, z = f(x, y), is fitted by a bivariate polynomial of degree
// d in the least-squares sense over the neighbours of a vertex; for a fit of degree d the
// k-th derivatives converge as O(h^(d−k+1)) with the sampling size h, so a degree-4 fit gives
// third derivatives (the derivative of the shape operator) that converge, O(h²), where the
// per-face estimates of S. Rusinkiewicz, "Estimating curvatures and their derivatives on
// triangle meshes" (3DPVT 2004) — finite differences of a per-face curvature — do not
// converge pointwise on irregular meshes. As in Cazals & Pouget's Monge step, the fit is
// repeated in the frame of the normal the first fit gives, so the tilt of the mesh's vertex
// normal does not enter the third derivatives.
//
// At a point where ∇f = 0 the shape operator is −Hess f and its derivative tensor is
// C_ijk = −∂³f/∂x_i∂x_j∂x_k (signs for outward normals: a convex surface has k > 0, as in
// shape/shape_cache.h).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/ext/vector_double3.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core/worker_pool.h"
#include "shape/adjacency.h"
#include "shape/shape_cache.h"

namespace lodline {

struct JetFitParams {
  /// Degree of the fitted polynomial, 3 or 4. Default 4 (third derivatives converge; a
  /// cubic fit's do not).
  int degree = 4;
  /// The neighbourhood: the vertices within this many of the vertex's longest edge, ...
  float radius_edges = 3.0f;
  /// ... grown by a quarter (up to 5 times) until it holds at least this many times the
  /// coefficients' count of vertices. Default 2.
  float points_per_coefficient = 2.0f;
};

/// Reused between calls: the per-vertex marks (all zero between calls) and the neighbourhood.
struct JetFitScratch {
  std::vector<uint8_t> mark;
  std::vector<uint32_t> ring;
  std::vector<uint32_t> touched;
  std::vector<glm::dvec3> offsets;
};

/// Per vertex of `vertices`: fits the jet over its neighbourhood (faces through
/// `adj`) in the frame of `normals` (outward, unit), and writes k1 ≥ k2, their unit principal
/// directions (pdir1 tangent to normals[v], pdir2 = normals[v] × pdir1) and the derivative
/// tensor (C_111, C_112, C_122, C_222) in that frame into the outputs at index v (vertexCount
/// entries each). A vertex whose fit is degenerate (too few neighbours, a boundary ring that
/// leaves the system rank-deficient) keeps its entries and is not counted. Returns the
/// vertices fitted. `pool` (optional) splits the vertices over its threads; the result is
/// the same.
size_t fitJets(std::span<const glm::vec3> positions, std::span<const std::array<uint32_t, 3>> faces,
               const MeshAdjacency& adj, std::span<const glm::vec3> normals, std::span<const uint32_t> vertices,
               const JetFitParams& params, JetFitScratch& scratch, std::span<float> k1, std::span<float> k2,
               std::span<glm::vec3> pdir1, std::span<glm::vec3> pdir2, std::span<glm::vec4> dcurv,
               WorkerPool* pool = nullptr);

/// Surface fields with the fitted jets in place at some vertices: owns the arrays the
/// returned SurfaceFields view (valid until the next fit()).
class FittedFields {
 public:
  /// `from` with k1, k2, pdir1, pdir2 and dcurv fitted at `vertices` (fitJets; its normals
  /// are the frame) and, elsewhere, `from`'s values and a zero dcurv.
  SurfaceFields fit(const SurfaceFields& from, std::span<const std::array<uint32_t, 3>> faces,
                    const MeshAdjacency& adj, std::span<const uint32_t> vertices, const JetFitParams& params = {},
                    WorkerPool* pool = nullptr);
  /// Vertices the last fit() fitted.
  size_t fitted() const { return fitted_; }

 private:
  JetFitScratch scratch_;
  std::vector<float> k1_, k2_;
  std::vector<glm::vec3> pdir1_, pdir2_;
  std::vector<glm::vec4> dcurv_;
  size_t fitted_ = 0;
};

}  // namespace lodline
