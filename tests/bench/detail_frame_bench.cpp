// Cost of a detail-controlled frame (docs/design.md §8: the controlled frame of a large model
// within a small factor of drawing its adapted mesh statically, and far less than the full
// mesh). Every frame goes through the SceneDrawing and presenter `render` uses. Side by side
// in one run, 1280x720, slow orbit (1 degree per frame), EGL surfaceless, median ms per
// stage over the frames:
//   controlled: adapt + shape update + lines (view, extract, chain) + upload + draw +
//               visibility (depth readback, visible/hidden runs, outline completion)
//   static:     drawing the same adapted mesh and lines again (no CPU stages): static_ms the
//               draw alone, static_present_ms with the lines' visibility and strokes, which
//               every presented frame recomputes; over_static[_present] the ratios
//   full:       full-detail mesh: lines (view, extract, chain) + draw
// The `/fades` cases add issue 20's sequence options (docs/temporal-coherence.md): suggestive
// contours faded by their motion (3 -> 12 px/s, in lines_ms) and new lines faded in over
// 0.25 s (fade_ms, part of strokes_ms); compare them with the case above them.
//   ./build/tests/bench/detail_frame_bench --benchmark_counters_tabular=true
// (armadillo and the 1.1M knot at T = 16 px², and the knot at T = 7 px², ~100k faces)
// The `scale/` series (issue 21): the same torus knot generated at about 0.1, 0.3, 1, 3 and
// 10M faces, the same framing, T = 16 px²: the progressive mesh built in the benchmark (build
// seconds per million faces, cache bytes per face), then the controlled frame per stage and
// the process's resident memory per input face. No full-detail comparison (a 10M-face
// full-detail frame takes seconds):
//   ./build/tests/bench/detail_frame_bench --benchmark_filter=scale --benchmark_counters_tabular=true
// The `pipelined/` cases (issue 21): the next frame's stages run while a frame is presented,
// against frames drawn in turn and the whole present of the same drawing (pipelinedFrame()):
//   ./build/tests/bench/detail_frame_bench --benchmark_filter=pipelined --benchmark_counters_tabular=true
// The `line_kind/` cases time each line kind's share of the lines stage (docs/lines.md; the
// `-fit` cases: ridges and valleys from fitted jets):
//   ./build/tests/bench/detail_frame_bench --benchmark_filter=line_kind --benchmark_counters_tabular=true
// The `stages/` cases run the CPU stages alone, no drawing, 30 frames of the same orbit (the
// environment variable STAGE_ITERS sets another count): the cases to profile the stages with,
//   STAGE_ITERS=300 perf record ./build/tests/bench/detail_frame_bench --benchmark_filter=stages/knot1m/T:7
// silhouette_ms is the mesh's own silhouette for the outline, part of the frame's CPU work
// but not of lines_ms (which the issue-21 figures have always been).
// The `controlled/` cases run controlled frames alone (stages, then present, nothing else):
// the stages as an application's frame loop sees them (controlledFrames()).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <map>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "core/timer.h"
#include "frame/lod_drawing.h"
#include "frame/scene_drawing.h"
#include "gl/context.h"
#include "present/gl_presenter.h"
#include "io/generate.h"
#include "io/load_mesh.h"
#include "pm/pm_file.h"
#include "bench_util.h"
#include "test_util.h"

namespace lodline {
namespace {

struct Model {
  TriMesh mesh;
  std::shared_ptr<const ProgressiveMesh> pm;
};

// Loads (or generates) a model and its progressive mesh (cached under build/bench-cache).
std::shared_ptr<Model> loadModel(const std::string& name) {
  static std::map<std::string, std::shared_ptr<Model>> models;
  if (auto it = models.find(name); it != models.end()) return it->second;
  auto m = std::make_shared<Model>();
  if (name == "knot1m") {
    m->mesh = makeTorusKnot(2, 3, 1.0f, 0.16f, 2900, 193, 0.18f);
  } else {
    const auto p = test::dataMesh(name);
    if (p.empty()) return nullptr;
    auto mesh = loadMesh(p);
    if (!mesh) return nullptr;
    m->mesh = std::move(mesh.value());
  }
  auto pm = loadOrBuildPm(m->mesh, meshContentHash(m->mesh), std::filesystem::temp_directory_path() / "lodline-bench-cache");
  if (!pm) return nullptr;
  m->pm = std::make_shared<const ProgressiveMesh>(std::move(pm.value()));
  models[name] = m;
  return m;
}

// A scene of one object drawn in the default style.
SceneDrawing sceneOf(std::unique_ptr<LodDrawing> drawing, const std::string& name) {
  SceneDrawing scene;
  SceneDrawing::Object o;
  o.name = name;
  o.input_faces = drawing->drawing().mesh().faceCount();
  o.drawing = std::move(drawing);
  scene.add(std::move(o));
  return scene;
}

// The frame cases' orbit: `azimuth` degrees around the scene (1° a frame), 20° up, at
// `distance` (0: the default framing), 35° field of view.
Camera orbitAt(const SceneDrawing& scene, float azimuth, float aspect, float distance = 0.0f) {
  return orbitCamera(scene.bounds(), {azimuth, 20.0f, distance}, 35.0f, aspect);
}

// Converges the scene's detail at the orbit's first camera, as captures do.
void convergeAtStart(SceneDrawing& scene, const FrameParams& frame, const DetailParams& detail,
                     float distance = 0.0f) {
  (void)scene.converge(orbitAt(scene, 0.0f, frame.aspect(), distance), frame.width, frame.height, detail,
                       1.0f / 30.0f, 300);
}

// Per-stage milliseconds of the last frame of a scene: adapt, shape (where the mesh
// changed), lines; and the progressive meshes' splits + collapses, curvature updates and
// full recomputes.
struct Stages {
  double adapt = 0.0, shape = 0.0, lines = 0.0, ops = 0.0, curvature = 0.0, full = 0.0, faces = 0.0;
  double waiting = 0.0;  // morphing vertices whose small moves wait (ShapeParams::move_tolerance)
};
Stages stagesOf(const SceneDrawing& scene) {
  Stages st;
  for (const auto& o : scene.objects()) {
    const LodDrawing& l = *o.drawing;
    const CpuTimings& t = l.drawing().timings();
    st.adapt += l.adaptMs();
    st.lines += t.view + t.extract + t.chain;
    if (l.meshChanged()) {
      st.shape += t.shape;
      const ShapeUpdateStats& us = l.drawing().shape().lastStats();
      st.curvature += us.curvature_vertices;
      st.waiting += us.waiting_vertices;
      st.full += us.full ? 1.0 : 0.0;
    }
    if (const AdaptiveMesh* lod = l.lod()) {
      st.ops += static_cast<double>(lod->stats().splits + lod->stats().collapses);
      st.faces += static_cast<double>(lod->activeFaceCount());
    }
  }
  return st;
}

// One detail-controlled frame per call (the scene's stages, then its present), kept per
// frame; counters() writes their medians and the frame's total.
struct ControlledFrames {
  std::vector<double> adapt, shape, lines, upload, draw, visibility, strokes, fade, faces;
  void record(SceneDrawing& scene, GlPresenter& presenter, const Camera& cam, const FrameParams& frame,
              const DetailParams& detail, bool first) {
    (void)scene.frame(cam, frame.width, frame.height, detail, 1.0f / 30.0f);
    const Stages st = stagesOf(scene);
    adapt.push_back(st.adapt);
    shape.push_back(st.shape);
    lines.push_back(st.lines);
    faces.push_back(st.faces);
    (void)presenter.present(scene, cam, frame, first);
    const auto& t = presenter.times();
    upload.push_back(t.upload);
    draw.push_back(t.render);
    visibility.push_back(t.visibility);
    strokes.push_back(t.strokes);
    fade.push_back(t.fade);
  }
  double cpuMs() const { return bench::median(adapt) + bench::median(shape) + bench::median(lines); }
  double totalMs() const {
    return cpuMs() + bench::median(upload) + bench::median(draw) + bench::median(visibility) +
           bench::median(strokes);
  }
  void counters(benchmark::State& state) const {
    state.counters["active_faces"] = bench::median(faces);
    state.counters["adapt_ms"] = bench::median(adapt);
    state.counters["shape_ms"] = bench::median(shape);
    state.counters["lines_ms"] = bench::median(lines);
    state.counters["upload_ms"] = bench::median(upload);
    state.counters["draw_ms"] = bench::median(draw);
    state.counters["visibility_ms"] = bench::median(visibility);
    state.counters["strokes_ms"] = bench::median(strokes);
    state.counters["fade_ms"] = bench::median(fade);
    state.counters["controlled_ms"] = totalMs();
  }
};

// What a side-by-side frame case needs: the model, a headless EGL context and two presenters
// on it (as two windows of one program would be). Null, with the benchmark skipped and the
// reason given, when any is missing.
struct TwoPresenters {
  std::shared_ptr<Model> model;
  std::unique_ptr<GlContext> context;
  std::unique_ptr<GlPresenter> first, second;
};
std::optional<TwoPresenters> twoPresenters(benchmark::State& state, const std::string& name) {
  TwoPresenters t;
  t.model = loadModel(name);
  if (!t.model) {
    state.SkipWithError(("cannot load " + name + " (run scripts/setup.sh)").c_str());
    return std::nullopt;
  }
  auto ctx = createHeadlessContext(ContextBackend::kEgl);
  if (!ctx) {
    state.SkipWithError(ctx.error().message.c_str());
    return std::nullopt;
  }
  t.context = std::move(ctx.value());
  auto a = GlPresenter::createOnCurrentContext();
  auto b = GlPresenter::createOnCurrentContext();
  if (!a || !b) {
    state.SkipWithError("presenter set-up failed");
    return std::nullopt;
  }
  t.first = std::move(a.value());
  t.second = std::move(b.value());
  return t;
}

void detailFrame(benchmark::State& state, const std::string& name, float target_area, bool fades) {
  auto set_up = twoPresenters(state, name);
  if (!set_up) return;
  const std::shared_ptr<Model>& model = set_up->model;
  GlPresenter* controlled_presenter = set_up->first.get();
  GlPresenter* full_presenter = set_up->second.get();
  FrameParams frame;
  frame.msaa = 1;
  LineParams line_params;
  if (fades) {
    line_params.suggestive_motion_fade_start = 3.0f;
    line_params.suggestive_motion_fade_end = 12.0f;
    controlled_presenter->setFadeStep((1.0f / 30.0f) / 0.25f);
  }
  SceneDrawing controlled =
      sceneOf(std::make_unique<LodDrawing>(model->mesh, model->pm, line_params), name);
  SceneDrawing full = sceneOf(std::make_unique<LodDrawing>(model->mesh), name);
  DetailParams detail;
  detail.target_area = target_area;
  const float aspect = frame.aspect();
  // Converge at the first camera, as captures do.
  convergeAtStart(controlled, frame, detail);
  ControlledFrames frames;
  std::vector<double> static_draw, static_present, full_lines, full_draw;
  float az = 0.0f;
  bool first = true;
  for (auto _ : state) {
    const Camera cam = orbitAt(controlled, az, aspect);
    az += 1.0f;
    frames.record(controlled, *controlled_presenter, cam, frame, detail, first);
    // The same adapted mesh drawn again: the static cost of what controlled detail draws
    // (the draw alone, and the whole present: upload, draw, visibility of the lines, strokes).
    (void)controlled_presenter->present(controlled, cam, frame, false);
    const auto& again = controlled_presenter->times();
    static_draw.push_back(again.render);
    static_present.push_back(again.upload + again.render + again.visibility + again.strokes);
    // Full detail: lines on the full mesh, full mesh drawn.
    Stopwatch sw;
    (void)full.frame(cam, frame.width, frame.height, detail, 1.0f / 30.0f);
    full_lines.push_back(sw.lap());
    (void)full_presenter->present(full, cam, frame, first);
    full_draw.push_back(sw.lap());
    first = false;
  }
  const double controlled_total = frames.totalMs();
  frames.counters(state);
  state.counters["model_faces"] = static_cast<double>(model->mesh.faceCount());
  state.counters["static_ms"] = bench::median(static_draw);
  state.counters["static_present_ms"] = bench::median(static_present);
  state.counters["over_static"] = controlled_total / bench::median(static_draw);
  state.counters["over_static_present"] = controlled_total / bench::median(static_present);
  state.counters["full_lines_ms"] = bench::median(full_lines);
  state.counters["full_draw_ms"] = bench::median(full_draw);
  state.counters["full_ms"] = bench::median(full_lines) + bench::median(full_draw);
}

// Controlled frames alone, one after the other (issue 21): each iteration computes a frame's
// CPU stages and presents it, nothing else, as `view` and `capture --metrics` do. In
// `detail_frame/` each controlled frame is followed by the static redraw and the full-detail
// frame of the same model; here the stage times are those of an application's frame loop.
// On llvmpipe they read as in `detail_frame/`, 40-50% above `stages/` (docs/performance.md,
// "The CPU stages alone and in a frame"): the software rasteriser, running on the same cores,
// takes the caches. Same orbit, convergence and counters as `detail_frame/`; STAGE_ITERS sets
// the frame count, as for `stages/`, to profile the stages as a frame leaves the caches:
//   STAGE_ITERS=300 perf record ./build/tests/bench/detail_frame_bench --benchmark_filter=controlled/knot1m/T:7
void controlledFrames(benchmark::State& state, const std::string& name, float target_area) {
  auto set_up = twoPresenters(state, name);
  if (!set_up) return;
  FrameParams frame;
  frame.msaa = 1;
  SceneDrawing controlled = sceneOf(std::make_unique<LodDrawing>(set_up->model->mesh, set_up->model->pm), name);
  DetailParams detail;
  detail.target_area = target_area;
  convergeAtStart(controlled, frame, detail);
  ControlledFrames frames;
  float az = 0.0f;
  for (auto _ : state) {
    frames.record(controlled, *set_up->first, orbitAt(controlled, az, frame.aspect()), frame, detail, az == 0.0f);
    az += 1.0f;
  }
  frames.counters(state);
  state.counters["cpu_ms"] = frames.cpuMs();
}

// Frames in a pipeline (issue 21; docs/performance.md, "Frames in a pipeline"): frame i + 1's
// CPU stages run on a second thread while frame i is presented (ScenePresenter::present's
// `overlap`). Two identical scenes take the same orbit, one frame after the other in each
// iteration: `pipelined` presents frame i while its stages compute frame i + 1, `sequential`
// computes its stages and then presents. The wall time of each frame, then `present`: the
// sequential scene's drawing presented again (upload, draw, visibility, strokes). The two
// scenes' drawings are the same frame for frame (`same_faces` counts the frames whose active
// face counts agree; the images are compared in tests/present/presenter_test.cpp).
//   ./build/tests/bench/detail_frame_bench --benchmark_filter=pipelined --benchmark_counters_tabular=true
void pipelinedFrame(benchmark::State& state, const std::string& name, float target_area) {
  auto set_up = twoPresenters(state, name);
  if (!set_up) return;
  const std::shared_ptr<Model>& model = set_up->model;
  GlPresenter* pipelined_presenter = set_up->first.get();
  GlPresenter* sequential_presenter = set_up->second.get();
  FrameParams frame;
  frame.msaa = 1;
  SceneDrawing pipelined = sceneOf(std::make_unique<LodDrawing>(model->mesh, model->pm), name);
  SceneDrawing sequential = sceneOf(std::make_unique<LodDrawing>(model->mesh, model->pm), name);
  DetailParams detail;
  detail.target_area = target_area;
  const float aspect = frame.aspect();
  const float dt = 1.0f / 30.0f;
  auto camera = [&](int i) { return orbitAt(pipelined, static_cast<float>(i), aspect); };
  for (SceneDrawing* s : {&pipelined, &sequential}) convergeAtStart(*s, frame, detail);
  (void)pipelined.frame(camera(0), frame.width, frame.height, detail, dt);  // frame 0's stages
  std::vector<double> pipe_ms, seq_ms, present_ms, overlapped_stages;
  double same = 0.0;
  int i = 0;
  for (auto _ : state) {
    const bool first = i == 0;
    const double pipe_faces = stagesOf(pipelined).faces;  // frame i, computed during the last present
    Stopwatch sw;
    (void)pipelined_presenter
        ->present(pipelined, camera(i), frame, first,
                  [&] {
                    Stopwatch st;
                    (void)pipelined.frameWhileDrawing(camera(i + 1), frame.width, frame.height, detail, dt);
                    overlapped_stages.push_back(st.lap());
                  });
    pipe_ms.push_back(sw.lap());
    (void)sequential.frame(camera(i), frame.width, frame.height, detail, dt);
    same += stagesOf(sequential).faces == pipe_faces;
    (void)sequential_presenter->present(sequential, camera(i), frame, first);
    seq_ms.push_back(sw.lap());
    (void)sequential_presenter->present(sequential, camera(i), frame, false);
    present_ms.push_back(sw.lap());
    ++i;
  }
  const double pipe = bench::median(pipe_ms), seq = bench::median(seq_ms), present = bench::median(present_ms);
  state.counters["pipelined_ms"] = pipe;
  state.counters["sequential_ms"] = seq;
  state.counters["present_ms"] = present;
  state.counters["pipelined_over_present"] = pipe / present;
  state.counters["sequential_over_present"] = seq / present;
  state.counters["same_faces"] = same;
  state.counters["overlapped_stages_ms"] = bench::median(overlapped_stages);
}

// The CPU stages alone (adapt, shape, lines), no drawing: the case to profile them with
// (`perf record ... --benchmark_filter=stages/knot1m/T:7`). Same orbit and convergence as
// detailFrame; one thread per core as in a frame.
void stagesFrame(benchmark::State& state, const std::string& name, float target_area) {
  const std::shared_ptr<Model> model = loadModel(name);
  if (!model) {
    state.SkipWithError(("cannot load " + name + " (run scripts/setup.sh)").c_str());
    return;
  }
  FrameParams frame;
  SceneDrawing scene = sceneOf(std::make_unique<LodDrawing>(model->mesh, model->pm), name);
  DetailParams detail;
  detail.target_area = target_area;
  const float aspect = frame.aspect();
  convergeAtStart(scene, frame, detail);
  std::vector<double> adapt, shape, lines, faces, silhouette, curvature, waiting;
  double full = 0.0, ordered = 0.0;
  float az = 0.0f;
  for (auto _ : state) {
    const Camera cam = orbitAt(scene, az, aspect);
    az += 1.0f;
    (void)scene.frame(cam, frame.width, frame.height, detail, 1.0f / 30.0f);
    const Stages st = stagesOf(scene);
    full += st.full;
    curvature.push_back(st.curvature);
    waiting.push_back(st.waiting);
    silhouette.push_back(scene.objects()[0].drawing->drawing().timings().silhouette);
    if (const AdaptiveMesh* lod = scene.objects()[0].drawing->lod()) ordered += lod->stats().slots_ordered;
    adapt.push_back(st.adapt);
    shape.push_back(st.shape);
    lines.push_back(st.lines);
    faces.push_back(st.faces);
  }
  state.counters["active_faces"] = bench::median(faces);
  state.counters["adapt_ms"] = bench::median(adapt);
  state.counters["shape_ms"] = bench::median(shape);
  state.counters["lines_ms"] = bench::median(lines);
  state.counters["cpu_ms"] = bench::median(adapt) + bench::median(shape) + bench::median(lines);
  state.counters["silhouette_ms"] = bench::median(silhouette);  // the outline's input, not in lines_ms
  state.counters["full_shape_frames"] = full;   // frames whose shape update recomputed everything
  state.counters["curvature_vertices"] = bench::median(curvature);  // per frame: the work the shape update did
  state.counters["waiting_vertices"] = bench::median(waiting);  // morphing vertices not recomputed this frame
  state.counters["ordered_frames"] = ordered;   // frames that renumbered the adapted mesh's slots
}

// Resident and peak resident memory of this process, bytes (/proc/self/status).
std::pair<double, double> residentBytes() {
  std::ifstream in("/proc/self/status");
  std::string key;
  double rss = 0.0, peak = 0.0;
  while (in >> key) {
    double kb = 0.0;
    if (key == "VmRSS:" && in >> kb) rss = kb * 1024.0;
    else if (key == "VmHWM:" && in >> kb) peak = kb * 1024.0;
    else in.ignore(1 << 12, '\n');
  }
  return {rss, peak};
}

// One case of the scale series: a knot of about `faces` faces (tube segments 1/15 of the
// length's, as the 1.1M knot), built, saved, converged (as a still is) and orbited like
// detailFrame's controlled side.
void scaleFrame(benchmark::State& state, double faces, float target_area) {
  const uint32_t tube = static_cast<uint32_t>(std::lround(std::sqrt(faces / 30.0)));
  TriMesh mesh = makeTorusKnot(2, 3, 1.0f, 0.16f, 15 * tube, tube, 0.18f);
  Stopwatch sw;
  auto built = buildProgressiveMesh(mesh);
  const double build_s = sw.lap() / 1000.0;
  if (!built) {
    state.SkipWithError(built.error().message.c_str());
    return;
  }
  test::TempDir dir;
  const auto file = dir / "scale.lpm";
  if (Status st = savePm(file, *built); !st) {
    state.SkipWithError(st.error().message.c_str());
    return;
  }
  const double cache_bytes = static_cast<double>(std::filesystem::file_size(file));
  auto pm = std::make_shared<const ProgressiveMesh>(std::move(built.value()));
  auto ctx = createHeadlessContext(ContextBackend::kEgl);
  if (!ctx) {
    state.SkipWithError(ctx.error().message.c_str());
    return;
  }
  FrameParams frame;
  frame.msaa = 1;
  auto presenter = GlPresenter::createOnCurrentContext();
  if (!presenter) {
    state.SkipWithError("presenter set-up failed");
    return;
  }
  const double input_faces = static_cast<double>(mesh.faceCount());
  SceneDrawing controlled = sceneOf(std::make_unique<LodDrawing>(std::move(mesh), pm, LineParams{}), "knot");
  DetailParams detail;
  detail.target_area = target_area;
  const float aspect = frame.aspect();
  (void)controlled.converge(orbitAt(controlled, 0.0f, aspect), frame.width, frame.height, detail,
                            SceneDrawing::kConvergeStepSeconds, 300);
  ControlledFrames frames;
  float az = 0.0f;
  bool first = true;
  for (auto _ : state) {
    const Camera cam = orbitAt(controlled, az, aspect);
    az += 1.0f;
    frames.record(controlled, **presenter, cam, frame, detail, first);
    first = false;
  }
  const auto [rss, peak] = residentBytes();
  frames.counters(state);
  state.counters["model_faces"] = input_faces;
  state.counters["cpu_ms"] = frames.cpuMs();
  state.counters["build_s_per_Mface"] = build_s / (input_faces / 1e6);
  state.counters["cache_B_per_face"] = cache_bytes / input_faces;
  state.counters["rss_B_per_face"] = rss / input_faces;
  state.counters["peak_rss_MB"] = peak / (1024.0 * 1024.0);
}

// The scene case (issue 12): three objects of ~1.2M input faces together (two torus knots
// and a torus, ~400k faces each, at different depths, one drawn coarser by its factor on T),
// adapted and drawn as a scene, side by side in the same loop with the single 1.1M-face knot
// at the same T. Both orbit 1 degree per frame; medians over the frames.
void sceneFrame(benchmark::State& state, float target_area) {
  static std::vector<std::shared_ptr<Model>> parts;
  static const glm::vec3 offsets[3] = {{0.0f, 0.0f, 0.6f}, {1.4f, 0.5f, -1.2f}, {-1.5f, -0.4f, -2.4f}};
  static const float factors[3] = {1.0f, 1.0f, 2.0f};
  // Closer than the framing distance (~3.6 radii), so the parts fill about as much of the
  // image as the single knot does.
  constexpr float kSceneDistance = 2.0f;
  if (parts.empty()) {
    TriMesh meshes[3] = {makeTorusKnot(2, 3, 1.0f, 0.16f, 1600, 125, 0.18f),
                         makeTorusKnot(3, 5, 1.0f, 0.12f, 1600, 125, 0.18f), makeTorus(1.0f, 0.35f, 640, 320)};
    for (int i = 0; i < 3; ++i) {
      auto m = std::make_shared<Model>();
      m->mesh = std::move(meshes[i]);
      for (glm::vec3& p : m->mesh.positions) p += offsets[i];
      auto pm = loadOrBuildPm(m->mesh, meshContentHash(m->mesh), std::filesystem::temp_directory_path() / "lodline-bench-cache");
      if (!pm) {
        state.SkipWithError(pm.error().message.c_str());
        return;
      }
      m->pm = std::make_shared<const ProgressiveMesh>(std::move(pm.value()));
      parts.push_back(m);
    }
  }
  auto knot = loadModel("knot1m");
  auto ctx = createHeadlessContext(ContextBackend::kEgl);
  if (!knot || !ctx) {
    state.SkipWithError("no knot1m or no EGL context");
    return;
  }
  FrameParams frame;
  frame.msaa = 1;
  auto scene_presenter = GlPresenter::createOnCurrentContext();
  auto knot_presenter = GlPresenter::createOnCurrentContext();
  if (!scene_presenter || !knot_presenter) {
    state.SkipWithError("presenter set-up failed");
    return;
  }
  SceneDrawing scene;
  auto pool = std::make_shared<WorkerPool>(ShapeParams{}.threads);
  size_t input_faces = 0;
  for (int i = 0; i < 3; ++i) {
    SceneDrawing::Object o;
    o.name = "part" + std::to_string(i);
    o.drawing = std::make_unique<LodDrawing>(parts[i]->mesh, parts[i]->pm, LineParams{}, pool);
    o.detail_factor = factors[i];
    input_faces += parts[i]->mesh.faceCount();
    scene.add(std::move(o));
  }
  SceneDrawing single = sceneOf(std::make_unique<LodDrawing>(knot->mesh, knot->pm), "knot1m");
  DetailParams detail;
  detail.target_area = target_area;
  const float aspect = frame.aspect();
  convergeAtStart(scene, frame, detail, kSceneDistance);
  convergeAtStart(single, frame, detail);
  std::vector<double> scene_ms, scene_cpu, knot_ms, knot_cpu, scene_faces, knot_faces;
  std::vector<double> scene_adapt, scene_shape, scene_lines, knot_adapt, knot_shape, knot_lines, scene_changes,
      knot_changes, scene_curv, knot_curv, scene_full, knot_full;
  // One controlled frame of `s` through presenter `p`, its stages recorded.
  auto run = [&](SceneDrawing& s, GlPresenter& p, const Camera& cam, bool first, std::vector<double>& cpu,
                 std::vector<double>& total, std::vector<double>& faces, std::vector<double>& a,
                 std::vector<double>& sh, std::vector<double>& li, std::vector<double>& ops, std::vector<double>& curv,
                 std::vector<double>& full) {
    Stopwatch sw;
    (void)s.frame(cam, frame.width, frame.height, detail, 1.0f / 30.0f);
    cpu.push_back(sw.elapsed());
    const Stages st = stagesOf(s);
    (void)p.present(s, cam, frame, first);
    total.push_back(sw.elapsed());
    faces.push_back(st.faces);
    a.push_back(st.adapt);
    sh.push_back(st.shape);
    li.push_back(st.lines);
    ops.push_back(st.ops);
    curv.push_back(st.curvature);
    full.push_back(st.full);
  };
  float az = 0.0f;
  bool first = true;
  for (auto _ : state) {
    az += 1.0f;
    run(scene, **scene_presenter, orbitAt(scene, az, aspect, kSceneDistance), first,
        scene_cpu, scene_ms, scene_faces, scene_adapt, scene_shape, scene_lines, scene_changes, scene_curv, scene_full);
    run(single, **knot_presenter, orbitAt(single, az, aspect), first, knot_cpu,
        knot_ms, knot_faces, knot_adapt, knot_shape, knot_lines, knot_changes, knot_curv, knot_full);
    first = false;
  }
  state.counters["scene_input_faces"] = static_cast<double>(input_faces);
  state.counters["knot_input_faces"] = static_cast<double>(knot->mesh.faceCount());
  state.counters["scene_active_faces"] = bench::median(scene_faces);
  state.counters["knot_active_faces"] = bench::median(knot_faces);
  state.counters["scene_cpu_ms"] = bench::median(scene_cpu);
  state.counters["knot_cpu_ms"] = bench::median(knot_cpu);
  state.counters["scene_ms"] = bench::median(scene_ms);
  state.counters["knot_ms"] = bench::median(knot_ms);
  state.counters["scene_over_knot"] = bench::median(scene_ms) / bench::median(knot_ms);
  state.counters["scene_adapt_ms"] = bench::median(scene_adapt);
  state.counters["scene_shape_ms"] = bench::median(scene_shape);
  state.counters["scene_lines_ms"] = bench::median(scene_lines);
  state.counters["scene_ops"] = bench::median(scene_changes);
  state.counters["knot_adapt_ms"] = bench::median(knot_adapt);
  state.counters["knot_shape_ms"] = bench::median(knot_shape);
  state.counters["knot_lines_ms"] = bench::median(knot_lines);
  state.counters["knot_ops"] = bench::median(knot_changes);
  state.counters["scene_curvature_vertices"] = bench::median(scene_curv);
  state.counters["knot_curvature_vertices"] = bench::median(knot_curv);
  double sf = 0.0, kf = 0.0;
  for (double v : scene_full) sf += v;
  for (double v : knot_full) kf += v;
  state.counters["scene_full_recomputes"] = sf;
  state.counters["knot_full_recomputes"] = kf;
}

// The CPU cost of each line kind per controlled frame (docs/lines.md): two scenes of the same
// model adapted side by side in one loop, one drawing contours only, the other contours and
// `kind`; lines_ms is the lines stage (view quantities, extraction, chaining, and the
// per-view quantities and derivative tensors the kind needs), shape_ms the shape update.
// Medians over the frames of a slow orbit (1 degree per frame), 1280x720.
// `fit_ridges`: ridges and valleys from fitted jets (--ridge-estimator fit).
void lineKindFrame(benchmark::State& state, const std::string& name, float target_area, LineKind kind,
                   bool fit_ridges = false) {
  auto model = loadModel(name);
  if (!model) {
    state.SkipWithError(("cannot load " + name + " (run scripts/setup.sh)").c_str());
    return;
  }
  auto make = [&](bool with_kind) {
    LineParams params;
    if (fit_ridges) params.ridge_estimator = RidgeEstimator::kFit;
    SceneDrawing scene = sceneOf(std::make_unique<LodDrawing>(model->mesh, model->pm, params), name);
    SceneDrawing::Object& o = scene.objects()[0];
    for (auto& k : o.style.lines.kinds) k.enabled = false;
    o.style.lines[LineKind::kContour].enabled = true;
    if (with_kind) o.style.lines[kind].enabled = true;
    return scene;
  };
  SceneDrawing base = make(false), with = make(true);
  FrameParams frame;
  DetailParams detail;
  detail.target_area = target_area;
  const float aspect = frame.aspect();
  for (SceneDrawing* s : {&base, &with}) convergeAtStart(*s, frame, detail);
  std::vector<double> base_lines, with_lines, base_shape, with_shape, segments;
  float az = 0.0f;
  for (auto _ : state) {
    const Camera cam = orbitAt(base, az, aspect);
    az += 1.0f;
    (void)base.frame(cam, frame.width, frame.height, detail, 1.0f / 30.0f);
    (void)with.frame(cam, frame.width, frame.height, detail, 1.0f / 30.0f);
    const Stages b = stagesOf(base), w = stagesOf(with);
    base_lines.push_back(b.lines);
    with_lines.push_back(w.lines);
    base_shape.push_back(b.shape);
    with_shape.push_back(w.shape);
    segments.push_back(with.objects()[0].drawing->drawing().segments().counts[static_cast<int>(kind)]);
  }
  state.SetLabel(std::string(lineKindName(kind)) + (fit_ridges ? " (fitted jets)" : ""));
  state.counters["contour_lines_ms"] = bench::median(base_lines);
  state.counters["lines_ms"] = bench::median(with_lines);
  state.counters["kind_ms"] = bench::median(with_lines) - bench::median(base_lines);
  state.counters["contour_shape_ms"] = bench::median(base_shape);
  state.counters["shape_ms"] = bench::median(with_shape);
  state.counters["segments"] = bench::median(segments);
}

}  // namespace
}  // namespace lodline

int main(int argc, char** argv) {
  // T = 16 px² (the default), and T = 7 px², which adapts the knot to ~100k active faces
  // (the size of the CPU-stage figure in docs/performance.md).
  const std::pair<const char*, float> cases[] = {{"armadillo.off", 16.0f}, {"knot1m", 16.0f}, {"knot1m", 7.0f}};
  for (const auto& [name, t] : cases)
    for (const bool fades : {false, true}) {
      if (fades && t != 16.0f) continue;
      const std::string label = std::string("detail_frame/") + name + "/T:" + std::to_string(static_cast<int>(t)) +
                                (fades ? "/fades" : "");
      benchmark::RegisterBenchmark(label.c_str(),
                                   [name, t, fades](benchmark::State& s) { lodline::detailFrame(s, name, t, fades); })
          ->Iterations(30)
          ->Unit(benchmark::kMillisecond);
    }
  for (const auto& [name, t] : cases) {
    const std::string label = std::string("stages/") + name + "/T:" + std::to_string(static_cast<int>(t));
    benchmark::RegisterBenchmark(label.c_str(), [name, t](benchmark::State& s) { lodline::stagesFrame(s, name, t); })
        ->Iterations(std::getenv("STAGE_ITERS") ? std::atoi(std::getenv("STAGE_ITERS")) : 30)
        ->Unit(benchmark::kMillisecond);
  }
  for (const double faces : {1e5, 3e5, 1e6, 3e6, 1e7}) {
    const std::string label = "scale/knot_" + std::to_string(static_cast<int>(faces / 1e5)) + "00k/T:16";
    benchmark::RegisterBenchmark(label.c_str(), [faces](benchmark::State& s) { lodline::scaleFrame(s, faces, 16.0f); })
        ->Iterations(30)
        ->Unit(benchmark::kMillisecond);
  }
  for (const auto& [name, t] : cases) {
    const std::string label = std::string("controlled/") + name + "/T:" + std::to_string(static_cast<int>(t));
    benchmark::RegisterBenchmark(label.c_str(),
                                 [name, t](benchmark::State& s) { lodline::controlledFrames(s, name, t); })
        ->Iterations(std::getenv("STAGE_ITERS") ? std::atoi(std::getenv("STAGE_ITERS")) : 30)
        ->Unit(benchmark::kMillisecond);
  }
  for (const auto& [name, t] : cases) {
    const std::string label = std::string("pipelined/") + name + "/T:" + std::to_string(static_cast<int>(t));
    benchmark::RegisterBenchmark(label.c_str(),
                                 [name, t](benchmark::State& s) { lodline::pipelinedFrame(s, name, t); })
        ->Iterations(30)
        ->Unit(benchmark::kMillisecond);
  }
  benchmark::RegisterBenchmark("detail_frame/scene3_vs_knot1m/T:16",
                               [](benchmark::State& s) { lodline::sceneFrame(s, 16.0f); })
      ->Iterations(30)
      ->Unit(benchmark::kMillisecond);
  for (const char* name : {"armadillo.off", "knot1m"})
    for (int k = 0; k < lodline::kLineKindCount; ++k) {
      const auto kind = static_cast<lodline::LineKind>(k);
      if (kind == lodline::LineKind::kContour || kind == lodline::LineKind::kIntersection) continue;
      const std::string label = std::string("line_kind/") + name + "/T:16/" + lodline::lineKindName(kind);
      benchmark::RegisterBenchmark(label.c_str(), [name, kind](benchmark::State& s) {
        lodline::lineKindFrame(s, name, 16.0f, kind);
      })->Iterations(30)->Unit(benchmark::kMillisecond);
      if (kind == lodline::LineKind::kRidge || kind == lodline::LineKind::kValley)
        benchmark::RegisterBenchmark((label + "-fit").c_str(), [name, kind](benchmark::State& s) {
          lodline::lineKindFrame(s, name, 16.0f, kind, true);
        })->Iterations(30)->Unit(benchmark::kMillisecond);
    }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
