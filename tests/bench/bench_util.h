// Shared set-up of the end-to-end GL frame benchmarks.
#pragma once

#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "gl/context.h"
#include "io/load_mesh.h"
#include "test_util.h"

namespace lodline::bench {

/// Median of `v` (0 for an empty vector).
inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

/// A CGAL demo mesh and a current EGL context for a GL benchmark.
struct GlBenchSetup {
  TriMesh mesh;
  std::unique_ptr<GlContext> context;
};

/// Loads data/meshes/NAME and creates an EGL context; on failure marks `state` skipped with
/// the reason and returns nothing.
inline std::optional<GlBenchSetup> setUpGlBenchmark(benchmark::State& state, const std::string& name) {
  const auto path = test::dataMesh(name);
  if (path.empty()) {
    state.SkipWithError(("data/meshes/" + name + " missing: run scripts/setup.sh").c_str());
    return std::nullopt;
  }
  auto mesh = loadMesh(path);
  if (!mesh) {
    state.SkipWithError(mesh.error().message.c_str());
    return std::nullopt;
  }
  auto ctx = createHeadlessContext(ContextBackend::kEgl);
  if (!ctx) {
    state.SkipWithError(ctx.error().message.c_str());
    return std::nullopt;
  }
  return GlBenchSetup{std::move(mesh.value()), std::move(ctx.value())};
}

}  // namespace lodline::bench
