// `lodline render MODEL -o out.png`: one headless frame (EGL surfaceless by default, OSMesa
// as fallback, or the software rasteriser), written atomically, with optional per-stage
// stats as JSON (docs/stats.md). Parses, then present/still.h does the work.
#include <iostream>
#include <memory>

#include "app/commands.h"
#include "app/model.h"
#include "app/options.h"
#include "core/timer.h"
#include "io/atomic_file.h"
#include "present/still.h"

namespace lodline {

int reportError(const Error& e) {
  std::cerr << "lodline: " << e.message << '\n';
  return e.exitCode();
}

namespace {

struct RenderOptions {
  ViewOptions view;
  DetailOptions detail;
  std::string output;
  std::string svg;
  std::string stats;
  std::string context = "auto";
  std::string backend = "gl";  ///< gl (OpenGL context) or soft (raster/, no OpenGL at all)
};

bool hasExtension(const std::string& path, const char* want) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == want;
}

int runRender(CLI::App& cmd, RenderOptions& o) {
  Stopwatch total;
  // Checked again after the scene's settings are applied; first here, to fail early.
  if (auto backend = parseContextBackend(o.context); !backend) return reportError(backend.error());
  if (o.output.empty() && o.svg.empty())
    return reportError(Error::usage("render: give an output: -o FILE.png and/or --svg FILE.svg"));
  if (!o.output.empty() && !hasExtension(o.output, ".png"))
    return reportError(Error::usage("-o: output must be a .png file, got '" + o.output + "'"));
  if (!o.svg.empty() && !hasExtension(o.svg, ".svg"))
    return reportError(Error::usage("--svg: output must be a .svg file, got '" + o.svg + "'"));
  // Fail early on unwritable outputs, before any expensive work.
  for (const std::string* path : {&o.output, &o.svg, &o.stats})
    if (!path->empty())
      if (Status s = checkWritable(*path); !s) return reportError(s.error());

  auto loaded = loadInput(cmd, o.view, o.detail);
  if (!loaded) return reportError(loaded.error());
  // Options the scene's settings may have set are read from here on.
  auto backend = parsePresenterBackend(o.backend);
  if (!backend) return reportError(backend.error());
  auto context = parseContextBackend(o.context);
  if (!context) return reportError(context.error());
  const StillRequest request{*backend, *context, o.output, o.svg, o.stats, total.elapsed()};
  if (Status s = renderStill(**loaded, request); !s) return reportError(s.error());
  return 0;
}

}  // namespace

Command addRenderCommand(CLI::App& parent) {
  auto o = std::make_shared<RenderOptions>();
  CLI::App* cmd = parent.add_subcommand("render", "Render a model or scene headlessly to a PNG line drawing");
  addViewOptions(*cmd, o->view);
  addDetailOptions(*cmd, o->detail);
  cmd->add_option("--max-adapt-frames", o->detail.max_adapt_frames,
                  "Adaptation steps at most before drawing the still image")
      ->capture_default_str();
  cmd->add_option("-o,--output", o->output, "Output PNG file");
  cmd->add_option("--svg", o->svg,
                  "Also (or only) write the visible strokes as an SVG line drawing of the same size");
  cmd->add_option("--stats", o->stats, "Write per-frame statistics as JSON to this file (docs/stats.md)");
  cmd->add_option("--context", o->context,
                  "OpenGL context: auto (EGL surfaceless, then OSMesa), egl or osmesa")
      ->capture_default_str();
  cmd->add_option("--backend", o->backend,
                  "Renderer: gl (OpenGL through --context) or soft (software rasteriser with "
                  "constant-depth scanlines, no OpenGL context; the lines and toon styles; "
                  "docs/softraster.md)")
      ->capture_default_str();
  return {cmd, [o, cmd] { return runRender(*cmd, *o); }};
}

}  // namespace lodline
