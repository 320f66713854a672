// The only translation unit that includes CGAL (its templates are slow to compile, so they
// are instantiated once):
// - mesh_distance.h: point-to-triangle distances through CGAL::AABB_tree over a
//   Simple_cartesian<double> kernel, for the error E_s of Pan, Zhou, Shi (hybrid static +
//   dynamic simplification, docs/design.md §2.4);
// - intersections.h: where surfaces cross, from CGAL's box intersection and exact
//   triangle-triangle intersection (Epick kernel).
#include "cgal/intersections.h"
#include "cgal/mesh_distance.h"

#include <algorithm>
#include <cmath>
#include <thread>

#include <glm/geometric.hpp>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Box_intersection_d/Box_with_handle_d.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/box_intersection_d.h>


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

// ---- Intersection lines ----

namespace {

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;

// One triangle of one mesh, as the box intersection sees it.
struct TriangleRef {
  uint32_t mesh;
  uint32_t face;
};

glm::dvec3 toVec(const Epick::Point_3& p) { return {p.x(), p.y(), p.z()}; }

// The piece of triangle `t` on the plane of `plane` (three points): the points where its
// edges cross the plane, from the exact side of each corner (CGAL::orientation), so a
// corner on the plane is itself a point and no division is by zero. False when `t` does
// not reach the plane in a segment.
bool pieceOnPlane(const Epick::Triangle_3& t, const Epick::Triangle_3& plane, glm::dvec3& a, glm::dvec3& b) {
  int side[3];
  double dist[3];
  const glm::dvec3 o = toVec(plane[0]);
  const glm::dvec3 n = glm::cross(toVec(plane[1]) - o, toVec(plane[2]) - o);
  for (int i = 0; i < 3; ++i) {
    side[i] = static_cast<int>(CGAL::orientation(plane[0], plane[1], plane[2], t[i]));
    dist[i] = glm::dot(toVec(t[i]) - o, n);
  }
  glm::dvec3 pts[3];
  int n_pts = 0;
  for (int i = 0; i < 3 && n_pts < 3; ++i) {
    const int j = (i + 1) % 3;
    if (side[i] == 0) pts[n_pts++] = toVec(t[i]);
    if (side[i] != 0 && side[j] != 0 && side[i] != side[j]) {
      const double s = dist[i] / (dist[i] - dist[j]);
      pts[n_pts++] = toVec(t[i]) + std::clamp(s, 0.0, 1.0) * (toVec(t[j]) - toVec(t[i]));
    }
  }
  if (n_pts < 2) return false;
  a = pts[0];
  b = pts[1];
  return true;
}

// The segment where two intersecting, non-coplanar triangles cross: the overlap, along the
// line of the two planes, of each triangle's piece on the other's plane.
bool crossingSegment(const Epick::Triangle_3& ta, const Epick::Triangle_3& tb, glm::dvec3& p0, glm::dvec3& p1) {
  glm::dvec3 a0, a1, b0, b1;
  if (!pieceOnPlane(ta, tb, a0, a1) || !pieceOnPlane(tb, ta, b0, b1)) return false;
  const glm::dvec3 d = a1 - a0;
  const double len2 = glm::dot(d, d);
  if (!(len2 > 0.0)) return false;
  // Parameters along a0 + t·d.
  double tb0 = glm::dot(b0 - a0, d) / len2, tb1 = glm::dot(b1 - a0, d) / len2;
  if (tb0 > tb1) std::swap(tb0, tb1);
  const double lo = std::max(0.0, tb0), hi = std::min(1.0, tb1);
  if (!(hi > lo)) return false;
  p0 = a0 + lo * d;
  p1 = a0 + hi * d;
  return std::isfinite(p0.x) && std::isfinite(p0.y) && std::isfinite(p0.z) && std::isfinite(p1.x) &&
         std::isfinite(p1.y) && std::isfinite(p1.z);
}

}  // namespace

std::vector<std::vector<glm::vec3>> findIntersectionSegments(std::span<const TriMesh* const> meshes) {
  std::vector<std::vector<glm::vec3>> out(meshes.size());
  std::vector<TriangleRef> refs;
  std::vector<Epick::Triangle_3> triangles;
  using Box = CGAL::Box_intersection_d::Box_with_handle_d<double, 3, const TriangleRef*,
                                                          CGAL::Box_intersection_d::ID_EXPLICIT>;
  for (uint32_t m = 0; m < meshes.size(); ++m) {
    const TriMesh& mesh = *meshes[m];
    for (uint32_t f = 0; f < mesh.faces.size(); ++f) {
      const auto& t = mesh.faces[f];
      if (t[0] >= mesh.positions.size() || t[1] >= mesh.positions.size() || t[2] >= mesh.positions.size()) continue;
      const glm::vec3 &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
      const Epick::Triangle_3 tri(Epick::Point_3(a.x, a.y, a.z), Epick::Point_3(b.x, b.y, b.z),
                                  Epick::Point_3(c.x, c.y, c.z));
      if (tri.is_degenerate()) continue;
      refs.push_back({m, f});
      triangles.push_back(tri);
    }
  }
  std::vector<Box> boxes;
  boxes.reserve(refs.size());
  for (size_t i = 0; i < refs.size(); ++i) boxes.emplace_back(triangles[i].bbox(), &refs[i]);
  auto index = [&](const TriangleRef* r) { return static_cast<size_t>(r - refs.data()); };
  auto callback = [&](const Box& a, const Box& b) {
    const TriangleRef* ra = a.handle();
    const TriangleRef* rb = b.handle();
    {  // triangles with a common corner (neighbours, or parts touching there) do not cross
      const TriMesh& ma = *meshes[ra->mesh];
      const TriMesh& mb = *meshes[rb->mesh];
      for (uint32_t va : ma.faces[ra->face])
        for (uint32_t vb : mb.faces[rb->face])
          if ((ra->mesh == rb->mesh && va == vb) || ma.positions[va] == mb.positions[vb]) return;
    }
    const Epick::Triangle_3& ta = triangles[index(ra)];
    const Epick::Triangle_3& tb = triangles[index(rb)];
    // Coplanar triangles overlap in an area (duplicate faces, coincident objects), not along
    // a curve; CGAL's construction for them is also not safe with inexact constructions.
    if (CGAL::coplanar(ta[0], ta[1], ta[2], tb[0]) && CGAL::coplanar(ta[0], ta[1], ta[2], tb[1]) &&
        CGAL::coplanar(ta[0], ta[1], ta[2], tb[2]))
      return;
    if (!CGAL::do_intersect(ta, tb)) return;
    glm::dvec3 p0, p1;
    if (!crossingSegment(ta, tb, p0, p1)) return;
    const uint32_t owner = std::min(ra->mesh, rb->mesh);
    out[owner].push_back(glm::vec3(p0));
    out[owner].push_back(glm::vec3(p1));
  };
  CGAL::box_self_intersection_d<CGAL::Sequential_tag>(boxes.begin(), boxes.end(), callback);
  return out;
}

}  // namespace lodline
