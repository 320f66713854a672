// Software rasteriser (Han & Wang 2011 constant-depth scanlines): exact coverage, the
// per-mode interpolation error on analytic planes, and the toon renderer built on it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "io/generate.h"
#include "raster/raster.h"
#include "raster/soft_renderer.h"

namespace lodline {
namespace {

std::vector<glm::vec4> toClip(const Camera& cam, std::span<const glm::vec3> p, int w, int h) {
  const glm::mat4 m = cam.projection(static_cast<float>(w) / static_cast<float>(h)) * cam.view();
  std::vector<glm::vec4> out;
  for (auto v : p) out.push_back(m * glm::vec4(v, 1.0f));
  return out;
}

RasterParams countingParams() {
  RasterParams p;
  p.depth_test = false;
  p.count_fragments = true;
  p.threads = 2;
  p.tile_size = 16;  // many tiles, so triangles straddle tile borders
  return p;
}

// A grid of triangles covering more than the whole image in clip space, with random
// perspective (w) and jitter, plus vertices and edges exactly on pixel centres: every pixel
// is covered exactly once (no gaps, no double hits on shared edges).
TEST(RasterCoverage, SharedEdgesCoverEachPixelExactlyOnce) {
  const int W = 97, H = 61;
  for (int variant = 0; variant < 3; ++variant) {
    std::mt19937 rng(7 + variant);
    std::uniform_real_distribution<float> jitter(-0.35f, 0.35f), wdist(0.5f, 3.0f);
    const int n = 12;
    std::vector<glm::vec4> clip;
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        const bool border = i == 0 || j == 0 || i == n || j == n;
        // Variant 0: jittered; 1: vertices exactly on pixel centres; 2: on pixel corners.
        float px = -10.0f + (W + 20.0f) * static_cast<float>(i) / n;
        float py = -10.0f + (H + 20.0f) * static_cast<float>(j) / n;
        if (variant == 0 && !border) {
          px += jitter(rng) * (W + 20.0f) / n;
          py += jitter(rng) * (H + 20.0f) / n;
        } else if (variant == 1) {
          px = std::floor(px) + 0.5f;
          py = std::floor(py) + 0.5f;
        } else if (variant == 2) {
          px = std::floor(px);
          py = std::floor(py);
        }
        const float w = wdist(rng);
        const float ndc_x = 2.0f * px / W - 1.0f, ndc_y = 1.0f - 2.0f * py / H;
        clip.push_back({ndc_x * w, ndc_y * w, 0.0f, w});
      }
    std::vector<std::array<uint32_t, 3>> faces;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
        // Alternate the diagonal so both orientations of shared edges occur.
        if ((i + j) % 2) {
          faces.push_back({a, b, d});
          faces.push_back({a, d, c});
        } else {
          faces.push_back({a, b, c});
          faces.push_back({b, d, c});
        }
      }
    RasterTarget t;
    t.resize(W, H, 0);
    RasterInput in;
    in.clip = clip;
    in.faces = faces;
    rasterize(in, countingParams(), t);
    int bad = 0;
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x)
        if (t.fragments[t.index(x, y)] != 1) ++bad;
    EXPECT_EQ(bad, 0) << "variant " << variant << ": pixels not covered exactly once";
  }
}

// A fan of thin triangles around a vertex on a pixel centre, with edges through pixel
// centres in all directions (horizontal, vertical, diagonal).
TEST(RasterCoverage, FanAroundPixelCentreCoversOnce) {
  const int W = 64, H = 64;
  std::vector<glm::vec4> clip;
  auto add = [&](float px, float py) {
    clip.push_back({2.0f * px / W - 1.0f, 1.0f - 2.0f * py / H, 0.0f, 1.0f});
    return static_cast<uint32_t>(clip.size() - 1);
  };
  const uint32_t c = add(32.5f, 32.5f);
  std::vector<uint32_t> ring;
  for (int k = 0; k < 32; ++k) {
    const float a = 2.0f * 3.14159265f * k / 32.0f;
    // Snap ring points to pixel centres so edges pass through many centres.
    ring.push_back(add(std::floor(32.5f + 60.0f * std::cos(a)) + 0.5f, std::floor(32.5f + 60.0f * std::sin(a)) + 0.5f));
  }
  std::vector<std::array<uint32_t, 3>> faces;
  for (int k = 0; k < 32; ++k) faces.push_back({c, ring[k], ring[(k + 1) % 32]});
  RasterTarget t;
  t.resize(W, H, 0);
  RasterInput in;
  in.clip = clip;
  in.faces = faces;
  rasterize(in, countingParams(), t);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) ASSERT_EQ(t.fragments[t.index(x, y)], 1u) << x << "," << y;
}

// A closed surface is crossed an even number of times by every viewing ray: a convex one
// exactly twice inside its silhouette, zero outside. A gap or a double hit on any edge
// (including the silhouette edges shared by a front and a back face) breaks this.
TEST(RasterCoverage, ClosedMeshCoversItsSilhouetteExactly) {
  const int W = 320, H = 240;
  struct Case {
    TriMesh mesh;
    bool convex;
  };
  std::vector<Case> cases;
  cases.push_back({makeIcoSphere(1.0f, 3), true});
  cases.push_back({makeTorus(1.0f, 0.4f, 40, 20), false});
  for (auto& c : cases)
    for (float az : {0.0f, 33.0f, 71.0f}) {
      const Bounds b = computeBounds(c.mesh.positions);
      const Camera cam = orbitCamera(b, {az, 27.0f, 2.6f}, 35.0f, static_cast<float>(W) / H);
      const auto clip = toClip(cam, c.mesh.positions, W, H);
      RasterTarget t;
      t.resize(W, H, 0);
      RasterInput in;
      in.clip = clip;
      in.faces = c.mesh.faces;
      rasterize(in, countingParams(), t);
      int covered = 0, odd = 0, not_two = 0;
      for (uint32_t n : t.fragments) {
        covered += n > 0;
        odd += n % 2;
        not_two += n != 0 && n != 2;
      }
      EXPECT_GT(covered, 5000);
      EXPECT_EQ(odd, 0) << "odd crossings (gap or double hit), az " << az;
      if (c.convex) {
        EXPECT_EQ(not_two, 0) << "az " << az;
      }
    }
}

// --- Interpolation error on a plane at known angles, against the analytic answer. ---

struct PlaneScene {
  Camera cam;
  std::vector<glm::vec3> positions;
  std::vector<float> uv;  // 2 per vertex
  std::vector<std::array<uint32_t, 3>> faces;
  glm::vec3 origin, e1, e2, normal;
  float half = 0;
};

// A square of half-size `half` centred `dist` in front of the camera, tilted by `tilt`
// degrees about an axis that is itself turned by `roll` degrees in the image, so the
// constant-depth lines have slope tan(roll). u, v run 0..1 across it.
PlaneScene tiltedPlane(float tilt, float roll, float dist, float half, int subdivisions) {
  PlaneScene s;
  s.cam.eye = {0, 0, 0};
  s.cam.target = {0, 0, -1};
  s.cam.fov_deg = 50.0f;
  s.cam.near_plane = 0.05f;
  s.cam.far_plane = 200.0f;
  const float t = glm::radians(tilt), r = glm::radians(roll);
  const glm::vec3 axis(std::cos(r), std::sin(r), 0.0f);         // tilt axis, in the image plane
  const glm::vec3 up(-std::sin(r), std::cos(r), 0.0f);          // ⟂ axis in the image plane
  s.e1 = axis;
  s.e2 = std::cos(t) * up + std::sin(t) * glm::vec3(0, 0, -1);  // tilts away from the viewer
  s.normal = glm::normalize(glm::cross(s.e1, s.e2));
  s.origin = {0, 0, -dist};
  s.half = half;
  const int n = subdivisions;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const float a = -half + 2.0f * half * i / n, b = -half + 2.0f * half * j / n;
      s.positions.push_back(s.origin + a * s.e1 + b * s.e2);
      s.uv.push_back(static_cast<float>(i) / n);
      s.uv.push_back(static_cast<float>(j) / n);
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      s.faces.push_back({a, b, d});
      s.faces.push_back({a, d, c});
    }
  return s;
}

struct ErrorStats {
  double mean = 0, max = 0;
  int pixels = 0;
};

// Texel error (texture of `texels`² over the plane) of `params` vs the ray–plane answer.
ErrorStats planeError(const PlaneScene& s, const RasterParams& params, int W, int H, float texels) {
  const auto clip = toClip(s.cam, s.positions, W, H);
  RasterTarget t;
  t.resize(W, H, 2);
  RasterInput in;
  in.clip = clip;
  in.attributes = s.uv;
  in.attribute_count = 2;
  in.faces = s.faces;
  rasterize(in, params, t);
  const double tan_half = std::tan(glm::radians(static_cast<double>(s.cam.fov_deg)) * 0.5);
  const double aspect = static_cast<double>(W) / H;
  ErrorStats e;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      if (t.face_id[t.index(x, y)] == kNoFace) continue;
      const double nx = 2.0 * (x + 0.5) / W - 1.0, ny = 1.0 - 2.0 * (y + 0.5) / H;
      const glm::dvec3 d(nx * tan_half * aspect, ny * tan_half, -1.0);
      const glm::dvec3 n(s.normal), o(s.origin);
      const glm::dvec3 p = d * (glm::dot(o, n) / glm::dot(d, n));
      const double u = (glm::dot(p - o, glm::dvec3(s.e1)) + s.half) / (2.0 * s.half);
      const double v = (glm::dot(p - o, glm::dvec3(s.e2)) + s.half) / (2.0 * s.half);
      const double du = (t.attribute(0, x, y) - u) * texels, dv = (t.attribute(1, x, y) - v) * texels;
      const double err = std::sqrt(du * du + dv * dv);
      e.mean += err;
      e.max = std::max(e.max, err);
      ++e.pixels;
    }
  if (e.pixels) e.mean /= e.pixels;
  return e;
}

RasterParams modeParams(Interpolation m, int density, bool linear) {
  RasterParams p;
  p.interpolation = m;
  p.line_density = density;
  p.linear_correction = linear;
  p.threads = 2;
  return p;
}

TEST(RasterInterpolation, ConstantDepthSlopeOfTiltedPlane) {
  for (float roll : {0.0f, 20.0f, -35.0f, 60.0f}) {
    const PlaneScene s = tiltedPlane(60.0f, roll, 3.0f, 1.0f, 1);
    const auto clip = toClip(s.cam, s.positions, 200, 200);
    const ConstantDepthSlope g = constantDepthSlope(clip[0], clip[1], clip[3], 200, 200);
    // Screen y points down: the tilt axis at angle roll (y up) has slope −tan(roll).
    if (std::abs(roll) <= 45.0f) {
      EXPECT_FALSE(g.rows) << roll;
      EXPECT_NEAR(g.g, -std::tan(glm::radians(roll)), 1e-3) << roll;
    } else {
      EXPECT_TRUE(g.rows) << roll;
      EXPECT_NEAR(g.g, -1.0f / std::tan(glm::radians(roll)), 1e-3) << roll;
    }
  }
}

// Stated bounds (texels, 512² texture over a plane filling much of a 320×240 image):
//   exact ≤ 0.02 (≤ 0.1 at 80°): vertices are snapped to 1/256 px, which at grazing angles
//   moves texture coordinates measurably; constant-depth + linear correction ≤ 0.05
//   (≤ 0.3 at 80°, where u is strongly non-linear across a line spacing), ≤ 0.1 with 4×
//   lines;
//   nearest line ≤ half a line spacing times the texel gradient across lines, so it shrinks
//   with density (checked as ordering); affine is far off at grazing angles.
TEST(RasterInterpolation, ErrorBoundsOnPlaneAtKnownAngles) {
  const int W = 320, H = 240;
  const float texels = 512.0f;
  for (float tilt : {30.0f, 60.0f, 80.0f}) {
    const PlaneScene s = tiltedPlane(tilt, 23.0f, 2.5f, 1.5f, 4);
    const ErrorStats exact = planeError(s, modeParams(Interpolation::kExact, 1, false), W, H, texels);
    const ErrorStats near1 = planeError(s, modeParams(Interpolation::kConstantDepth, 1, false), W, H, texels);
    const ErrorStats near2 = planeError(s, modeParams(Interpolation::kConstantDepth, 2, false), W, H, texels);
    const ErrorStats near4 = planeError(s, modeParams(Interpolation::kConstantDepth, 4, false), W, H, texels);
    const ErrorStats lin1 = planeError(s, modeParams(Interpolation::kConstantDepth, 1, true), W, H, texels);
    const ErrorStats lin4 = planeError(s, modeParams(Interpolation::kConstantDepth, 4, true), W, H, texels);
    const ErrorStats affine = planeError(s, modeParams(Interpolation::kAffine, 1, false), W, H, texels);
    ASSERT_GT(exact.pixels, 10000) << tilt;
    SCOPED_TRACE(::testing::Message() << "tilt " << tilt << " exact " << exact.max << " near1 " << near1.max
                                      << " near2 " << near2.max << " near4 " << near4.max << " lin1 "
                                      << lin1.max << " lin4 " << lin4.max << " affine " << affine.max);
    EXPECT_LT(exact.max, tilt < 70.0f ? 0.02 : 0.1);
    std::printf("tilt %.0f max texel error: exact %.4f near1 %.3f near2 %.3f near4 %.3f lin1 %.4f lin4 %.4f affine %.2f\n", tilt, exact.max, near1.max, near2.max, near4.max, lin1.max, lin4.max, affine.max);
    EXPECT_LT(lin1.max, tilt < 70.0f ? 0.05 : 0.3);
    EXPECT_LT(lin4.max, 0.1);
    EXPECT_GT(near1.max, 0.1);  // the error the correction removes is real
    EXPECT_LT(near2.mean, near1.mean);
    EXPECT_LT(near4.mean, near2.mean);
    EXPECT_LT(near4.max, 0.6 * near1.max);
    EXPECT_LT(lin1.mean, near4.mean);
    if (tilt >= 60.0f) {
      EXPECT_GT(affine.max, 5.0);
    }
  }
}

// All interpolation modes share setup and traversal: identical coverage and depth. Thread
// count and tile size do not change the result.
TEST(RasterInterpolation, ModesShareCoverageAndThreadsDoNotMatter) {
  const int W = 256, H = 192;
  TriMesh torus = makeTorus(1.0f, 0.4f, 48, 24);
  const Camera cam = orbitCamera(computeBounds(torus.positions), {30, 35, 2.5f}, 35.0f, static_cast<float>(W) / H);
  const auto clip = toClip(cam, torus.positions, W, H);
  std::vector<float> attrs;
  for (auto p : torus.positions) attrs.insert(attrs.end(), {p.x, p.y, p.z});
  RasterInput in;
  in.clip = clip;
  in.attributes = attrs;
  in.attribute_count = 3;
  in.faces = torus.faces;
  RasterTarget ref;
  ref.resize(W, H, 3);
  rasterize(in, modeParams(Interpolation::kExact, 1, false), ref);
  for (auto m : {Interpolation::kConstantDepth, Interpolation::kAffine}) {
    RasterTarget t;
    t.resize(W, H, 3);
    rasterize(in, modeParams(m, 2, true), t);
    EXPECT_EQ(t.face_id, ref.face_id) << interpolationName(m);
    EXPECT_EQ(t.depth.depth, ref.depth.depth) << interpolationName(m);
  }
  RasterParams one = modeParams(Interpolation::kConstantDepth, 1, true), many = one;
  one.threads = 1;
  many.threads = 4;
  RasterTarget a, b, c;
  a.resize(W, H, 3);
  b.resize(W, H, 3);
  c.resize(W, H, 3);
  rasterize(in, one, a);
  rasterize(in, many, b);
  EXPECT_EQ(a.face_id, b.face_id);
  EXPECT_EQ(a.depth.depth, b.depth.depth);
  EXPECT_EQ(a.attributes, b.attributes);
  // Another tile size: the same lines (one lattice per triangle), re-based per tile, so
  // values differ by float rounding only.
  many.tile_size = 32;
  rasterize(in, many, c);
  EXPECT_EQ(a.face_id, c.face_id);
  double worst_depth = 0, worst = 0;
  for (size_t i = 0; i < a.depth.depth.size(); ++i)
    worst_depth = std::max(worst_depth, double(std::abs(a.depth.depth[i] - c.depth.depth[i])));
  for (size_t i = 0; i < a.attributes.size(); ++i)
    worst = std::max(worst, double(std::abs(a.attributes[i] - c.attributes[i])));
  EXPECT_LT(worst_depth, 1e-6);
  EXPECT_LT(worst, 1e-4);
}

// A large floor crossing the near plane at a grazing angle: clipped, no crash, the ground
// fills the lower image and the sky stays empty; depth grows towards the horizon.
TEST(RasterClipping, FloorThroughNearPlane) {
  const int W = 320, H = 180;
  Camera cam;
  cam.eye = {0, 1, 0};
  cam.target = {0, 0.9f, -10};
  cam.near_plane = 0.1f;
  cam.far_plane = 500.0f;
  std::vector<glm::vec3> p = {{-1000, 0, -1000}, {1000, 0, -1000}, {1000, 0, 1000}, {-1000, 0, 1000}};
  std::vector<std::array<uint32_t, 3>> faces = {{0, 2, 1}, {0, 3, 2}};
  const auto clip = toClip(cam, p, W, H);
  RasterTarget t;
  t.resize(W, H, 0);
  RasterInput in;
  in.clip = clip;
  in.faces = faces;
  SoftRasterizer r;
  r.draw(in, {}, t);
  EXPECT_GT(r.stats().clipped, 0u);
  for (int x = 0; x < W; x += 7) {
    EXPECT_NE(t.face_id[t.index(x, H - 1)], kNoFace);
    EXPECT_EQ(t.face_id[t.index(x, 0)], kNoFace);
    EXPECT_LT(t.depth.at(x, H - 1), t.depth.at(x, H / 2 + 10));
  }
}

// Hostile input: NaN / infinite coordinates, zero-area and behind-the-eye triangles draw
// nothing and do not crash.
TEST(RasterClipping, DegenerateAndNonFiniteTrianglesDrawNothing) {
  const float nan = std::nanf(""), inf = std::numeric_limits<float>::infinity();
  std::vector<glm::vec4> clip = {{0, 0, 0, 1},  {0.5f, 0, 0, 1},  {0, 0.5f, 0, 1},  {nan, 0, 0, 1},
                                 {inf, 0, 0, 1}, {1, 1, 0, 1},     {0, 0, 0, -1},    {1, 0, 0, -1},
                                 {0, 1, 0, -1},  {0.25f, 0, 0, 1}};
  std::vector<std::array<uint32_t, 3>> faces = {{0, 3, 2}, {0, 4, 2}, {0, 1, 9}, {6, 7, 8}, {0, 0, 5}};
  std::vector<float> attrs(clip.size(), 1.0f);
  RasterTarget t;
  t.resize(64, 64, 1);
  RasterInput in;
  in.clip = clip;
  in.attributes = attrs;
  in.attribute_count = 1;
  in.faces = faces;
  for (auto m : {Interpolation::kConstantDepth, Interpolation::kExact, Interpolation::kAffine}) {
    t.clear();
    rasterize(in, modeParams(m, 1, true), t);
    for (uint32_t f : t.face_id) ASSERT_EQ(f, kNoFace) << interpolationName(m);
  }
}

TEST(SoftRenderer, ToonCentreHasTheRampTone) {
  FrameParams rp;
  rp.width = 160;
  rp.height = 120;
  const ObjectStyle style;
  TriMesh sphere = makeIcoSphere(1.0f, 4);
  std::vector<glm::vec3> normals;
  for (auto p : sphere.positions) normals.push_back(glm::normalize(p));
  Camera cam = orbitCamera(computeBounds(sphere.positions), {0, 0, 4}, 35.0f, 160.0f / 120.0f);
  SoftRenderer r;
  r.setMesh(0, sphere.positions, normals, sphere.faces);
  r.drawSurfaces(cam, rp, std::span<const ObjectStyle>(&style, 1));
  // At the centre n ≈ (0, 0, 1) in eye space: n·l = l.z of the normalised light.
  const glm::vec3 l = glm::normalize(rp.light_dir_eye);
  const ToonParams& toon = style.toon;
  const float tone = l.z < toon.thresholds[0] ? toon.tones[0] : l.z < toon.thresholds[1] ? toon.tones[1] : toon.tones[2];
  const uint8_t* c = r.image().pixel(80, 60);
  EXPECT_NEAR(c[0], std::lround(toon.base_color.r * tone * 255), 1);
  EXPECT_NEAR(c[2], std::lround(toon.base_color.b * tone * 255), 1);
  const uint8_t* corner = r.image().pixel(0, 0);
  EXPECT_EQ(corner[0], 255);
  EXPECT_LT(r.depth().at(80, 60), 1.0f);
  EXPECT_EQ(r.depth().at(0, 0), 1.0f);
}

// Stroke triangles are drawn with their coverage: a band whose vertices say "1.5 px either
// side of the centre line at y = 16.5" inks three rows fully and nothing outside; the
// triangles of a strip never blend a pixel twice; half opacity blends halfway.
TEST(SoftRenderer, StrokeTrianglesAreDrawnByCoverage) {
  const int W = 64, H = 32;
  auto vertex = [](float x, float y, float across, float alpha) {
    return StrokeVertex{{x, y}, {0.0f, across}, 1.5f, alpha, 0.0f, 0.0f};
  };
  auto band = [&](float alpha) {
    // Two quads (four triangles) from x = 8 to 32 and 32 to 56, 2.5 px either side.
    std::vector<StrokeVertex> v;
    for (float x0 : {8.0f, 32.0f}) {
      const float x1 = x0 + 24.0f;
      const StrokeVertex a0 = vertex(x0, 14.0f, 2.5f, alpha), a1 = vertex(x0, 19.0f, -2.5f, alpha);
      const StrokeVertex b0 = vertex(x1, 14.0f, 2.5f, alpha), b1 = vertex(x1, 19.0f, -2.5f, alpha);
      for (const StrokeVertex& p : {a0, a1, b0, a1, b1, b0}) v.push_back(p);
    }
    return v;
  };
  Image img(W, H);
  std::fill(img.rgba.begin(), img.rgba.end(), 255);
  WorkerPool pool(2);
  EXPECT_EQ(drawStrokeTriangles(band(1.0f), glm::vec4(0.0f, 0.0f, 0.0f, 1.0f), nullptr, img, pool), 4u);
  for (int x = 8; x < 56; ++x) {
    int dark = 0;
    for (int y = 0; y < H; ++y) dark += img.pixel(x, y)[0] == 0;
    EXPECT_EQ(dark, 3) << x;
    EXPECT_EQ(img.pixel(x, 14)[0], 255) << x;  // centre 14.5: 2 px from the line, no ink
  }
  for (int x : {0, 4, 7, 56, 60, 63})
    for (int y = 0; y < H; ++y) ASSERT_EQ(img.pixel(x, y)[0], 255) << x << "," << y;
  std::fill(img.rgba.begin(), img.rgba.end(), 255);
  drawStrokeTriangles(band(0.5f), glm::vec4(0.0f, 0.0f, 0.0f, 1.0f), nullptr, img, pool);
  for (int x = 8; x < 56; ++x) EXPECT_NEAR(img.pixel(x, 16)[0], 128, 1) << x;  // x = 32: two quads meet
}

TEST(SoftRenderer, TextureSampling) {
  Image tex(2, 2);
  const uint8_t colors[4] = {0, 100, 200, 255};
  for (int i = 0; i < 4; ++i) {
    uint8_t* p = tex.pixel(i % 2, i / 2);
    p[0] = p[1] = p[2] = colors[i];
    p[3] = 255;
  }
  EXPECT_NEAR(sampleTexture(tex, 0.25f, 0.25f, TextureFilter::kNearest).r, 0.0f, 1e-6);
  EXPECT_NEAR(sampleTexture(tex, 0.75f, 0.75f, TextureFilter::kNearest).r, 1.0f, 1e-6);
  EXPECT_NEAR(sampleTexture(tex, 1.25f, -0.75f, TextureFilter::kNearest).r, 0.0f, 1e-6);  // repeat
  // Bilinear halfway between texel centres of the top row.
  EXPECT_NEAR(sampleTexture(tex, 0.5f, 0.25f, TextureFilter::kBilinear).r, 50.0f / 255.0f, 1e-4);
}

}  // namespace
}  // namespace lodline
