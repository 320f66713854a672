// Progressive mesh build and cache load times (Google Benchmark).
//   pm_bench --benchmark_filter=Build   build time; s_per_Mtri is seconds per million faces
//   pm_bench --benchmark_filter=Load    cache file load time
//   pm_bench --benchmark_filter='Build|Meshopt'   the build beside meshopt_simplify to 1% of the
//                                      faces on the same meshes, in one run (when meshoptimizer
//                                      is installed: Debian libmeshoptimizer-dev)
//   pm_bench --benchmark_filter=knot_     the scale series: the same knot at about 0.1, 0.3, 1,
//                                      3 and 10M faces, meshopt and the build side by side
#include <benchmark/benchmark.h>

#ifdef LODLINE_HAVE_MESHOPT
#include <meshoptimizer.h>
#endif

#include <algorithm>
#include <vector>

#include "io/generate.h"
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

/// The 1.1M-face torus knot of `lodline generate knot --resolution 2900` (detail_frame_bench's
/// knot1m).
const TriMesh& knot1m() {
  static const TriMesh mesh = makeTorusKnot(2, 3, 1.0f, 0.16f, 2900, 193, 0.18f);
  return mesh;
}

/// The same knot at about 30·tube² faces (tube segments 1/15 of the length's, as knot1m):
/// the scale series, 58 → 0.1M, 100 → 0.3M, 183 → 1M, 316 → 3M, 577 → 10M faces.
template <uint32_t Tube>
const TriMesh& knotScale() {
  static const TriMesh mesh = makeTorusKnot(2, 3, 1.0f, 0.16f, 15 * Tube, Tube, 0.18f);
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

#ifdef LODLINE_HAVE_MESHOPT
// The peer: meshoptimizer's edge-collapse simplifier to 1% of the faces (target error 1, so
// the face count decides), on the same flat arrays. It builds one simplified mesh, not a
// progressive mesh with its hierarchy, so it is the floor the build is compared against.
void BM_MeshoptSimplify(benchmark::State& state, const TriMesh& (*get)()) {
  const TriMesh& m = get();
  if (m.faces.empty()) {
    state.SkipWithError("mesh not found (run scripts/setup.sh)");
    return;
  }
  const size_t index_count = m.faces.size() * 3;
  const size_t target = std::max<size_t>(3, index_count / 100 / 3 * 3);
  std::vector<unsigned int> out(index_count);
  size_t kept = 0;
  for (auto _ : state) {
    kept = meshopt_simplify(out.data(), m.faces.front().data(), index_count, &m.positions.front().x,
                            m.positions.size(), sizeof(glm::vec3), target, 1.0f, 0, nullptr);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["faces_out"] = static_cast<double>(kept / 3);
  setFaceCounters(state, m);
}
BENCHMARK_CAPTURE(BM_MeshoptSimplify, armadillo, &armadillo)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_MeshoptSimplify, knot1m, &knot1m)->Unit(benchmark::kSecond)->Iterations(1);
#define LODLINE_PEER(label, get) BENCHMARK_CAPTURE(BM_MeshoptSimplify, label, get)->Unit(benchmark::kSecond)->Iterations(1);
#else
#define LODLINE_PEER(label, get)
#endif
// The scale series, each size's peer beside its build.
#define LODLINE_SCALE(label, tube)   \
  LODLINE_PEER(label, &knotScale<tube>) \
  BENCHMARK_CAPTURE(BM_PmBuild, label, &knotScale<tube>)->Unit(benchmark::kSecond)->Iterations(1);
LODLINE_SCALE(knot_100k, 58)
LODLINE_SCALE(knot_300k, 100)
LODLINE_SCALE(knot_1000k, 183)
LODLINE_SCALE(knot_3000k, 316)
LODLINE_SCALE(knot_10000k, 577)

BENCHMARK_CAPTURE(BM_PmBuild, armadillo, &armadillo)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_PmBuild, knot1m, &knot1m)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_PmBuild, ico_noise_1M, &icoNoise)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_PmLoad, armadillo, &armadillo)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PmLoad, ico_noise_1M, &icoNoise)->Unit(benchmark::kMillisecond)->Iterations(5);

}  // namespace
}  // namespace lodline

BENCHMARK_MAIN();
