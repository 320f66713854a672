#include "shape/jet_fit.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include <Eigen/Dense>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/ext/vector_double2.hpp>
#include <glm/ext/vector_double3.hpp>

namespace lodline {
namespace {

// Monomials x^i y^j with 1 ≤ i + j ≤ degree, by degree then by decreasing power of x:
// x, y, x², xy, y², x³, x²y, xy², y³, x⁴, … (no constant: the vertex lies on the surface).
int coefficientCount(int degree) { return (degree + 1) * (degree + 2) / 2 - 1; }

// Index of x^i y^j in that order.
int monomial(int i, int j) {
  const int d = i + j;
  return coefficientCount(d - 1) + j;
}

// A unit vector perpendicular to unit n.
glm::vec3 anyPerpendicular(glm::vec3 n) {
  const glm::vec3 a = std::abs(n.x) < 0.6f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  return glm::normalize(a - glm::dot(a, n) * n);
}

constexpr int kMaxCoefficients = 14;  // degree 4
using Vec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxCoefficients, 1>;
using Mat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxCoefficients, kMaxCoefficients>;

struct Fit {
  Vec c;  // coefficients of the monomials, unscaled
  bool ok = false;
};

// The monomials of (x, y) up to `degree`, in coefficient order.
void monomials(double x, double y, int degree, double* out) {
  double xp[5] = {1.0, x, x * x, x * x * x, x * x * x * x};
  double yp[5] = {1.0, y, y * y, y * y * y, y * y * y * y};
  int k = 0;
  for (int deg = 1; deg <= degree; ++deg)
    for (int j = 0; j <= deg; ++j) out[k++] = xp[deg - j] * yp[j];
}

// Least-squares fit of z = f(x, y) with K coefficients over the neighbours' offsets `d`
// from the vertex (scaled by 1/h to the unit disc, which keeps the normal equations well
// conditioned) in the frame (t1, t2, n); a singular system — too few or collinear
// neighbours — is refused.
template <int K>
Fit fitHeightK(std::span<const glm::dvec3> d, double h, glm::dvec3 t1, glm::dvec3 t2, glm::dvec3 n, int degree) {
  using MatK = Eigen::Matrix<double, K, K>;
  using VecK = Eigen::Matrix<double, K, 1>;
  Fit fit;
  if (static_cast<int>(d.size()) < K) return fit;
  MatK M = MatK::Zero();
  VecK r = VecK::Zero(), phi;
  for (const glm::dvec3& q : d) {
    monomials(glm::dot(q, t1), glm::dot(q, t2), degree, phi.data());
    M.noalias() += phi * phi.transpose();
    r += glm::dot(q, n) * phi;
  }
  const Eigen::LDLT<MatK> ldlt(M);
  if (ldlt.info() != Eigen::Success) return fit;
  const VecK D = ldlt.vectorD();
  const double dmax = D.cwiseAbs().maxCoeff();
  if (!(dmax > 0.0) || D.minCoeff() <= 1e-10 * dmax) return fit;
  VecK c = ldlt.solve(r);
  // z/h = Σ c' (x/h)^i (y/h)^j: the unscaled coefficient of a degree-d monomial is c'·h^(1−d).
  double scale = 1.0;
  for (int deg = 1; deg <= degree; ++deg, scale /= h)
    for (int j = 0; j <= deg; ++j) c(monomial(deg - j, j)) *= scale;
  if (!c.allFinite()) return fit;
  fit.c = c;
  fit.ok = true;
  return fit;
}

Fit fitHeight(std::span<const glm::dvec3> d, double h, glm::dvec3 t1, glm::dvec3 t2, glm::dvec3 n, int degree) {
  return degree == 3 ? fitHeightK<9>(d, h, t1, t2, n, 3) : fitHeightK<14>(d, h, t1, t2, n, 4);
}

}  // namespace

namespace {

size_t fitJetsSerial(std::span<const glm::vec3> positions, std::span<const std::array<uint32_t, 3>> faces,
                     const MeshAdjacency& adj, std::span<const glm::vec3> normals, std::span<const uint32_t> vertices,
                     const JetFitParams& params, JetFitScratch& scratch, std::span<float> k1, std::span<float> k2,
                     std::span<glm::vec3> pdir1, std::span<glm::vec3> pdir2, std::span<glm::vec4> dcurv) {
  const int degree = std::clamp(params.degree, 3, 4);
  const size_t need = static_cast<size_t>(std::ceil(params.points_per_coefficient * coefficientCount(degree)));
  const size_t nv = positions.size();
  if (scratch.mark.size() < nv) scratch.mark.assign(nv, 0);
  size_t fitted = 0;
  for (uint32_t v : vertices) {
    if (v >= nv || v >= adj.vertex_count) continue;
    // The neighbourhood: the vertices within a radius of `radius_edges` of v's longest edge,
    // reached through faces (a disc, whatever the triangles' shapes: on a latitude-longitude
    // mesh near a pole, rings of faces would be slivers a few rows wide and hundreds of
    // vertices long), grown until it holds enough vertices.
    const glm::vec3 p0 = positions[v];
    float longest = 0.0f;
    for (uint32_t f : adj.facesOf(v))
      for (uint32_t u : faces[f])
        if (u < nv) longest = std::max(longest, glm::length(positions[u] - p0));
    if (!(longest > 0.0f)) continue;
    std::vector<uint32_t>& ring = scratch.ring;
    float radius = params.radius_edges * longest;
    for (int grow = 0; grow < 6; ++grow, radius *= 1.25f) {
      ring.assign(1, v);
      scratch.mark[v] = 1;
      for (size_t i = 0; i < ring.size(); ++i)
        for (uint32_t f : adj.facesOf(ring[i]))
          for (uint32_t u : faces[f])
            if (u < nv && !scratch.mark[u]) {
              scratch.mark[u] = 1;
              if (glm::length(positions[u] - p0) <= radius) ring.push_back(u);
              else scratch.touched.push_back(u);
            }
      for (uint32_t u : scratch.touched) scratch.mark[u] = 0;
      scratch.touched.clear();
      if (ring.size() >= need) break;
      for (uint32_t u : ring) scratch.mark[u] = 0;
    }
    for (uint32_t u : ring) scratch.mark[u] = 0;
    // The neighbours' offsets from the vertex, scaled to the unit disc.
    double h = 0.0;
    for (uint32_t u : ring) h = std::max(h, glm::length(glm::dvec3(positions[u]) - glm::dvec3(p0)));
    if (!(h > 0.0)) continue;
    scratch.offsets.resize(ring.size());
    for (size_t i = 0; i < ring.size(); ++i) scratch.offsets[i] = (glm::dvec3(positions[ring[i]]) - glm::dvec3(p0)) / h;
    glm::dvec3 n = glm::dvec3(normals[v]);
    if (!(glm::length(n) > 0.5)) continue;
    n = glm::normalize(n);
    // First fit in the frame of the vertex normal; the second in that of the fitted normal
    // (Cazals & Pouget's Monge step), where the gradient of f vanishes to first order.
    Fit fit;
    glm::dvec3 t1, t2;
    bool ok = true;
    for (int pass = 0; pass < 2 && ok; ++pass) {
      t1 = glm::dvec3(anyPerpendicular(glm::vec3(n)));
      t2 = glm::cross(n, t1);
      fit = fitHeight(scratch.offsets, h, t1, t2, n, degree);
      ok = fit.ok;
      if (ok && pass == 0) {
        const double fx = fit.c(monomial(1, 0)), fy = fit.c(monomial(0, 1));
        n = glm::normalize(n - fx * t1 - fy * t2);
      }
    }
    if (!ok) continue;
    const Vec& c = fit.c;
    const double fxx = 2.0 * c(monomial(2, 0)), fxy = c(monomial(1, 1)), fyy = 2.0 * c(monomial(0, 2));
    const double fxxx = 6.0 * c(monomial(3, 0)), fxxy = 2.0 * c(monomial(2, 1)), fxyy = 2.0 * c(monomial(1, 2)),
                 fyyy = 6.0 * c(monomial(0, 3));
    // Shape operator −Hess f: eigenvalues k1 ≥ k2, eigenvector of k1.
    const double a = -fxx, b = -fxy, d = -fyy;
    const double mean = 0.5 * (a + d), rad = std::sqrt(0.25 * (a - d) * (a - d) + b * b);
    const double kmax = mean + rad, kmin = mean - rad;
    glm::dvec2 e(1.0, 0.0);
    const glm::dvec2 v1(b, kmax - a), v2(kmax - d, b);
    const double l1 = glm::length(v1), l2 = glm::length(v2);
    if (std::max(l1, l2) > 1e-12 * std::max(1.0, std::abs(kmax))) e = l1 > l2 ? v1 / l1 : v2 / l2;
    const glm::dvec2 w(-e.y, e.x);  // n × e1 in the (t1, t2) plane
    auto third = [&](glm::dvec2 p, glm::dvec2 q, glm::dvec2 s) {
      return fxxx * p.x * q.x * s.x + fxxy * (p.x * q.x * s.y + p.x * q.y * s.x + p.y * q.x * s.x) +
             fxyy * (p.x * q.y * s.y + p.y * q.x * s.y + p.y * q.y * s.x) + fyyy * p.y * q.y * s.y;
    };
    // Directions in 3D, made tangent to the mesh's normal (the frame the fields use).
    const glm::vec3 nm = glm::normalize(normals[v]);
    glm::vec3 e1 = glm::vec3(e.x * t1 + e.y * t2);
    e1 = e1 - glm::dot(e1, nm) * nm;
    if (!(glm::length(e1) > 1e-6f)) continue;
    e1 = glm::normalize(e1);
    k1[v] = static_cast<float>(kmax);
    k2[v] = static_cast<float>(kmin);
    pdir1[v] = e1;
    pdir2[v] = glm::cross(nm, e1);
    dcurv[v] = glm::vec4(static_cast<float>(-third(e, e, e)), static_cast<float>(-third(e, e, w)),
                         static_cast<float>(-third(e, w, w)), static_cast<float>(-third(w, w, w)));
    ++fitted;
  }
  return fitted;
}

}  // namespace

size_t fitJets(std::span<const glm::vec3> positions, std::span<const std::array<uint32_t, 3>> faces,
               const MeshAdjacency& adj, std::span<const glm::vec3> normals, std::span<const uint32_t> vertices,
               const JetFitParams& params, JetFitScratch& scratch, std::span<float> k1, std::span<float> k2,
               std::span<glm::vec3> pdir1, std::span<glm::vec3> pdir2, std::span<glm::vec4> dcurv, WorkerPool* pool) {
  if (!pool || pool->threadCount() < 2 || vertices.size() < 256)
    return fitJetsSerial(positions, faces, adj, normals, vertices, params, scratch, k1, k2, pdir1, pdir2, dcurv);
  // One chunk per thread, each with its own marks (a vertex's outputs are its own).
  const size_t chunk = (vertices.size() + pool->threadCount() - 1) / pool->threadCount();
  std::atomic<size_t> fitted{0};
  pool->forRange(vertices.size(), chunk, [&](size_t begin, size_t end) {
    JetFitScratch local;
    fitted += fitJetsSerial(positions, faces, adj, normals, vertices.subspan(begin, end - begin), params, local, k1,
                            k2, pdir1, pdir2, dcurv);
  });
  return fitted.load();
}

SurfaceFields FittedFields::fit(const SurfaceFields& from, std::span<const std::array<uint32_t, 3>> faces,
                                const MeshAdjacency& adj, std::span<const uint32_t> vertices,
                                const JetFitParams& params, WorkerPool* pool) {
  k1_.assign(from.k1.begin(), from.k1.end());
  k2_.assign(from.k2.begin(), from.k2.end());
  pdir1_.assign(from.pdir1.begin(), from.pdir1.end());
  pdir2_.assign(from.pdir2.begin(), from.pdir2.end());
  dcurv_.assign(from.k1.size(), glm::vec4(0.0f));
  fitted_ = fitJets(from.positions, faces, adj, from.normals, vertices, params, scratch_, k1_, k2_, pdir1_, pdir2_,
                    dcurv_, pool);
  SurfaceFields out = from;
  out.k1 = k1_;
  out.k2 = k2_;
  out.pdir1 = pdir1_;
  out.pdir2 = pdir2_;
  out.dcurv = dcurv_;
  return out;
}

}  // namespace lodline
