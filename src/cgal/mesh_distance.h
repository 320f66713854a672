// Exact surface-to-surface distances between two triangle meshes, for the static half of
//
//   Pan, Zhou, Shi, "Real-time rendering algorithm based on hybrid static and dynamic
//   simplification methods" (docs/design.md §2.4): the approximation error of a simplified mesh
//     E_s = (Σ_{v∈X_o} d(v, M_s) + Σ_{v∈X_s} d(v, M_o)) / (|X_o| + |X_s|),
//   X_o, X_s the vertex sets of the original and simplified meshes and d the exact
//   point-to-surface distance, reported relative to the bounding-box diagonal of M_o.
//
// The distances come from CGAL's AABB_tree (Simple_cartesian<double> kernel). CGAL stays in
// one translation unit (cgal_algorithms.cpp) of the optional target lodline_cgal; this header
// has no CGAL in it.
#pragma once

#include <memory>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "core/mesh.h"
#include "core/result.h"

namespace lodline {

/// An AABB tree over the triangles of one mesh for exact point-to-surface distances.
/// Degenerate (zero-area) triangles are left out. Move-only.
class SurfaceDistance {
 public:
  /// Builds the tree of `mesh` (its positions and faces are copied). Error if the mesh has
  /// no non-degenerate triangle; `what` (usually a file name) prefixes the message.
  static Result<SurfaceDistance> create(const TriMesh& mesh, const std::string& what);
  SurfaceDistance(SurfaceDistance&&) noexcept;
  SurfaceDistance& operator=(SurfaceDistance&&) noexcept;
  ~SurfaceDistance();

  /// Distance from `p` to the nearest point of the surface, model units.
  double distance(const glm::vec3& p) const;
  /// `out` gets points.size() distances, model units (runs on up to 2 threads).
  void distances(std::span<const glm::vec3> points, std::vector<double>& out) const;

 private:
  struct Impl;
  explicit SurfaceDistance(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

/// Pan et al.'s two-sided error and the symmetric Hausdorff distance over the vertices.
struct MeshDistance {
  double e_s = 0.0;         ///< E_s, model units
  double hausdorff = 0.0;   ///< max over both vertex sets of the same distances, model units
  double mean_o_to_s = 0.0; ///< mean d(v, M_s) over X_o
  double mean_s_to_o = 0.0; ///< mean d(v, M_o) over X_s
  double diagonal = 0.0;    ///< bounding-box diagonal of M_o, model units
  double relativeEs() const { return diagonal > 0.0 ? e_s / diagonal : 0.0; }
  double relativeHausdorff() const { return diagonal > 0.0 ? hausdorff / diagonal : 0.0; }
};

/// E_s and Hausdorff of `simplified` against `original`, with `original_tree` built from
/// `original` (reused across calls, e.g. while searching for an error bound).
Result<MeshDistance> measureMeshDistance(const TriMesh& original, const SurfaceDistance& original_tree,
                                         const TriMesh& simplified);

/// One-shot form: builds both trees.
Result<MeshDistance> measureMeshDistance(const TriMesh& original, const TriMesh& simplified);

}  // namespace lodline
