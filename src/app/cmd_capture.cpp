// `lodline capture MODEL --path P -o out.mp4|DIR/`: renders a camera path headlessly, frame
// by frame at a fixed simulated frame rate (so results do not depend on the machine's
// speed), into an MP4 (through ffmpeg) or a numbered PNG sequence, with optional per-frame
// temporal-coherence metrics (docs/capture.md).
#include <algorithm>
#include <atomic>
#include <charconv>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include "app/commands.h"
#include "app/headless.h"
#include "app/options.h"
#include "core/timer.h"
#include "export/coherence.h"
#include "export/video_writer.h"
#include "export/visibility.h"
#include "frame/camera_path.h"
#include "io/atomic_file.h"
#include "app/model.h"

namespace lodline {
namespace {

// Set by SIGINT/SIGTERM; the capture loop stops after the current frame and finishes its
// outputs. (Signal handlers can only reach process-wide state.)
std::atomic<bool> g_interrupted{false};
extern "C" void onInterrupt(int) { g_interrupted.store(true); }

struct CaptureOptions {
  ViewOptions view;
  DetailOptions detail;
  std::string path = "orbit";
  double duration = 8.0;
  std::string frames;
  double fps = 30.0;
  std::string output;
  std::string metrics;
  std::string stats;
  std::string context = "auto";
};

struct FrameRange {
  int64_t first = 0;
  int64_t end = 0;  // exclusive
};

Result<FrameRange> parseFrames(const std::string& s, int64_t total) {
  FrameRange r{0, total};
  if (s.empty()) return r;
  const auto bad = Error::usage("--frames: invalid value '" + s + "' (expected N or A:B with 0 <= A < B)");
  auto parse = [](std::string_view v, int64_t& out) {
    auto [p, ec] = std::from_chars(v.data(), v.data() + v.size(), out);
    return ec == std::errc() && p == v.data() + v.size() && out >= 0;
  };
  const auto colon = s.find(':');
  if (colon == std::string::npos) {
    if (!parse(s, r.end) || r.end == 0) return bad;
    return r;
  }
  if (!parse(std::string_view(s).substr(0, colon), r.first) ||
      !parse(std::string_view(s).substr(colon + 1), r.end) || r.first >= r.end)
    return bad;
  return r;
}

void progress(int64_t done, int64_t total, double elapsed_ms) {
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

int runCapture(CLI::App& cmd, CaptureOptions& o) {
  if (o.output.empty()) return reportError(Error::usage("capture: -o out.mp4 or -o DIR/ is required"));
  const bool png_sequence = o.output.back() == '/' || std::filesystem::is_directory(o.output);
  const std::filesystem::path out(o.output);
  if (!png_sequence && out.extension() != ".mp4")
    return reportError(Error::usage("-o: expected a .mp4 file or a directory ending in '/', got '" + o.output + "'"));
  for (const std::string* p : {&o.metrics, &o.stats})
    if (!p->empty())
      if (Status s = checkWritable(*p); !s) return reportError(s.error());
  if (!png_sequence) {
    if (Status s = checkWritable(out); !s) return reportError(s.error());
    if (!ffmpegAvailable())
      return reportError(Error::runtime(o.output + ": ffmpeg not found (install Debian's ffmpeg, or write a "
                                        "PNG sequence with -o DIR/)"));
  }

  auto loaded_input = loadInput(cmd, o.view, o.detail);
  if (!loaded_input) return reportError(loaded_input.error());
  LoadedScene& loaded = **loaded_input;
  // Options the scene's settings may have set are read from here on.
  auto backend = parseContextBackend(o.context);
  if (!backend) return reportError(backend.error());
  if (!(o.fps > 0.0 && o.fps <= 1000.0)) return reportError(Error::usage("--fps: must be in (0, 1000]"));
  if (png_sequence) {
    std::error_code ec;
    std::filesystem::create_directories(out, ec);
    if (ec) return reportError(Error::runtime(o.output + ": cannot create directory: " + ec.message()));
  }
  const ResolvedDetail* detail = &loaded.detail;
  const RenderParams& rp = loaded.view.render;
  SceneDrawing& scene = loaded.drawing;
  const float aspect = static_cast<float>(rp.width) / static_cast<float>(rp.height);

  Result<CameraPath> cam_path = scenePath(loaded, o.path, givenOnCommandLine(cmd, "path"), o.duration, aspect);
  if (!cam_path) return reportError(cam_path.error());
  const int64_t total = std::max<int64_t>(1, std::llround(cam_path->duration() * o.fps));
  auto range = parseFrames(o.frames, total);
  if (!range) return reportError(range.error());

  auto headless = HeadlessRenderer::create(*backend, rp);
  if (!headless) return reportError(headless.error());
  std::optional<VideoWriter> video;
  if (!png_sequence) {
    auto v = VideoWriter::open(out, {rp.width, rp.height, o.fps, 18});
    if (!v) return reportError(v.error());
    video.emplace(std::move(v.value()));
  }

  const bool want_metrics = !o.metrics.empty() || !o.stats.empty();
  VisibleStrokes visible, object_visible;
  LineMask prev_mask, mask;
  // The motion-compensated measure also needs each frame's visible surface and camera.
  SurfaceImage prev_surface, surface;
  Camera prev_camera;
  bool have_prev = false;
  std::ostringstream csv;
  csv << "frame,line_pixels,appeared,vanished,churn,dropped,appeared_raw,vanished_raw,churn_raw,strokes,specks,"
         "active_faces,splits,collapses,ms_total\n";
  std::vector<double> churns, raw_churns, specks_per_frame, frame_ms;

  // One step of the simulation at frame k (time k/fps): the state every later frame builds
  // on. Level of detail and temporal smoothing will keep state here; with full detail a
  // frame depends on its camera only.
  // Smoothing at the capture's frame rate (Jeong §3.3: f is the capture rate when capturing).
  const float smoothing_w = detail->smoothing.enabled
                                ? smoothingWeight(detail->smoothing.alpha, detail->smoothing.seconds, static_cast<float>(o.fps))
                                : 1.0f;
  // Errors from the detail parameters were ruled out by resolveDetailOptions.
  const double t0 = cam_path->keys().front().time;
  auto simulate = [&](int64_t k) -> Camera {
    const Camera cam = cam_path->at(t0 + static_cast<double>(k) / o.fps, scene.bounds());
    (void)scene.frame(cam, rp.width, rp.height, detail->params, static_cast<float>(1.0 / o.fps), smoothing_w);
    return cam;
  };
  // Visible strokes of every object against the depth of all faces, as one set.
  auto visible_lines = [&](const Camera& cam, const DepthImage& depth) {
    visible.clear();
    for (const auto& obj : scene.objects()) {
      visibleStrokes(obj.drawing->drawing().strokes(), cam, depth, {}, object_visible);
      appendStrokes(object_visible, visible);
    }
  };
  auto line_mask = [&](const Camera& cam, LineMask& m, SurfaceImage& surf) -> Status {
    if (Status s = headless->setMeshes(scene, true); !s) return s;
    headless->draw(scene, cam, rp);
    visible_lines(cam, headless->readDepth());
    rasterizeStrokes(visible, rp.width, rp.height, m);
    return headless->drawSurface(cam, surf);
  };
  // Frame 0 starts from the detail converged for its camera (as a still render would), not
  // from the base mesh, so the first frames are not a refinement transient.
  {
    const Camera cam0 = cam_path->at(t0, scene.bounds());
    if (auto steps = scene.converge(cam0, rp.width, rp.height, detail->params, static_cast<float>(1.0 / o.fps),
                                    detail->max_adapt_frames);
        !steps)
      return reportError(steps.error());
  }
  // Frames before the range only advance the simulation; the one just before it also gives
  // the previous line mask, so frame k's metrics are the same whichever range renders it.
  for (int64_t k = 0; k < range->first; ++k) {
    const Camera cam = simulate(k);
    if (want_metrics && k == range->first - 1) {
      if (Status s = line_mask(cam, prev_mask, prev_surface); !s) return reportError(s.error());
      prev_camera = cam;
      have_prev = true;
    }
  }

  std::signal(SIGINT, onInterrupt);
  std::signal(SIGTERM, onInterrupt);
  const bool tty = isatty(STDERR_FILENO);
  Stopwatch wall;
  int64_t done = 0;
  Status failure;
  for (int64_t k = range->first; k < range->end && !g_interrupted.load(); ++k) {
    Stopwatch frame_clock;
    const Camera cam = simulate(k);
    if (Status s = headless->setMeshes(scene, k == range->first); !s) {
      failure = s;
      break;
    }
    headless->draw(scene, cam, rp);
    const Image image = headless->readImage();
    if (png_sequence) {
      char name[32];
      std::snprintf(name, sizeof(name), "frame_%05lld.png", static_cast<long long>(k));
      failure = writePng(out / name, image);
    } else {
      failure = video->write(image.rgba);
    }
    if (!failure) break;
    if (want_metrics) {
      visible_lines(cam, headless->readDepth());
      rasterizeStrokes(visible, rp.width, rp.height, mask);
      if (Status s = headless->drawSurface(cam, surface); !s) {
        failure = s;
        break;
      }
      MaskChange raw;
      CompensatedChange change;
      if (have_prev) {
        raw = compareMasks(prev_mask, mask);
        change = compareMasksCompensated(prev_mask, prev_surface, prev_camera, mask, surface, cam);
      } else {
        raw.line_pixels = mask.count();  // frame 0: nothing to compare with
        change.line_pixels = raw.line_pixels;
      }
      const size_t specks = countSpecks(visible.length_px);
      size_t active_faces = 0, splits = 0, collapses = 0;
      for (const auto& obj : scene.objects()) {
        active_faces += obj.drawing->drawing().mesh().faceCount();
        if (const AdaptiveMesh* lod = obj.drawing->lod()) {
          splits += lod->stats().splits;
          collapses += lod->stats().collapses;
        }
      }
      const double ms = frame_clock.elapsed();
      csv << k << ',' << change.line_pixels << ',' << change.appeared << ',' << change.vanished << ','
          << change.churn() << ',' << change.dropped << ',' << raw.appeared << ',' << raw.vanished << ','
          << raw.churn() << ',' << visible.strokeCount() << ',' << specks << ',' << active_faces << ',' << splits
          << ',' << collapses << ',' << ms << '\n';
      if (have_prev) {
        churns.push_back(change.churn());
        raw_churns.push_back(raw.churn());
      }
      specks_per_frame.push_back(static_cast<double>(specks));
      std::swap(prev_mask, mask);
      std::swap(prev_surface, surface);
      prev_camera = cam;
      have_prev = true;
    }
    frame_ms.push_back(frame_clock.elapsed());
    ++done;
    if (tty) progress(done, range->end - range->first, wall.elapsed());
  }
  if (tty) std::fputc('\n', stderr);
  const bool interrupted = g_interrupted.load();
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);

  // Finish every output, even after an interruption or a failure: the frames done so far
  // make a valid video / complete PNG files.
  if (video) {
    if (Status s = video->finish(); !s && failure) failure = s;
  }
  if (!o.metrics.empty()) {
    const std::string text = csv.str();
    if (Status s = writeFileAtomically(o.metrics, [&](std::ostream& os) -> Status {
          os << text;
          return {};
        });
        !s && failure)
      failure = s;
  }
  double mean_churn = 0.0, mean_raw = 0.0, mean_specks = 0.0;
  for (double c : churns) mean_churn += c;
  for (double c : raw_churns) mean_raw += c;
  for (double s : specks_per_frame) mean_specks += s;
  if (!churns.empty()) mean_churn /= static_cast<double>(churns.size());
  if (!raw_churns.empty()) mean_raw /= static_cast<double>(raw_churns.size());
  if (!specks_per_frame.empty()) mean_specks /= static_cast<double>(specks_per_frame.size());
  if (want_metrics)
    std::cout << "frames " << done << "  churn mean " << mean_churn << " p95 " << percentile(churns, 0.95)
              << "  churn_raw mean " << mean_raw << "  specks mean " << mean_specks << '\n';
  if (!o.stats.empty()) {
    nlohmann::json j;
    j["model"] = {{"path", loaded.view.model.string()}, {"vertices", scene.inputVertexCount()},
                  {"faces", scene.inputFaceCount()}};
    j["image"] = {{"width", rp.width}, {"height", rp.height}};
    j["capture"] = {{"path", o.path}, {"fps", o.fps}, {"first_frame", range->first},
                    {"frames", done}, {"interrupted", interrupted}};
    j["coherence"] = {{"churn_mean", mean_churn}, {"churn_p95", percentile(churns, 0.95)},
                      {"churn_raw_mean", mean_raw}, {"churn_raw_p95", percentile(raw_churns, 0.95)},
                      {"specks_mean", mean_specks}};
    double mean_ms = 0.0;
    for (double m : frame_ms) mean_ms += m;
    j["ms"] = {{"frame_mean", frame_ms.empty() ? 0.0 : mean_ms / static_cast<double>(frame_ms.size())},
               {"frame_p95", percentile(frame_ms, 0.95)}, {"total", wall.elapsed()}};
    const std::string text = j.dump(2) + "\n";
    if (Status s = writeFileAtomically(o.stats, [&](std::ostream& os) -> Status {
          os << text;
          return {};
        });
        !s && failure)
      failure = s;
  }
  if (!failure) return reportError(failure.error());
  if (interrupted) {
    std::cerr << "lodline: interrupted after " << done << " frame(s); outputs hold the frames done\n";
    return 130;
  }
  return 0;
}

}  // namespace

Command addCaptureCommand(CLI::App& parent) {
  auto o = std::make_shared<CaptureOptions>();
  CLI::App* cmd = parent.add_subcommand(
      "capture", "Render a camera path around a model or scene headlessly to an MP4 video or a numbered PNG sequence");
  addViewOptions(*cmd, o->view);
  addDetailOptions(*cmd, o->detail);
  cmd->add_option("--path", o->path,
                  "Camera path: orbit, zoom-out, dolly, flyover, or a path file (.json); default: the scene file's "
                  "camera path, else orbit")
      ->capture_default_str();
  cmd->add_option("--duration", o->duration, "Length of a built-in path in seconds")->capture_default_str();
  cmd->add_option("--frames", o->frames,
                  "N renders frames 0..N-1; A:B renders frames A..B-1 only (frame k is identical "
                  "whichever range renders it); default: the whole path");
  cmd->add_option("--fps", o->fps, "Simulated frame rate (the video's rate)")->capture_default_str();
  cmd->add_option("-o,--output", o->output, "out.mp4 (through ffmpeg) or DIR/ for frame_NNNNN.png files")
      ->required();
  cmd->add_option("--metrics", o->metrics, "Per-frame temporal-coherence metrics as CSV (docs/capture.md)");
  cmd->add_option("--stats", o->stats, "Summary statistics as JSON");
  cmd->add_option("--context", o->context, "OpenGL context: auto, egl or osmesa")->capture_default_str();
  return {cmd, [o, cmd] { return runCapture(*cmd, *o); }};
}

}  // namespace lodline
