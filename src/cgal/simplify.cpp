#include "cgal/simplify.h"

#include "cgal/mesh_distance.h"
#include "pm/progressive_mesh.h"

namespace lodline {

Result<SimplifyOutcome> simplifyMesh(const TriMesh& mesh, double bound, const std::string& what) {
  auto pm = buildProgressiveMesh(mesh);
  if (!pm) return Error::runtime(what + ": " + pm.error().message);
  auto tree = SurfaceDistance::create(mesh, what);
  if (!tree) return tree.error();
  const double diagonal = computeBounds(mesh.positions).diagonal();
  if (!(diagonal > 0.0)) return Error::runtime(what + ": bounding box has zero diagonal");
  auto error = [&](const TriMesh& candidate) -> double {
    auto d = measureMeshDistance(mesh, *tree, candidate);
    return d ? d->e_s / diagonal : -1.0;
  };
  BoundedSimplification b = simplifyWithinBound(*pm, bound, error);
  auto d = measureMeshDistance(mesh, *tree, b.mesh);
  if (!d) return Error::runtime(what + ": " + d.error().message);
  SimplifyOutcome out;
  out.mesh = std::move(b.mesh);
  out.e_s = d->e_s;
  out.e_s_rel = d->relativeEs();
  out.hausdorff = d->hausdorff;
  out.evaluations = b.evaluations + 1;
  return out;
}

}  // namespace lodline
