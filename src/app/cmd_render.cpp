// `lodline render MODEL -o out.png`: one headless frame (EGL surfaceless by default, OSMesa
// as fallback), written atomically, with optional per-stage stats as JSON (docs/stats.md).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "app/headless.h"
#include "app/options.h"
#include "core/timer.h"
#include "frame/line_drawing.h"
#include "export/svg.h"
#include "export/visibility.h"
#include "io/atomic_file.h"
#include "io/image.h"
#include "io/load_mesh.h"

namespace lodline {

int reportError(const Error& e) {
  std::cerr << "lodline: " << e.message << '\n';
  return e.exitCode();
}

namespace {

std::string colorToHex(const glm::vec4& c) {
  char buf[8];
  auto byte = [](float v) { return static_cast<int>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
  std::snprintf(buf, sizeof(buf), "#%02x%02x%02x", byte(c.r), byte(c.g), byte(c.b));
  return buf;
}

struct RenderOptions {
  ViewOptions view;
  std::string output;
  std::string svg;
  std::string stats;
  std::string context = "auto";
};

int runRender(const RenderOptions& o) {
  Stopwatch total;
  auto resolved = resolveViewOptions(o.view);
  if (!resolved) return reportError(resolved.error());
  auto backend = parseContextBackend(o.context);
  if (!backend) return reportError(backend.error());
  if (o.output.empty() && o.svg.empty())
    return reportError(Error::usage("render: give an output: -o FILE.png and/or --svg FILE.svg"));
  auto has_ext = [](const std::string& path, const char* want) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext == want;
  };
  if (!o.output.empty() && !has_ext(o.output, ".png"))
    return reportError(Error::usage("-o: output must be a .png file, got '" + o.output + "'"));
  if (!o.svg.empty() && !has_ext(o.svg, ".svg"))
    return reportError(Error::usage("--svg: output must be a .svg file, got '" + o.svg + "'"));
  // Fail early on unwritable outputs, before any expensive work.
  for (const std::string* path : {&o.output, &o.svg, &o.stats})
    if (!path->empty())
      if (Status s = checkWritable(*path); !s) return reportError(s.error());

  const RenderParams& rp = resolved->render;
  Stopwatch stage;
  auto mesh = loadMesh(resolved->model);
  if (!mesh) return reportError(mesh.error());
  const size_t model_vertices = mesh->vertexCount(), model_faces = mesh->faceCount();
  const double ms_load = stage.lap();

  LineDrawing drawing(std::move(mesh.value()));
  const float aspect = static_cast<float>(rp.width) / static_cast<float>(rp.height);
  const Camera camera = orbitCamera(drawing.bounds(), resolved->orbit, resolved->fov_deg, aspect);
  std::array<bool, kLineKindCount> enabled{};
  for (int k = 0; k < kLineKindCount; ++k) enabled[k] = rp.lines.kinds[k].enabled;
  drawing.update(camera, enabled);
  stage.lap();

  auto headless = HeadlessRenderer::create(*backend, rp);
  if (!headless) return reportError(headless.error());
  headless->setMesh(drawing);
  const double ms_setup = stage.lap();

  headless->draw(drawing, camera, rp);
  const double ms_render = stage.lap();
  const Image image = headless->readImage();
  const double ms_readback = stage.lap();

  // Visible lines, from the depth buffer of the faces just drawn: for the SVG and the stats.
  const DepthImage depth = headless->readDepth();
  VisibleStrokes visible;
  visibleStrokes(drawing.strokes(), camera, depth, {}, visible);
  const auto visible_segments = countVisibleSegments(drawing.segments(), camera, depth);
  const double ms_visibility = stage.lap();

  if (!o.output.empty())
    if (Status s = writePng(o.output, image); !s) return reportError(s.error());
  if (!o.svg.empty()) {
    SvgStyle style;
    style.background = rp.background.a > 0.0f;
    style.background_colour = colorToHex(rp.background);
    for (int k = 0; k < kLineKindCount; ++k) {
      const LineStyle& ls = rp.lines.kinds[k];
      style.lines[k] = {colorToHex(ls.color), ls.width_px, ls.color.a};
    }
    const SvgStrokes strokes{visible.points, visible.offsets, visible.types, visible.opacity};
    if (Status s = writeSvg(o.svg, rp.width, rp.height, strokes, style); !s) return reportError(s.error());
  }

  if (!o.stats.empty()) {
    const CpuTimings& t = drawing.timings();
    nlohmann::json j;
    j["model"] = {{"path", resolved->model.string()}, {"vertices", model_vertices}, {"faces", model_faces}};
    j["image"] = {{"width", rp.width}, {"height", rp.height}};
    j["context"] = {{"backend", backendName(headless->context().backend())},
                    {"gl", headless->context().description()}};
    j["faces_drawn"] = headless->renderer().faceCount();
    j["line_segments"] = headless->renderer().segmentsDrawn();
    nlohmann::json lines, extracted;
    for (int k = 0; k < kLineKindCount; ++k) {
      const char* name = lineKindName(static_cast<LineKind>(k));
      lines[name] = rp.lines.kinds[k].enabled ? visible_segments[k] : 0;
      extracted[name] = drawing.lines().count[k] / 2;
    }
    j["lines"] = lines;
    j["lines_extracted"] = extracted;
    j["strokes"] = visible.strokeCount();
    j["specks"] = std::count_if(visible.length_px.begin(), visible.length_px.end(),
                                [](float len) { return len < 3.0f; });
    j["ms"] = {{"load", ms_load},   {"shape", t.shape},   {"view", t.view},
               {"extract", t.extract}, {"chain", t.chain}, {"setup", ms_setup},
               {"render", ms_render}, {"readback", ms_readback}, {"visibility", ms_visibility}, {"total", total.elapsed()}};
    const std::string text = j.dump(2) + "\n";
    Status s = writeFileAtomically(o.stats, [&](std::ostream& out) -> Status {
      out << text;
      return {};
    });
    if (!s) return reportError(s.error());
  }
  return 0;
}

}  // namespace

Command addRenderCommand(CLI::App& parent) {
  auto o = std::make_shared<RenderOptions>();
  CLI::App* cmd = parent.add_subcommand("render", "Render a model headlessly to a PNG line drawing");
  addViewOptions(*cmd, o->view);
  cmd->add_option("-o,--output", o->output, "Output PNG file");
  cmd->add_option("--svg", o->svg,
                  "Also (or only) write the visible strokes as an SVG line drawing of the same size");
  cmd->add_option("--stats", o->stats, "Write per-frame statistics as JSON to this file (docs/stats.md)");
  cmd->add_option("--context", o->context,
                  "OpenGL context: auto (EGL surfaceless, then OSMesa), egl or osmesa")
      ->capture_default_str();
  return {cmd, [o] { return runRender(*o); }};
}

}  // namespace lodline
