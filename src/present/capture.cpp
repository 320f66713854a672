#include "present/capture.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/timer.h"
#include "export/coherence.h"
#include "export/video_writer.h"
#include "frame/lod_drawing.h"
#include "io/atomic_file.h"
#include "io/image.h"
#include "lod/adaptive_mesh.h"
#include "present/frame_report.h"
#include "present/presenter.h"
#include "present/stroke_ids.h"
#include "present/svg_output.h"

namespace lodline {
namespace {

void progressBar(int64_t done, int64_t total, double elapsed_ms) {
  const int width = 30;
  const double f = total ? static_cast<double>(done) / static_cast<double>(total) : 1.0;
  const int filled = static_cast<int>(f * width);
  const double eta_s = done ? elapsed_ms / static_cast<double>(done) * static_cast<double>(total - done) / 1000.0 : 0.0;
  std::fprintf(stderr, "\r  frame %lld/%lld [%s%s] %3d%%  ETA %dm%02ds ", static_cast<long long>(done),
               static_cast<long long>(total), std::string(filled, '#').c_str(),
               std::string(width - filled, ' ').c_str(), static_cast<int>(f * 100.0),
               static_cast<int>(eta_s) / 60, static_cast<int>(eta_s) % 60);
  std::fflush(stderr);
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t i = std::min(v.size() - 1, static_cast<size_t>(std::ceil(p * static_cast<double>(v.size()))) - (p > 0 ? 1 : 0));
  return v[i];
}

double mean(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

// Around how many pixels of a changed vertex a popped pixel is attributed to it: about one
// edge of a face at the default T = 16 px² (an equilateral triangle of 16 px² has 6.1-px edges),
// so a line across any face around the vertex is near it.
constexpr int kChangeZoneRadius = 6;

// The pixels near where the scene's level of detail split or collapsed a vertex in the last
// frame (at the parent's position, where both happen), and near the vertices a geomorph moved
// (where they are drawn now). Occlusion is not tested: a change behind a surface marks the
// pixels in front of it too.
void changeZones(const SceneDrawing& scene, const Camera& camera, int width, int height, ChangeZones& zones) {
  zones.reset(width, height);
  const PixelProjector proj(camera, width, height);
  auto mark = [&](const glm::vec3& p, uint8_t bit) {
    glm::vec2 px;
    float depth = 0.0f;
    if (proj.project(p, px, depth)) zones.mark(px, kChangeZoneRadius, bit);
  };
  for (const SceneDrawing::Object& o : scene.objects()) {
    const AdaptiveMesh* lod = o.drawing->lod();
    if (!lod) continue;
    const LodChanges& ch = lod->changes();
    const ProgressiveMesh& pm = lod->pm();
    for (const std::vector<uint32_t>* nodes : {&ch.split, &ch.collapsed})
      for (uint32_t p : *nodes) mark(pm.positions[pm.origin[p]], ChangeZones::kNearOps);
    const auto positions = lod->positions();
    for (uint32_t s : ch.moved)
      if (s < positions.size()) mark(positions[s], ChangeZones::kNearMorph);
  }
}

Status writeText(const std::filesystem::path& path, const std::string& text) {
  return writeFileAtomically(path, [&](std::ostream& os) -> Status {
    os << text;
    return {};
  });
}

}  // namespace

int64_t captureFrameCount(const CameraPath& path, double fps) {
  return std::max<int64_t>(1, std::llround(path.duration() * fps));
}

CaptureRun::CaptureRun(LoadedScene& loaded, ScenePresenter& presenter, const CaptureRequest& rq, bool measure)
    : loaded_(loaded), presenter_(presenter), path_(rq.path), fps_(rq.fps), range_(rq.range), measure_(measure),
      want_pops_(!rq.pop_dir.empty()), next_(rq.range.first), t0_(rq.path.keys().front().time) {
  // Smoothing at the capture's frame rate (Jeong §3.3: f is the capture rate when capturing).
  const SmoothingParams& sm = loaded.detail.smoothing;
  smoothing_w_ = sm.enabled ? smoothingWeight(sm.alpha, sm.seconds, static_cast<float>(fps_)) : 1.0f;
}

// The camera of frame k (time k/fps).
Camera CaptureRun::cameraAt(int64_t k) const {
  return path_.at(t0_ + static_cast<double>(k) / fps_, loaded_.drawing.bounds());
}

// One step of the simulation at frame k: the state every later frame builds on (level of
// detail, geomorphs, temporal smoothing). Detail parameters were checked by the caller, so
// frame() cannot fail.
Camera CaptureRun::simulate(int64_t k, bool while_drawing) {
  SceneDrawing& scene = loaded_.drawing;
  const FrameParams& frame = loaded_.view.frame;
  const Camera cam = cameraAt(k);
  const float dt = static_cast<float>(1.0 / fps_);
  if (while_drawing) (void)scene.frameWhileDrawing(cam, frame.width, frame.height, loaded_.detail.params, dt, smoothing_w_);
  else (void)scene.frame(cam, frame.width, frame.height, loaded_.detail.params, dt, smoothing_w_);
  return cam;
}

Result<std::unique_ptr<CaptureRun>> CaptureRun::start(LoadedScene& loaded, ScenePresenter& p, const CaptureRequest& rq,
                                                      bool measure, bool pipeline) {
  std::unique_ptr<CaptureRun> run(new CaptureRun(loaded, p, rq, measure));
  run->pipeline_ = pipeline && !measure;
  SceneDrawing& scene = loaded.drawing;
  const FrameParams& frame = loaded.view.frame;
  const float dt = static_cast<float>(1.0 / rq.fps);
  // Frame 0 starts from the detail converged for its camera, by the same steps as a still
  // render (so it is that still's mesh), not from the base mesh, so the first frames are not a
  // refinement transient.
  const Camera cam0 = rq.path.at(run->t0_, scene.bounds());
  if (auto steps = scene.converge(cam0, frame.width, frame.height, loaded.detail.params,
                                  SceneDrawing::kConvergeStepSeconds, loaded.detail.max_adapt_frames);
      !steps)
    return steps.error();
  // When the camera moves from frame 0 to 1, frame 0 is already a frame in motion.
  const Camera c1 = rq.path.at(run->t0_ + 1.0 / rq.fps, scene.bounds());
  p.startSequence(cam0.eye != c1.eye || cam0.target != c1.target || cam0.up != c1.up || cam0.fov_deg != c1.fov_deg);
  p.setStrokeCoherence(rq.stroke_coherence);
  p.setFadeStep(rq.fade_in > 0.0f ? std::min(1.0f, dt / rq.fade_in) : 0.0f);
  // Frames before the range advance the simulation and are drawn (the outline's hysteresis
  // builds on the frames drawn before); the one just before it also gives the previous frame
  // of the coherence measure, so frame k and its metrics are the same whichever range
  // renders it.
  for (int64_t k = 0; k < rq.range.first; ++k) {
    const Camera cam = run->simulate(k);
    if (Status s = p.present(scene, cam, frame, k == 0); !s) return s.error();
    if (measure && k == rq.range.first - 1) {
      (void)reportFrame(scene, p, &run->mask_);
      if (Status s = p.readSurface(run->surface_); !s) return s.error();
      (void)run->meter_.measure(run->mask_, run->surface_, cam);
    }
  }
  return run;
}

Result<CapturedFrame> CaptureRun::next() {
  Stopwatch frame_clock;
  CapturedFrame f;
  f.index = next_++;
  f.camera = simulated_ahead_ ? cameraAt(f.index) : simulate(f.index);
  SceneDrawing& scene = loaded_.drawing;
  // Pipelined: the next frame's stages run while this one is drawn.
  const bool ahead = pipeline_ && next_ < range_.end;
  std::function<void()> overlap;
  if (ahead) overlap = [this, k = next_] { (void)simulate(k, /*while_drawing=*/true); };
  simulated_ahead_ = false;
  if (Status s = presenter_.present(scene, f.camera, loaded_.view.frame, f.index == 0, overlap); !s)
    return s.error();
  simulated_ahead_ = ahead;
  f.image = presenter_.readImage();
  if (measure_) {
    const FrameReport report = reportFrame(scene, presenter_, &mask_);
    if (Status s = presenter_.readSurface(surface_); !s) return s.error();
    changeZones(scene, f.camera, loaded_.view.frame.width, loaded_.view.frame.height, zones_);
    CompensationParams cp;
    cp.zones = &zones_;
    if (want_pops_) cp.pops = &f.pops;
    f.coherence = meter_.measure(mask_, surface_, f.camera, cp);
    std::ostringstream row;
    writeMetricsRow(row, f.index, report, f.coherence, frame_clock.elapsed());
    f.metrics_row = row.str();
    f.measured = true;
    f.specks = static_cast<double>(report.total.specks);
    f.texture_drift = report.texture_drift;
  }
  return f;
}

Result<CaptureOutcome> captureFrames(LoadedScene& loaded, const CaptureRequest& rq) {
  SceneDrawing& scene = loaded.drawing;
  const FrameParams& frame = loaded.view.frame;
  auto presenter = createPresenter(PresenterBackend::kGl, rq.context, scene, frame);
  if (!presenter) return presenter.error();
  ScenePresenter& p = **presenter;
  std::optional<VideoWriter> video;
  if (!rq.png_sequence) {
    auto v = VideoWriter::open(rq.output, {frame.width, frame.height, rq.fps, 18});
    if (!v) return v.error();
    video.emplace(std::move(v.value()));
  }

  const bool want_pops = !rq.pop_dir.empty();
  const bool want_metrics = !rq.metrics.empty() || !rq.stats.empty() || want_pops;
  const bool want_svg = !rq.svg_dir.empty();
  StrokeIdTracker ids;  // stroke ids from frame 0 on, so frame k's are the same whichever range
  std::ostringstream csv;
  csv << metricsCsvHeader();
  std::vector<double> churns, binary_churns, raw_churns, specks_per_frame, frame_ms, drifts;

  // Stroke ids need every frame from 0: the frames before the range are replayed here with
  // their ids (CaptureRun::start draws them only when ids are not wanted).
  CaptureRequest first = rq;
  if (want_svg) first.range = {0, rq.range.end};
  // Nothing reads the scene between frames unless metrics or SVGs are written: then the
  // frames are pipelined (the same frames, sooner). Not with an adaptation time budget,
  // which stops on the clock: overlapped stages run slower, so the frames would differ.
  const bool pipeline = !want_svg && !(loaded.detail.params.max_adapt_ms > 0.0f);
  auto run = CaptureRun::start(loaded, p, first, want_metrics, pipeline);
  if (!run) return run.error();
  CaptureRun& r = **run;

  Stopwatch wall;
  CaptureOutcome out;
  out.measured = want_metrics;
  Status failure;
  while (!r.done() && !(rq.interrupted && rq.interrupted->load())) {
    Stopwatch frame_clock;
    auto f = r.next();
    if (!f) {
      failure = f.error();
      break;
    }
    const int64_t k = f->index;
    if (want_svg) {
      ids.update(p.visible(), f->camera, frame.width, frame.height);
      if (k < rq.range.first) continue;
      char name[32];
      std::snprintf(name, sizeof(name), "frame_%05lld.svg", static_cast<long long>(k));
      if (failure = writeFrameSvg(rq.svg_dir / name, scene, p, &ids.ids()); !failure) break;
    }
    if (want_pops && f->coherence.compared) {
      char name[32];
      std::snprintf(name, sizeof(name), "pop_%05lld.png", static_cast<long long>(k));
      if (failure = writePng(rq.pop_dir / name, popImage(f->image, f->pops)); !failure) break;
    }
    if (rq.png_sequence) {
      char name[32];
      std::snprintf(name, sizeof(name), "frame_%05lld.png", static_cast<long long>(k));
      failure = writePng(rq.output / name, f->image);
    } else {
      failure = video->write(f->image.rgba);
    }
    if (!failure) break;
    if (f->measured) {
      csv << f->metrics_row;
      if (f->coherence.compared) {
        churns.push_back(f->coherence.compensated.churn());
        binary_churns.push_back(f->coherence.compensated.churnBinary());
        raw_churns.push_back(f->coherence.raw.churn());
        drifts.push_back(f->texture_drift);
      }
      specks_per_frame.push_back(f->specks);
    }
    frame_ms.push_back(frame_clock.elapsed());
    ++out.frames;
    if (rq.progress) progressBar(out.frames, rq.range.end - rq.range.first, wall.elapsed());
  }
  if (rq.progress) std::fputc('\n', stderr);
  out.interrupted = rq.interrupted && rq.interrupted->load();

  // Finish every output, even after an interruption or a failure: the frames done so far
  // make a valid video / complete PNG files.
  if (video)
    if (Status s = video->finish(); !s && failure) failure = s;
  if (!rq.metrics.empty())
    if (Status s = writeText(rq.metrics, csv.str()); !s && failure) failure = s;
  out.churn_mean = mean(churns);
  out.churn_p95 = percentile(churns, 0.95);
  out.churn_raw_mean = mean(raw_churns);
  out.churn_binary_mean = mean(binary_churns);
  out.texture_drift_mean = mean(drifts);
  out.specks_mean = mean(specks_per_frame);
  if (!rq.stats.empty()) {
    nlohmann::json j;
    j["model"] = {{"path", loaded.view.model.string()}, {"vertices", scene.inputVertexCount()},
                  {"faces", scene.inputFaceCount()}};
    j["image"] = {{"width", frame.width}, {"height", frame.height}};
    j["capture"] = {{"path", rq.path_name}, {"fps", rq.fps}, {"first_frame", rq.range.first},
                    {"frames", out.frames}, {"interrupted", out.interrupted}};
    j["coherence"] = {{"churn_mean", out.churn_mean}, {"churn_p95", out.churn_p95}, {"churn_binary_mean", out.churn_binary_mean},
                      {"churn_raw_mean", out.churn_raw_mean}, {"churn_raw_p95", percentile(raw_churns, 0.95)},
                      {"specks_mean", out.specks_mean}, {"texture_drift_mean", out.texture_drift_mean}};
    j["ms"] = {{"frame_mean", mean(frame_ms)}, {"frame_p95", percentile(frame_ms, 0.95)}, {"total", wall.elapsed()}};
    if (Status s = writeText(rq.stats, j.dump(2) + "\n"); !s && failure) failure = s;
  }
  if (!failure) return failure.error();
  return out;
}

}  // namespace lodline
