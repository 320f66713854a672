// `lodline bench walkthrough MODEL --path P [--frames N]`: the walkthrough benchmark of Pan,
// Zhou, Shi (present/walkthrough.h), with every render and detail option of `render` (the
// scene's settings, styles and light apply as they do there). Parses, then present/ replays.
#include <iostream>
#include <memory>
#include <sstream>

#include "app/commands.h"
#include "app/model.h"
#include "app/options.h"
#include "present/walkthrough.h"

namespace lodline {
namespace {

struct BenchOptions {
  ViewOptions view;
  DetailOptions detail;
  std::string path = "orbit";
  int frames = 60;
  std::string pre_simplify = "0.02%";
  std::string context = "auto";
  std::string modes = "none,cluster,hybrid,pm";
  std::string snapshot;
};

int runWalkthroughCommand(CLI::App& cmd, BenchOptions& o) {
  if (o.frames < 2 || o.frames > 100000) return reportError(Error::usage("--frames: must be in [2, 100000]"));
  auto bound = parsePercent(o.pre_simplify, "--pre-simplify");
  if (!bound) return reportError(bound.error());
  WalkthroughRequest rq;
  rq.modes.clear();
  std::stringstream ss(o.modes);
  for (std::string m; std::getline(ss, m, ',');) {
    if (Status s = checkWalkthroughMode(m); !s) return reportError(s.error());
    rq.modes.push_back(m);
  }
  auto input = readInput(cmd, o.view, o.detail);
  if (!input) return reportError(input.error());
  auto context = parseContextBackend(o.context);
  if (!context) return reportError(context.error());
  rq.path = {o.path, givenOnCommandLine(cmd, "path"), o.frames / 30.0};
  rq.frames = o.frames;
  rq.pixel_error = o.detail.pixel_error;
  rq.pre_simplify = *bound;
  rq.context = *context;
  rq.snapshot_prefix = o.snapshot;
  auto results = runWalkthrough(*input, rq, std::cout);
  if (!results) return reportError(results.error());
  return 0;
}

}  // namespace

Command addBenchCommand(CLI::App& parent) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* bench = parent.add_subcommand("bench", "Benchmarks");
  bench->require_subcommand(1);
  CLI::App* walk = bench->add_subcommand(
      "walkthrough",
      "Replay a camera path with no LOD, vertex clustering, hybrid (pre-simplified + clustering) and the "
      "progressive mesh; print mean fps and triangles drawn (Pan/Zhou/Shi Table 2). Takes every render and "
      "detail option (--size, --msaa, --target-area, --style, ...; --pixel-error for clustering)");
  addViewOptions(*walk, o->view);
  addDetailOptions(*walk, o->detail);
  walk->add_option("--path", o->path, "Camera path: a JSON path file (docs/capture.md) or orbit, zoom-out, dolly, flyover")
      ->capture_default_str();
  walk->add_option("--frames", o->frames, "Frames replayed per mode (built-in paths last frames/30 s)")
      ->capture_default_str();
  walk->add_option("--pre-simplify", o->pre_simplify, "Hybrid: static E_s bound, % of the diagonal")
      ->capture_default_str();
  walk->add_option("--context", o->context, "OpenGL context: auto, egl or osmesa")->capture_default_str();
  walk->add_option("--modes", o->modes, "Comma-separated subset of none,cluster,hybrid,pm")->capture_default_str();
  walk->add_option("--snapshot", o->snapshot,
                   "Write each mode's first frame (converged at the path's start, not timed) as PREFIX-MODE.png");
  return {bench, [o, walk]() -> int {
            if (!walk->parsed()) return reportError(Error::usage("bench: expected a benchmark (walkthrough)"));
            return runWalkthroughCommand(*walk, *o);
          }};
}

}  // namespace lodline
