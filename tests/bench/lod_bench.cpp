// Selective refinement cost per frame during a slow orbit (Google Benchmark). One iteration is
// one adapt() call at 1280x720, T = 16 px², geomorphs on, after a warm-up to convergence.
// Counters: per_active_vertex (time per active vertex and frame), active vertices/faces,
// band fraction, splits+collapses per frame.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>

#include "lod/adaptive_mesh.h"
#include "pm/pm_test_meshes.h"
#include "pm/progressive_mesh.h"
#include "test_util.h"

namespace lodline {
namespace {

struct Model {
  TriMesh mesh;
  ProgressiveMesh pm;
  Bounds bounds;
  bool ok = false;
};

const Model& model(const std::string& name) {
  static std::map<std::string, std::unique_ptr<Model>> cache;
  auto& m = cache[name];
  if (m) return *m;
  m = std::make_unique<Model>();
  if (name == "ico_noise_1M") {
    m->mesh = makeIcoSphere(1.0f, 8);
    test::perturbRadially(m->mesh, 0.002f);
  } else {
    const auto path = test::dataMesh(name);
    if (path.empty() || !test::readOff(path, m->mesh)) return *m;
  }
  auto pm = buildProgressiveMesh(m->mesh);
  if (!pm.ok()) return *m;
  m->pm = std::move(pm).value();
  m->bounds = computeBounds(m->mesh.positions);
  m->ok = true;
  return *m;
}

Camera orbit(const Bounds& b, float az) {
  OrbitView v;
  v.azimuth_deg = az;
  v.elevation_deg = 15.0f;
  return orbitCamera(b, v, 35.0f, 1280.0f / 720.0f);  // model fills the view
}

void BM_AdaptOrbit(benchmark::State& state, const char* name) {
  const Model& m = model(name);
  if (!m.ok) {
    state.SkipWithError("mesh not found (run scripts/setup.sh)");
    return;
  }
  AdaptiveMesh lod(m.pm);
  DetailParams detail;
  float az = 0.0f;
  for (int i = 0; i < 120; ++i, az += 0.5f) {  // warm-up: converge
    (void)lod.setView(orbit(m.bounds, az), 1280, 720, detail);
    lod.adapt(1.0f / 30.0f);
  }
  double vertices = 0, faces = 0, band = 0, ops = 0;
  for (auto _ : state) {
    (void)lod.setView(orbit(m.bounds, az), 1280, 720, detail);
    lod.adapt(1.0f / 30.0f);
    az += 0.5f;  // 15°/s at 30 fps
    vertices += lod.stats().active_vertices;
    faces += lod.stats().active_faces;
    band += lod.stats().band_fraction;
    ops += lod.stats().splits + lod.stats().collapses;
  }
  const double n = static_cast<double>(state.iterations());
  state.SetItemsProcessed(static_cast<int64_t>(vertices));
  state.counters["per_active_vertex"] =
      benchmark::Counter(vertices, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["active_vertices"] = vertices / n;
  state.counters["active_faces"] = faces / n;
  state.counters["band"] = band / n;
  state.counters["ops_per_frame"] = ops / n;
}

BENCHMARK_CAPTURE(BM_AdaptOrbit, bunny, "bunny00.off")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AdaptOrbit, armadillo, "armadillo.off")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AdaptOrbit, ico_noise_1M, "ico_noise_1M")->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace lodline

BENCHMARK_MAIN();
