// The only translation unit that includes CGAL (see mesh_distance.h): point-to-triangle
// distances through CGAL::AABB_tree over a Simple_cartesian<double> kernel, for the error
// E_s of Pan, Zhou, Shi (hybrid static + dynamic simplification, docs/design.md §2.4).
#include "cgal/mesh_distance.h"

#include <algorithm>
#include <cmath>
#include <thread>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

namespace lodline {

namespace {
using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using TriangleIterator = std::vector<Triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, TriangleIterator>;
using Traits = CGAL::AABB_traits<Kernel, Primitive>;
using Tree = CGAL::AABB_tree<Traits>;

Point toPoint(const glm::vec3& p) { return Point(p.x, p.y, p.z); }
}  // namespace

struct SurfaceDistance::Impl {
  std::vector<Triangle> triangles;
  Tree tree;
};

SurfaceDistance::SurfaceDistance(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
SurfaceDistance::SurfaceDistance(SurfaceDistance&&) noexcept = default;
SurfaceDistance& SurfaceDistance::operator=(SurfaceDistance&&) noexcept = default;
SurfaceDistance::~SurfaceDistance() = default;

Result<SurfaceDistance> SurfaceDistance::create(const TriMesh& mesh, const std::string& what) {
  auto impl = std::make_unique<Impl>();
  impl->triangles.reserve(mesh.faces.size());
  for (const auto& f : mesh.faces) {
    if (f[0] >= mesh.positions.size() || f[1] >= mesh.positions.size() || f[2] >= mesh.positions.size())
      return Error::runtime(what + ": face references a vertex out of range");
    const Triangle t(toPoint(mesh.positions[f[0]]), toPoint(mesh.positions[f[1]]), toPoint(mesh.positions[f[2]]));
    if (t.is_degenerate()) continue;
    impl->triangles.push_back(t);
  }
  if (impl->triangles.empty()) return Error::runtime(what + ": no non-degenerate triangle to measure distances to");
  impl->tree.rebuild(impl->triangles.begin(), impl->triangles.end());
  impl->tree.accelerate_distance_queries();
  return SurfaceDistance(std::move(impl));
}

double SurfaceDistance::distance(const glm::vec3& p) const {
  return std::sqrt(impl_->tree.squared_distance(toPoint(p)));
}

void SurfaceDistance::distances(std::span<const glm::vec3> points, std::vector<double>& out) const {
  out.resize(points.size());
  auto work = [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) out[i] = std::sqrt(impl_->tree.squared_distance(toPoint(points[i])));
  };
  // The tree is read-only after accelerate_distance_queries(): queries may run concurrently.
  if (points.size() < 4096) {
    work(0, points.size());
    return;
  }
  const size_t half = points.size() / 2;
  std::thread helper(work, half, points.size());
  work(0, half);
  helper.join();
}

Result<MeshDistance> measureMeshDistance(const TriMesh& original, const SurfaceDistance& original_tree,
                                         const TriMesh& simplified) {
  auto simplified_tree = SurfaceDistance::create(simplified, "simplified mesh");
  if (!simplified_tree) return simplified_tree.error();
  MeshDistance m;
  m.diagonal = computeBounds(original.positions).diagonal();
  std::vector<double> d_o, d_s;
  simplified_tree->distances(original.positions, d_o);  // X_o against M_s
  original_tree.distances(simplified.positions, d_s);   // X_s against M_o
  double sum_o = 0.0, sum_s = 0.0;
  for (double d : d_o) { sum_o += d; m.hausdorff = std::max(m.hausdorff, d); }
  for (double d : d_s) { sum_s += d; m.hausdorff = std::max(m.hausdorff, d); }
  const size_t n = d_o.size() + d_s.size();
  m.e_s = n ? (sum_o + sum_s) / static_cast<double>(n) : 0.0;
  m.mean_o_to_s = d_o.empty() ? 0.0 : sum_o / static_cast<double>(d_o.size());
  m.mean_s_to_o = d_s.empty() ? 0.0 : sum_s / static_cast<double>(d_s.size());
  return m;
}

Result<MeshDistance> measureMeshDistance(const TriMesh& original, const TriMesh& simplified) {
  auto tree = SurfaceDistance::create(original, "original mesh");
  if (!tree) return tree.error();
  return measureMeshDistance(original, *tree, simplified);
}

}  // namespace lodline
