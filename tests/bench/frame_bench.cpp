// End-to-end frame benchmark: per-stage milliseconds (median over the frames of a slow orbit)
// for the CGAL demo meshes at 1280x720 through EGL surfaceless. Run:
//   ./build/tests/bench/frame_bench --benchmark_counters_tabular=true
// Counters are median ms per stage: lines (view quantities + extraction + chaining),
// upload (line buffer), draw (faces + lines, glFinish), readback (resolve + glReadPixels);
// the frame goes through the same SceneDrawing and presenter as `render`.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <memory>
#include <vector>

#include "core/timer.h"
#include "frame/scene_drawing.h"
#include "gl/context.h"
#include "io/load_mesh.h"
#include "present/gl_presenter.h"
#include "bench_util.h"
#include "test_util.h"

namespace lodline {
namespace {

void frameBenchmark(benchmark::State& state, const std::string& name, Style style, int msaa) {
  auto setup = bench::setUpGlBenchmark(state, name);
  if (!setup) return;
  const size_t faces = setup->mesh.faceCount();
  // One full-detail object, drawn through the presenter every command uses.
  SceneDrawing scene;
  SceneDrawing::Object object;
  object.name = name;
  object.style.style = style;
  object.input_faces = faces;
  object.drawing = std::make_unique<LodDrawing>(std::move(setup->mesh));
  scene.add(std::move(object));
  FrameParams frame;
  frame.msaa = msaa;
  auto presenter = GlPresenter::createOnCurrentContext();
  if (!presenter) {
    state.SkipWithError(presenter.error().message.c_str());
    return;
  }
  GlPresenter& p = **presenter;
  const DetailParams detail;
  std::vector<double> lines_ms, upload_ms, draw_ms, readback_ms;
  float az = 0.0f;
  bool first = true;
  for (auto _ : state) {
    const Camera cam = orbitCamera(scene.bounds(), {az, 15.0f, 0.0f}, 35.0f, frame.aspect());
    az += 1.0f;  // a slow orbit: one degree per frame
    Stopwatch sw;
    (void)scene.frame(cam, frame.width, frame.height, detail, 1.0f / 30.0f);
    lines_ms.push_back(sw.lap());
    (void)p.present(scene, cam, frame, first);
    first = false;
    upload_ms.push_back(p.times().upload);
    draw_ms.push_back(p.times().render);
    benchmark::DoNotOptimize(p.readImage());
    readback_ms.push_back(p.times().readback);
  }
  state.counters["faces"] = static_cast<double>(faces);
  state.counters["lines_ms"] = bench::median(lines_ms);
  state.counters["upload_ms"] = bench::median(upload_ms);
  state.counters["draw_ms"] = bench::median(draw_ms);
  state.counters["readback_ms"] = bench::median(readback_ms);
  state.counters["frame_ms"] =
      bench::median(lines_ms) + bench::median(upload_ms) + bench::median(draw_ms) + bench::median(readback_ms);
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(faces));
}

void registerAll() {
  for (const char* name : {"bunny00.off", "armadillo.off", "refined_elephant.off", "fandisk.off",
                           "ChineseDragon-10kv.off"}) {
    benchmark::RegisterBenchmark((std::string("toon_msaa4/") + name).c_str(),
                                 [name](benchmark::State& s) { frameBenchmark(s, name, Style::kToon, 4); })
        ->Iterations(24)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark((std::string("lines_nomsaa/") + name).c_str(),
                                 [name](benchmark::State& s) { frameBenchmark(s, name, Style::kLines, 1); })
        ->Iterations(24)
        ->Unit(benchmark::kMillisecond);
  }
}

}  // namespace
}  // namespace lodline

int main(int argc, char** argv) {
  lodline::registerAll();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
