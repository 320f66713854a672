// `lodline render MODEL -o out.png`: one headless frame (EGL surfaceless by default, OSMesa
// as fallback), written atomically, with optional per-stage stats as JSON (docs/stats.md).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "app/headless.h"
#include "app/options.h"
#include "core/timer.h"
#include "app/model.h"
#include "export/coherence.h"
#include "export/svg.h"
#include "export/visibility.h"
#include "io/atomic_file.h"
#include "io/image.h"
#include "io/load_mesh.h"
#include "raster/soft_renderer.h"

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
  DetailOptions detail;
  std::string output;
  std::string svg;
  std::string stats;
  std::string context = "auto";
  std::string backend = "gl";  ///< gl (OpenGL context) or soft (raster/, no OpenGL at all)
};

int runRender(const RenderOptions& o) {
  Stopwatch total;
  auto resolved = resolveViewOptions(o.view);
  if (!resolved) return reportError(resolved.error());
  auto backend = parseContextBackend(o.context);
  if (!backend) return reportError(backend.error());
  if (o.backend != "gl" && o.backend != "soft")
    return reportError(Error::usage("--backend: expected gl or soft, got '" + o.backend + "'"));
  const bool soft = o.backend == "soft";
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
  auto detail = resolveDetailOptions(o.detail);
  if (!detail) return reportError(detail.error());
  Stopwatch stage;
  double ms_load = 0.0, ms_pm = 0.0;
  std::string cache_note;
  auto model = loadModel(resolved->model, *detail, &ms_load, &ms_pm, &cache_note);
  if (!model) return reportError(model.error());
  LodDrawing& lod_drawing = **model;
  const LineDrawing& drawing = lod_drawing.drawing();
  const size_t model_vertices = drawing.mesh().vertexCount(), model_faces = drawing.mesh().faceCount();
  stage.lap();

  const float aspect = static_cast<float>(rp.width) / static_cast<float>(rp.height);
  const Camera camera = orbitCamera(drawing.bounds(), resolved->orbit, resolved->fov_deg, aspect);
  std::array<bool, kLineKindCount> enabled{};
  for (int k = 0; k < kLineKindCount; ++k) enabled[k] = rp.lines.kinds[k].enabled;
  // A still image shows the converged detail.
  auto steps = lod_drawing.converge(camera, rp.width, rp.height, detail->params, 1.0f / 30.0f,
                                    detail->max_adapt_frames, enabled);
  if (!steps) return reportError(steps.error());
  const double ms_adapt = stage.lap();

  // --backend soft: the software rasteriser (raster/), no OpenGL context is created.
  std::optional<Result<HeadlessRenderer>> headless;
  SoftRenderer soft_renderer;
  Image image;
  DepthImage depth;
  double ms_setup = 0.0, ms_render = 0.0, ms_readback = 0.0;
  if (soft) {
    soft_renderer.setMesh(drawing.mesh().positions, drawing.normals(), drawing.mesh().faces);
    soft_renderer.setLines(drawing.lines());
    ms_setup = stage.lap();
    soft_renderer.draw(camera, rp);
    ms_render = stage.lap();
    image = soft_renderer.image();
    depth = soft_renderer.depth();
    ms_readback = stage.lap();
  } else {
    headless = HeadlessRenderer::create(*backend, rp);
    if (!*headless) return reportError(headless->error());
    (*headless)->setMesh(drawing);
    ms_setup = stage.lap();
    (*headless)->draw(drawing, camera, rp);
    ms_render = stage.lap();
    image = (*headless)->readImage();
    ms_readback = stage.lap();
    depth = (*headless)->readDepth();
  }

  // Visible lines, from the depth buffer of the faces just drawn: for the SVG and the stats.
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
    // Pixels the model covers (differ from the background): the image area detail control
    // divides by T.
    size_t coverage = 0;
    for (size_t i = 0; i < image.rgba.size(); i += 4) {
      const int dr = std::abs(image.rgba[i] - static_cast<int>(std::lround(rp.background.r * 255.0f)));
      const int dg = std::abs(image.rgba[i + 1] - static_cast<int>(std::lround(rp.background.g * 255.0f)));
      const int db = std::abs(image.rgba[i + 2] - static_cast<int>(std::lround(rp.background.b * 255.0f)));
      coverage += std::max({dr, dg, db}) > 8;
    }
    j["image"]["coverage_px"] = coverage;
    if (soft) {
      j["context"] = {{"backend", "soft"}, {"gl", "none"}};
      j["faces_drawn"] = soft_renderer.faceCount();
      j["line_segments"] = soft_renderer.segmentsDrawn();
      const SoftTimes& st = soft_renderer.times();
      j["soft_ms"] = {{"transform", st.transform}, {"setup", st.setup}, {"raster", st.raster},
                      {"shade", st.shade}, {"lines", st.lines}};
    } else {
      j["context"] = {{"backend", backendName((*headless)->context().backend())},
                      {"gl", (*headless)->context().description()}};
      j["faces_drawn"] = (*headless)->renderer().faceCount();
      j["line_segments"] = (*headless)->renderer().segmentsDrawn();
    }
    nlohmann::json lines, extracted;
    for (int k = 0; k < kLineKindCount; ++k) {
      const char* name = lineKindName(static_cast<LineKind>(k));
      lines[name] = rp.lines.kinds[k].enabled ? visible_segments[k] : 0;
      extracted[name] = drawing.lines().count[k] / 2;
    }
    j["lines"] = lines;
    if (const VertexClustering* vc = lod_drawing.clustering()) {
      const ClusterStats& cs = vc->stats();
      j["cluster"] = {{"faces", cs.faces},
                      {"representatives", cs.representatives},
                      {"absorbed", cs.absorbed},
                      {"culled_vertices", cs.culled_vertices},
                      {"culled_faces", cs.culled_faces},
                      {"collapsed_faces", cs.collapsed_faces},
                      {"duplicate_faces", cs.duplicate_faces}};
    }
    if (const AdaptiveMesh* lod = lod_drawing.lod()) {
      const LodStats& ls = lod->stats();
      float band = 0.0f;
      uint32_t visible_faces = 0;
      lod->measureBand(band, visible_faces);
      j["lod"] = {{"active_vertices", lod->activeVertexCount()}, {"active_faces", lod->activeFaceCount()},
                  {"visible_faces", visible_faces}, {"splits", ls.splits}, {"collapses", ls.collapses},
                  {"morphing", ls.morphing}, {"band_fraction", band}, {"target_area", ls.target_area},
                  {"adapt_steps", *steps}, {"cache", cache_note}};
    }
    j["lines_extracted"] = extracted;
    j["strokes"] = visible.strokeCount();
    j["specks"] = std::count_if(visible.length_px.begin(), visible.length_px.end(),
                                [](float len) { return len < 3.0f; });
    // Pixels under the visible strokes, rasterised 1 px wide (as capture's metrics count them).
    LineMask line_mask;
    rasterizeStrokes(visible, rp.width, rp.height, line_mask);
    j["line_pixels"] = std::count(line_mask.on.begin(), line_mask.on.end(), uint8_t{1});
    j["ms"] = {{"load", ms_load}, {"pm", ms_pm}, {"adapt", ms_adapt},   {"shape", t.shape},   {"view", t.view},
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
                  "constant-depth scanlines, no OpenGL context; docs/softraster.md)")
      ->capture_default_str();
  return {cmd, [o] { return runRender(*o); }};
}

}  // namespace lodline
