// Chamfer edge highlights (Wei, Shi, Yong, "Rendering chamfering structures of sharp edges",
// Visual Computer 2014; docs/design.md §2.2): ground truth and cost.
//
//   ./build/tests/bench/chamfer_bench --ground-truth DIR
//       The paper's Fig. 5 comparison: a box with real rounded edges of radius r (many small
//       patches, makeRoundedBox) rendered with per-pixel Blinn–Phong at 4×4 supersampling,
//       against the sharp box with chamfer highlights of the same r and against the sharp
//       box without them. Prints the mean absolute difference of edge pixels' intensity
//       (edges between two visible faces whose projected strip is ≤ 1 px wide) and writes
//       the images (crops side by side) to DIR. For inspection: CHAMFER_RADII=r (one radius),
//       CHAMFER_GT_SS=n (n×n supersampling instead of 4×4), CHAMFER_ALL_IMAGES=1 (every
//       render as PNG), CHAMFER_MASK_PNG=file (the edge-pixel mask of r = 0.003).
//   ./build/tests/bench/chamfer_bench --benchmark_counters_tabular=true
//       Frame time of the shaded style at 1280×720 (MSAA 4) with highlights (replacement
//       composition: on_ms; the paper's alpha blend: alpha_ms) and without (off_ms),
//       alternating frame by frame along a slow orbit (median ms side by side). Lines are
//       extracted outside the timed part; the timed draw includes drawing them.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <glad/gl.h>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "core/timer.h"
#include "export/visibility.h"
#include "frame/line_drawing.h"
#include "gl/chamfer_edges.h"
#include "gl/context.h"
#include "gl/renderer.h"
#include "io/generate.h"
#include "io/image.h"
#include "io/load_mesh.h"
#include "bench_util.h"
#include "test_util.h"

namespace lodline {
namespace {

float lum(const Image& im, int x, int y) {
  const uint8_t* p = im.pixel(x, y);
  return (p[0] + p[1] + p[2]) / 3.0f;
}

// Averages s×s blocks (the supersampled ground truth down to the image size).
Image downsample(const Image& big, int s) {
  Image out(big.width / s, big.height / s);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int c = 0; c < 4; ++c) {
        int sum = 0;
        for (int j = 0; j < s; ++j)
          for (int i = 0; i < s; ++i) sum += big.pixel(x * s + i, y * s + j)[c];
        out.pixel(x, y)[c] = static_cast<uint8_t>((sum + s * s / 2) / (s * s));
      }
  return out;
}

// Copies the w×h block at (x0, y0) of each image, zoomed `zoom`× (nearest), side by side
// with a 4-px white gap.
Image sideBySide(const std::vector<const Image*>& images, int x0, int y0, int w, int h, int zoom) {
  const int gap = 4;
  const int n = static_cast<int>(images.size());
  Image out(n * w * zoom + (n - 1) * gap, h * zoom);
  std::fill(out.rgba.begin(), out.rgba.end(), 255);
  for (int k = 0; k < n; ++k)
    for (int y = 0; y < h * zoom; ++y)
      for (int x = 0; x < w * zoom; ++x) {
        const uint8_t* src = images[k]->pixel(x0 + x / zoom, y0 + y / zoom);
        std::memcpy(out.pixel(k * (w * zoom + gap) + x, y), src, 4);
      }
  return out;
}

struct Renders {
  Image truth, chamfer, replace, plain;
  Image sharp_truth;  // the sharp box at the same supersampling: the MSAA noise floor
  Camera camera;
};

Image renderOnce(const TriMesh& mesh, const Camera& cam, const test::Look& look) {
  const FrameParams& rp = look.frame;
  auto renderer = Renderer::create();
  auto target = OffscreenTarget::create(rp.width, rp.height, rp.msaa);
  if (!renderer || !target) {
    std::fprintf(stderr, "renderer setup failed\n");
    std::exit(1);
  }
  // The shaded style draws crease-aware corner normals; the indexed normals are unused.
  std::vector<glm::vec3> normals(mesh.positions.size(), glm::vec3(0.0f, 0.0f, 1.0f));
  renderer->setMesh(0, mesh.positions, normals, mesh.faces);
  target->bind();
  renderer->drawSurfaces(cam, rp, std::span<const ObjectStyle>(&look.style, 1));
  glFinish();
  return target->readback();
}

test::Look shadedParams(int w, int h, float radius) {
  test::Look rp;
  rp.frame.width = w;
  rp.frame.height = h;
  rp.style.style = Style::kShaded;
  for (auto& k : rp.style.lines.kinds) k.enabled = false;
  rp.style.chamfer.radius = radius;
  return rp;
}

struct EdgeStats {
  double mad_chamfer = 0.0, mad_replace = 0.0, mad_plain = 0.0, max_chamfer = 0.0,
         max_replace = 0.0, max_plain = 0.0, floor = 0.0;
  size_t pixels = 0, edges = 0, edges_too_wide = 0;
};

// Edge pixels: centre within 1 px of a visible sharp edge between two front faces whose
// projected strip width r·|P·(N1 − N2)|·f/d at its midpoint is ≤ 1 px, ≥ 4 px from its ends.
EdgeStats compareEdges(const TriMesh& sharp, const Renders& r, float radius, int w, int h) {
  ChamferEdgeScratch scratch;
  ChamferEdges edges;
  findChamferEdges(sharp.positions, sharp.faces, {}, 30.0f, scratch, edges);
  const float f = 0.5f * h / std::tan(0.5f * glm::radians(r.camera.fov_deg));
  std::vector<uint8_t> mask(static_cast<size_t>(w) * h, 0);
  EdgeStats s;
  for (size_t e = 0; e < edges.size(); ++e) {
    const glm::vec3 a = sharp.positions[edges.vertices[e][0]];
    const glm::vec3 b = sharp.positions[edges.vertices[e][1]];
    const glm::vec3 mid = 0.5f * (a + b);
    const glm::vec3 v = glm::normalize(r.camera.eye - mid);
    if (glm::dot(edges.normal1[e], v) <= 0.0f || glm::dot(edges.normal2[e], v) <= 0.0f) continue;
    const glm::vec3 axis = glm::normalize(b - a);
    const glm::vec3 p = glm::normalize(glm::cross(v, axis));
    const float d = glm::dot(mid - r.camera.eye, r.camera.forward());
    const float width_px = radius * std::abs(glm::dot(p, edges.normal1[e] - edges.normal2[e])) * f / d;
    if (width_px > 1.0f) {
      ++s.edges_too_wide;
      continue;
    }
    ++s.edges;
    const glm::vec2 pa = projectToPixels(r.camera, a, w, h), pb = projectToPixels(r.camera, b, w, h);
    const glm::vec2 ab = pb - pa;
    const float len = glm::length(ab);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const glm::vec2 q(x + 0.5f, y + 0.5f);
        const float t = glm::dot(q - pa, ab) / (len * len);
        if (t * len < 4.0f || (1.0f - t) * len < 4.0f) continue;
        if (glm::length(q - (pa + t * ab)) <= 1.0f) mask[static_cast<size_t>(y) * w + x] = 1;
      }
  }
  if (const char* dump = std::getenv("CHAMFER_MASK_PNG"); dump && radius == 0.003f) {
    Image m(w, h);
    for (size_t i = 0; i < mask.size(); ++i)
      for (int c = 0; c < 4; ++c) m.rgba[4 * i + c] = c == 3 ? 255 : (mask[i] ? 255 : 0);
    (void)writePng(dump, m);
  }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!mask[static_cast<size_t>(y) * w + x]) continue;
      const double t = lum(r.truth, x, y);
      const double dc = std::abs(lum(r.chamfer, x, y) - t), dp = std::abs(lum(r.plain, x, y) - t);
      const double dr = std::abs(lum(r.replace, x, y) - t);
      s.mad_replace += dr;
      s.floor += std::abs(lum(r.plain, x, y) - lum(r.sharp_truth, x, y));
      s.max_replace = std::max(s.max_replace, dr);
      s.mad_chamfer += dc;
      s.mad_plain += dp;
      s.max_chamfer = std::max(s.max_chamfer, dc);
      s.max_plain = std::max(s.max_plain, dp);
      ++s.pixels;
    }
  if (s.pixels) {
    s.mad_chamfer /= s.pixels;
    s.mad_replace /= s.pixels;
    s.floor /= s.pixels;
    s.mad_plain /= s.pixels;
  }
  return s;
}

int groundTruth(const std::filesystem::path& dir) {
  auto ctx = createHeadlessContext(ContextBackend::kEgl);
  if (!ctx) {
    std::fprintf(stderr, "%s\n", ctx.error().message.c_str());
    return 1;
  }
  std::filesystem::create_directories(dir);
  const int w = 1280, h = 720;
  // 4×4 supersampling as the paper's Fig. 5 (CHAMFER_GT_SS overrides, to check convergence).
  const int ss = std::getenv("CHAMFER_GT_SS") ? std::max(1, std::atoi(std::getenv("CHAMFER_GT_SS"))) : 4;
  const glm::vec3 half(1.0f, 0.6f, 0.8f);
  const TriMesh sharp = makeRoundedBox(half, 0.0f, 0, 1);
  const Bounds bounds = computeBounds(sharp.positions);
  struct View {
    const char* name;
    OrbitView orbit;
  };
  // At 5 bounding radii the box spans ~400 px; the strips of r ≤ 0.004 stay ≤ 1 px wide.
  const View views[] = {{"a", {35.0f, 25.0f, 5.0f}}, {"b", {-55.0f, 35.0f, 5.0f}},
                        {"c", {120.0f, -20.0f, 5.0f}}};
  std::printf("%-6s %-5s %7s %6s %8s  %9s %9s %9s  %9s %9s %9s  %6s\n", "r", "view", "pixels",
              "edges", "too_wide", "MAD_alpha", "MAD_repl", "MAD_none", "max_alpha", "max_repl",
              "max_none", "floor");
  std::vector<float> radii{0.002f, 0.003f, 0.004f};
  if (const char* env = std::getenv("CHAMFER_RADII")) radii = {static_cast<float>(std::atof(env))};
  for (float radius : radii) {
    const TriMesh rounded = makeRoundedBox(half, radius, 32, 1);
    for (const View& view : views) {
      Renders r;
      r.camera = orbitCamera(bounds, view.orbit, 35.0f, static_cast<float>(w) / h);
      test::Look big = shadedParams(w * ss, h * ss, radius);
      big.frame.msaa = 1;
      big.style.chamfer.enabled = false;
      const Image truth_big = renderOnce(rounded, r.camera, big);
      r.truth = downsample(truth_big, ss);
      r.sharp_truth = downsample(renderOnce(sharp, r.camera, big), ss);
      test::Look rp = shadedParams(w, h, radius);
      rp.style.chamfer.compose = ChamferCompose::kAlpha;
      r.chamfer = renderOnce(sharp, r.camera, rp);
      rp.style.chamfer.compose = ChamferCompose::kReplace;
      r.replace = renderOnce(sharp, r.camera, rp);
      rp.style.chamfer.enabled = false;
      r.plain = renderOnce(sharp, r.camera, rp);
      const EdgeStats s = compareEdges(sharp, r, radius, w, h);
      std::printf("%-6.3f %-5s %7zu %6zu %8zu  %9.2f %9.2f %9.2f  %9.1f %9.1f %9.1f  %6.2f\n", radius,
                  view.name, s.pixels, s.edges, s.edges_too_wide, s.mad_chamfer, s.mad_replace,
                  s.mad_plain, s.max_chamfer, s.max_replace, s.max_plain, s.floor);
      if (std::getenv("CHAMFER_ALL_IMAGES")) {
        const std::string tag = std::to_string(static_cast<int>(radius * 1000)) + view.name;
        (void)writePng(dir / ("gt-" + tag + ".png"), r.truth);
        (void)writePng(dir / ("ch-" + tag + ".png"), r.chamfer);
        (void)writePng(dir / ("re-" + tag + ".png"), r.replace);
        (void)writePng(dir / ("pl-" + tag + ".png"), r.plain);
      }
      if (radius == 0.004f && view.name[0] == 'a') {
        // Side by side: ground truth | replacement | the paper's alpha blend | no highlights,
        // cropped to the box, and a 4× zoom of the near top corner.
        const glm::vec2 c = projectToPixels(r.camera, bounds.center, w, h);
        const int cw = 440, ch = 400;
        const int x0 = std::clamp(static_cast<int>(c.x) - cw / 2, 0, w - cw);
        const int y0 = std::clamp(static_cast<int>(c.y) - ch / 2, 0, h - ch);
        (void)writePng(dir / "chamfer-box-compare.png",
                       sideBySide({&r.truth, &r.replace, &r.chamfer, &r.plain}, x0, y0, cw, ch, 1));
        const glm::vec2 corner = projectToPixels(r.camera, glm::vec3(half.x, half.y, half.z), w, h);
        const int zw = 64, zh = 64;
        const int zx = std::clamp(static_cast<int>(corner.x) - zw / 2, 0, w - zw);
        const int zy = std::clamp(static_cast<int>(corner.y) - zh / 2, 0, h - zh);
        (void)writePng(dir / "chamfer-box-zoom.png",
                       sideBySide({&r.truth, &r.replace, &r.chamfer, &r.plain}, zx, zy, zw, zh, 4));
      }
    }
  }
  return 0;
}

// Shaded surfaces (faces + highlights, the lines left out: they cost the same with or
// without highlights) with and without highlights, alternating, along a slow orbit.
void chamferFrameBenchmark(benchmark::State& state, const std::string& name) {
  auto setup = bench::setUpGlBenchmark(state, name);
  if (!setup) return;
  const size_t faces = setup->mesh.faceCount();
  LineDrawing drawing(std::move(setup->mesh));
  FrameParams rp;
  ObjectStyle style;
  style.style = Style::kShaded;
  auto renderer = Renderer::create();
  auto target = OffscreenTarget::create(rp.width, rp.height, rp.msaa);
  if (!renderer || !target) {
    state.SkipWithError("renderer setup failed");
    return;
  }
  renderer->setMesh(0, drawing.mesh().positions, drawing.normals(), drawing.mesh().faces,
                    drawing.mesh().marked_edges);
  std::vector<double> on_ms, alpha_ms, off_ms;
  size_t edges = 0;
  float az = 0.0f;
  // Warm-up: edge finding and corner normals happen at the first draw.
  target->bind();
  renderer->drawSurfaces(orbitCamera(drawing.bounds(), {az, 15.0f, 0.0f}, 35.0f, 1280.0f / 720.0f), rp,
                         std::span<const ObjectStyle>(&style, 1));
  glFinish();
  for (auto _ : state) {
    const Camera cam = orbitCamera(drawing.bounds(), {az, 15.0f, 0.0f}, 35.0f, 1280.0f / 720.0f);
    az += 1.0f;
    for (int mode = 0; mode < 3; ++mode) {  // replace (default), alpha (the paper's), off
      style.chamfer.enabled = mode < 2;
      style.chamfer.compose = mode == 0 ? ChamferCompose::kReplace : ChamferCompose::kAlpha;
      target->bind();
      Stopwatch sw;
      renderer->drawSurfaces(cam, rp, std::span<const ObjectStyle>(&style, 1));
      glFinish();
      (mode == 0 ? on_ms : mode == 1 ? alpha_ms : off_ms).push_back(sw.lap());
      if (mode == 0) edges = renderer->chamferEdgesDrawn();
    }
  }
  state.counters["faces"] = static_cast<double>(faces);
  state.counters["sharp_edges"] = static_cast<double>(edges);
  state.counters["on_ms"] = bench::median(on_ms);
  state.counters["off_ms"] = bench::median(off_ms);
  state.counters["alpha_ms"] = bench::median(alpha_ms);
  state.counters["ratio"] = bench::median(on_ms) / std::max(bench::median(off_ms), 1e-9);
  state.counters["alpha_ratio"] = bench::median(alpha_ms) / std::max(bench::median(off_ms), 1e-9);
}

void registerAll() {
  for (const char* name : {"fandisk.off", "turbine.off", "couplingdown.off"})
    benchmark::RegisterBenchmark((std::string("shaded_chamfer/") + name).c_str(),
                                 [name](benchmark::State& s) { chamferFrameBenchmark(s, name); })
        ->Iterations(24)
        ->Unit(benchmark::kMillisecond);
}

}  // namespace
}  // namespace lodline

int main(int argc, char** argv) {
  for (int i = 1; i + 1 < argc; ++i)
    if (std::strcmp(argv[i], "--ground-truth") == 0) return lodline::groundTruth(argv[i + 1]);
  lodline::registerAll();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
