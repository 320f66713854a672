// Ridges and valleys on analytic surfaces (docs/lines.md): the ridges of an ellipsoid with
// three different axes lie in its symmetry planes (they are arcs of its principal ellipses),
// within a tolerance that shrinks as the mesh is refined; turned inside out, the same lines
// are valleys. The errors printed are the table in docs/lines.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "core/worker_pool.h"
#include "io/generate.h"
#include "lines/lines.h"
#include "lines/ridge_lines.h"
#include "shape/jet_fit.h"
#include "shape/shape_cache.h"

namespace lodline {
namespace {

constexpr float kA = 1.0f, kB = 0.7f, kC = 0.5f;

// `fit`: ridges from fitted jets (shape/jet_fit.h, --ridge-estimator fit) at every vertex.
LineSet ridgeLines(const TriMesh& m, bool ridges, bool valleys, float threshold = 0.05f, bool fit = false) {
  ShapeCache shape;
  shape.compute(m);
  FittedFields fitted;
  SurfaceFields f = shape.fields(m);
  if (fit) {
    std::vector<uint32_t> all(m.positions.size());
    for (uint32_t v = 0; v < all.size(); ++v) all[v] = v;
    f = fitted.fit(f, m.faces, shape.adjacency(), all);
    EXPECT_EQ(fitted.fitted(), all.size());
  }
  RidgeSpec spec;
  spec.ridges = ridges;
  spec.valleys = valleys;
  spec.threshold = threshold;
  spec.feature_size = 1.0f;  // absolute: |k| > threshold
  LineScratch scratch;
  LineSet out;
  extractRidges(m.positions, m.faces, shape.adjacency(), f, spec, scratch, out);
  return out;
}

// Distance from the nearest symmetry plane, in units of that axis (0 on the plane).
double offPlanes(const glm::vec3& p) {
  return std::min({std::abs(p.x) / kA, std::abs(p.y) / kB, std::abs(p.z) / kC});
}

double lengthOf(const LineSet& s) {
  double len = 0.0;
  for (size_t i = 0; i < s.segmentCount(); ++i) len += glm::length(s.points[2 * i + 1] - s.points[2 * i]);
  return len;
}

TriMesh uvEllipsoid(int n) {
  TriMesh m = makeUvSphere(1.0f, 2 * n, n);
  for (auto& p : m.positions) p *= glm::vec3(kA, kB, kC);
  return m;
}

TEST(RidgeLines, EllipsoidRidgesLieInItsSymmetryPlanes) {
  // A latitude-longitude ellipsoid (poles on the y axis): its vertex rows are symmetric about
  // the three planes. The discrete curvature is noisy by about 3% (more at the poles), and
  // where k1 is nearly flat across a ridge the line wobbles by an edge or two; the mean
  // distance shrinks with refinement, the largest stays within a few edge lengths (table in
  // docs/lines.md).
  double previous_mean = 1e9;
  for (int n : {24, 48, 96, 192}) {
    const TriMesh m = uvEllipsoid(n);
    const LineSet s = ridgeLines(m, true, false);
    ASSERT_GT(s.segmentCount(), 0u);
    EXPECT_EQ(s.counts[static_cast<int>(LineKind::kValley)], 0u) << "a convex surface has no valleys";
    std::vector<double> off;
    double weighted = 0.0, total_alpha = 0.0;
    for (size_t i = 0; i < s.points.size(); ++i) {
      off.push_back(offPlanes(s.points[i]));
      weighted += s.alpha[i] * off.back();
      total_alpha += s.alpha[i];
    }
    std::sort(off.begin(), off.end());
    const double mean = weighted / total_alpha, p99 = off[off.size() * 99 / 100], worst = off.back();
    const double len = lengthOf(s);
    std::printf("ridges, ellipsoid %dx%d (%zu faces): length %.2f, off the planes: mean %.2e, 99%% %.2e, max %.2e\n",
                2 * n, n, m.faces.size(), len, mean, p99, worst);
    // The principal ellipse in the plane z = 0 (circumference 5.4) is a ridge all round.
    EXPECT_GT(len, 5.0);
    EXPECT_LT(mean, previous_mean) << "the error shrinks as the ellipsoid is refined";
    EXPECT_LT(worst, 0.08);
    previous_mean = mean;
  }
  EXPECT_LT(previous_mean, 0.01);
}

struct OffPlanes {
  double length = 0.0, mean = 0.0, worst = 0.0;
};
OffPlanes offPlanesOf(const LineSet& s) {
  OffPlanes o;
  double total_alpha = 0.0;
  for (size_t i = 0; i < s.points.size(); ++i) {
    const double d = offPlanes(s.points[i]);
    o.mean += s.alpha[i] * d;
    total_alpha += s.alpha[i];
    o.worst = std::max(o.worst, d);
  }
  o.mean /= std::max(total_alpha, 1e-30);
  o.length = lengthOf(s);
  return o;
}

// An icosphere ellipsoid with every vertex moved along the surface by up to a quarter of an
// edge (deterministic), so that no symmetry of the mesh puts the lines on the planes.
TriMesh jitteredEllipsoid(int level) {
  TriMesh m = makeEllipsoid(kA, kB, kC, level);
  const float edge = 0.9f * kA * 1.1f / static_cast<float>(1 << level);
  uint32_t state = 12345u;
  auto next = [&] {
    state = state * 1664525u + 1013904223u;
    return static_cast<float>(state >> 8) / static_cast<float>(1u << 24) - 0.5f;
  };
  for (glm::vec3& p : m.positions) {
    p += 0.5f * edge * glm::vec3(next(), next(), next());
    const glm::vec3 q = p / glm::vec3(kA, kB, kC);
    p /= glm::length(q);  // back onto the ellipsoid
  }
  return m;
}

TEST(RidgeLines, FittedJetRidgesConvergeOnAnIrregularEllipsoid) {
  // The per-face tensors' derivative is noisy where k1 is nearly flat across a ridge, and
  // does not converge pointwise on an irregular mesh: off the planes they draw spurious
  // ridges that refinement does not remove. The fitted jets' third derivatives converge:
  // the ridges' distance from the planes shrinks with the edge length (table in
  // docs/lines.md), and their length is the principal ellipses' arcs' (5.38) at every level.
  double previous_mean = 1e9, previous_worst = 1e9;
  for (int level : {3, 4, 5, 6}) {
    const TriMesh m = jitteredEllipsoid(level);
    const OffPlanes fit = offPlanesOf(ridgeLines(m, true, false, 0.05f, true));
    const OffPlanes tensor = offPlanesOf(ridgeLines(m, true, false));
    std::printf("ridges, jittered ellipsoid level %d (%zu faces): fitted jets length %.2f, off the planes mean %.2e "
                "max %.2e; tensors length %.2f, mean %.2e max %.2e\n",
                level, m.faces.size(), fit.length, fit.mean, fit.worst, tensor.length, tensor.mean, tensor.worst);
    EXPECT_NEAR(fit.length, 5.38, 0.15);
    EXPECT_LT(fit.mean, previous_mean);
    EXPECT_LT(fit.worst, previous_worst);
    if (level >= 4) {
      EXPECT_LT(fit.worst, tensor.worst);
    }
    previous_mean = fit.mean;
    previous_worst = fit.worst;
  }
  // A cubic fit, or one left in the mesh normal's frame, stays above 7e-3 at 82k faces.
  EXPECT_LT(previous_worst, 2e-3);
}

TEST(RidgeLines, FittedJetRidgesOnALatitudeLongitudeEllipsoid) {
  // The mesh of EllipsoidRidgesLieInItsSymmetryPlanes, whose poles are fans of slivers:
  // neighbourhoods are discs in space, not rings of faces, so the fit holds there too.
  for (int n : {24, 48, 96, 192}) {
    const TriMesh m = uvEllipsoid(n);
    const OffPlanes fit = offPlanesOf(ridgeLines(m, true, false, 0.05f, true));
    const OffPlanes tensor = offPlanesOf(ridgeLines(m, true, false));
    std::printf("ridges, ellipsoid %dx%d: fitted jets length %.2f, off the planes mean %.2e max %.2e; tensors length "
                "%.2f, mean %.2e max %.2e\n",
                2 * n, n, fit.length, fit.mean, fit.worst, tensor.length, tensor.mean, tensor.worst);
    EXPECT_NEAR(fit.length, 5.38, 0.1);
    EXPECT_LT(fit.worst, 0.3 * tensor.worst);
    EXPECT_LT(fit.worst, 1e-3);
  }
}

TEST(RidgeLines, InsideOutRidgesAreValleys) {
  TriMesh m = makeEllipsoid(kA, kB, kC, 4);
  const LineSet ridges = ridgeLines(m, true, true);
  for (auto& f : m.faces) std::swap(f[1], f[2]);  // normals inward: every curvature negates
  const LineSet valleys = ridgeLines(m, true, true);
  const uint32_t r = ridges.counts[static_cast<int>(LineKind::kRidge)];
  EXPECT_GT(r, 0u);
  // The same lines up to rounding (the curvature is estimated from corners in another order).
  EXPECT_NEAR(valleys.counts[static_cast<int>(LineKind::kValley)], r, 0.02 * r);
  EXPECT_EQ(valleys.counts[static_cast<int>(LineKind::kRidge)], 0u);
}

TEST(RidgeLines, TheThresholdRemovesWeakLines) {
  const TriMesh m = makeEllipsoid(kA, kB, kC, 4);
  // k1 on the ridges runs from b/c² = 2.8 (the middle axis' tips) to a/c² = 4 (the long
  // axis'): above that, nothing; at 3.3 only the parts near the long axis' tips.
  EXPECT_EQ(ridgeLines(m, true, true, 8.0f).segmentCount(), 0u);
  const size_t all = ridgeLines(m, true, true, 0.05f).segmentCount();
  const size_t strong = ridgeLines(m, true, true, 3.3f).segmentCount();
  EXPECT_GT(strong, 0u);
  EXPECT_LT(strong, all);
}

TEST(RidgeLines, SharedEdgesGiveIdenticalPoints) {
  const TriMesh m = makeEllipsoid(kA, kB, kC, 5);
  const LineSet s = ridgeLines(m, true, false);
  // Two points with the same edge id are the same point, bit for bit (chaining relies on it).
  std::vector<std::pair<uint32_t, glm::vec3>> seen;
  for (size_t i = 0; i < s.points.size(); ++i) seen.emplace_back(s.point_ids[i], s.points[i]);
  std::sort(seen.begin(), seen.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  size_t shared = 0;
  for (size_t i = 1; i < seen.size(); ++i) {
    if (seen[i].first != seen[i - 1].first) continue;
    ++shared;
    EXPECT_EQ(seen[i].second, seen[i - 1].second);
  }
  EXPECT_GT(shared, s.segmentCount() / 2) << "most segments continue through their edges";
}

}  // namespace
}  // namespace lodline

namespace lodline {
namespace {

// Apparent ridges (Judd, Durand, Adelson 2007) follow the view. A rounded box's fillet has the
// same curvature 1/r all across, so its ordinary ridge is undefined; seen from a view, the
// view-dependent curvature q1 = secθ/r grows towards the side of the fillet that turns away
// from the viewer, and the strong apparent ridge runs along the fillet's join with the face
// seen more obliquely (q1 ≈ 2.9/r there for a view 20° off the other face; q1 falls to 0 on
// the flat faces, so a weak maximum, q1 ≈ 1.06/r, also lies at the other join: the threshold,
// 5 with r = 0.3, keeps the strong one). Turning the view from near +z to near +x moves it
// across the fillet of the vertical edge between the +x and +z faces. Without the view term
// q1 = 1/r = 3.3 on the whole fillet, below the threshold, and the test fails.
TEST(ApparentRidges, FollowTheViewAcrossARoundedEdge) {
  const glm::vec3 half(1.0f, 1.0f, 1.0f);
  const float r = 0.3f;
  const TriMesh m = makeRoundedBox(half, r, 16, 12);
  ShapeCache shape;
  shape.compute(m);
  const glm::vec2 axis(half.x - r, half.z - r);  // the fillet's axis in (x, z)
  for (float az_deg : {20.0f, 70.0f}) {
    const float az = glm::radians(az_deg);
    ViewSpec view;
    view.orthographic = true;
    view.toward_viewer = glm::normalize(glm::vec3(std::sin(az), 0.25f, std::cos(az)));
    ApparentRidgeQuantities q;
    computeApparentRidgeQuantities(m.faces, shape.adjacency(), shape.fields(m), view, q);
    LineSet s;
    extractApparentRidges(m.positions, m.faces, shape.adjacency(), q, 5.0f, 1.0f, s);
    // Points on that fillet, away from the box's corners: their angle around its axis, 0 at
    // the join with the +x face, 90° at the join with the +z face.
    double sum = 0.0, weight = 0.0;
    for (size_t i = 0; i < s.points.size(); ++i) {
      const glm::vec3 p = s.points[i];
      if (std::abs(p.y) > half.y - r - 0.05f || p.x < axis.x - 0.01f || p.z < axis.y - 0.01f) continue;
      const double angle = glm::degrees(std::atan2(p.z - axis.y, p.x - axis.x));
      sum += s.alpha[i] * angle;
      weight += s.alpha[i];
    }
    ASSERT_GT(weight, 4.0) << "an apparent ridge along the fillet at azimuth " << az_deg;
    const double mean = sum / weight;
    std::printf("apparent ridge on the fillet, view azimuth %.0f deg: mean angle %.1f deg (0: +x side)\n", az_deg,
                mean);
    // From near +z the +x face is the oblique one: the ridge is on its side; and vice versa.
    if (az_deg < 45.0f) EXPECT_LT(mean, 25.0);
    else EXPECT_GT(mean, 65.0);
  }
}

TEST(ApparentRidges, ViewDependentCurvatureOfASphere) {
  // On a sphere S = I/R, so q1 = secθ/R with t1 along ŵ, towards the contour.
  const TriMesh m = makeIcoSphere(2.0f, 4);
  ShapeCache shape;
  shape.compute(m);
  ViewSpec view;
  view.orthographic = true;
  view.toward_viewer = {0.0f, 0.0f, 1.0f};
  ApparentRidgeQuantities q;
  computeApparentRidgeQuantities(m.faces, shape.adjacency(), shape.fields(m), view, q);
  for (size_t v = 0; v < m.positions.size(); ++v) {
    const float c = m.positions[v].z / 2.0f;
    if (c < 0.2f) continue;
    EXPECT_NEAR(q.q1[v], 0.5f / c, 0.03f * 0.5f / c);
    // ŵ: the view direction's part in the tangent plane (undefined at the pole).
    const glm::vec3 n = m.positions[v] / 2.0f;
    if (c < 0.95f) {
      EXPECT_GT(std::abs(glm::dot(q.t1[v], glm::normalize(glm::vec3(0, 0, 1) - c * n))), 0.95f);
    }
  }
}

}  // namespace
}  // namespace lodline

namespace lodline {
namespace {

// Principal highlights (DeCarlo & Rusinkiewicz 2007) of a torus: across the tube, the dominant
// curvature 1/r, n·v̂ is largest where the tube's normal is nearest the view direction in
// the meridian plane — the line a headlight's highlight follows along the ring.
TEST(PrincipalHighlights, TorusHighlightFollowsTheTubeWhereNormalMeetsTheView) {
  const float R = 1.0f, r = 0.3f;
  const TriMesh m = makeTorus(R, r, 192, 96);
  ShapeCache shape;
  shape.compute(m);
  ViewSpec view;
  view.orthographic = true;
  view.toward_viewer = glm::normalize(glm::vec3(0.3f, 1.0f, 0.5f));
  PrincipalHighlightQuantities q;
  computePrincipalHighlightQuantities(shape.fields(m), view, 1.0f, q);
  LineSet s;
  extractPrincipalHighlights(m.positions, m.faces, shape.adjacency(), q, 0.5f, s);
  ASSERT_GT(s.segmentCount(), 50u);
  const glm::vec3 d = view.toward_viewer;
  double worst = 0.0, len = 0.0;
  for (size_t i = 0; i < s.points.size(); ++i) {
    const glm::vec3 p = s.points[i];
    const glm::vec3 radial = glm::normalize(glm::vec3(p.x, 0.0f, p.z));
    const glm::vec3 centre = R * radial;  // the tube's centre line at this ring angle
    const glm::vec3 n = glm::normalize(p - centre);
    const double psi = std::atan2(n.y, glm::dot(n, radial));
    const double best = std::atan2(d.y, glm::dot(d, radial));  // the normal nearest d
    worst = std::max(worst, std::abs(glm::degrees(psi - best)));
  }
  for (size_t i = 0; i < s.segmentCount(); ++i) len += glm::length(s.points[2 * i + 1] - s.points[2 * i]);
  std::printf("principal highlight of a torus: %zu segments, length %.2f (ring 6.28), max angle off %.2f deg\n",
              s.segmentCount(), len, worst);
  EXPECT_LT(worst, 2.0);
  EXPECT_GT(len, 0.8 * 2.0 * 3.14159 * R);  // nearly all round the ring
}

}  // namespace
}  // namespace lodline

namespace lodline {
namespace {

// The per-view quantities of apparent ridges and principal highlights split over worker
// threads equal the serial ones, bit for bit.
TEST(ApparentRidges, WorkerThreadsGiveTheSerialQuantities) {
  const TriMesh m = makeTorusKnot(2, 3, 1.0f, 0.2f, 600, 24, 0.18f);  // 28,800 faces
  ShapeCache shape;
  shape.compute(m);
  ViewSpec view;
  view.eye = {0.3f, 1.2f, 3.5f};
  WorkerPool pool(3);
  ApparentRidgeQuantities a, b;
  computeApparentRidgeQuantities(m.faces, shape.adjacency(), shape.fields(m), view, a);
  computeApparentRidgeQuantities(m.faces, shape.adjacency(), shape.fields(m), view, b, &pool);
  EXPECT_EQ(a.q1, b.q1);
  EXPECT_EQ(a.t1, b.t1);
  EXPECT_EQ(a.dt1q1, b.dt1q1);
  PrincipalHighlightQuantities c, d;
  computePrincipalHighlightQuantities(shape.fields(m), view, 0.01f, c);
  computePrincipalHighlightQuantities(shape.fields(m), view, 0.01f, d, &pool);
  EXPECT_EQ(c.vdote, d.vdote);
  EXPECT_EQ(c.strength, d.strength);
  EXPECT_EQ(c.first, d.first);
}

}  // namespace
}  // namespace lodline

namespace lodline {
namespace {

// Apparent ridges of a turning ellipsoid (Judd, Durand, Adelson 2007, §3: q1 is the normal's
// variation per unit of *screen* distance, so a view that foreshortens a strongly curved
// band raises it). A flat oblate ellipsoid (semi-axes 1, 1, c = 0.15) has a sharp rim: its
// meridian curvature κ(t) = c/(sin²t + c²cos²t)^{3/2} (x = cos t, z = c sin t) peaks at 1/c²
// there. In the meridian plane that holds the view, tilted φ from the axis, q1 = κ(t)·secθ(t),
// which also grows without bound towards the contour just below the rim. Whether q1 has a
// maximum on the visible side of the rim — an apparent ridge — depends on the view: up to a
// critical tilt φc (60.8° for c = 0.15, found below) the contour's growth swamps the rim's
// peak and there is none; beyond it there is one, and round the rim it reaches as far as
// the rim is seen at least that obliquely: tanφ·cosψ ≥ tanφc, ψ the angle round the axis from
// the point nearest the viewer. Turning the ellipsoid edge-on grows the ridge from nothing
// into a widening arc. Without the view term (q1 = κ) the ridge would lie along the rim at
// every view, already at 45°, and the test fails (checked by dropping secθ − 1).
bool rimMaximum(double c, double phi) {  // q1(t) = κ·secθ has a local maximum on the visible side
  const double tc = std::atan(-c * std::tan(phi)), step = 1e-5;
  double prev = 0.0, prev_slope = 0.0;
  for (double t = tc + step; t < 0.5; t += step) {
    const double d = std::sin(t) * std::sin(t) + c * c * std::cos(t) * std::cos(t);
    const double g = c * std::cos(t) * std::sin(phi) + std::sin(t) * std::cos(phi);  // ∝ n·v
    const double q = c / (d * g);
    if (t > tc + step) {
      const double slope = q - prev;
      if (prev_slope > 0.0 && slope <= 0.0) return true;
      prev_slope = slope;
    }
    prev = q;
  }
  return false;
}

TEST(ApparentRidges, TurningAFlatEllipsoidGrowsItsRimRidge) {
  const float c = 0.15f;
  double lo = 0.2, hi = 1.5;  // the critical tilt φc, by bisection
  for (int k = 0; k < 30; ++k) (rimMaximum(c, 0.5 * (lo + hi)) ? hi : lo) = 0.5 * (lo + hi);
  const double phi_c = hi;
  EXPECT_NEAR(glm::degrees(phi_c), 60.8, 0.1);
  TriMesh m = makeUvSphere(1.0f, 384, 192);  // uniform in the ellipse parameter t
  for (auto& p : m.positions) p.z *= c;
  ShapeCache shape;
  shape.compute(m);
  for (float phi_deg : {45.0f, 70.0f, 75.0f, 80.0f}) {
    const float phi = glm::radians(phi_deg);
    ViewSpec view;
    view.orthographic = true;
    view.toward_viewer = {std::sin(phi), 0.0f, std::cos(phi)};
    ApparentRidgeQuantities q;
    computeApparentRidgeQuantities(m.faces, shape.adjacency(), shape.fields(m), view, q);
    LineSet s;
    extractApparentRidges(m.positions, m.faces, shape.adjacency(), q, 10.0f, 1.0f, s);
    // The ridge's reach round the rim: the largest |ψ| of its points on the rim band, seen
    // (n·v > 0.2: the points at the contour itself, where apparent ridges meet it, aside).
    double reach = 0.0;
    size_t on_rim = 0;
    for (size_t i = 0; i < s.points.size(); ++i) {
      const glm::vec3 p = s.points[i];
      if (std::abs(p.z) > 0.3f * c || s.alpha[i] < 0.5f) continue;
      const glm::vec3 n = glm::normalize(glm::vec3(p.x, p.y, p.z / (c * c)));
      if (glm::dot(n, view.toward_viewer) < 0.2f) continue;
      ++on_rim;
      reach = std::max(reach, std::abs(glm::degrees(std::atan2(double(p.y), double(p.x)))));
    }
    const double predicted = phi < phi_c ? 0.0 : glm::degrees(std::acos(std::tan(phi_c) / std::tan(phi)));
    std::printf("apparent ridge of a flat ellipsoid turned %.0f deg: %zu points on the rim, reach %.1f deg "
                "(predicted %.1f)\n", phi_deg, on_rim, reach, predicted);
    if (phi < phi_c) {
      EXPECT_EQ(on_rim, 0u) << "no rim ridge seen face-on";
    } else {
      EXPECT_GT(on_rim, 100u);
      EXPECT_NEAR(reach, predicted, 5.0);
    }
  }
}

}  // namespace
}  // namespace lodline
