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
#include "export/svg.h"
#include "export/visibility.h"
#include "io/atomic_file.h"
#include "io/image.h"
#include "io/load_mesh.h"
#include "raster/soft_renderer.h"
#include "export/coherence.h"

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

SvgStyle svgStyleOf(const RenderParams& rp) {
  SvgStyle style;
  style.background = rp.background.a > 0.0f;
  style.background_colour = colorToHex(rp.background);
  for (int k = 0; k < kLineKindCount; ++k) {
    const LineStyle& ls = rp.lines.kinds[k];
    style.lines[k] = {colorToHex(ls.color), ls.width_px, ls.color.a};
  }
  return style;
}

int runRender(CLI::App& cmd, RenderOptions& o) {
  Stopwatch total;
  // Checked again after the scene's settings are applied; first here, to fail early.
  if (auto backend = parseContextBackend(o.context); !backend) return reportError(backend.error());
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

  auto loaded_input = loadInput(cmd, o.view, o.detail);
  if (!loaded_input) return reportError(loaded_input.error());
  LoadedScene& loaded = **loaded_input;
  // Options the scene's settings may have set are read from here on.
  if (o.backend != "gl" && o.backend != "soft")
    return reportError(Error::usage("--backend: expected gl or soft, got '" + o.backend + "'"));
  auto backend = parseContextBackend(o.context);
  if (!backend) return reportError(backend.error());
  const bool soft = o.backend == "soft";
  SceneDrawing& scene = loaded.drawing;
  if (soft && scene.size() != 1)
    return reportError(Error::usage("--backend soft draws one object; this scene has " + std::to_string(scene.size()) +
                                    " (use --backend gl)"));
  const RenderParams& rp = loaded.view.render;
  const ResolvedDetail& detail = loaded.detail;
  Stopwatch stage;

  const float aspect = static_cast<float>(rp.width) / static_cast<float>(rp.height);
  auto camera_result = initialCamera(loaded, aspect);
  if (!camera_result) return reportError(camera_result.error());
  const Camera camera = *camera_result;
  // A still image shows the converged detail.
  auto steps = scene.converge(camera, rp.width, rp.height, detail.params, 1.0f / 30.0f, detail.max_adapt_frames);
  if (!steps) return reportError(steps.error());
  const double ms_adapt = stage.lap();

  // --backend soft: the software rasteriser (raster/), no OpenGL context is created.
  std::optional<Result<HeadlessRenderer>> headless;
  SoftRenderer soft_renderer;
  Image image;
  DepthImage depth;
  double ms_setup = 0.0, ms_render = 0.0, ms_readback = 0.0;
  if (soft) {
    const LineDrawing& drawing = scene[0].drawing->drawing();
    soft_renderer.setMesh(drawing.mesh().positions, drawing.normals(), drawing.mesh().faces);
    soft_renderer.setLines(drawing.lines());
    ms_setup = stage.lap();
    // The object's style on the frame's page (size, background, msaa).
    RenderParams p = scene[0].style;
    p.width = rp.width;
    p.height = rp.height;
    p.background = rp.background;
    p.msaa = rp.msaa;
    soft_renderer.draw(camera, p);
    ms_render = stage.lap();
    image = soft_renderer.image();
    depth = soft_renderer.depth();
    ms_readback = stage.lap();
  } else {
    headless = HeadlessRenderer::create(*backend, rp);
    if (!*headless) return reportError(headless->error());
    if (Status s = (*headless)->setMeshes(scene, true); !s) return reportError(s.error());
    ms_setup = stage.lap();
    (*headless)->draw(scene, camera, rp);
    ms_render = stage.lap();
    image = (*headless)->readImage();
    ms_readback = stage.lap();
    depth = (*headless)->readDepth();
  }

  // Visible lines of every object, from the depth buffer of all faces just drawn (so one
  // object hides another's lines): for the SVG and the stats.
  std::vector<VisibleStrokes> visible(scene.size());
  std::vector<std::array<uint32_t, kLineTypeCount>> visible_segments(scene.size());
  LineMask line_mask, object_mask;
  for (size_t i = 0; i < scene.size(); ++i) {
    const LineDrawing& d = scene[i].drawing->drawing();
    visibleStrokes(d.strokes(), camera, depth, {}, visible[i]);
    visible_segments[i] = countVisibleSegments(d.segments(), camera, depth);
  }
  const double ms_visibility = stage.lap();

  if (!o.output.empty())
    if (Status s = writePng(o.output, image); !s) return reportError(s.error());
  if (!o.svg.empty()) {
    std::vector<SvgLayer> layers;
    for (size_t i = 0; i < scene.size(); ++i) {
      const VisibleStrokes& v = visible[i];
      layers.push_back({scene[i].name, SvgStrokes{v.points, v.offsets, v.types, v.opacity}, svgStyleOf(scene[i].style)});
    }
    if (Status s = writeSvgLayers(o.svg, rp.width, rp.height, layers, svgStyleOf(rp)); !s) return reportError(s.error());
  }

  if (!o.stats.empty()) {
    const CpuTimings t = scene.timings();
    nlohmann::json j;
    j["model"] = {{"path", loaded.view.model.string()}, {"vertices", scene.inputVertexCount()}, {"faces", scene.inputFaceCount()}};
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
    std::vector<size_t> faces_drawn(scene.size()), segments_drawn(scene.size());
    if (soft) {
      j["context"] = {{"backend", "soft"}, {"gl", "none"}};
      faces_drawn[0] = soft_renderer.faceCount();
      segments_drawn[0] = soft_renderer.segmentsDrawn();
      const SoftTimes& st = soft_renderer.times();
      j["soft_ms"] = {{"transform", st.transform}, {"setup", st.setup}, {"raster", st.raster},
                      {"shade", st.shade}, {"lines", st.lines}};
    } else {
      j["context"] = {{"backend", backendName((*headless)->context().backend())},
                      {"gl", (*headless)->context().description()}};
      for (size_t i = 0; i < scene.size(); ++i) {
        faces_drawn[i] = (*headless)->renderer().faceCount(i);
        segments_drawn[i] = (*headless)->renderer().segmentsDrawn(i);
      }
    }
    // Per object, then the totals at the top level (the keys a single model always had).
    nlohmann::json objects = nlohmann::json::array();
    size_t total_faces_drawn = 0, total_segments = 0, total_strokes = 0, total_specks = 0;
    uint64_t total_line_pixels = 0;
    std::array<uint64_t, kLineKindCount> lines_total{}, extracted_total{};
    uint64_t active_vertices = 0, active_faces = 0, visible_faces = 0, splits = 0, collapses = 0, morphing = 0;
    double band_weighted = 0.0;
    bool any_lod = false;
    for (size_t i = 0; i < scene.size(); ++i) {
      const SceneDrawing::Object& obj = scene[i];
      const LineDrawing& d = obj.drawing->drawing();
      rasterizeStrokes(visible[i], rp.width, rp.height, object_mask);
      const uint64_t line_pixels = object_mask.count();
      nlohmann::json lines, extracted;
      for (int k = 0; k < kLineKindCount; ++k) {
        const char* name = lineKindName(static_cast<LineKind>(k));
        const uint32_t vis = obj.style.lines.kinds[k].enabled ? visible_segments[i][k] : 0;
        lines[name] = vis;
        extracted[name] = d.lines().count[k] / 2;
        lines_total[k] += vis;
        extracted_total[k] += d.lines().count[k] / 2;
      }
      const size_t specks = countSpecks(visible[i].length_px);
      nlohmann::json oj = {{"name", obj.name},
                           {"vertices", obj.input_vertices},
                           {"faces", obj.input_faces},
                           {"detail_factor", obj.detail_factor},
                           {"style", styleName(obj.style.style)},
                           {"faces_drawn", faces_drawn[i]},
                           {"line_segments", segments_drawn[i]},
                           {"lines", lines},
                           {"lines_extracted", extracted},
                           {"strokes", visible[i].strokeCount()},
                           {"specks", specks},
                           {"line_pixels", line_pixels}};
      if (const AdaptiveMesh* lod = obj.drawing->lod()) {
        const LodStats& ls = lod->stats();
        float band = 0.0f;
        uint32_t vis_faces = 0;
        lod->measureBand(band, vis_faces);
        oj["lod"] = {{"active_vertices", lod->activeVertexCount()}, {"active_faces", lod->activeFaceCount()},
                     {"visible_faces", vis_faces}, {"splits", ls.splits}, {"collapses", ls.collapses},
                     {"morphing", ls.morphing}, {"band_fraction", band}, {"target_area", ls.target_area}};
        any_lod = true;
        active_vertices += lod->activeVertexCount();
        active_faces += lod->activeFaceCount();
        visible_faces += vis_faces;
        splits += ls.splits;
        collapses += ls.collapses;
        morphing += ls.morphing;
        band_weighted += static_cast<double>(band) * vis_faces;
      }
      if (const VertexClustering* vc = obj.drawing->clustering()) {
        const ClusterStats& cs = vc->stats();
        oj["cluster"] = {{"faces", cs.faces},
                         {"representatives", cs.representatives},
                         {"absorbed", cs.absorbed},
                         {"culled_vertices", cs.culled_vertices},
                         {"culled_faces", cs.culled_faces},
                         {"collapsed_faces", cs.collapsed_faces},
                         {"duplicate_faces", cs.duplicate_faces}};
        if (scene.size() == 1) j["cluster"] = oj["cluster"];
      }
      objects.push_back(oj);
      total_faces_drawn += faces_drawn[i];
      total_segments += segments_drawn[i];
      total_strokes += visible[i].strokeCount();
      total_specks += specks;
    }
    // Line pixels of the whole image count a pixel two objects share once.
    {
      VisibleStrokes all;
      for (const VisibleStrokes& v : visible) appendStrokes(v, all);
      rasterizeStrokes(all, rp.width, rp.height, line_mask);
      total_line_pixels = line_mask.count();
    }
    j["faces_drawn"] = total_faces_drawn;
    j["line_segments"] = total_segments;
    nlohmann::json lines, extracted;
    for (int k = 0; k < kLineKindCount; ++k) {
      lines[lineKindName(static_cast<LineKind>(k))] = lines_total[k];
      extracted[lineKindName(static_cast<LineKind>(k))] = extracted_total[k];
    }
    j["lines"] = lines;
    if (any_lod) {
      j["lod"] = {{"active_vertices", active_vertices}, {"active_faces", active_faces},
                  {"visible_faces", visible_faces}, {"splits", splits}, {"collapses", collapses},
                  {"morphing", morphing},
                  {"band_fraction", visible_faces ? band_weighted / static_cast<double>(visible_faces) : 0.0},
                  {"target_area", detail.params.target_area * detail.params.object_factor},
                  {"adapt_steps", *steps}, {"cache", loaded.cache_note}};
    }
    j["lines_extracted"] = extracted;
    j["strokes"] = total_strokes;
    j["specks"] = total_specks;
    j["line_pixels"] = total_line_pixels;
    j["objects"] = objects;
    j["ms"] = {{"load", loaded.load_ms}, {"pm", loaded.pm_ms}, {"adapt", ms_adapt},   {"shape", t.shape},   {"view", t.view},
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
                  "constant-depth scanlines, no OpenGL context; docs/softraster.md)")
      ->capture_default_str();
  return {cmd, [o, cmd] { return runRender(*cmd, *o); }};
}

}  // namespace lodline
