// End-to-end frame benchmark: per-stage milliseconds (median over the frames of a slow orbit)
// for the CGAL demo meshes at 1280x720 through EGL surfaceless. Run:
//   ./build/tests/bench/frame_bench --benchmark_counters_tabular=true
// Counters are median ms per stage: lines (view quantities + extraction + chaining),
// upload (line buffer), draw (faces + lines, glFinish), readback (resolve + glReadPixels).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <memory>
#include <vector>

#include <glad/gl.h>

#include "core/timer.h"
#include "frame/line_drawing.h"
#include "gl/context.h"
#include "gl/renderer.h"
#include "io/load_mesh.h"
#include "bench_util.h"
#include "test_util.h"

namespace lodline {
namespace {

void frameBenchmark(benchmark::State& state, const std::string& name, Style style, int msaa) {
  auto setup = bench::setUpGlBenchmark(state, name);
  if (!setup) return;
  const size_t faces = setup->mesh.faceCount();
  LineDrawing drawing(std::move(setup->mesh));
  RenderParams rp;
  rp.style = style;
  rp.msaa = msaa;
  auto renderer = Renderer::create();
  auto target = OffscreenTarget::create(rp.width, rp.height, rp.msaa);
  if (!renderer || !target) {
    state.SkipWithError("renderer setup failed");
    return;
  }
  renderer->setMesh(drawing.mesh().positions, drawing.normals(), drawing.mesh().faces);
  std::array<bool, kLineKindCount> enabled{};
  enabled.fill(true);
  std::vector<double> lines_ms, upload_ms, draw_ms, readback_ms;
  float az = 0.0f;
  for (auto _ : state) {
    const Camera cam = orbitCamera(drawing.bounds(), {az, 15.0f, 0.0f}, 35.0f, 1280.0f / 720.0f);
    az += 1.0f;  // a slow orbit: one degree per frame
    Stopwatch sw;
    drawing.update(cam, enabled);
    lines_ms.push_back(sw.lap());
    renderer->setLines(drawing.lines());
    upload_ms.push_back(sw.lap());
    target->bind();
    renderer->draw(cam, rp, rp.width, rp.height);
    glFinish();
    draw_ms.push_back(sw.lap());
    benchmark::DoNotOptimize(target->readback());
    readback_ms.push_back(sw.lap());
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
