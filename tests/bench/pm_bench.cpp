// Progressive mesh build and cache load times (Google Benchmark).
//   pm_bench --benchmark_filter=Build   build time; s_per_Mtri is seconds per million faces
//   pm_bench --benchmark_filter=Load    cache file load time
#include <benchmark/benchmark.h>

#include "pm/pm_file.h"
#include "pm/pm_test_meshes.h"
#include "pm/progressive_mesh.h"
#include "test_util.h"

namespace lodline {
namespace {

const TriMesh& armadillo() {
  static const TriMesh mesh = [] {
    TriMesh m;
    const auto path = test::dataMesh("armadillo.off");
    if (!path.empty()) test::readOff(path, m);
    return m;
  }();
  return mesh;
}

/// ~1.3M faces: icosphere level 8 with radial noise (0.2% of the radius).
const TriMesh& icoNoise() {
  static const TriMesh mesh = [] {
    TriMesh m = makeIcoSphere(1.0f, 8);
    test::perturbRadially(m, 0.002f);
    return m;
  }();
  return mesh;
}

void setFaceCounters(benchmark::State& state, const TriMesh& m) {
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(m.faceCount()));
  state.counters["faces"] = static_cast<double>(m.faceCount());
  // Seconds per million faces.
  state.counters["s_per_Mtri"] = benchmark::Counter(
      static_cast<double>(m.faceCount()) * static_cast<double>(state.iterations()) / 1e6,
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_PmBuild(benchmark::State& state, const TriMesh& (*get)()) {
  const TriMesh& m = get();
  if (m.faces.empty()) {
    state.SkipWithError("mesh not found (run scripts/setup.sh)");
    return;
  }
  for (auto _ : state) {
    auto pm = buildProgressiveMesh(m);
    if (!pm.ok()) state.SkipWithError(pm.error().message.c_str());
    benchmark::DoNotOptimize(pm);
  }
  setFaceCounters(state, m);
}

void BM_PmLoad(benchmark::State& state, const TriMesh& (*get)()) {
  const TriMesh& m = get();
  if (m.faces.empty()) {
    state.SkipWithError("mesh not found (run scripts/setup.sh)");
    return;
  }
  test::TempDir dir;
  const auto path = dir / "bench.lpm";
  {
    auto pm = buildProgressiveMesh(m);
    if (!pm.ok() || !savePm(path, *pm).ok()) {
      state.SkipWithError("build/save failed");
      return;
    }
  }
  for (auto _ : state) {
    auto pm = loadPm(path);
    if (!pm.ok()) state.SkipWithError(pm.error().message.c_str());
    benchmark::DoNotOptimize(pm);
  }
  setFaceCounters(state, m);
}

BENCHMARK_CAPTURE(BM_PmBuild, armadillo, &armadillo)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_PmBuild, ico_noise_1M, &icoNoise)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_PmLoad, armadillo, &armadillo)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PmLoad, ico_noise_1M, &icoNoise)->Unit(benchmark::kMillisecond)->Iterations(5);

}  // namespace
}  // namespace lodline

BENCHMARK_MAIN();
