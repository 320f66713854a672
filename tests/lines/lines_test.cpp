// View quantities (signs checked by finite differences), the generic zero-set extractor,
// contours / suggestive contours / creases / boundaries, and chaining into strokes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>

#include "io/generate.h"
#include "io/load_mesh.h"
#include "lines/lines.h"
#include "lines/strokes.h"
#include "lines/view_quantities.h"
#include "shape/shape_cache.h"
#include "shape/shape_test_util.h"
#include "test_util.h"

namespace lodline {
namespace {

LineParams only(LineKind t) {
  LineParams p;
  p.contours = t == LineKind::kContour;
  p.suggestive = t == LineKind::kSuggestive;
  p.creases = t == LineKind::kCrease;
  p.marked_edges = t == LineKind::kCrease;
  p.boundaries = t == LineKind::kBoundary;
  return p;
}

TEST(ViewQuantities, SphereMatchesAnalytic) {
  const float r = 1.0f;
  const TriMesh m = makeIcoSphere(r, 4);
  ShapeCache shape;
  shape.compute(m);
  for (bool ortho : {false, true}) {
    ViewSpec view;
    view.orthographic = ortho;
    view.eye = {0.3f, 0.5f, 4.0f};
    view.toward_viewer = glm::normalize(glm::vec3(1, 1, 1));
    ViewQuantities q;
    computeViewQuantities(shape.fields(m), view, 0.0f, q);
    ASSERT_EQ(q.ndotv.size(), m.vertexCount());
    ASSERT_EQ(q.sc_num.size(), m.vertexCount());
    for (size_t v = 0; v < m.vertexCount(); ++v) {
      const glm::vec3 p = m.positions[v];
      const glm::vec3 dir = ortho ? view.toward_viewer : glm::normalize(view.eye - p);
      const float ndotv = glm::dot(p / r, dir);
      EXPECT_NEAR(q.ndotv[v], ndotv, 1e-4f);
      // kr = 1/r in every direction, so kr·sin²θ = (1 − cos²θ)/r.
      EXPECT_NEAR(q.kr[v], (1.0f - ndotv * ndotv) / r, 1e-4f);
      // Constant curvature: Dw kr = 0 (τ = 0 and C = 0 up to the estimate's noise).
      EXPECT_NEAR(q.dwkr[v], 0.0f, 2e-2f);
    }
  }
}

// Dw kr against central differences of the analytic radial curvature of the torus, moving
// along ŵ on the exact surface with a perspective eye (the view vector changes along the
// path). Both the sign of C and the −2·τ²·cotθ term are checked: without the correction
// term the error is many times larger. Measured on the 192x96 mesh (6257 front-facing
// vertices): rms error 2.4e-4 of max |Dw kr| (25.6) with the correction, 0.135 without.
TEST(ViewQuantities, DwKrMatchesFiniteDifferencesOnTorus) {
  const test::AnalyticTorus torus{1.0, 0.4};
  const TriMesh m = makeTorus(1.0f, 0.4f, 192, 96);
  ShapeCache shape;
  shape.compute(m);
  const glm::dvec3 eye(0.4, 1.6, 3.5);
  ViewSpec view;
  view.eye = glm::vec3(eye);
  ViewQuantities q;
  computeViewQuantities(shape.fields(m), view, 0.0f, q);
  double sum2 = 0.0, sum2_no_tau = 0.0, max_fd = 0.0;
  size_t n = 0;
  const double h = 1e-4;
  for (size_t i = 0; i < m.vertexCount(); ++i) {
    const glm::dvec3 p(m.positions[i]);
    const double u = torus.ringAngle(p), v = torus.tubeAngle(p);
    const glm::dvec3 vdir = glm::normalize(eye - p);
    const glm::dvec3 nrm = torus.normal(p);
    const double cos_t = glm::dot(vdir, nrm);
    const double a = glm::dot(vdir, torus.ringDir(u)), b = glm::dot(vdir, torus.tubeDir(u, v));
    const double sin_t = std::sqrt(a * a + b * b);
    if (cos_t < 0.2 || sin_t < 0.3) continue;  // front-facing, w well defined
    const double wa = a / sin_t, wb = b / sin_t;  // ŵ in (ring, tube) coordinates
    auto kr_at = [&](double s) {
      const double uu = u + s * wa / (torus.R + torus.r * std::cos(v));
      const double vv = v + s * wb / torus.r;
      return torus.radialCurvature(uu, vv, eye);
    };
    const double fd = (kr_at(h) - kr_at(-h)) / (2.0 * h);
    const double tau = (torus.tubeCurvature() - torus.ringCurvature(v)) * wa * wb;
    const double est = q.dwkr[i];
    sum2 += (est - fd) * (est - fd);
    const double without_tau = est + 2.0 * tau * tau * cos_t / sin_t;
    sum2_no_tau += (without_tau - fd) * (without_tau - fd);
    max_fd = std::max(max_fd, std::abs(fd));
    ++n;
  }
  ASSERT_GT(n, 1000u);
  const double rms = std::sqrt(sum2 / n) / max_fd;
  const double rms_no_tau = std::sqrt(sum2_no_tau / n) / max_fd;
  std::printf("Dw kr vs finite differences: rms %.3g of max %.3g; without the tau term %.3g "
              "(%zu vertices)\n",
              rms, max_fd, rms_no_tau, n);
  EXPECT_LT(rms, 0.02);
  EXPECT_GT(rms_no_tau, 5.0 * rms);
}

// The whole-mesh pass runs several vertices a step (with AVX2 where the processor has it);
// the per-vertex path that lazily evaluated derivatives use must give the same bits, or the
// lines drawn with lazy tensors would differ from the eager ones. This checks the clone this
// machine picks (core/simd_clones.h).
TEST(ViewQuantities, VectorPassEqualsThePerVertexPathBitForBit) {
  const TriMesh m = makeTorus(1.0f, 0.4f, 96, 48);
  ShapeCache shape;
  shape.compute(m);
  std::vector<uint32_t> all(m.vertexCount());
  for (uint32_t i = 0; i < all.size(); ++i) all[i] = i;
  for (bool ortho : {false, true}) {
    ViewSpec view;
    view.orthographic = ortho;
    view.eye = {0.4f, 1.6f, 3.5f};
    view.toward_viewer = glm::normalize(glm::vec3(0.2f, 0.9f, 0.4f));
    ViewQuantities whole, each;
    computeViewQuantities(shape.fields(m), view, 0.03f, whole);
    computeSuggestiveQuantities(shape.fields(m), view, 0.03f, all, each);
    ASSERT_EQ(whole.dwkr.size(), m.vertexCount());
    ASSERT_EQ(each.dwkr.size(), m.vertexCount());
    // n·v and kr·sin²θ as the per-vertex code forms them (view_quantities.cpp, viewAt()).
    const SurfaceFields f = shape.fields(m);
    const glm::vec3 ortho_dir = glm::normalize(view.toward_viewer);
    size_t differ = 0, differ_kr = 0;
    for (size_t i = 0; i < m.vertexCount(); ++i) {
      differ += whole.dwkr[i] != each.dwkr[i] || whole.sc_num[i] != each.sc_num[i];
      glm::vec3 vdir = ortho_dir;
      if (!ortho) {
        const glm::vec3 d = view.eye - f.positions[i];
        vdir = d * (1.0f / glm::length(d));
      }
      const float ndotv = glm::dot(vdir, f.normals[i]);
      const float u = glm::dot(vdir, f.pdir1[i]), v = glm::dot(vdir, f.pdir2[i]);
      differ_kr += whole.ndotv[i] != ndotv || whole.kr[i] != f.k1[i] * (u * u) + f.k2[i] * (v * v);
    }
    EXPECT_EQ(differ, 0u) << (ortho ? "orthographic" : "perspective");
    EXPECT_EQ(differ_kr, 0u) << (ortho ? "orthographic" : "perspective");
  }
}

TEST(Contours, SphereContourIsTheAnalyticCircleAndOneClosedStroke) {
  const float r = 1.0f, d = 3.0f;
  const TriMesh m = makeIcoSphere(r, 5);
  ShapeCache shape;
  shape.compute(m);
  const glm::vec3 axis = glm::normalize(glm::vec3(0.2f, 0.3f, 1.0f));
  ViewSpec view;
  view.eye = d * axis;
  LineExtractor ex;
  LineSet lines;
  ex.extract(m, shape, view, only(LineKind::kContour), 0.01f, lines);
  ASSERT_GT(lines.counts[0], 50u);
  EXPECT_EQ(lines.counts[1] + lines.counts[2] + lines.counts[3], 0u);
  // Circle at distance r²/d from the centre along the axis, radius r·sqrt(1 − r²/d²).
  const float along = r * r / d, radius = r * std::sqrt(1.0f - r * r / (d * d));
  float worst = 0.0f;
  for (const glm::vec3& p : lines.points) {
    const float a = glm::dot(p, axis);
    const float rad = glm::length(p - a * axis);
    worst = std::max({worst, std::abs(a - along), std::abs(rad - radius)});
  }
  std::printf("sphere contour: %u segments, max deviation %.3g (edge length ~%.3g)\n",
              lines.counts[0], worst, 0.03f);
  EXPECT_LT(worst, 2e-3f);
  StrokeSet strokes;
  ChainScratch scratch;
  chainStrokes(lines, strokes, scratch);
  ASSERT_EQ(strokes.strokeCount(), 1u);
  EXPECT_EQ(strokes.closed[0], 1);
  EXPECT_EQ(strokes.kinds[0], LineKind::kContour);
  EXPECT_EQ(strokes.offsets[1] - strokes.offsets[0], lines.counts[0] + 1);
  EXPECT_EQ(strokes.points[strokes.offsets[0]], strokes.points[strokes.offsets[1] - 1]);
  // Length of the circle, measured in a plane ⟂ axis (orthographic "projection").
  const glm::vec3 e1 = glm::normalize(glm::cross(axis, glm::vec3(0, 1, 0)));
  const glm::vec3 e2 = glm::cross(axis, e1);
  std::vector<float> lengths;
  measureStrokeLengths(
      strokes, [&](glm::vec3 p) { return glm::vec2(glm::dot(p, e1), glm::dot(p, e2)); }, lengths);
  ASSERT_EQ(lengths.size(), 1u);
  EXPECT_NEAR(lengths[0], 2.0f * std::numbers::pi_v<float> * radius, 5e-3f);
}

TEST(Contours, OrthographicSphereContourIsTheEquator) {
  const TriMesh m = makeUvSphere(2.0f, 64, 32);
  ShapeCache shape;
  shape.compute(m);
  ViewSpec view;
  view.orthographic = true;
  view.toward_viewer = {0, 1, 0};  // looking down the pole axis
  LineExtractor ex;
  LineSet lines;
  ex.extract(m, shape, view, only(LineKind::kContour), 0.02f, lines);
  ASSERT_GT(lines.counts[0], 0u);
  for (const glm::vec3& p : lines.points) EXPECT_NEAR(p.y, 0.0f, 1e-5f);
}

TEST(Contours, RequirePositiveKrTrimsHiddenLoops) {
  // Visible contour points have kr > 0; where the n·v = 0 set runs with kr < 0 the surface
  // folds away behind itself (hidden parts of the loops). The option keeps only kr > 0.
  const TriMesh m = makeTorus(1.0f, 0.4f, 128, 64);
  ShapeCache shape;
  shape.compute(m);
  ViewSpec view;
  view.eye = {0.0f, 1.5f, 4.0f};
  LineExtractor ex;
  LineSet all, trimmed;
  LineParams p = only(LineKind::kContour);
  ex.extract(m, shape, view, p, 0.03f, all);
  p.contours_require_positive_kr = true;
  ex.extract(m, shape, view, p, 0.03f, trimmed);
  EXPECT_GT(trimmed.counts[0], 0u);
  EXPECT_LT(trimmed.counts[0], all.counts[0]);
  const std::vector<float>& kr = ex.viewQuantities().kr;
  int violations = 0;
  for (size_t s = 0; s < trimmed.segmentCount(); ++s) {
    const auto& f = m.faces[trimmed.sources[s]];
    if (std::max({kr[f[0]], kr[f[1]], kr[f[2]]}) <= 0.0f) ++violations;
  }
  EXPECT_EQ(violations, 0) << "kept contour segments on faces with kr ≤ 0 everywhere";
}

TEST(Suggestive, NoneOnASphere) {
  const TriMesh m = makeIcoSphere(1.0f, 4);
  ShapeCache shape;
  shape.compute(m);
  const float fs = computeFeatureSize(shape.k1(), shape.k2(), 1.0f);
  LineExtractor ex;
  LineSet lines;
  for (glm::vec3 eye : {glm::vec3(0, 0, 3), glm::vec3(2, 2, 2), glm::vec3(0, 10, 0.1f)}) {
    ViewSpec view;
    view.eye = eye;
    LineParams p;
    p.suggestive_threshold = 0.0f;  // even without a threshold: kr > 0 everywhere
    ex.extract(m, shape, view, p, fs, lines);
    EXPECT_EQ(lines.counts[static_cast<int>(LineKind::kSuggestive)], 0u);
    EXPECT_GT(lines.counts[static_cast<int>(LineKind::kContour)], 0u);
    for (float x : ex.viewQuantities().kr) EXPECT_GE(x, 0.0f);
  }
}

TEST(Suggestive, TorusFromAboveTheSideHasThemInTheSaddleRegion) {
  const test::AnalyticTorus torus{1.0, 0.4};
  const TriMesh m = makeTorus(1.0f, 0.4f, 128, 64);
  ShapeCache shape;
  shape.compute(m);
  const float fs = computeFeatureSize(shape.k1(), shape.k2(), computeBounds(m.positions).radius);
  ViewSpec view;
  view.eye = {0.0f, 1.5f, 4.0f};  // side view, 20° above the ring plane
  LineExtractor ex;
  LineSet lines;
  ex.extract(m, shape, view, LineParams{}, fs, lines);
  const uint32_t ns = lines.counts[static_cast<int>(LineKind::kSuggestive)];
  std::printf("torus: fs %.4g, %u contour and %u suggestive segments\n", fs, lines.counts[0], ns);
  ASSERT_GT(ns, 10u);
  EXPECT_EQ(lines.counts[static_cast<int>(LineKind::kCrease)], 0u);
  EXPECT_EQ(lines.counts[static_cast<int>(LineKind::kBoundary)], 0u);
  // kr = 0 needs K ≤ 0: the inner half of the tube (distance to the axis < R), and the
  // points must face the viewer and pass the Dw kr > 0 test (alpha in [0, 1]).
  for (size_t s = 0; s < lines.segmentCount(); ++s) {
    if (lines.kinds[s] != LineKind::kSuggestive) continue;
    for (int e = 0; e < 2; ++e) {
      const glm::vec3 p = lines.points[2 * s + e];
      EXPECT_LT(std::hypot(p.x, p.z), torus.R + 0.01) << "suggestive point on the convex part";
      const glm::dvec3 dp(p);
      EXPECT_GT(glm::dot(torus.normal(dp), glm::normalize(glm::dvec3(view.eye) - dp)), -0.01);
      const float a = lines.alpha[2 * s + e];
      EXPECT_GE(a, 0.0f);
      EXPECT_LE(a, 1.0f);
    }
  }
  // Rejection near contours: requiring n·v ≥ 0.3 on every face vertex keeps fewer.
  LineParams away = LineParams{};
  away.suggestive_min_ndotv = 0.3f;
  LineSet far_from_contours;
  ex.extract(m, shape, view, away, fs, far_from_contours);
  EXPECT_LT(far_from_contours.counts[1], ns);
  for (size_t s = 0; s < far_from_contours.segmentCount(); ++s) {
    if (far_from_contours.kinds[s] != LineKind::kSuggestive) continue;
    for (uint32_t v : m.faces[far_from_contours.sources[s]])
      EXPECT_GE(ex.viewQuantities().ndotv[v], 0.3f);
  }
  // A higher threshold keeps fewer lines, fading off gives alpha 1.
  LineParams strict;
  strict.suggestive_threshold = 0.2f;
  strict.suggestive_fade = 0.0f;
  LineSet fewer;
  ex.extract(m, shape, view, strict, fs, fewer);
  EXPECT_LT(fewer.counts[1], ns);
  for (size_t i = 0; i < fewer.points.size(); ++i)
    if (fewer.kinds[i / 2] == LineKind::kSuggestive) {
      EXPECT_EQ(fewer.alpha[i], 1.0f);
    }
}

// A cube with every face split into n×n quads (two triangles each), outward.
TriMesh makeSubdividedCube(int n) {
  TriMesh m;
  auto add_face = [&](glm::vec3 origin, glm::vec3 du, glm::vec3 dv) {
    const uint32_t base = static_cast<uint32_t>(m.positions.size());
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j)
        m.positions.push_back(origin + du * (float(j) / n) + dv * (float(i) / n));
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const uint32_t a = base + i * (n + 1) + j, b = a + 1, c = a + n + 2, d = a + n + 1;
        m.faces.push_back({a, b, c});
        m.faces.push_back({a, c, d});
      }
  };
  // du × dv points outward for each face.
  add_face({-1, -1, 1}, {2, 0, 0}, {0, 2, 0});    // +z
  add_face({1, -1, -1}, {-2, 0, 0}, {0, 2, 0});   // −z
  add_face({1, -1, 1}, {0, 0, -2}, {0, 2, 0});    // +x
  add_face({-1, -1, -1}, {0, 0, 2}, {0, 2, 0});   // −x
  add_face({-1, 1, 1}, {2, 0, 0}, {0, 0, -2});    // +y
  add_face({-1, -1, -1}, {2, 0, 0}, {0, 0, 2});   // −y
  // Weld coincident vertices.
  std::vector<uint32_t> remap(m.positions.size());
  std::vector<glm::vec3> unique;
  for (size_t i = 0; i < m.positions.size(); ++i) {
    uint32_t k = 0;
    while (k < unique.size() && glm::length(unique[k] - m.positions[i]) > 1e-5f) ++k;
    if (k == unique.size()) unique.push_back(m.positions[i]);
    remap[i] = k;
  }
  for (auto& f : m.faces)
    for (auto& v : f) v = remap[v];
  m.positions = unique;
  return m;
}

// Suggestive highlights (DeCarlo & Rusinkiewicz 2007) are the other half of the front-facing
// kr = 0 set: with no threshold and no fading, every front-facing kr = 0 segment is drawn as
// a suggestive contour (Dw kr > 0) or as a suggestive highlight (Dw kr < 0), and the two
// never share a piece.
TEST(SuggestiveHighlights, AreTheKrZeroSetWhereSuggestiveContoursAreNot) {
  const TriMesh m = makeTorus(1.0f, 0.4f, 128, 64);
  ShapeCache shape;
  shape.compute(m);
  ViewSpec view;
  view.eye = {0.0f, 1.5f, 4.0f};
  LineParams p = only(LineKind::kSuggestive);
  p.suggestive_highlights = true;
  p.suggestive_threshold = 0.0f;
  p.suggestive_fade = 0.0f;
  LineExtractor ex;
  LineSet lines;
  ex.extract(m, shape, view, p, 1.0f, lines);
  auto lengthOf = [](const LineSet& s, LineKind k) {
    double len = 0.0;
    for (size_t i = 0; i < s.segmentCount(); ++i)
      if (s.kinds[i] == k) len += glm::length(s.points[2 * i + 1] - s.points[2 * i]);
    return len;
  };
  const double sc = lengthOf(lines, LineKind::kSuggestive), sh = lengthOf(lines, LineKind::kSuggestiveHighlight);
  // The whole front-facing kr = 0 set, untested.
  ViewQuantities q;
  computeViewQuantities(shape.fields(m), view, 0.0f, q);
  ZeroSetInput all;
  all.value = q.kr;
  all.gate = q.ndotv;
  LineScratch scratch;
  LineSet zero;
  extractZeroSet(m.positions, m.faces, shape.adjacency(), all, LineKind::kSuggestive, scratch, zero);
  const double total = lengthOf(zero, LineKind::kSuggestive);
  std::printf("torus kr = 0: %.3f long; suggestive %.3f + highlights %.3f\n", total, sc, sh);
  EXPECT_GT(sc, 0.1 * total);
  EXPECT_GT(sh, 0.1 * total);
  EXPECT_NEAR(sc + sh, total, 1e-3 * total);
  // No piece twice: highlight points are where the suggestive test fails.
  for (size_t i = 0; i < lines.segmentCount(); ++i) {
    if (lines.kinds[i] != LineKind::kSuggestiveHighlight) continue;
    const glm::vec3 mid = 0.5f * (lines.points[2 * i] + lines.points[2 * i + 1]);
    for (size_t j = 0; j < lines.segmentCount(); ++j) {
      if (lines.kinds[j] != LineKind::kSuggestive || lines.sources[j] != lines.sources[i]) continue;
      const glm::vec3 a = lines.points[2 * j], b = lines.points[2 * j + 1];
      const float t = std::clamp(glm::dot(mid - a, b - a) / std::max(1e-12f, glm::dot(b - a, b - a)), 0.0f, 1.0f);
      EXPECT_GT(glm::length(a + t * (b - a) - mid), 1e-6f) << "face " << lines.sources[i];
    }
  }
}

TEST(Creases, CubeEdgesAndMarkedEdges) {
  const TriMesh m = makeSubdividedCube(2);
  EXPECT_GT(test::signedVolume(m), 0.0);
  ShapeCache shape;
  shape.compute(m);
  LineExtractor ex;
  LineSet lines;
  ViewSpec view;
  ex.extract(m, shape, view, only(LineKind::kCrease), 0.1f, lines);
  EXPECT_EQ(lines.counts[static_cast<int>(LineKind::kCrease)], 24u);  // 12 edges × 2
  for (size_t i = 0; i < lines.points.size(); ++i) {
    const glm::vec3 a = glm::abs(lines.points[i]);
    // On a cube edge: at least two coordinates at ±1.
    EXPECT_GE(int(a.x > 0.999f) + int(a.y > 0.999f) + int(a.z > 0.999f), 2);
  }
  StrokeSet strokes;
  ChainScratch scratch;
  chainStrokes(lines, strokes, scratch);
  EXPECT_EQ(strokes.strokeCount(), 12u);  // corners join three ends: strokes stop there
  for (size_t s = 0; s < strokes.strokeCount(); ++s) {
    EXPECT_EQ(strokes.offsets[s + 1] - strokes.offsets[s], 3u);
    EXPECT_EQ(strokes.closed[s], 0);
  }
  // A 90° dihedral is not a crease at a 100° threshold; a marked flat edge always is.
  TriMesh marked = m;
  marked.marked_edges.push_back({m.faces[0][0], m.faces[0][2]});  // a flat diagonal
  LineParams p = only(LineKind::kCrease);
  p.crease_angle_deg = 100.0f;
  ex.extract(marked, shape, view, p, 0.1f, lines);
  EXPECT_EQ(lines.counts[static_cast<int>(LineKind::kCrease)], 1u);
  p.marked_edges = false;
  ex.extract(marked, shape, view, p, 0.1f, lines);
  EXPECT_EQ(lines.counts[static_cast<int>(LineKind::kCrease)], 0u);
  // A non-manifold edge (three faces) is drawn as a crease when marked edges are on.
  TriMesh fin;
  fin.positions = {{0, 0, 0}, {1, 0, 0}, {0.5f, 1, 0}, {0.5f, -1, 0}, {0.5f, 0, 1}};
  fin.faces = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  ShapeCache fin_shape;
  fin_shape.compute(fin);
  LineParams fp = only(LineKind::kCrease);
  fp.crease_angle_deg = 179.0f;
  ex.extract(fin, fin_shape, view, fp, 0.1f, lines);
  ASSERT_EQ(lines.counts[static_cast<int>(LineKind::kCrease)], 1u);
  EXPECT_EQ(lines.sources[0], fin_shape.adjacency().findEdge(0, 1));
  // Smooth surfaces have none at the default threshold.
  const TriMesh sphere = makeIcoSphere(1.0f, 3);
  ShapeCache s2;
  s2.compute(sphere);
  ex.extract(sphere, s2, view, only(LineKind::kCrease), 0.1f, lines);
  EXPECT_EQ(lines.counts[static_cast<int>(LineKind::kCrease)], 0u);
}

// A closed cylinder of radius 1 from y = −1 to 1: `stacks` rings of `slices` quads on the
// side, fans to a centre vertex on the caps (sharp 90° rims), outward.
TriMesh makeCappedCylinder(int slices, int stacks) {
  TriMesh m;
  for (int i = 0; i <= stacks; ++i)
    for (int j = 0; j < slices; ++j) {
      const float a = 2.0f * std::numbers::pi_v<float> * j / slices;
      m.positions.push_back({std::cos(a), -1.0f + 2.0f * i / stacks, std::sin(a)});
    }
  auto at = [&](int i, int j) { return static_cast<uint32_t>(i * slices + (j % slices)); };
  for (int i = 0; i < stacks; ++i)
    for (int j = 0; j < slices; ++j) {
      m.faces.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
      m.faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
    }
  const uint32_t bottom = static_cast<uint32_t>(m.positions.size()), top = bottom + 1;
  m.positions.push_back({0, -1, 0});
  m.positions.push_back({0, 1, 0});
  for (int j = 0; j < slices; ++j) {
    m.faces.push_back({bottom, at(0, j), at(0, j + 1)});
    m.faces.push_back({top, at(stacks, j + 1), at(stacks, j)});
  }
  return m;
}

// Where a crease is itself a silhouette the contour runs along it, and joins the smooth
// contour where that meets the crease (LineParams::contours_follow_creases).
TEST(Suggestive, NotBesideCreases) {
  // Across a sharp edge the curvature estimate averages both sides, and its kr zero set runs
  // beside the edge as scratches. By default no suggestive contour is drawn in a face with a
  // corner on a crease; as rtsc draws them (off), these meshes have some there.
  // CAD parts from the CGAL demo data (the machine scene's): exact synthetic solids have no
  // kr zero crossing beside their edges to begin with.
  std::vector<TriMesh> meshes;
  for (const char* name : {"fandisk.off", "couplingdown.off"}) {
    const auto path = test::dataMesh(name);
    if (path.empty()) continue;
    auto m = loadMesh(path);
    if (m.ok()) meshes.push_back(std::move(m).value());
  }
  if (meshes.empty()) GTEST_SKIP() << "CGAL data meshes not installed";
  for (const TriMesh& m : meshes) {
    ShapeCache shape;
    shape.compute(m);
    const float fs = computeFeatureSize(shape.k1(), shape.k2(), computeBounds(m.positions).radius);
    ViewSpec view;
    view.eye = {3.1f, 2.3f, 2.7f};
    LineExtractor ex;
    LineSet lines;
    LineParams p = only(LineKind::kSuggestive);
    p.suggestive_off_creases = false;
    ex.extract(m, shape, view, p, fs, lines);
    // Crease vertices: the ends of the edges the crease pass finds.
    LineSet creases;
    ex.extract(m, shape, view, only(LineKind::kCrease), fs, creases);
    std::vector<uint8_t> on_crease(m.positions.size(), 0);
    for (uint32_t id : creases.point_ids)
      if (id < m.positions.size()) on_crease[id] = 1;
    auto beside = [&](const LineSet& s) {
      size_t n = 0;
      for (size_t k = 0; k < s.segmentCount(); ++k) {
        if (s.kinds[k] != LineKind::kSuggestive) continue;
        const auto& f = m.faces[s.sources[k]];
        n += on_crease[f[0]] || on_crease[f[1]] || on_crease[f[2]];
      }
      return n;
    };
    const size_t before = beside(lines);
    p.suggestive_off_creases = true;
    ex.extract(m, shape, view, p, fs, lines);
    std::printf("suggestive segments beside creases: %zu as rtsc, %zu by default (%u left)\n", before, beside(lines),
                lines.counts[static_cast<int>(LineKind::kSuggestive)]);
    EXPECT_GT(before, 0u);
    EXPECT_EQ(beside(lines), 0u);
  }
}

TEST(Contours, FollowSilhouetteCreases) {
  // A cube seen corner-on: the contour is the hexagon of its silhouette edges, one loop.
  const TriMesh cube = makeSubdividedCube(2);
  ShapeCache cube_shape;
  cube_shape.compute(cube);
  LineExtractor ex;
  LineSet lines;
  StrokeSet strokes;
  ChainScratch chain;
  ViewSpec view;
  view.eye = {3.1f, 2.3f, 2.7f};
  ex.extract(cube, cube_shape, view, only(LineKind::kContour), 0.1f, lines);
  EXPECT_EQ(lines.counts[static_cast<int>(LineKind::kContour)], 12u);  // 6 edges × 2 segments
  for (const glm::vec3& p : lines.points) {
    const glm::vec3 a = glm::abs(p);
    EXPECT_GE(int(a.x > 0.9999f) + int(a.y > 0.9999f) + int(a.z > 0.9999f), 2) << p.x << " " << p.y << " " << p.z;
  }
  chainStrokes(lines, strokes, chain);
  ASSERT_EQ(strokes.strokeCount(), 1u);
  EXPECT_EQ(strokes.closed[0], 1);
  // Without it, vertex normals averaged over the cube's corners put n·v = 0 inside faces.
  LineParams off = only(LineKind::kContour);
  off.contours_follow_creases = false;
  ex.extract(cube, cube_shape, view, off, 0.1f, lines);
  size_t off_edges = 0;
  for (const glm::vec3& p : lines.points) {
    const glm::vec3 a = glm::abs(p);
    off_edges += int(a.x > 0.9999f) + int(a.y > 0.9999f) + int(a.z > 0.9999f) < 2;
  }
  EXPECT_GT(off_edges, 0u);

  // A capped cylinder seen from above: the far half of the top rim and the near half of the
  // bottom rim are silhouette creases; the two side lines are smooth contour. One closed
  // loop, and no contour point inside a cap.
  const TriMesh cyl = makeCappedCylinder(48, 6);
  ShapeCache cyl_shape;
  cyl_shape.compute(cyl);
  view.eye = {0.0f, 2.5f, 5.0f};
  ex.extract(cyl, cyl_shape, view, only(LineKind::kContour), 0.1f, lines);
  size_t on_rims = 0;
  for (const glm::vec3& p : lines.points) {
    EXPECT_NEAR(p.x * p.x + p.z * p.z, 1.0f, 0.01f) << p.x << " " << p.y << " " << p.z;  // never inside a cap
    on_rims += std::abs(std::abs(p.y) - 1.0f) < 1e-6f;
  }
  EXPECT_GT(on_rims, 40u);  // about half of each rim's 48 vertices, twice per segment
  chainStrokes(lines, strokes, chain);
  ASSERT_EQ(strokes.strokeCount(), 1u);
  EXPECT_EQ(strokes.closed[0], 1);
  // Without it the rims' contour wanders onto the caps and the loop comes apart.
  ex.extract(cyl, cyl_shape, view, off, 0.1f, lines);
  size_t on_caps = 0;
  for (const glm::vec3& p : lines.points) on_caps += p.x * p.x + p.z * p.z < 0.98f;
  EXPECT_GT(on_caps, 0u);
}

TEST(Boundaries, GridAndCylinderLoops) {
  StrokeSet strokes;
  ChainScratch scratch;
  LineExtractor ex;
  LineSet lines;
  ViewSpec view;
  {
    const TriMesh g = makeGrid(2.0f, 5);
    ShapeCache shape;
    shape.compute(g);
    ex.extract(g, shape, view, only(LineKind::kBoundary), 0.1f, lines);
    EXPECT_EQ(lines.counts[static_cast<int>(LineKind::kBoundary)], 20u);
    chainStrokes(lines, strokes, scratch);
    ASSERT_EQ(strokes.strokeCount(), 1u);
    EXPECT_EQ(strokes.closed[0], 1);
    EXPECT_EQ(strokes.offsets[1], 21u);
  }
  {
    const TriMesh c = makeCylinder(1.0f, 2.0f, 24, 6);
    ShapeCache shape;
    shape.compute(c);
    ex.extract(c, shape, view, LineParams{}, 0.05f, lines);
    EXPECT_EQ(lines.counts[static_cast<int>(LineKind::kBoundary)], 48u);
    EXPECT_EQ(lines.counts[static_cast<int>(LineKind::kCrease)], 0u);
    chainStrokes(lines, strokes, scratch);
    int boundary_loops = 0;
    for (size_t s = 0; s < strokes.strokeCount(); ++s)
      if (strokes.kinds[s] == LineKind::kBoundary) {
        ++boundary_loops;
        EXPECT_EQ(strokes.closed[s], 1);
      }
    EXPECT_EQ(boundary_loops, 2);
  }
}

TEST(ZeroSet, CrossingsSharedExactlyAndAllContoursClosed) {
  // A bumpy closed surface: every contour curve must chain into closed strokes.
  const TriMesh m = makeTorusKnot(3, 2, 1.0f, 0.25f, 300, 24, 0.15f);
  ShapeCache shape;
  shape.compute(m);
  const float fs = computeFeatureSize(shape.k1(), shape.k2(), computeBounds(m.positions).radius);
  LineExtractor ex;
  LineSet lines;
  StrokeSet strokes;
  ChainScratch scratch;
  for (glm::vec3 eye : {glm::vec3(0, 0, 4), glm::vec3(3, 2, 1), glm::vec3(-1, 4, -2)}) {
    ViewSpec view;
    view.eye = eye;
    ex.extract(m, shape, view, only(LineKind::kContour), fs, lines);
    ASSERT_GT(lines.counts[0], 0u);
    chainStrokes(lines, strokes, scratch);
    size_t points = 0;
    for (size_t s = 0; s < strokes.strokeCount(); ++s) {
      EXPECT_EQ(strokes.closed[s], 1);
      points += strokes.offsets[s + 1] - strokes.offsets[s] - 1;
    }
    EXPECT_EQ(points, lines.counts[0]);  // every segment used exactly once
  }
}

// The zero-set tests' surface: the grid of makeGrid(2, n) (the square [−1, 1]² in x and z, at
// y = 0) with its adjacency, and per-vertex fields given as functions of the position.
struct Grid {
  TriMesh mesh;
  MeshAdjacency adj;
  explicit Grid(int n) : mesh(makeGrid(2.0f, n)) { buildAdjacency(mesh, adj); }
  template <class F>
  std::vector<float> field(F f) const {
    std::vector<float> out(mesh.vertexCount());
    for (size_t v = 0; v < out.size(); ++v) out[v] = f(mesh.positions[v]);
    return out;
  }
};

TEST(ZeroSet, TestSplitsSegmentsInsideFaces) {
  // value = x (line x = 0 across the grid), test num = z: keep only the z > 0 half; the cut
  // point inside a face gets an id ≥ edgeCount.
  const Grid grid(7);
  const TriMesh& g = grid.mesh;
  const MeshAdjacency& adj = grid.adj;
  const std::vector<float> value = grid.field([](const glm::vec3& p) { return p.x - 0.01f; });
  const std::vector<float> num = grid.field([](const glm::vec3& p) { return p.z - 0.05f; });
  ZeroSetInput in;
  in.value = value;
  in.test_num = num;
  LineScratch scratch;
  LineSet out;
  extractZeroSet(g.positions, g.faces, adj, in, LineKind::kContour, scratch, out);
  ASSERT_GT(out.segmentCount(), 0u);
  float min_z = 1e9f, max_z = -1e9f;
  bool has_interior = false;
  for (size_t i = 0; i < out.points.size(); ++i) {
    EXPECT_NEAR(out.points[i].x, 0.01f, 1e-5f);
    min_z = std::min(min_z, out.points[i].z);
    max_z = std::max(max_z, out.points[i].z);
    has_interior |= out.point_ids[i] >= adj.edgeCount();
  }
  EXPECT_NEAR(min_z, 0.05f, 1e-5f);  // cut exactly where the test changes sign
  EXPECT_NEAR(max_z, 1.0f, 1e-5f);
  EXPECT_TRUE(has_interior);
  StrokeSet strokes;
  ChainScratch cs;
  chainStrokes(out, strokes, cs);
  EXPECT_EQ(strokes.strokeCount(), 1u);
  // Gate: reject every face (gate below the minimum everywhere).
  std::vector<float> gate(g.vertexCount(), -1.0f);
  in.gate = gate;
  out.clear();
  extractZeroSet(g.positions, g.faces, adj, in, LineKind::kContour, scratch, out);
  EXPECT_EQ(out.segmentCount(), 0u);
}

// A per-vertex gain (the suggestive contours' motion fade) scales the alpha, interpolated
// along the edges like the test: gain = 1 − x on the grid halves the alpha on the line x = ½.
TEST(ZeroSet, GainScalesTheAlpha) {
  const Grid grid(9);
  const TriMesh& g = grid.mesh;
  const MeshAdjacency& adj = grid.adj;
  const std::vector<float> value = grid.field([](const glm::vec3& p) { return p.x - 0.5f; });
  const std::vector<float> num = grid.field([](const glm::vec3&) { return 1.0f; });
  const std::vector<float> gain = grid.field([](const glm::vec3& p) { return std::clamp(1.0f - p.x, 0.0f, 1.0f); });
  ZeroSetInput in;
  in.value = value;
  in.test_num = num;
  LineScratch scratch;
  LineSet plain, faded;
  extractZeroSet(g.positions, g.faces, adj, in, LineKind::kSuggestive, scratch, plain);
  in.gain = gain;
  extractZeroSet(g.positions, g.faces, adj, in, LineKind::kSuggestive, scratch, faded);
  ASSERT_GT(plain.segmentCount(), 0u);
  ASSERT_EQ(plain.points.size(), faded.points.size());
  for (size_t i = 0; i < plain.points.size(); ++i) {
    EXPECT_EQ(plain.alpha[i], 1.0f);
    EXPECT_NEAR(faded.alpha[i], 0.5f, 1e-5f);
  }
}

// A gate below its minimum at some corners of a face cuts the line where the interpolated gate
// crosses the minimum (suggestive contours end where n·v does on a face straddling the
// contour), instead of leaving the whole face out: on the grid the line x = 0.05 with the
// gate z − 0.1 runs from z = 0.1 exactly (between the grid rows at z = −0.111 and 0.111:
// dropping the faces with a corner below would end it at 0.111) to the far side, in one
// stroke. With a test and without one; the gate alone cuts (the test passes everywhere).
TEST(ZeroSet, AGateCutsTheLineWhereItCrossesItsMinimum) {
  const Grid grid(9);
  const TriMesh& g = grid.mesh;
  const MeshAdjacency& adj = grid.adj;
  const std::vector<float> value = grid.field([](const glm::vec3& p) { return p.x - 0.05f; });
  const std::vector<float> num = grid.field([](const glm::vec3&) { return 1.0f; });
  const std::vector<float> gate = grid.field([](const glm::vec3& p) { return p.z - 0.1f; });
  for (const bool with_test : {true, false}) {
    SCOPED_TRACE(with_test ? "with a test" : "without a test");
    ZeroSetInput in;
    in.value = value;
    if (with_test) {
      in.test_num = num;
      in.fade = 0.5f;  // alpha num/(num + fade·den) = 1/1.5 with a test; 1 without
    }
    in.gate = gate;
    LineScratch scratch;
    LineSet out;
    extractZeroSet(g.positions, g.faces, adj, in, LineKind::kSuggestive, scratch, out);
    ASSERT_GT(out.segmentCount(), 0u);
    float min_z = 1e9f, max_z = -1e9f;
    for (size_t i = 0; i < out.points.size(); ++i) {
      EXPECT_NEAR(out.points[i].x, 0.05f, 1e-5f);
      EXPECT_NEAR(out.alpha[i], with_test ? 1.0f / 1.5f : 1.0f, 1e-6f);
      min_z = std::min(min_z, out.points[i].z);
      max_z = std::max(max_z, out.points[i].z);
    }
    EXPECT_NEAR(min_z, 0.1f, 1e-5f);
    EXPECT_NEAR(max_z, 1.0f, 1e-5f);
    StrokeSet strokes;
    ChainScratch cs;
    chainStrokes(out, strokes, cs);
    EXPECT_EQ(strokes.strokeCount(), 1u);
    // With every corner below, nothing: the gate moved past the whole grid.
    std::vector<float> low(gate);
    for (float& x : low) x -= 3.0f;
    in.gate = low;
    out.clear();
    extractZeroSet(g.positions, g.faces, adj, in, LineKind::kSuggestive, scratch, out);
    EXPECT_EQ(out.segmentCount(), 0u);
  }
}

// The motion fade's speed: |Δkr| / (sin²θ·Dw kr) along ŵ, × cosθ on screen, × px per unit,
// / dt; the gain is 1 below `start`, 0 above `end` and a smoothstep between.
TEST(ViewQuantities, SuggestiveMotionGainFollowsTheSpeed) {
  Camera cam;
  cam.orthographic = true;
  cam.ortho_height = 2.0f;  // 100 px per unit in a 200-px-high image
  ViewQuantities view;
  view.ndotv = {0.6f, 0.6f, 0.6f, 0.6f, 0.6f};
  view.dwkr = {2.0f, 2.0f, 2.0f, -1.0f, 2.0f};
  const std::vector<glm::vec3> positions(5, glm::vec3(0.0f));
  // Speeds 0.01/(0.64·2)·0.6·100·30 = 14.06 px/s, a tenth of it, ten times it; Dw kr < 0
  // (no suggestive contour: unknown speed); no change recorded.
  const std::vector<float> change = {0.01f, 0.001f, 0.1f, 0.01f, 0.0f};
  std::vector<float> gain;
  suggestiveMotionGain(positions, view, change, cam, 200, 1.0f / 30.0f, 10.0f, 20.0f, gain);
  ASSERT_EQ(gain.size(), 5u);
  const float t = (0.01f / (0.64f * 2.0f) * 0.6f * 100.0f * 30.0f - 10.0f) / 10.0f;
  EXPECT_NEAR(gain[0], 1.0f - t * t * (3.0f - 2.0f * t), 1e-4f);
  EXPECT_EQ(gain[1], 1.0f);
  EXPECT_EQ(gain[2], 0.0f);
  EXPECT_EQ(gain[3], 1.0f);
  EXPECT_EQ(gain[4], 1.0f);
  // Off (end 0), or a still (dt 0): every gain 1.
  suggestiveMotionGain(positions, view, change, cam, 200, 1.0f / 30.0f, 10.0f, 0.0f, gain);
  EXPECT_EQ(std::count(gain.begin(), gain.end(), 1.0f), 5);
  suggestiveMotionGain(positions, view, change, cam, 200, 0.0f, 10.0f, 20.0f, gain);
  EXPECT_EQ(std::count(gain.begin(), gain.end(), 1.0f), 5);
}

TEST(LineExtractor, NoReallocationAfterWarmUp) {
  const TriMesh m = makeTorusKnot(3, 2, 1.0f, 0.25f, 200, 16, 0.1f);
  ShapeCache shape;
  shape.compute(m);
  LineExtractor ex;
  LineSet lines;
  StrokeSet strokes;
  ChainScratch scratch;
  ViewSpec view;
  view.eye = {0, 1, 4};
  ex.extract(m, shape, view, LineParams{}, 0.01f, lines);
  chainStrokes(lines, strokes, scratch);
  const glm::vec3* p = lines.points.data();
  const glm::vec3* sp = strokes.points.data();
  const float* nv = ex.viewQuantities().ndotv.data();
  for (int i = 0; i < 3; ++i) {
    ex.extract(m, shape, view, LineParams{}, 0.01f, lines);
    chainStrokes(lines, strokes, scratch);
  }
  EXPECT_EQ(lines.points.data(), p);
  EXPECT_EQ(strokes.points.data(), sp);
  EXPECT_EQ(ex.viewQuantities().ndotv.data(), nv);
}

TEST(ViewSpec, FromCamera) {
  Camera cam;
  cam.eye = {1, 2, 3};
  cam.target = {1, 2, 0};
  ViewSpec v = ViewSpec::fromCamera(cam);
  EXPECT_FALSE(v.orthographic);
  EXPECT_EQ(v.eye, cam.eye);
  cam.orthographic = true;
  v = ViewSpec::fromCamera(cam);
  EXPECT_TRUE(v.orthographic);
  EXPECT_NEAR(v.toward_viewer.z, 1.0f, 1e-6f);  // from the target toward the eye
}

TEST(LineTypes, Names) {
  EXPECT_STREQ(lineKindName(LineKind::kContour), "contour");
  EXPECT_STREQ(lineKindName(LineKind::kSuggestive), "suggestive");
  EXPECT_STREQ(lineKindName(LineKind::kCrease), "crease");
  EXPECT_STREQ(lineKindName(LineKind::kBoundary), "boundary");
  EXPECT_STREQ(lineKindName(LineKind::kSuggestiveHighlight), "suggestive-highlight");
  for (int k = 0; k < kLineKindCount; ++k)
    EXPECT_EQ(parseLineKind(lineKindName(static_cast<LineKind>(k))), static_cast<LineKind>(k));
}

}  // namespace
}  // namespace lodline

namespace lodline {
namespace {

// Every field of two line sets equal: the same segments, in the same order, with the same ids.
void expectSameLines(const LineSet& a, const LineSet& b) {
  EXPECT_EQ(a.counts, b.counts);
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.alpha, b.alpha);
  EXPECT_EQ(a.point_ids, b.point_ids);
  EXPECT_EQ(a.kinds, b.kinds);
  EXPECT_EQ(a.sources, b.sources);
}

// The per-edge and per-face passes split over worker threads give exactly the serial output
// (same segments in the same order, same point ids), for all line kinds together.
// A mesh's lines extracted twice from one view, on one thread and on three (scratch.pool).
struct ExtractedTwice {
  ShapeCache shape;
  ViewSpec view;
  float fs = 1.0f;
  ViewQuantities vq;
  WorkerPool pool{3};
  LineScratch serial_scratch, threaded_scratch;
  LineSet serial, threaded;

  ExtractedTwice(const TriMesh& m, const LineParams& params) {
    shape.compute(m);
    view.eye = {0.3f, 1.2f, 3.5f};
    fs = computeFeatureSize(shape.k1(), shape.k2(), computeBounds(m.positions).radius);
    computeViewQuantities(shape.fields(m), view, params.suggestive_threshold / (fs * fs), vq);
    threaded_scratch.pool = &pool;
    extractLines(m, shape.adjacency(), shape.faceNormals(), vq, params, fs, serial_scratch, serial);
    extractLines(m, shape.adjacency(), shape.faceNormals(), vq, params, fs, threaded_scratch, threaded);
  }
};

TEST(ExtractLines, WorkerThreadsGiveTheSerialOutput) {
  const TriMesh m = makeTorusKnot(2, 3, 1.0f, 0.2f, 600, 24, 0.18f);  // 28,800 faces
  const ExtractedTwice x(m, LineParams{});
  const LineSet &serial = x.serial, &threaded = x.threaded;
  ASSERT_GT(serial.counts[static_cast<int>(LineKind::kContour)], 100u);
  ASSERT_GT(serial.counts[static_cast<int>(LineKind::kSuggestive)], 100u);
  expectSameLines(serial, threaded);
}

// The edge passes on worker threads (crease and boundary marks, the list of marked edges the
// later passes read, the mesh silhouette's facing and edges) give exactly the serial output,
// on a mesh with creases (a five-sided tube turns 72° at each edge), a boundary (some faces
// removed), marked edges and silhouette creases.
TEST(ExtractLines, EdgePassesOnWorkerThreadsGiveTheSerialOutput) {
  TriMesh m = makeTorusKnot(2, 3, 1.0f, 0.2f, 4000, 5, 0.18f);  // 40,000 faces, 60,000 edges
  m.faces.resize(m.faces.size() - 50);  // an open end: a boundary loop
  for (uint32_t k = 0; k < 40; ++k) m.marked_edges.push_back({m.faces[k * 97][0], m.faces[k * 97][1]});
  for (auto& e : m.marked_edges)
    if (e[0] > e[1]) std::swap(e[0], e[1]);
  LineParams params;
  params.boundaries = true;
  ExtractedTwice x(m, params);
  const ShapeCache& shape = x.shape;
  const ViewSpec& view = x.view;
  const ViewQuantities& vq = x.vq;
  const float fs = x.fs;
  LineScratch &serial_scratch = x.serial_scratch, &threaded_scratch = x.threaded_scratch;
  const LineSet &serial = x.serial, &threaded = x.threaded;
  ASSERT_GT(serial.counts[static_cast<int>(LineKind::kCrease)], 1000u);
  ASSERT_GT(serial.counts[static_cast<int>(LineKind::kBoundary)], 3u);
  ASSERT_GT(serial.counts[static_cast<int>(LineKind::kContour)], 100u);
  expectSameLines(serial, threaded);
  // The marked edges are listed once each, in edge order, and only those.
  const MeshAdjacency& adj = shape.adjacency();
  std::vector<uint32_t> marked;
  for (uint32_t e = 0; e < adj.edges.size(); ++e)
    if (serial_scratch.edge_mark[e]) marked.push_back(e);
  EXPECT_EQ(serial_scratch.marked_edges, marked);
  EXPECT_EQ(threaded_scratch.marked_edges, marked);
  // A marked edge whose faces meet at under 60° is a crease all the same.
  size_t flat_marked = 0;
  for (const EdgeKey& k : m.marked_edges) {
    const uint32_t e = adj.findEdge(k[0], k[1]);
    ASSERT_NE(e, kNoIndex);
    EXPECT_EQ(serial_scratch.edge_mark[e], adj.edge_face_count[e] == 1 ? 2 : 1);
    const auto& f = adj.edge_faces[e];
    if (adj.edge_face_count[e] == 2 &&
        glm::dot(shape.faceNormals()[f[0]], shape.faceNormals()[f[1]]) > 0.9f)
      ++flat_marked;
  }
  EXPECT_GT(flat_marked, 0u);
  // Under a mask of crease vertices (an adapted mesh) only the edges at masked and boundary
  // vertices are tested: with every vertex masked, the same lines as without a mask.
  const std::vector<uint8_t> all(m.positions.size(), 1);
  LineSet all_masked;
  extractLines(m, adj, shape.faceNormals(), vq, params, fs, threaded_scratch, all_masked, all);
  expectSameLines(serial, all_masked);
  // With a sparse mask: exactly the edges with both ends masked whose faces turn by over 60°,
  // the boundary and the marked edges.
  std::vector<uint8_t> some(m.positions.size(), 0);
  for (size_t v = 0; v < some.size(); v += 3) some[v] = 1;
  LineSet sparse;
  extractLines(m, adj, shape.faceNormals(), vq, params, fs, threaded_scratch, sparse, some);
  std::vector<uint32_t> expected;
  const float cos60 = std::cos(60.0f * std::numbers::pi_v<float> / 180.0f);
  for (uint32_t e = 0; e < adj.edges.size(); ++e) {
    const auto& f = adj.edge_faces[e];
    const bool crease = adj.edge_face_count[e] == 2 && some[adj.edges[e][0]] && some[adj.edges[e][1]] &&
                        glm::dot(shape.faceNormals()[f[0]], shape.faceNormals()[f[1]]) < cos60;
    const bool listed_key = std::find(m.marked_edges.begin(), m.marked_edges.end(), adj.edges[e]) != m.marked_edges.end();
    if (crease || adj.edge_face_count[e] == 1 || listed_key) expected.push_back(e);
  }
  ASSERT_GT(expected.size(), 100u);
  EXPECT_EQ(threaded_scratch.marked_edges, expected);
  for (uint32_t e = 0; e < adj.edges.size(); ++e)
    if (!std::binary_search(expected.begin(), expected.end(), e)) {
      ASSERT_EQ(threaded_scratch.edge_mark[e], 0) << e;
    }
  LineSet serial_silhouette, threaded_silhouette;
  extractMeshSilhouette(m, adj, shape.faceNormals(), view, serial_scratch, serial_silhouette);
  extractMeshSilhouette(m, adj, shape.faceNormals(), view, threaded_scratch, threaded_silhouette);
  ASSERT_GT(serial_silhouette.counts[static_cast<int>(LineKind::kContour)], 100u);
  expectSameLines(serial_silhouette, threaded_silhouette);
  // Each silhouette edge joins a front face and a back face.
  for (size_t s = 0; s < serial_silhouette.kinds.size(); ++s) {
    const uint32_t e = serial_silhouette.sources[s];
    ASSERT_LT(e, adj.edges.size());
    const auto& f = adj.edge_faces[e];
    const auto facing = [&](uint32_t face) {
      return glm::dot(shape.faceNormals()[face], view.eye - m.positions[m.faces[face][0]]) > 0.0f;
    };
    EXPECT_NE(facing(f[0]), facing(f[1])) << "edge " << e;
  }
}

// The face pass finds its faces sixteen at a time with AVX-512 where the processor has it
// (extractZeroSets): the same segments as the face-by-face scan, on random values with exact
// zeros, tests, gates and shut vertices, over faces whose count is no multiple of 16 and some
// of which are invalid (an index out of range, a repeated one: they must read no code).
TEST(ExtractLines, WideFaceScanGivesTheFaceByFaceOutput) {
  TriMesh m = makeTorusKnot(2, 3, 1.0f, 0.2f, 333, 17, 0.18f);
  const uint32_t nv = static_cast<uint32_t>(m.positions.size());
  for (size_t f = 7; f < m.faces.size(); f += 101) m.faces[f][f % 3] = nv + static_cast<uint32_t>(f);
  for (size_t f = 50; f < m.faces.size(); f += 257) m.faces[f][1] = m.faces[f][0];
  MeshAdjacency adj;
  buildAdjacency(m, adj);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<float> value(nv), num(nv), den(nv), gate(nv), value2(nv), num2(nv), gate2(nv);
  std::vector<uint8_t> shut(nv), shut2(nv);
  for (uint32_t v = 0; v < nv; ++v) {
    value[v] = v % 13 == 0 ? 0.0f : u(rng) + 0.3f;
    num[v] = u(rng);
    den[v] = u(rng);
    gate[v] = u(rng);
    value2[v] = u(rng);
    num2[v] = u(rng);
    shut[v] = v % 29 == 0;
    gate2[v] = u(rng);
    shut2[v] = v % 31 == 0;
  }
  ZeroSetInput a, b;
  a.value = value;
  a.test_num = num;
  a.test_den = den;
  a.gate = gate;
  a.gate_min = -0.8f;
  a.fade = 0.1f;
  a.shut = shut2;
  b.value = value2;
  b.test_num = num2;
  b.shut = shut;
  b.gate = gate2;
  b.gate_min = 0.2f;
  const ZeroSetInput both[2] = {a, b};
  const LineKind types[2] = {LineKind::kContour, LineKind::kSuggestive};
  LineScratch wide, narrow;
  narrow.wide_face_scan = false;
  LineSet w, n;
  extractZeroSets(m.positions, m.faces, adj, both, types, wide, w);
  extractZeroSets(m.positions, m.faces, adj, both, types, narrow, n);
#if defined(__x86_64__)
  RecordProperty("avx512f", __builtin_cpu_supports("avx512f") ? "yes" : "no");
#endif
  ASSERT_GT(n.counts[static_cast<int>(LineKind::kContour)], 500u);
  ASSERT_GT(n.counts[static_cast<int>(LineKind::kSuggestive)], 500u);
  expectSameLines(w, n);
}

}  // namespace
}  // namespace lodline

namespace lodline {
namespace {

// chainStrokes joins two segment ends exactly when they are the only two ends with their
// (type, point id), and never a segment to itself: checked on random segments with many
// shared ids (junctions of three and more ends) and degenerate segments.
TEST(Strokes, KeepStrokesCompactsInPlaceAndKeepsOrder) {
  StrokeSet s;
  // Three strokes: 2 points (contour), 3 points closed (suggestive), 2 points (crease).
  for (int i = 0; i < 7; ++i) {
    s.points.push_back(glm::vec3(static_cast<float>(i), 0.0f, 0.0f));
    s.alpha.push_back(0.1f * static_cast<float>(i));
  }
  s.offsets = {0, 2, 5, 7};
  s.kinds = {LineKind::kContour, LineKind::kSuggestive, LineKind::kCrease};
  s.closed = {0, 1, 0};
  StrokeSet none = s;
  keepStrokes(none, [](size_t) { return true; });
  EXPECT_EQ(none.points, s.points);
  EXPECT_EQ(none.offsets, s.offsets);

  keepStrokes(s, [](size_t i) { return i != 1; });
  ASSERT_EQ(s.strokeCount(), 2u);
  EXPECT_EQ(s.offsets, (std::vector<uint32_t>{0, 2, 4}));
  EXPECT_EQ(s.kinds[1], LineKind::kCrease);
  EXPECT_EQ(s.closed[1], 0);
  ASSERT_EQ(s.points.size(), 4u);
  EXPECT_EQ(s.points[2].x, 5.0f);
  EXPECT_FLOAT_EQ(s.alpha[3], 0.6f);

  keepStrokes(s, [](size_t) { return false; });
  EXPECT_EQ(s.strokeCount(), 0u);
  EXPECT_TRUE(s.points.empty());
  EXPECT_EQ(s.offsets, (std::vector<uint32_t>{0}));
}

TEST(Strokes, JoinExactlyTheEndsThatPairUp) {
  std::mt19937 rng(5);
  for (int round = 0; round < 20; ++round) {
    LineSet lines;
    const int ns = 200 + static_cast<int>(rng() % 300);
    std::map<std::pair<int, uint32_t>, int> ends_with_key;  // (type, id) -> count
    for (int k = 0; k < ns; ++k) {
      const auto type = static_cast<LineKind>(rng() % 2);
      const uint32_t a = rng() % 90, b = (rng() % 10 == 0) ? a : rng() % 90;
      for (uint32_t id : {a, b}) {
        lines.points.push_back(glm::vec3(static_cast<float>(id), static_cast<float>(type), 0.0f));
        lines.alpha.push_back(1.0f);
        lines.point_ids.push_back(id);
        ++ends_with_key[{static_cast<int>(type), id}];
      }
      lines.kinds.push_back(type);
      lines.sources.push_back(static_cast<uint32_t>(k));
      ++lines.counts[static_cast<int>(type)];
    }
    StrokeSet strokes;
    ChainScratch scratch;
    chainStrokes(lines, strokes, scratch);
    auto count = [&](const glm::vec3& p) {
      return ends_with_key[{static_cast<int>(p.y), static_cast<uint32_t>(p.x)}];
    };
    size_t segments = 0;
    for (size_t s = 0; s < strokes.strokeCount(); ++s) {
      const uint32_t b = strokes.offsets[s], e = strokes.offsets[s + 1];
      ASSERT_GE(e - b, 2u);
      segments += e - b - 1;
      for (uint32_t i = b + 1; i + 1 < e; ++i) ASSERT_EQ(count(strokes.points[i]), 2) << round;  // joints
      if (strokes.closed[s]) {
        ASSERT_EQ(strokes.points[b], strokes.points[e - 1]);
        ASSERT_EQ(count(strokes.points[b]), 2) << round;
      } else if (!(e - b == 2 && strokes.points[b] == strokes.points[b + 1])) {
        // Open strokes stop where the ends do not pair up (a lone degenerate segment may
        // hold both ends of its id).
        ASSERT_NE(count(strokes.points[b]), 2) << round;
        ASSERT_NE(count(strokes.points[e - 1]), 2) << round;
      }
    }
    EXPECT_EQ(segments, static_cast<size_t>(ns)) << round;
  }
}

}  // namespace
}  // namespace lodline
