// Per-frame cost of the lines stage on ~100k faces: per-view quantities (n·v, kr, Dw kr,
// suggestive test) + zero-set extraction of all line kinds, and chaining into strokes, for
// a camera orbiting the model (a new view every iteration). Items = vertices.
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/mesh_order.h"
#include "io/generate.h"
#include "io/load_mesh.h"
#include "lines/lines.h"
#include "lines/strokes.h"
#include "shape/shape_cache.h"

namespace lodline {
namespace {

struct Scene {
  TriMesh mesh;
  ShapeCache shape;
  Bounds bounds;
  float feature_size = 1.0f;
};

// 0: bumpy torus knot, 100,000 faces; 1: refined_elephant.off (88,928 faces);
// 2: icosphere level 6 (81,920 faces).
const Scene* benchScene(int which) {
  static std::unique_ptr<Scene> scenes[3];
  if (scenes[which]) return scenes[which].get();
  auto s = std::make_unique<Scene>();
  if (which == 0) {
    s->mesh = makeTorusKnot(3, 2, 1.0f, 0.25f, 1000, 50, 0.15f);
  } else if (which == 1) {
    auto loaded = loadMesh(std::string(LODLINE_DATA_MESHES) + "/refined_elephant.off");
    if (!loaded) return nullptr;
    s->mesh = std::move(loaded.value());
  } else {
    s->mesh = makeIcoSphere(1.0f, 6);
  }
  s->shape.compute(s->mesh);
  s->bounds = computeBounds(s->mesh.positions);
  s->feature_size = computeFeatureSize(s->shape.k1(), s->shape.k2(), s->bounds.radius);
  scenes[which] = std::move(s);
  return scenes[which].get();
}

const char* kNames[] = {"torus knot 100k", "refined_elephant", "icosphere 82k"};

Camera orbit(const Scene& s, int step) {
  OrbitView v;
  v.azimuth_deg = 35.0f + 0.5f * static_cast<float>(step % 720);
  v.elevation_deg = 20.0f;
  return orbitCamera(s.bounds, v, 35.0f, 16.0f / 9.0f);
}

// View quantities + extraction (contours, suggestive contours, creases, boundaries).
void BM_LinesExtract(benchmark::State& state) {
  const Scene* s = benchScene(static_cast<int>(state.range(0)));
  if (!s) return state.SkipWithError("mesh not found (run scripts/setup.sh)");
  state.SetLabel(kNames[state.range(0)]);
  LineExtractor ex;
  LineSet lines;
  LineParams params;
  ex.extract(s->mesh, s->shape, ViewSpec::fromCamera(orbit(*s, 0)), params, s->feature_size, lines);
  int step = 0;
  for (auto _ : state) {
    ex.extract(s->mesh, s->shape, ViewSpec::fromCamera(orbit(*s, ++step)), params,
               s->feature_size, lines);
    benchmark::DoNotOptimize(lines.points.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(s->mesh.vertexCount()));
  state.counters["faces"] = static_cast<double>(s->mesh.faceCount());
  state.counters["segments"] = static_cast<double>(lines.segmentCount());
}
BENCHMARK(BM_LinesExtract)->DenseRange(0, 2)->ArgName("mesh")->Unit(benchmark::kMillisecond);

// Only the per-view quantities.
void BM_ViewQuantities(benchmark::State& state) {
  const Scene* s = benchScene(static_cast<int>(state.range(0)));
  if (!s) return state.SkipWithError("mesh not found (run scripts/setup.sh)");
  state.SetLabel(kNames[state.range(0)]);
  ViewQuantities q;
  const SurfaceFields fields = s->shape.fields(s->mesh);
  int step = 0;
  for (auto _ : state) {
    computeViewQuantities(fields, ViewSpec::fromCamera(orbit(*s, ++step)), 10.0f, q);
    benchmark::DoNotOptimize(q.kr.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(s->mesh.vertexCount()));
}
BENCHMARK(BM_ViewQuantities)->DenseRange(0, 2)->ArgName("mesh")->Unit(benchmark::kMillisecond);

// Extraction + chaining, as a frame does it.
void BM_LinesExtractAndChain(benchmark::State& state) {
  const Scene* s = benchScene(static_cast<int>(state.range(0)));
  if (!s) return state.SkipWithError("mesh not found (run scripts/setup.sh)");
  state.SetLabel(kNames[state.range(0)]);
  LineExtractor ex;
  LineSet lines;
  StrokeSet strokes;
  ChainScratch scratch;
  LineParams params;
  int step = 0;
  for (auto _ : state) {
    ex.extract(s->mesh, s->shape, ViewSpec::fromCamera(orbit(*s, ++step)), params,
               s->feature_size, lines);
    chainStrokes(lines, strokes, scratch);
    benchmark::DoNotOptimize(strokes.points.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(s->mesh.vertexCount()));
  state.counters["strokes"] = static_cast<double>(strokes.strokeCount());
}
BENCHMARK(BM_LinesExtractAndChain)->DenseRange(0, 2)->ArgName("mesh")->Unit(benchmark::kMillisecond);

// Occluding contours (kept where kr > 0) and suggestive contours only, as rtsc draws them
// (threshold 0.01/fs², fade 0.03/fs², back faces rejected), on one thread, over the orbit
// above: the per-view work `scripts/peer_side_by_side.py` times against rtsc's
// compute_perview + zero-crossing extraction on the same meshes, as stored (0–2) and in the
// order lodline draws a full-detail mesh in (3–5, core/mesh_order.h).
const char* kPeerMeshes[] = {"armadillo.off", "bunny00.off", "refined_elephant.off",
                             "armadillo.off (ordered)", "bunny00.off (ordered)", "refined_elephant.off (ordered)"};

const Scene* peerScene(int which) {
  static std::unique_ptr<Scene> scenes[6];
  if (scenes[which]) return scenes[which].get();
  auto loaded = loadMesh(std::string(LODLINE_DATA_MESHES) + "/" + kPeerMeshes[which % 3]);
  if (!loaded) return nullptr;
  auto s = std::make_unique<Scene>();
  s->mesh = std::move(loaded.value());
  // Ordered as a full-detail drawing orders it, with the feature size of the stored order.
  std::vector<uint32_t> stored_to_drawn;
  if (which >= 3) orderForLocality(s->mesh, &stored_to_drawn);
  ShapeParams sp;
  sp.threads = 1;
  s->shape = ShapeCache(sp);
  s->shape.compute(s->mesh);
  s->bounds = computeBounds(s->mesh.positions);
  s->feature_size = computeFeatureSize(s->shape.k1(), s->shape.k2(), s->bounds.radius, {}, stored_to_drawn);
  scenes[which] = std::move(s);
  return scenes[which].get();
}

void BM_ContoursSuggestive(benchmark::State& state) {
  const Scene* s = peerScene(static_cast<int>(state.range(0)));
  if (!s) return state.SkipWithError("mesh not found (run scripts/setup.sh)");
  state.SetLabel(kPeerMeshes[state.range(0)]);
  LineExtractor ex;
  LineSet lines;
  LineParams params;
  params.contours_require_positive_kr = true;
  params.creases = params.boundaries = params.complete_outline = false;
  params.contours_follow_creases = false;  // rtsc interpolates n·v on vertex normals everywhere
  params.suggestive_off_creases = false;   // and draws suggestive contours at creases too
  ex.extract(s->mesh, s->shape, ViewSpec::fromCamera(orbit(*s, 0)), params, s->feature_size, lines);
  int step = 0;
  for (auto _ : state) {
    ex.extract(s->mesh, s->shape, ViewSpec::fromCamera(orbit(*s, ++step)), params, s->feature_size, lines);
    benchmark::DoNotOptimize(lines.points.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(s->mesh.faceCount()));
  state.counters["faces"] = static_cast<double>(s->mesh.faceCount());
  state.counters["contour_segments"] = lines.counts[static_cast<int>(LineKind::kContour)];
  state.counters["suggestive_segments"] = lines.counts[static_cast<int>(LineKind::kSuggestive)];
}
BENCHMARK(BM_ContoursSuggestive)->DenseRange(0, 5)->ArgName("mesh")->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace lodline

BENCHMARK_MAIN();
