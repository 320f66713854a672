// Accuracy and speed of the constant-depth-scanline rasteriser (Han, Wang, "Linear texture
// coordinate interpolation in rasterization", J. CAD & CG 23(6), 2011, §4–5: the paper's
// Figs. 7–10) on today's CPU, for docs/softraster.md.
//
// For each scene (CGAL meshes with generated checker-texture coordinates at several views,
// plus a large textured floor at grazing angles), every interpolation mode draws the same
// 1280x720 frame; texture-coordinate errors are measured in texels against the exact
// (per-pixel division, double precision) mode, and times are the best of interleaved
// repetitions (load on a shared machine only adds time), so all modes
// see the same machine load. Run:
//   ./build/tests/bench/raster_bench [--images DIR] [--reps N] [--threads T] [benchmark flags]
// It prints a markdown table, then runs the Google Benchmark cases (one scene per mode,
// items = fragments).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "core/timer.h"
#include "io/image.h"
#include "io/load_mesh.h"
#include "raster/raster.h"
#include "raster/soft_renderer.h"
#include "test_util.h"

namespace lodline {
namespace {

constexpr int kWidth = 1280, kHeight = 720;
constexpr float kTexels = 512.0f;  // texels per unit of u or v (one checker texture repeat)

struct Mode {
  const char* name;
  RasterParams params;
};

std::vector<Mode> modes(int threads) {
  auto make = [&](Interpolation i, int density, bool linear) {
    RasterParams p;
    p.interpolation = i;
    p.line_density = density;
    p.linear_correction = linear;
    p.threads = threads;
    return p;
  };
  RasterParams reference = make(Interpolation::kExact, 1, false);
  reference.double_precision = true;
  return {
      {"exact f64 (reference)", reference},
      {"exact (1 div/px)", make(Interpolation::kExact, 1, false)},
      {"affine", make(Interpolation::kAffine, 1, false)},
      {"CD ×1, none", make(Interpolation::kConstantDepth, 1, false)},
      {"CD ×2", make(Interpolation::kConstantDepth, 2, false)},
      {"CD ×4", make(Interpolation::kConstantDepth, 4, false)},
      {"CD ×1 + linear", make(Interpolation::kConstantDepth, 1, true)},
      {"CD ×2 + linear", make(Interpolation::kConstantDepth, 2, true)},
      {"CD ×4 + linear", make(Interpolation::kConstantDepth, 4, true)},
  };
}

struct Scene {
  std::string name;
  TriMesh mesh;
  std::vector<float> uv;  // 2 per vertex
  Camera camera;
};

// Texture coordinates per face corner: the mesh is unwelded (3 vertices per face) so each
// face carries one consistent mapping and no triangle straddles a texture seam.
// Box projection: the two coordinates across the face's dominant normal axis, scaled so the
// model's largest extent holds 4 checker repeats.
void unweldBoxUv(TriMesh& m, std::vector<float>& uv) {
  std::vector<glm::vec3> fn;
  computeFaceNormals(m, fn);
  const Bounds b = computeBounds(m.positions);
  const glm::vec3 ext = b.max - b.min;
  const float s = 4.0f / std::max({ext.x, ext.y, ext.z, 1e-6f});
  TriMesh out;
  uv.clear();
  for (size_t f = 0; f < m.faceCount(); ++f) {
    const glm::vec3 n = glm::abs(fn[f]);
    std::array<uint32_t, 3> tri;
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 p = (m.positions[m.faces[f][k]] - b.min) * s;
      if (n.x >= n.y && n.x >= n.z)
        uv.insert(uv.end(), {p.z, p.y});
      else if (n.y >= n.z)
        uv.insert(uv.end(), {p.x, p.z});
      else
        uv.insert(uv.end(), {p.x, p.y});
      tri[k] = static_cast<uint32_t>(out.positions.size());
      out.positions.push_back(m.positions[m.faces[f][k]]);
    }
    out.faces.push_back(tri);
  }
  m = std::move(out);
}

// Spherical projection about the bounding-box centre: u = longitude (4 repeats), v =
// latitude (2 repeats); u is made continuous within each face across the seam.
void unweldSphericalUv(TriMesh& m, std::vector<float>& uv) {
  const Bounds b = computeBounds(m.positions);
  TriMesh out;
  uv.clear();
  for (const auto& face : m.faces) {
    float u[3], v[3];
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 d = m.positions[face[k]] - b.center;
      const float r = std::max(glm::length(d), 1e-9f);
      u[k] = 4.0f * (std::atan2(d.z, d.x) / (2.0f * std::numbers::pi_v<float>) + 0.5f);
      v[k] = 2.0f * std::acos(std::clamp(d.y / r, -1.0f, 1.0f)) / std::numbers::pi_v<float>;
    }
    const float hi = std::max({u[0], u[1], u[2]});
    std::array<uint32_t, 3> tri;
    for (int k = 0; k < 3; ++k) {
      if (hi - u[k] > 2.0f) u[k] += 4.0f;
      uv.insert(uv.end(), {u[k], v[k]});
      tri[k] = static_cast<uint32_t>(out.positions.size());
      out.positions.push_back(m.positions[face[k]]);
    }
    out.faces.push_back(tri);
  }
  m = std::move(out);
}

// A 400 × 400 floor of 8 × 8 quads (large triangles), one checker repeat per 4 units, seen
// from 1.7 units up, looking `pitch_deg` below the horizon, the camera rolled by `roll_deg`
// (with no roll the constant-depth lines of a floor are image rows: a trivial case).
Scene floorScene(float pitch_deg, float yaw_deg, float roll_deg) {
  Scene s;
  s.name = "floor, " + std::to_string(static_cast<int>(pitch_deg)) + "° below horizon, roll " +
           std::to_string(static_cast<int>(roll_deg)) + "°";
  const int n = 8;
  const float half = 200.0f;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const float x = -half + 2 * half * i / n, z = -half + 2 * half * j / n;
      s.mesh.positions.push_back({x, 0.0f, z});
      s.uv.insert(s.uv.end(), {x / 4.0f, z / 4.0f});
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      s.mesh.faces.push_back({a, c, d});
      s.mesh.faces.push_back({a, d, b});
    }
  const float p = glm::radians(pitch_deg), y = glm::radians(yaw_deg);
  s.camera.eye = {0.0f, 1.7f, 0.0f};
  s.camera.target = s.camera.eye + glm::vec3(std::sin(y) * std::cos(p), -std::sin(p), -std::cos(y) * std::cos(p));
  const glm::vec3 f = glm::normalize(s.camera.target - s.camera.eye);
  const glm::vec3 r = glm::normalize(glm::cross(f, glm::vec3(0.0f, 1.0f, 0.0f)));
  const float roll = glm::radians(roll_deg);
  s.camera.up = std::cos(roll) * glm::cross(r, f) + std::sin(roll) * r;
  s.camera.fov_deg = 60.0f;
  s.camera.near_plane = 0.1f;
  s.camera.far_plane = 600.0f;
  return s;
}

bool meshScene(std::vector<Scene>& out, const char* file, bool spherical, OrbitView view) {
  const auto path = test::dataMesh(file);
  if (path.empty()) {
    std::fprintf(stderr, "raster_bench: data/meshes/%s missing (run scripts/setup.sh); skipped\n", file);
    return false;
  }
  auto mesh = loadMesh(path);
  if (!mesh) {
    std::fprintf(stderr, "raster_bench: %s\n", mesh.error().message.c_str());
    return false;
  }
  Scene s;
  s.mesh = std::move(mesh.value());
  s.camera = orbitCamera(computeBounds(s.mesh.positions), view, 35.0f, static_cast<float>(kWidth) / kHeight);
  if (spherical)
    unweldSphericalUv(s.mesh, s.uv);
  else
    unweldBoxUv(s.mesh, s.uv);
  char buf[160];
  std::snprintf(buf, sizeof(buf), "%s (%zu tris, %s UV, view %g,%g%s)", file, s.mesh.faceCount(),
                spherical ? "spherical" : "box", view.azimuth_deg, view.elevation_deg,
                view.distance > 0 ? (", dist " + std::to_string(view.distance).substr(0, 3)).c_str() : "");
  s.name = buf;
  out.push_back(std::move(s));
  return true;
}

std::vector<Scene> scenes() {
  std::vector<Scene> s;
  meshScene(s, "armadillo.off", false, {200, 10, 0});
  meshScene(s, "armadillo.off", true, {90, 35, 0});
  meshScene(s, "bunny00.off", false, {30, 20, 0});
  meshScene(s, "elephant.off", true, {60, 15, 0});
  meshScene(s, "cow.off", false, {300, 25, 0});
  meshScene(s, "man.off", false, {0, 0, 0});
  meshScene(s, "camel.off", true, {135, 40, 0});
  meshScene(s, "ChineseDragon-10kv.off", false, {45, 10, 1.6f});
  meshScene(s, "lion-head.off", false, {20, 5, 1.5f});
  s.push_back(floorScene(2.0f, 20.0f, 0.0f));
  s.push_back(floorScene(5.0f, 35.0f, 20.0f));
  s.push_back(floorScene(8.0f, 35.0f, 30.0f));
  s.push_back(floorScene(25.0f, 10.0f, 60.0f));
  return s;
}

struct Prepared {
  std::vector<glm::vec4> clip;
  RasterInput input;
};

Prepared prepare(const Scene& s) {
  Prepared p;
  const glm::mat4 m = s.camera.projection(static_cast<float>(kWidth) / kHeight) * s.camera.view();
  for (auto v : s.mesh.positions) p.clip.push_back(m * glm::vec4(v, 1.0f));
  p.input.clip = p.clip;
  p.input.attributes = s.uv;
  p.input.attribute_count = 2;
  p.input.faces = s.mesh.faces;
  return p;
}

struct Error {
  double mean = 0.0, p99 = 0.0, max = 0.0;
};

Error uvError(const RasterTarget& t, const RasterTarget& ref, std::vector<float>& scratch) {
  scratch.clear();
  const size_t n = static_cast<size_t>(t.width) * t.height;
  for (size_t i = 0; i < n; ++i) {
    if (ref.face_id[i] == kNoFace) continue;
    const double du = (t.attributes[i] - ref.attributes[i]) * kTexels;
    const double dv = (t.attributes[n + i] - ref.attributes[n + i]) * kTexels;
    scratch.push_back(static_cast<float>(std::sqrt(du * du + dv * dv)));
  }
  Error e;
  if (scratch.empty()) return e;
  double sum = 0.0;
  for (float v : scratch) sum += v;
  e.mean = sum / static_cast<double>(scratch.size());
  std::sort(scratch.begin(), scratch.end());
  e.p99 = scratch[scratch.size() * 99 / 100];
  e.max = scratch.back();
  return e;
}

Image checker(int size, int squares) {
  Image img(size, size);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const bool dark = ((x * squares / size) + (y * squares / size)) % 2;
      uint8_t* p = img.pixel(x, y);
      p[0] = dark ? 60 : 235;
      p[1] = dark ? 70 : 230;
      p[2] = dark ? 90 : 215;
      p[3] = 255;
    }
  return img;
}

// Colours a rasterised frame with the checker texture (nearest), or the error as a heat map.
Image shadeChecker(const RasterTarget& t, const Image& tex) {
  Image img(t.width, t.height);
  const size_t n = static_cast<size_t>(t.width) * t.height;
  for (size_t i = 0; i < n; ++i) {
    uint8_t* p = &img.rgba[i * 4];
    if (t.face_id[i] == kNoFace) {
      p[0] = p[1] = p[2] = p[3] = 255;
      continue;
    }
    const glm::vec4 c = sampleTexture(tex, t.attributes[i], t.attributes[n + i], TextureFilter::kNearest);
    for (int k = 0; k < 3; ++k) p[k] = static_cast<uint8_t>(c[k] * 255.0f);
    p[3] = 255;
  }
  return img;
}

Image errorHeatMap(const RasterTarget& t, const RasterTarget& ref) {
  Image img(t.width, t.height);
  const size_t n = static_cast<size_t>(t.width) * t.height;
  for (size_t i = 0; i < n; ++i) {
    uint8_t* p = &img.rgba[i * 4];
    p[3] = 255;
    if (ref.face_id[i] == kNoFace) {
      p[0] = p[1] = p[2] = 255;
      continue;
    }
    const double du = (t.attributes[i] - ref.attributes[i]) * kTexels;
    const double dv = (t.attributes[n + i] - ref.attributes[n + i]) * kTexels;
    // 0 texels black → 1 texel red → ≥ 4 texels yellow (log-ish scale).
    const double e = std::sqrt(du * du + dv * dv);
    const double r = std::clamp(e, 0.0, 1.0), g = std::clamp((e - 1.0) / 3.0, 0.0, 1.0);
    p[0] = static_cast<uint8_t>(40 + 215 * r);
    p[1] = static_cast<uint8_t>(40 + 215 * g);
    p[2] = 40;
  }
  return img;
}

void writeImages(const std::string& dir, const std::vector<Scene>& all, int threads) {
  const Image tex = checker(512, 8);
  // The grazing floor: exact, affine, constant-depth without and with linear correction.
  for (const Scene& s : all) {
    if (s.name.rfind("floor, 8", 0) != 0) continue;
    Prepared p = prepare(s);
    RasterTarget ref, t;
    ref.resize(kWidth, kHeight, 2);
    t.resize(kWidth, kHeight, 2);
    const auto ms = modes(threads);
    rasterize(p.input, ms[0].params, ref);
    (void)writePng(dir + "/softraster-floor-exact.png", shadeChecker(ref, tex));
    const std::pair<int, const char*> shots[] = {{2, "affine"}, {3, "cd1"}, {6, "cd1-linear"}};
    for (auto [m, tag] : shots) {
      t.clear();
      rasterize(p.input, ms[m].params, t);
      (void)writePng(dir + "/softraster-floor-" + tag + ".png", shadeChecker(t, tex));
      (void)writePng(dir + "/softraster-floor-" + tag + "-error.png", errorHeatMap(t, ref));
    }
  }
  // A CGAL mesh through the full soft toon renderer with the checker as a texture.
  for (const Scene& s : all) {
    if (s.name.rfind("armadillo.off", 0) != 0) continue;
    std::vector<glm::vec3> fn, vn(s.mesh.vertexCount(), glm::vec3(0.0f));
    computeFaceNormals(s.mesh, fn);
    for (size_t f = 0; f < s.mesh.faceCount(); ++f)
      for (uint32_t v : s.mesh.faces[f]) vn[v] += fn[f];
    for (auto& n : vn) n = glm::length(n) > 0 ? glm::normalize(n) : glm::vec3(0, 0, 1);
    std::vector<glm::vec2> uv(s.mesh.vertexCount());
    for (size_t v = 0; v < uv.size(); ++v) uv[v] = {s.uv[2 * v], s.uv[2 * v + 1]};
    SoftRenderer r;
    r.setMesh(0, s.mesh.positions, vn, s.mesh.faces);
    r.setTexture(0, checker(512, 8), uv);
    const FrameParams frame;
    const ObjectStyle style;
    r.drawSurfaces(s.camera, frame, std::span<const ObjectStyle>(&style, 1));
    (void)writePng(dir + "/softraster-armadillo-checker.png", r.image());
    break;
  }
}

void runTable(int reps, int threads) {
  const std::vector<Scene> all = scenes();
  const auto ms = modes(threads);
  const size_t M = ms.size();
  std::vector<std::vector<Error>> err(all.size(), std::vector<Error>(M));
  std::vector<std::vector<double>> time_ms(all.size(), std::vector<double>(M));
  std::vector<size_t> fragments(all.size()), lines(all.size() * M);
  std::vector<float> scratch;
  SoftRasterizer rasterizer;
  RasterTarget ref, t;
  ref.resize(kWidth, kHeight, 2);
  t.resize(kWidth, kHeight, 2);
  for (size_t si = 0; si < all.size(); ++si) {
    Prepared p = prepare(all[si]);
    ref.clear();
    rasterizer.draw(p.input, ms[0].params, ref);
    fragments[si] = rasterizer.stats().fragments;
    for (size_t m = 0; m < M; ++m) {
      t.clear();
      rasterizer.draw(p.input, ms[m].params, t);
      err[si][m] = uvError(t, ref, scratch);
      lines[si * M + m] = rasterizer.stats().lines;
    }
    // Interleaved repetitions: each round draws every mode once.
    std::vector<std::vector<double>> samples(M);
    for (int r = 0; r < reps; ++r)
      for (size_t m = 0; m < M; ++m) {
        t.clear();
        Stopwatch sw;
        rasterizer.draw(p.input, ms[m].params, t);
        samples[m].push_back(sw.lap());
      }
    // Best of the repetitions: on a shared machine, load only ever adds time.
    for (size_t m = 0; m < M; ++m) time_ms[si][m] = *std::min_element(samples[m].begin(), samples[m].end());
  }

  std::printf("\n## Texture-coordinate error vs exact (double precision), texels (mean / max), %dx%d, %g texels per repeat\n\n",
              kWidth, kHeight, kTexels);
  std::printf("| scene | fragments |");
  for (size_t m = 1; m < M; ++m) std::printf(" %s |", ms[m].name);
  std::printf("\n|---|---:|");
  for (size_t m = 1; m < M; ++m) std::printf("---:|");
  std::printf("\n");
  for (size_t si = 0; si < all.size(); ++si) {
    std::printf("| %s | %zu |", all[si].name.c_str(), fragments[si]);
    for (size_t m = 1; m < M; ++m) std::printf(" %.3f / %.2f |", err[si][m].mean, err[si][m].max);
    std::printf("\n");
  }
  std::printf("\n## 99th percentile error, texels\n\n| scene |");
  for (size_t m = 1; m < M; ++m) std::printf(" %s |", ms[m].name);
  std::printf("\n|---|");
  for (size_t m = 1; m < M; ++m) std::printf("---:|");
  std::printf("\n");
  for (size_t si = 0; si < all.size(); ++si) {
    std::printf("| %s |", all[si].name.c_str());
    for (size_t m = 1; m < M; ++m) std::printf(" %.3f |", err[si][m].p99);
    std::printf("\n");
  }
  std::printf("\n## Time per frame, ms (best of %d interleaved runs, setup + traversal, %d threads)\n\n| scene |",
              reps, threads);
  for (size_t m = 0; m < M; ++m) std::printf(" %s |", ms[m].name);
  std::printf("\n|---|");
  for (size_t m = 0; m < M; ++m) std::printf("---:|");
  std::printf("\n");
  std::vector<double> total(M, 0.0);
  for (size_t si = 0; si < all.size(); ++si) {
    std::printf("| %s |", all[si].name.c_str());
    for (size_t m = 0; m < M; ++m) {
      std::printf(" %.2f |", time_ms[si][m]);
      total[m] += time_ms[si][m];
    }
    std::printf("\n");
  }
  std::printf("| **sum** |");
  for (size_t m = 0; m < M; ++m) std::printf(" **%.1f** |", total[m]);
  std::printf("\n| **time / exact (geometric mean)** |");
  for (size_t m = 0; m < M; ++m) {
    double log_sum = 0.0;
    for (size_t si = 0; si < all.size(); ++si) log_sum += std::log(time_ms[si][m] / time_ms[si][1]);
    std::printf(" **%.2f** |", std::exp(log_sum / static_cast<double>(all.size())));
  }
  std::printf("\n\n## Constant-depth line entries computed per frame (paper's arrays)\n\n| scene | fragments |");
  for (size_t m = 3; m < M; ++m) std::printf(" %s |", ms[m].name);
  std::printf("\n|---|---:|");
  for (size_t m = 3; m < M; ++m) std::printf("---:|");
  std::printf("\n");
  for (size_t si = 0; si < all.size(); ++si) {
    std::printf("| %s | %zu |", all[si].name.c_str(), fragments[si]);
    for (size_t m = 3; m < M; ++m) std::printf(" %zu |", lines[si * M + m]);
    std::printf("\n");
  }
  std::fflush(stdout);
}

// Google Benchmark cases: the 8°-floor and the armadillo, per mode; items = fragments.
void registerBenchmarks(int threads) {
  static std::vector<Scene> picked;
  for (Scene& s : scenes())
    if (s.name.rfind("floor, 8", 0) == 0 || s.name.rfind("armadillo.off (52000 tris, box", 0) == 0)
      picked.push_back(std::move(s));
  for (const Scene& s : picked)
    for (const Mode& m : modes(threads)) {
      benchmark::RegisterBenchmark((std::string(s.name[0] == 'f' ? "floor8" : "armadillo") + "/" + m.name).c_str(),
                                   [&s, m](benchmark::State& state) {
                                     Prepared p = prepare(s);
                                     SoftRasterizer r;
                                     RasterTarget t;
                                     t.resize(kWidth, kHeight, 2);
                                     size_t frags = 0;
                                     for (auto _ : state) {
                                       state.PauseTiming();
                                       t.clear();
                                       state.ResumeTiming();
                                       r.draw(p.input, m.params, t);
                                       frags += r.stats().fragments;
                                     }
                                     state.SetItemsProcessed(static_cast<int64_t>(frags));
                                   })
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
}

}  // namespace
}  // namespace lodline

int main(int argc, char** argv) {
  std::string images;
  int reps = 15, threads = 2;
  bool table = true;
  std::vector<char*> rest = {argv[0]};
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--images") && i + 1 < argc)
      images = argv[++i];
    else if (!std::strcmp(argv[i], "--reps") && i + 1 < argc)
      reps = std::max(1, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc)
      threads = std::max(1, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--no-table"))
      table = false;
    else
      rest.push_back(argv[i]);
  }
  if (!images.empty()) lodline::writeImages(images, lodline::scenes(), threads);
  if (table) lodline::runTable(reps, threads);
  int n = static_cast<int>(rest.size());
  benchmark::Initialize(&n, rest.data());
  lodline::registerBenchmarks(threads);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
