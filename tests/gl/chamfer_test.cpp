// Chamfer edge highlights (Wei, Shi, Yong, "Rendering chamfering structures of sharp edges",
// Visual Computer 2014; docs/design.md §2.2): the F(φ, n) table against direct integration, the
// per-pixel formula against brute-force integration over the arc, sharp-edge finding, and a
// headless render where the highlights appear on a box's edges only when switched on.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <random>

#include <glad/gl.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "frame/line_drawing.h"
#include "gl/chamfer_edges.h"
#include "gl/chamfer_math.h"
#include "gl/context.h"
#include "gl/renderer.h"
#include "io/generate.h"
#include "io/image.h"

namespace lodline {
namespace {

constexpr double kHalfPiD = std::numbers::pi / 2.0;

// ∫₀^φ cos^m θ dθ by composite Gauss–Legendre (5 points, 64 panels), double precision:
// independent of the recurrence the table is built with.
double integrateCosPow(double phi, double m) {
  static const double x[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                              0.9061798459386640};
  static const double w[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                              0.4786286704993665, 0.2369268850561891};
  const int panels = 64;
  const double h = phi / panels;
  double sum = 0.0;
  for (int p = 0; p < panels; ++p) {
    const double c = (p + 0.5) * h;
    for (int k = 0; k < 5; ++k) sum += w[k] * std::pow(std::cos(c + 0.5 * h * x[k]), m);
  }
  return sum * 0.5 * h;
}

glm::vec3 randomUnit(std::mt19937& rng) {
  std::normal_distribution<float> g(0.0f, 1.0f);
  glm::vec3 v;
  do v = glm::vec3(g(rng), g(rng), g(rng));
  while (glm::length(v) < 1e-3f);
  return glm::normalize(v);
}

const std::vector<float>& table() {
  static const std::vector<float> t = [] {
    std::vector<float> v;
    buildChamferTable(v);
    return v;
  }();
  return t;
}

TEST(ChamferTable, ExactRecurrenceMatchesQuadrature) {
  for (int m : {0, 1, 2, 3, 7, 32, 64, 127, 128})
    for (double phi : {0.0, 0.1, 0.7, 1.2, kHalfPiD})
      EXPECT_NEAR(chamferTableExact(phi, m), integrateCosPow(phi, m), 1e-12) << m << " " << phi;
  // Wallis: F(π/2, 2) = π/4.
  EXPECT_NEAR(chamferTableExact(kHalfPiD, 2), std::numbers::pi / 4.0, 1e-14);
}

// The paper bounds linear interpolation of its 1024×128 table by about 2e-6.
TEST(ChamferTable, InterpolationErrorBelow3e6) {
  const auto& t = table();
  ASSERT_EQ(t.size(), static_cast<size_t>(kChamferTablePhiSamples) * kChamferTableExponents);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uphi(0.0, kHalfPiD);
  std::uniform_int_distribution<int> um(1, kChamferTableExponents);
  double max_err = 0.0;
  for (int k = 0; k < 20000; ++k) {
    const double phi = uphi(rng);
    const int m = um(rng);
    const double err = std::abs(chamferTableLookup(t, static_cast<float>(phi), static_cast<float>(m)) -
                                integrateCosPow(phi, m));
    max_err = std::max(max_err, err);
  }
  std::printf("chamfer table: max |F_table - F| over 20000 random (phi, n) = %.3g\n", max_err);
  EXPECT_LE(max_err, 3e-6);
  // Odd extension for arcs straddling the half vector.
  EXPECT_FLOAT_EQ(chamferTableLookup(t, -0.4f, 9.0f), -chamferTableLookup(t, 0.4f, 9.0f));
}

// Brute force: ∫ max(N(t)·x, 0)^n (p·N'(t)) dt over [0, β] by the midpoint rule in double.
double bruteArcIntegral(const ChamferArc& arc, glm::dvec3 x, glm::dvec3 p, double n, double lo,
                        double hi, int steps = 40000) {
  const glm::dvec3 u(arc.u), w(arc.w);
  double sum = 0.0;
  const double dt = (hi - lo) / steps;
  for (int i = 0; i < steps; ++i) {
    const double t = lo + (i + 0.5) * dt;
    const glm::dvec3 nrm = std::cos(t) * u + std::sin(t) * w;
    const glm::dvec3 dn = -std::sin(t) * u + std::cos(t) * w;
    sum += std::pow(std::max(glm::dot(nrm, x), 0.0), n) * glm::dot(p, dn);
  }
  return sum * dt;
}

TEST(ChamferFormula, ArcIntegralMatchesBruteForce) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> un(1, 127);
  double max_rel = 0.0;
  int checked = 0;
  for (int k = 0; k < 3000; ++k) {
    const glm::vec3 n1 = randomUnit(rng), n2 = randomUnit(rng);
    ChamferArc arc;
    if (!makeChamferArc(n1, n2, arc) || arc.beta < 0.05f) continue;
    const glm::vec3 x = randomUnit(rng), p = randomUnit(rng);
    const float n = static_cast<float>(k % 4 == 0 ? 1 : un(rng));
    // Whole arc, or a random sub-arc (the replacement composition integrates sub-arcs).
    float lo = 0.0f, hi = arc.beta;
    if (k % 2 == 1) {
      std::uniform_real_distribution<float> ut(0.0f, arc.beta);
      lo = ut(rng);
      hi = ut(rng);
      if (lo > hi) std::swap(lo, hi);
      if (hi - lo < 0.02f) continue;
    }
    const double ref = bruteArcIntegral(arc, glm::dvec3(x), glm::dvec3(p), n, lo, hi);
    const float got = chamferArcIntegral(arc, table(), x, p, n, lo, hi);
    // Where the integral is tiny (the arc barely reaches the lobe, or p·N' changes sign and
    // cancels), relative error is float noise: check those absolutely.
    if (std::abs(ref) < 1e-4) {
      EXPECT_NEAR(got, ref, 1e-6) << "n=" << n;
      continue;
    }
    const double rel = std::abs(got - ref) / std::abs(ref);
    max_rel = std::max(max_rel, rel);
    ++checked;
    EXPECT_LE(rel, 1e-3) << "n=" << n << " beta=" << arc.beta << " ref=" << ref;
  }
  std::printf("chamfer formula: max relative error %.3g over %d random (N1, N2, H, P, n)\n",
              max_rel, checked);
  EXPECT_GT(checked, 500);
}

// The whole pixel: Blinn–Phong averaged over the visible part of the strip, weighted by its
// projected width, against sampling the strip.
TEST(ChamferFormula, ShadeMatchesSampledStrip) {
  std::mt19937 rng(5);
  ChamferMaterial mat;
  mat.ambient = glm::vec3(0.2f);
  mat.diffuse = glm::vec3(0.6f, 0.5f, 0.4f);
  mat.specular = glm::vec3(0.5f);
  double max_rel = 0.0, max_width_err = 0.0;
  int checked = 0;
  for (int k = 0; k < 2000; ++k) {
    const glm::vec3 n1 = randomUnit(rng), n2 = randomUnit(rng);
    const glm::vec3 v = randomUnit(rng), l = randomUnit(rng);
    mat.shininess = static_cast<float>(1 + k % 127);
    const ChamferShade s = chamferShade(table(), n1, n2, v, l, mat);
    ChamferArc arc;
    if (!makeChamferArc(n1, n2, arc) || arc.beta < 0.05f) continue;
    const glm::vec3 p = glm::normalize(glm::cross(v, arc.axis));
    // Sample the strip: visible normals only, weight |p·dN|.
    const int steps = 40000;
    glm::dvec3 sum(0.0);
    double wsum = 0.0;
    for (int i = 0; i < steps; ++i) {
      const float t = arc.beta * (i + 0.5f) / steps;
      const glm::vec3 nrm = chamferArcNormal(arc, t);
      if (glm::dot(nrm, v) < 0.0f) continue;
      const glm::vec3 dn = -std::sin(t) * arc.u + std::cos(t) * arc.w;
      const double wgt = std::abs(glm::dot(p, dn)) * arc.beta / steps;
      sum += glm::dvec3(blinnPhong(nrm, v, l, mat)) * wgt;
      wsum += wgt;
    }
    if (wsum < 1e-3) {
      EXPECT_LT(s.width, 2e-3f);
      continue;
    }
    max_width_err = std::max(max_width_err, std::abs(s.width - wsum));
    const glm::dvec3 ref = sum / wsum;
    for (int c = 0; c < 3; ++c) {
      const double rel = std::abs(s.color[c] - ref[c]) / std::abs(ref[c]);
      max_rel = std::max(max_rel, rel);
      EXPECT_LE(rel, 1e-3) << "channel " << c << " n=" << mat.shininess;
    }
    ++checked;
  }
  std::printf("chamfer pixel: max relative colour error %.3g, max width error %.3g (%d cases)\n",
              max_rel, max_width_err, checked);
  EXPECT_GT(checked, 500);
  EXPECT_LT(max_width_err, 1e-3);
}

TEST(ChamferFormula, WeightIsProjectedWidthInPixels) {
  // A 45° view of a right-angled edge: strip width r·|P·(N1 − N2)| = r·√2.
  EXPECT_NEAR(chamferWeight(1000.0f, 0.001f, 2.0f, std::sqrt(2.0f)), 0.7071f, 1e-4f);
  EXPECT_EQ(chamferWeight(1000.0f, 1.0f, 2.0f, 1.0f), 1.0f);
  EXPECT_EQ(chamferWeight(1000.0f, 0.0f, 2.0f, 1.0f), 0.0f);
  EXPECT_EQ(chamferWeight(1000.0f, 1.0f, 0.0f, 1.0f), 0.0f);
}

TEST(ChamferEdges, BoxHasTwelveSharpEdges) {
  const TriMesh box = makeRoundedBox(glm::vec3(1.0f, 0.6f, 0.8f), 0.0f, 0, 1);
  ChamferEdgeScratch scratch;
  ChamferEdges edges;
  findChamferEdges(box.positions, box.faces, {}, 1.0f, scratch, edges);
  EXPECT_EQ(edges.countAtLeast(30.0f), 12u);
  EXPECT_EQ(edges.size(), 12u);  // the face diagonals are flat: no candidate
  for (size_t e = 0; e < edges.size(); ++e) EXPECT_NEAR(edges.angle_deg[e], 90.0f, 1e-3f);
  EXPECT_EQ(edges.countAtLeast(91.0f), 0u);
  // Subdivided faces: each box edge is split into 3 edges, the inner edges stay flat.
  const TriMesh fine = makeRoundedBox(glm::vec3(1.0f, 0.6f, 0.8f), 0.0f, 0, 3);
  findChamferEdges(fine.positions, fine.faces, {}, 1.0f, scratch, edges);
  EXPECT_EQ(edges.size(), 36u);

  // Split vertices (one copy per face corner, as flat-shaded exports have) weld back.
  TriMesh split;
  for (const auto& f : box.faces) {
    const uint32_t b = static_cast<uint32_t>(split.positions.size());
    for (int j = 0; j < 3; ++j) split.positions.push_back(box.positions[f[j]]);
    split.faces.push_back({b, b + 1, b + 2});
  }
  findChamferEdges(split.positions, split.faces, {}, 1.0f, scratch, edges);
  EXPECT_EQ(edges.countAtLeast(30.0f), 12u);
}

TEST(ChamferEdges, RoundedBoxHasNoSharpEdgeAndMarkedEdgesAlwaysCount) {
  const TriMesh rounded = makeRoundedBox(glm::vec3(1.0f), 0.2f, 16, 2);
  ChamferEdgeScratch scratch;
  ChamferEdges edges;
  findChamferEdges(rounded.positions, rounded.faces, {}, 1.0f, scratch, edges);
  EXPECT_EQ(edges.countAtLeast(30.0f), 0u);
  EXPECT_GT(edges.size(), 0u);

  const TriMesh sphere = makeIcoSphere(1.0f, 3);
  const EdgeKey marked{sphere.faces[0][0], sphere.faces[0][1]};
  findChamferEdges(sphere.positions, sphere.faces, std::span(&marked, 1), 30.0f, scratch, edges);
  ASSERT_EQ(edges.size(), 1u);
  EXPECT_EQ(edges.angle_deg[0], kMarkedEdgeAngleDeg);
}

TEST(ChamferEdges, RoundedBoxIsClosedAndRoundedWhereExpected) {
  const float r = 0.25f;
  const TriMesh m = makeRoundedBox(glm::vec3(1.0f, 0.7f, 0.5f), r, 12, 3);
  MeshAdjacency adj;
  buildAdjacency(m, adj);
  for (uint32_t c : adj.edge_face_count) ASSERT_EQ(c, 2u) << "not closed";
  // Every vertex is at distance r from the inner box.
  const glm::vec3 inner = glm::vec3(1.0f, 0.7f, 0.5f) - glm::vec3(r);
  for (const glm::vec3& p : m.positions) {
    const glm::vec3 c = glm::clamp(p, -inner, inner);
    EXPECT_NEAR(glm::length(p - c), r, 1e-5f);
  }
}

// Renders `mesh` shaded, with or without highlights.
Image renderShaded(const TriMesh& mesh, const Camera& cam, const FrameParams& rp, const ObjectStyle& style) {
  LineDrawing drawing(mesh);
  std::array<bool, kLineKindCount> enabled{};
  drawing.update(cam, enabled);
  auto renderer = Renderer::create();
  EXPECT_TRUE(renderer.ok()) << renderer.error().message;
  if (!renderer) return {};
  auto target = OffscreenTarget::create(rp.width, rp.height, rp.msaa);
  EXPECT_TRUE(target.ok());
  if (!target) return {};
  renderer->setMesh(0, drawing.mesh().positions, drawing.normals(), drawing.mesh().faces);
  target->bind();
  renderer->drawSurfaces(cam, rp, std::span<const ObjectStyle>(&style, 1));
  if (style.chamfer.enabled) {
    EXPECT_EQ(renderer->chamferEdgesDrawn(), 12u);
  } else {
    EXPECT_EQ(renderer->chamferEdgesDrawn(), 0u);
  }
  return target->readback();
}

float lum(const Image& im, int x, int y) {
  const uint8_t* p = im.pixel(x, y);
  return (p[0] + p[1] + p[2]) / 3.0f;
}

// Distance from pixel centre q to segment ab (pixels).
float segDist(glm::vec2 q, glm::vec2 a, glm::vec2 b) {
  const glm::vec2 ab = b - a;
  const float t = std::clamp(glm::dot(q - a, ab) / glm::dot(ab, ab), 0.0f, 1.0f);
  return glm::length(q - (a + t * ab));
}

void checkHighlights(ChamferCompose compose) {
  const glm::vec3 half(1.0f, 0.6f, 0.8f);
  const TriMesh box = makeRoundedBox(half, 0.0f, 0, 1);
  FrameParams rp;
  rp.width = 320;
  rp.height = 240;
  rp.msaa = 4;
  ObjectStyle style;
  style.style = Style::kShaded;
  for (auto& k : style.lines.kinds) k.enabled = false;
  style.chamfer.radius = 0.02f;  // ≈ 1.5 px at this distance: W saturates on most edges
  style.chamfer.compose = compose;
  const Bounds b = computeBounds(box.positions);
  const Camera cam = orbitCamera(b, {35.0f, 25.0f, 0.0f}, 35.0f, 320.0f / 240.0f);
  const Image on = renderShaded(box, cam, rp, style);
  style.chamfer.enabled = false;
  const Image off = renderShaded(box, cam, rp, style);
  ASSERT_EQ(on.width, 320);
  ASSERT_EQ(off.width, 320);
  if (const char* dir = std::getenv("LODLINE_TEST_IMAGES")) {  // for looking at the renders
    const std::string tag = compose == ChamferCompose::kAlpha ? "alpha" : "replace";
    (void)writePng(std::string(dir) + "/chamfer-test-" + tag + ".png", on);
    (void)writePng(std::string(dir) + "/chamfer-test-off.png", off);
  }

  // Projected visible edges: those with at least one face towards the eye.
  ChamferEdgeScratch scratch;
  ChamferEdges edges;
  findChamferEdges(box.positions, box.faces, {}, 30.0f, scratch, edges);
  std::vector<std::array<glm::vec2, 2>> visible, interior;
  for (size_t e = 0; e < edges.size(); ++e) {
    const glm::vec3 a = box.positions[edges.vertices[e][0]], c = box.positions[edges.vertices[e][1]];
    const glm::vec3 to_eye = glm::normalize(cam.eye - 0.5f * (a + c));
    if (glm::dot(edges.normal1[e], to_eye) <= 0.0f && glm::dot(edges.normal2[e], to_eye) <= 0.0f)
      continue;
    visible.push_back({projectToPixels(cam, a, 320, 240), projectToPixels(cam, c, 320, 240)});
    if (glm::dot(edges.normal1[e], to_eye) > 0.0f && glm::dot(edges.normal2[e], to_eye) > 0.0f)
      interior.push_back(visible.back());
  }
  ASSERT_EQ(visible.size(), 9u);
  ASSERT_EQ(interior.size(), 3u);

  int changed = 0, changed_off_edges = 0, bright_on = 0, bright_off = 0;
  for (int y = 0; y < 240; ++y)
    for (int x = 0; x < 320; ++x) {
      const glm::vec2 q(x + 0.5f, y + 0.5f);
      float d = 1e9f;
      for (const auto& s : visible) d = std::min(d, segDist(q, s[0], s[1]));
      const float diff = std::abs(lum(on, x, y) - lum(off, x, y));
      if (diff > 3.0f) {
        ++changed;
        if (d > 2.0f) ++changed_off_edges;
      }
    }
  // A highlight: an edge pixel brighter than the faces on both sides (3 px across the edge),
  // on the edges between two visible faces, away from the corners.
  for (const auto& s : interior) {
    const glm::vec2 dir = glm::normalize(s[1] - s[0]);
    const glm::vec2 nrm(-dir.y, dir.x);
    const float len = glm::length(s[1] - s[0]);
    for (float t = 10.0f; t < len - 10.0f; t += 1.0f) {
      const glm::vec2 c = s[0] + dir * t;
      auto sample = [&](const Image& im, glm::vec2 p) {
        const int x = std::clamp(static_cast<int>(p.x), 0, 319), y = std::clamp(static_cast<int>(p.y), 0, 239);
        return lum(im, x, y);
      };
      for (const Image* im : {&on, &off}) {
        float centre = 0.0f;
        for (float o = -0.7f; o <= 0.71f; o += 0.7f) centre = std::max(centre, sample(*im, c + o * nrm));
        const float side = std::max(sample(*im, c + 3.0f * nrm), sample(*im, c - 3.0f * nrm));
        if (centre > side + 12.0f) (im == &on ? bright_on : bright_off)++;
      }
    }
  }
  std::printf("chamfer render (%s): %d pixels changed (%d away from edges), bright edge samples on %d off %d\n",
              compose == ChamferCompose::kAlpha ? "alpha" : "replace", changed, changed_off_edges, bright_on, bright_off);
  EXPECT_GT(changed, 300);
  EXPECT_EQ(changed_off_edges, 0);
  EXPECT_GT(bright_on, 50);
  EXPECT_EQ(bright_off, 0);
}

TEST(ChamferRender, HighlightsAppearOnBoxEdgesOnlyWhenOn) {
  auto ctx = createHeadlessContext(ContextBackend::kEgl);
  ASSERT_TRUE(ctx.ok()) << ctx.error().message;
  checkHighlights(ChamferCompose::kReplace);
  checkHighlights(ChamferCompose::kAlpha);
}

}  // namespace
}  // namespace lodline
