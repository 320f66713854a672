// ShapeCache throughput (Rusinkiewicz 2004 curvature + derivative tensor): full recompute on
// the CGAL demo meshes and a ~1.3M-triangle icosphere, and incremental updates for 1% / 10%
// changed vertices (random, and a spatially coherent patch like the LOD stage produces).
// Items = vertices (full) or changed vertices (update).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "core/mesh.h"
#include "core/mesh_order.h"
#include "io/generate.h"
#include "io/load_mesh.h"
#include "shape/shape_cache.h"

namespace lodline {
namespace {

// Meshes are loaded once per process. Null when the file is missing (setup.sh not run).
// A name ending in ":sorted" is the same mesh after orderForLocality(), the order lodline
// draws a full-detail mesh in (core/mesh_order.h); a mesh local already would keep its order
// (none of these is: BM_OrderForLocality's spread_after counter shows it).
const TriMesh* benchMesh(const std::string& full_name) {
  static std::map<std::string, std::unique_ptr<TriMesh>> cache;
  auto it = cache.find(full_name);
  if (it != cache.end()) return it->second.get();
  const size_t colon = full_name.find(':');
  const std::string name = full_name.substr(0, colon);
  std::unique_ptr<TriMesh> mesh;
  if (name == "icosphere8") {
    mesh = std::make_unique<TriMesh>(makeIcoSphere(1.0f, 8));  // 1,310,720 triangles
  } else {
    auto loaded = loadMesh(std::string(LODLINE_DATA_MESHES) + "/" + name);
    if (loaded) mesh = std::make_unique<TriMesh>(std::move(loaded.value()));
  }
  if (mesh && colon != std::string::npos) orderForLocality(*mesh);
  return cache.emplace(full_name, std::move(mesh)).first->second.get();
}

const char* kMeshes[] = {"armadillo.off",        "bunny00.off",        "refined_elephant.off",
                         "icosphere8",           "armadillo.off:sorted", "bunny00.off:sorted",
                         "refined_elephant.off:sorted", "icosphere8:sorted"};

// Full compute with adjacency already built (the per-frame cost when all vertices move).
// range(2): worker threads, caller included (0: one per core, the default; 1: none).
void BM_ShapeFull(benchmark::State& state) {
  const TriMesh* mesh = benchMesh(kMeshes[state.range(0)]);
  if (!mesh) return state.SkipWithError("mesh not found (run scripts/setup.sh)");
  state.SetLabel(kMeshes[state.range(0)]);
  ShapeParams params;
  params.derivatives = state.range(1) != 0;
  params.threads = static_cast<unsigned>(state.range(2));
  ShapeCache shape(params);
  shape.compute(*mesh);
  for (auto _ : state) {
    shape.compute(*mesh);
    benchmark::DoNotOptimize(shape.k1().data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(mesh->vertexCount()));
  state.counters["faces"] = static_cast<double>(mesh->faceCount());
}
BENCHMARK(BM_ShapeFull)
    ->ArgsProduct({{0, 1, 2, 3, 4, 5, 6, 7}, {1}, {1, 0}})
    ->ArgNames({"mesh", "derivs", "threads"})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ShapeFull)->Args({1, 0, 1})->ArgNames({"mesh", "derivs", "threads"})->Unit(benchmark::kMillisecond);

// From nothing: a new cache (arrays, corner areas, normals, curvature, derivatives), as
// rtsc's need_curvatures + need_dcurv on a fresh mesh do (scripts/peer_side_by_side.py). On
// one thread the compute runs over the faces and builds no adjacency until it is asked for;
// on several (as in every drawing) it gathers over the rings, so it builds it first.
// range(1): worker threads as in BM_ShapeFull.
void shapeFromNothing(benchmark::State& state, bool with_adjacency) {
  const TriMesh* mesh = benchMesh(kMeshes[state.range(0)]);
  if (!mesh) return state.SkipWithError("mesh not found (run scripts/setup.sh)");
  state.SetLabel(kMeshes[state.range(0)]);
  ShapeParams params;
  params.threads = static_cast<unsigned>(state.range(1));
  for (auto _ : state) {
    ShapeCache shape(params);
    shape.compute(*mesh);
    benchmark::DoNotOptimize(shape.k1().data());
    if (with_adjacency) benchmark::DoNotOptimize(shape.adjacency().edges.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(mesh->vertexCount()));
}
void BM_ShapeFresh(benchmark::State& state) { shapeFromNothing(state, false); }
BENCHMARK(BM_ShapeFresh)
    ->ArgsProduct({{0, 1, 2, 3, 4, 5, 6, 7}, {1, 0}})
    ->ArgNames({"mesh", "threads"})
    ->Unit(benchmark::kMillisecond);

// The same and the adjacency too (vertex rings, edges), as the first frame of a drawing pays.
void BM_ShapeFullWithAdjacency(benchmark::State& state) { shapeFromNothing(state, true); }
BENCHMARK(BM_ShapeFullWithAdjacency)
    ->ArgsProduct({{0, 1, 2, 3, 4, 5, 6, 7}, {1, 0}})
    ->ArgNames({"mesh", "threads"})
    ->Unit(benchmark::kMillisecond);

// The reorder itself (core/mesh_order.h), on a copy of the mesh as stored: what loading a
// full-detail model adds before the stages above.
void BM_OrderForLocality(benchmark::State& state) {
  const TriMesh* mesh = benchMesh(kMeshes[state.range(0)]);
  if (!mesh) return state.SkipWithError("mesh not found (run scripts/setup.sh)");
  state.SetLabel(kMeshes[state.range(0)]);
  TriMesh m;
  for (auto _ : state) {
    state.PauseTiming();
    m = *mesh;
    state.ResumeTiming();
    orderForLocality(m);
    benchmark::DoNotOptimize(m.faces.data());
  }
  state.counters["spread_before"] = medianCornerSpread(*mesh);
  state.counters["spread_after"] = medianCornerSpread(m);
}
BENCHMARK(BM_OrderForLocality)->DenseRange(0, 3)->ArgName("mesh")->Unit(benchmark::kMillisecond);

// Connectivity changes every frame (the LOD stage splits and collapses): update() rebuilds
// the adjacency (O(V + F)) and recomputes around the changed face slot only. Two face arrays
// differing in one face slot alternate; the cost is dominated by the adjacency rebuild.
void BM_ShapeConnectivityChange(benchmark::State& state) {
  const TriMesh* mesh = benchMesh(kMeshes[state.range(0)]);
  if (!mesh) return state.SkipWithError("mesh not found (run scripts/setup.sh)");
  state.SetLabel(kMeshes[state.range(0)]);
  TriMesh a = *mesh, b = *mesh;
  std::swap(b.faces[0][1], b.faces[0][2]);  // a change of the face array (orientation flip)
  ShapeCache shape;
  shape.compute(a);
  shape.compute(b);
  const uint32_t changed[] = {b.faces[0][0]};
  bool flip = false;
  for (auto _ : state) {
    shape.update(flip ? b : a, changed);
    flip = !flip;
    benchmark::DoNotOptimize(shape.k1().data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(mesh->vertexCount()));
}
BENCHMARK(BM_ShapeConnectivityChange)->Args({0})->Args({4})->ArgName("mesh")->Unit(benchmark::kMillisecond);

// Incremental update: range(1) = changed per mille, range(2) = 0 random / 1 coherent patch.
void BM_ShapeUpdate(benchmark::State& state) {
  const TriMesh* mesh = benchMesh(kMeshes[state.range(0)]);
  if (!mesh) return state.SkipWithError("mesh not found (run scripts/setup.sh)");
  const size_t nv = mesh->vertexCount();
  const size_t count = std::max<size_t>(1, nv * state.range(1) / 1000);
  std::vector<uint32_t> changed;
  if (state.range(2) == 0) {
    std::mt19937 rng(1);
    std::uniform_int_distribution<uint32_t> pick(0, static_cast<uint32_t>(nv - 1));
    for (size_t i = 0; i < count; ++i) changed.push_back(pick(rng));
  } else {  // the `count` vertices nearest to one vertex
    const glm::vec3 c = mesh->positions[nv / 3];
    std::vector<uint32_t> order(nv);
    for (uint32_t i = 0; i < nv; ++i) order[i] = i;
    std::nth_element(order.begin(), order.begin() + (count - 1), order.end(), [&](uint32_t a, uint32_t b) {
      return glm::distance(mesh->positions[a], c) < glm::distance(mesh->positions[b], c);
    });
    changed.assign(order.begin(), order.begin() + count);
  }
  state.SetLabel(std::string(kMeshes[state.range(0)]) + (state.range(2) ? " patch" : " random"));
  ShapeCache shape;
  shape.compute(*mesh);
  shape.update(*mesh, changed);
  for (auto _ : state) {
    shape.update(*mesh, changed);
    benchmark::DoNotOptimize(shape.k1().data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(count));
  state.counters["changed"] = static_cast<double>(count);
  state.counters["touched"] = shape.lastStats().derivative_vertices;
  state.counters["full"] = shape.lastStats().full ? 1 : 0;
}
BENCHMARK(BM_ShapeUpdate)
    ->ArgsProduct({{0, 3, 4, 7}, {10, 100}, {0, 1}})
    ->ArgNames({"mesh", "permille", "patch"})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace lodline

BENCHMARK_MAIN();
