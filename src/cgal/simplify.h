// Static pre-simplification within a measured error bound: the static half of Pan, Zhou,
// Shi, "Real-time rendering algorithm based on hybrid static and dynamic simplification
// methods" (docs/design.md §2.4). The quadric-error half-edge collapses of the
// progressive-mesh builder (src/pm) run until the measured error
//   E_s = (Σ_{v∈X_o} d(v,M_s) + Σ_{v∈X_s} d(v,M_o)) / (|X_o|+|X_s|)
// (exact distances through CGAL's AABB tree, mesh_distance.h) would exceed the bound × the
// bounding-box diagonal; the returned level is always a measured one, so the bound is never
// exceeded. Part of the optional lodline_cgal target; a build without CGAL links
// simplify_unavailable.cpp instead, whose simplifyMesh() says so.
#pragma once

#include <string>

#include "core/mesh.h"
#include "core/result.h"

namespace lodline {

/// Outcome of simplifyMesh().
struct SimplifyOutcome {
  TriMesh mesh;            ///< the simplified mesh
  double e_s_rel = 0.0;    ///< measured E_s / diagonal
  double e_s = 0.0;        ///< measured E_s, model units
  double hausdorff = 0.0;  ///< symmetric Hausdorff distance over the vertices, model units
  int evaluations = 0;     ///< E_s measurements made by the search
};

/// Simplifies `mesh` as far as E_s stays within `bound` (a fraction of the bounding-box
/// diagonal, e.g. 0.0002 for 0.02%). `what` names the model in errors.
Result<SimplifyOutcome> simplifyMesh(const TriMesh& mesh, double bound, const std::string& what);

}  // namespace lodline
