// Ridges and valleys: the curvature extrema along the lines of curvature (docs/lines.md).
//
// Papers: Y. Ohtake, A. Belyaev, H.-P. Seidel, "Ridge-valley lines on meshes via implicit
// surface fitting" (SIGGRAPH 2004), §2 (definitions: a ridge is where the larger principal
// curvature k_max, dominant (k_max > |k_min|), has a maximum along its own curvature line,
// e_max·∇k_max = 0 with e_max·∇(e_max·∇k_max) < 0; a valley is the same for −k_min), and
// their per-face extraction with the principal direction's sign made to agree across a face;
// S. Rusinkiewicz, "Estimating curvatures and their derivatives on triangle meshes" (3DPVT
// 2004), §4, for the derivative tensor C whose C(e1,e1,e1) is that derivative (or, with
// LineParams::ridge_estimator = kFit, C from fitted jets: shape/jet_fit.h). On lodline's
// adapted mesh these lines inherit detail control like the other kinds.
//
// The derivative d = C(e,e,e) changes sign with e, and e is defined only up to sign. An
// edge's crossing compares d at its first vertex with d at its second taken along the first
// vertex's direction (flipped where e_a·e_b < 0): the two faces of an edge agree on the
// crossing, bit for bit (exact chaining, as lines/lines.h). A face whose three such
// agreements are inconsistent (an odd number of flips around it: the direction field turns
// half a turn, near an umbilic) draws nothing.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/line_kind.h"
#include "core/worker_pool.h"
#include "lines/lines.h"
#include "shape/adjacency.h"
#include "shape/shape_cache.h"

namespace lodline {

/// What extractRidges() draws.
struct RidgeSpec {
  bool ridges = false;
  bool valleys = false;
  /// Strength threshold on |k|·fs at the crossing (k the dominant curvature, fs the feature
  /// size): alpha fades from 0 at the threshold to 1 at twice it. > 0.
  float threshold = 0.1f;
  float feature_size = 1.0f;  ///< model units, > 0
};

/// The vertices whose derivative tensor extractRidges() reads (corners of faces where a line
/// of a requested kind can be: all three corners dominant and above half the threshold), in
/// increasing order. `code` and `mark` are scratch (vertexCount bytes each; `mark` all zero
/// after the call).
void ridgeCandidateVertices(std::span<const std::array<uint32_t, 3>> faces, const MeshAdjacency& adj,
                            const SurfaceFields& fields, const RidgeSpec& spec, std::vector<uint8_t>& code,
                            std::vector<uint8_t>& mark, std::vector<uint32_t>& out);

/// Per view, per vertex: what apparent ridges need (Judd, Durand, Adelson, "Apparent Ridges
/// for Line Drawing", SIGGRAPH 2007, §3–4). The view-dependent curvature operator Q = S·P⁻¹
/// maps a direction in the image (P projects the tangent plane onto the plane facing the
/// viewer, P⁻¹ = I + (secθ − 1)·ŵŵᵀ in the tangent plane, ŵ the unit projected view
/// vector) to the change of the normal; q1 is its largest singular value, t1 the image
/// direction it belongs to. An apparent ridge is where q1 has a maximum along t1: the
/// curvature of the shape as the image shows it, so the lines move over the surface as the
/// view changes and gather towards the contours, where secθ grows.
struct ApparentRidgeQuantities {
  std::vector<float> ndotv;     ///< n·v̂ (faces need all three corners > 0)
  std::vector<float> q1;        ///< the maximum view-dependent curvature, 1/units, ≥ 0
  std::vector<glm::vec3> t1;    ///< unit surface direction P⁻¹t1 (sign arbitrary)
  std::vector<float> dt1q1;     ///< the derivative of q1 along t1, 1/units² (sign follows t1)
};

/// |cosθ| in secθ is at least this, so q1 stays finite at the contour (where it grows without
/// bound, and apparent ridges give way to the contour itself).
inline constexpr float kApparentRidgeMinCos = 1e-4f;

/// Fills `out` (vertexCount entries each) for `view` from the normals, principal curvatures
/// and directions of `fields`; Dt1 q1 from the area-weighted mean of the faces' gradients
/// of q1 around each vertex (the mean, not the sum: a vertex's ring area must not scale it,
/// or the crossings between vertices would move).
/// `pool` (optional) splits the vertices over its threads; the result is the same.
void computeApparentRidgeQuantities(std::span<const std::array<uint32_t, 3>> faces, const MeshAdjacency& adj,
                                    const SurfaceFields& fields, const ViewSpec& view, ApparentRidgeQuantities& out,
                                    WorkerPool* pool = nullptr);

/// Appends the apparent ridges (LineKind::kApparentRidge) of the front-facing valid faces to
/// `out`: maxima of q1 along t1 where q1·fs exceeds `threshold`, faded in over one more
/// threshold; endpoint ids the edges' indices.
void extractApparentRidges(std::span<const glm::vec3> positions, std::span<const std::array<uint32_t, 3>> faces,
                           const MeshAdjacency& adj, const ApparentRidgeQuantities& q, float threshold,
                           float feature_size, LineSet& out);

/// Per view, per vertex: what principal highlights need (DeCarlo & Rusinkiewicz, "Highlight
/// Lines for Conveying Shape", NPAR 2007, §4). Along the dominant principal direction e (that
/// of the larger |k|), n·v̂ changes at the rate −k·(v̂·e): where v̂·e = 0 on a convex part,
/// n·v̂ has a maximum across the strongly curved direction — the line a headlight's
/// highlight runs along on a ridge-like shape. Drawn where the anisotropy (k_d² − k_o²)·n·v̂·fs²
/// exceeds the threshold.
struct PrincipalHighlightQuantities {
  std::vector<float> ndotv;
  std::vector<glm::vec3> e;     ///< the dominant principal direction (sign arbitrary)
  std::vector<float> vdote;     ///< v̂·e (sign follows e)
  std::vector<float> strength;  ///< (k_d² − k_o²)·n·v̂·fs² where k_d > 0 and n·v̂ > 0, else 0
  std::vector<uint8_t> first;   ///< 1 where e is e1 (|k1| ≥ |k2|), 0 where it is e2
};

void computePrincipalHighlightQuantities(const SurfaceFields& fields, const ViewSpec& view, float feature_size,
                                         PrincipalHighlightQuantities& out, WorkerPool* pool = nullptr);

/// Appends the principal highlights (LineKind::kPrincipalHighlight): zero crossings of v̂·e
/// with the directions' signs agreed per edge, in faces whose corners are all convex and
/// front-facing and dominated by the same principal direction, where the strength exceeds
/// `threshold` (faded in over one more threshold).
void extractPrincipalHighlights(std::span<const glm::vec3> positions, std::span<const std::array<uint32_t, 3>> faces,
                                const MeshAdjacency& adj, const PrincipalHighlightQuantities& q, float threshold,
                                LineSet& out);

/// Appends the ridge (LineKind::kRidge) and valley (kValley) segments of the valid faces to
/// `out`, each endpoint id the index of the edge it lies on. Needs fields.k1, k2, pdir1,
/// pdir2 and dcurv valid at the candidate vertices (ridgeCandidateVertices()). `c111` and
/// `c222` (optional, vertexCount each) replace dcurv's C(e1,e1,e1) and C(e2,e2,e2) along
/// fields.pdir1 and pdir2 (temporally smoothed in sequences).
void extractRidges(std::span<const glm::vec3> positions, std::span<const std::array<uint32_t, 3>> faces,
                   const MeshAdjacency& adj, const SurfaceFields& fields, const RidgeSpec& spec,
                   LineScratch& scratch, LineSet& out, std::span<const float> c111 = {},
                   std::span<const float> c222 = {});

}  // namespace lodline
