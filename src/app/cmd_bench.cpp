// `lodline bench walkthrough MODEL --path P [--frames N]`: the walkthrough benchmark of Pan,
// Zhou, Shi, "Real-time rendering algorithm based on hybrid static and dynamic simplification
// methods" (their Table 2; DESIGN.md §4), on today's machine. One camera path is replayed
// for four levels of detail, side by side in one run:
//   none     the full-detail mesh;
//   cluster  view-dependent vertex clustering every frame (src/lod/vertex_clustering.h);
//   hybrid   static pre-simplification within --pre-simplify of the diagonal (E_s measured
//            with CGAL), then clustering;
//   pm       the progressive mesh with image-area detail control (Jeong et al. 2005).
// A frame is the CPU stages (LOD, shape, lines) plus the GL draw up to glFinish, headless, with
// lines. Prints a markdown table (mean fps, ms per frame, triangles drawn).
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

#include "app/commands.h"
#include "app/headless.h"
#include "app/model.h"
#include "app/options.h"
#include "io/scene_file.h"
#include "core/timer.h"
#include "frame/camera_path.h"
#include "io/load_mesh.h"
#include "pm/pm_file.h"

namespace lodline {

namespace {

struct BenchOptions {
  std::string model;
  std::string path = "orbit";
  int frames = 60;
  float pixel_error = 1.0f;
  std::string pre_simplify = "0.02%";
  float target_area = DetailParams{}.target_area;
  std::string size = "1280x720";
  int msaa = 4;
  std::string context = "auto";
  std::string cache_dir;
  std::string modes = "none,cluster,hybrid,pm";
};

struct ModeResult {
  std::string mode;
  double mean_ms = 0.0, cpu_ms = 0.0, gl_ms = 0.0;
  double faces = 0.0;     ///< mean triangles drawn per frame
  size_t model_faces = 0; ///< faces of the mesh the mode starts from
  double setup_s = 0.0;   ///< load + preprocessing (PM build or cache, pre-simplification)
  std::string note;
};

int runWalkthrough(const BenchOptions& o) {
  auto size = parseSize(o.size);
  if (!size) return reportError(size.error());
  auto backend = parseContextBackend(o.context);
  if (!backend) return reportError(backend.error());
  if (o.frames < 2 || o.frames > 100000) return reportError(Error::usage("--frames: must be in [2, 100000]"));
  if (!(o.pixel_error > 0.0f)) return reportError(Error::usage("--pixel-error: must be > 0"));
  if (!(o.target_area > 0.0f)) return reportError(Error::usage("--target-area: must be > 0"));
  if (o.msaa < 1 || o.msaa > 16) return reportError(Error::usage("--msaa: must be in [1, 16]"));
  auto bound = parsePercent(o.pre_simplify, "--pre-simplify");
  if (!bound) return reportError(bound.error());
  std::vector<std::string> modes;
  {
    std::stringstream ss(o.modes);
    std::string m;
    while (std::getline(ss, m, ','))
      if (m == "none" || m == "cluster" || m == "hybrid" || m == "pm") modes.push_back(m);
      else return reportError(Error::usage("--modes: unknown mode '" + m + "' (none, cluster, hybrid, pm)"));
  }
  RenderParams rp;
  rp.width = (*size)[0];
  rp.height = (*size)[1];
  rp.msaa = o.msaa;
  const float aspect = static_cast<float>(rp.width) / static_cast<float>(rp.height);

  Stopwatch sw;
  // The model may be a scene: every object is walked through with the same level of detail
  // (its own detail factor and style from the scene file; the scene's settings do not apply,
  // the benchmark's options do).
  auto scene = loadScene(std::filesystem::path(o.model));
  if (!scene) return reportError(scene.error());
  struct BenchObject {
    const SceneObject* source;
    TriMesh mesh;
    RenderParams style;
  };
  std::vector<BenchObject> objects;
  size_t input_faces = 0;
  Bounds bounds;
  for (const SceneObject& obj : scene->objects) {
    auto mesh = loadObjectMesh(obj);
    if (!mesh) return reportError(mesh.error());
    ViewOptions vo;
    auto style = resolveObjectStyle(vo, obj.style, obj.where);
    if (!style) return reportError(style.error());
    style->msaa = o.msaa;
    const Bounds b = computeBounds(mesh->positions);
    bounds = objects.empty() ? b : unionBounds(bounds, b);
    input_faces += mesh->faceCount();
    objects.push_back({&obj, std::move(mesh.value()), *style});
  }
  const double load_s = sw.lap() / 1000.0;
  const double duration = o.frames / 30.0;
  Result<CameraPath> path = Error::usage("");
  {
    bool builtin = false;
    for (const auto& n : builtinPathNames()) builtin = builtin || n == o.path;
    path = builtin ? builtinPath(o.path, bounds, 35.0f, aspect, duration) : loadCameraPath(o.path);
  }
  if (!path) return reportError(path.error());
  auto headless = HeadlessRenderer::create(*backend, rp);
  if (!headless) return reportError(headless.error());

  std::vector<ModeResult> results;
  for (const std::string& mode : modes) {
    ModeResult r;
    r.mode = mode;
    sw.lap();
    ClusterParams cp;
    cp.pixel_error = o.pixel_error;
    SceneDrawing lod;
    auto pool = std::make_shared<WorkerPool>(ShapeParams{}.threads);
    for (const BenchObject& bo : objects) {
      SceneDrawing::Object so;
      so.name = bo.source->name;
      so.style = bo.style;
      so.detail_factor = bo.source->detail_factor;
      so.input_faces = bo.mesh.faceCount();
      so.input_vertices = bo.mesh.vertexCount();
      const std::string what = bo.source->mesh.string();
      if (mode == "none") {
        so.drawing = std::make_unique<LodDrawing>(bo.mesh, LineParams{}, pool);
        r.model_faces += bo.mesh.faceCount();
      } else if (mode == "cluster") {
        so.drawing = std::make_unique<LodDrawing>(bo.mesh, cp, LineParams{}, pool);
        r.model_faces += bo.mesh.faceCount();
      } else if (mode == "hybrid") {
        auto s = simplifyMesh(bo.mesh, *bound, what);
        if (!s) return reportError(s.error());
        std::ostringstream note;
        note << (r.note.empty() ? "" : "; ") << "pre-simplified " << bo.mesh.faceCount() << " -> "
             << s->mesh.faceCount() << " faces, E_s " << std::setprecision(3) << 100.0 * s->e_s_rel << "%";
        r.note += note.str();
        r.model_faces += s->mesh.faceCount();
        so.drawing = std::make_unique<LodDrawing>(std::move(s->mesh), cp, LineParams{}, pool);
      } else {
        const std::filesystem::path dir = o.cache_dir.empty() ? defaultCacheDir() : std::filesystem::path(o.cache_dir);
        std::string note;
        auto pm = loadOrBuildPm(bo.mesh, meshContentHash(bo.mesh), dir, {}, {}, &note);
        if (!pm) return reportError(Error::runtime(what + ": " + pm.error().message));
        r.note += (r.note.empty() ? "" : "; ") + note;
        r.model_faces += bo.mesh.faceCount();
        so.drawing = std::make_unique<LodDrawing>(bo.mesh, std::make_shared<const ProgressiveMesh>(std::move(pm.value())),
                                                  LineParams{}, pool);
      }
      lod.add(std::move(so));
    }
    DetailParams detail;
    detail.target_area = o.target_area;
    const double dt = path->duration() / (o.frames - 1);
    // Warm-up (not timed): the progressive mesh converges at the first camera, as a viewer
    // would before the walk starts; every mode uploads its first mesh.
    const Camera first = path->at(path->keys().front().time, lod.bounds());
    if (auto st = lod.converge(first, rp.width, rp.height, detail, static_cast<float>(dt), 300); !st)
      return reportError(st.error());
    if (Status st = headless->setMeshes(lod, true); !st) return reportError(st.error());
    headless->draw(lod, first, rp);
    r.setup_s = sw.lap() / 1000.0 + load_s;
    double total = 0.0, cpu = 0.0, gl = 0.0, faces = 0.0;
    for (int i = 0; i < o.frames; ++i) {
      const double t = path->keys().front().time + i * dt;
      const Camera cam = path->at(t, lod.bounds());
      Stopwatch frame;
      if (Status st = lod.frame(cam, rp.width, rp.height, detail, static_cast<float>(dt)); !st)
        return reportError(st.error());
      if (Status st = headless->setMeshes(lod, false); !st) return reportError(st.error());
      const double c = frame.elapsed();
      headless->draw(lod, cam, rp);
      const double all = frame.elapsed();
      total += all;
      cpu += c;
      gl += all - c;
      faces += static_cast<double>(headless->renderer().faceCount());
    }
    r.mean_ms = total / o.frames;
    r.cpu_ms = cpu / o.frames;
    r.gl_ms = gl / o.frames;
    r.faces = faces / o.frames;
    results.push_back(r);
    std::cerr << "lodline: " << mode << ": " << std::fixed << std::setprecision(1) << 1000.0 / r.mean_ms << " fps\n";
  }

  std::cout << "Walkthrough of " << o.model << " (" << input_faces << " faces"
            << (objects.size() > 1 ? " in " + std::to_string(objects.size()) + " objects" : std::string()) << "), path " << o.path << ", "
            << o.frames << " frames at " << rp.width << "x" << rp.height << ", msaa " << rp.msaa
            << ", pixel error " << o.pixel_error << " px^2, T " << o.target_area << " px^2; "
            << headless->context().description() << "\n\n";
  std::cout << "| mode | mean fps | ms/frame | CPU ms | GL ms | triangles drawn | mesh faces | setup s | note |\n"
            << "|---|---:|---:|---:|---:|---:|---:|---:|---|\n";
  for (const auto& r : results) {
    std::cout << std::fixed << "| " << r.mode << " | " << std::setprecision(2) << 1000.0 / r.mean_ms << " | "
              << std::setprecision(1) << r.mean_ms << " | " << r.cpu_ms << " | " << r.gl_ms << " | "
              << std::setprecision(0) << r.faces << " | " << r.model_faces << " | " << std::setprecision(2)
              << r.setup_s << " | " << r.note << " |\n";
  }
  if (results.size() > 1 && results[0].mode == "none") {
    std::cout << "\nfps ratios to no LOD:";
    for (size_t i = 1; i < results.size(); ++i)
      std::cout << ' ' << results[i].mode << ' ' << std::setprecision(2) << results[0].mean_ms / results[i].mean_ms
                << 'x';
    std::cout << " (Pan et al. 1999, bunny at 1 px: cluster 2.48x, hybrid 6.78x)\n";
  }
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
      "progressive mesh; print mean fps and triangles drawn (Pan/Zhou/Shi Table 2)");
  walk->add_option("model", o->model, "Mesh, scene (.json) or glTF file")->required();
  walk->add_option("--path", o->path, "Camera path: a JSON path file (docs/capture.md) or orbit, zoom-out, dolly, flyover")
      ->capture_default_str();
  walk->add_option("--frames", o->frames, "Frames replayed per mode (built-in paths last frames/30 s)")
      ->capture_default_str();
  walk->add_option("--pixel-error", o->pixel_error, "Clustering pixel error K, px^2")->capture_default_str();
  walk->add_option("--pre-simplify", o->pre_simplify, "Hybrid: static E_s bound, % of the diagonal")
      ->capture_default_str();
  walk->add_option("--target-area", o->target_area, "Progressive mesh: target triangle area T, px^2")
      ->capture_default_str();
  walk->add_option("--size", o->size, "Image size")->capture_default_str();
  walk->add_option("--msaa", o->msaa, "Multisample count")->capture_default_str();
  walk->add_option("--context", o->context, "OpenGL context: auto, egl or osmesa")->capture_default_str();
  walk->add_option("--cache-dir", o->cache_dir, "Progressive-mesh cache directory");
  walk->add_option("--modes", o->modes, "Comma-separated subset of none,cluster,hybrid,pm")->capture_default_str();
  return {bench, [o, walk]() -> int {
            if (!walk->parsed()) return reportError(Error::usage("bench: expected a benchmark (walkthrough)"));
            return runWalkthrough(*o);
          }};
}

}  // namespace lodline
