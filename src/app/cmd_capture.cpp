// `lodline capture MODEL --path P -o out.mp4|DIR/`: renders a camera path headlessly, frame
// by frame at a fixed simulated frame rate (so results do not depend on the machine's
// speed), into an MP4 (through ffmpeg) or a numbered PNG sequence, with optional per-frame
// temporal-coherence metrics (docs/capture.md). Parses, then present/capture.h does the work.
#include <atomic>
#include <csignal>
#include <iostream>
#include <memory>

#include <unistd.h>

#include "app/commands.h"
#include "app/model.h"
#include "app/options.h"
#include "export/video_writer.h"
#include "io/atomic_file.h"
#include "present/capture.h"

namespace lodline {
namespace {

// Set by SIGINT/SIGTERM; the capture loop stops after the current frame and finishes its
// outputs. (Signal handlers can only reach process-wide state.)
std::atomic<bool> g_interrupted{false};
extern "C" void onInterrupt(int) { g_interrupted.store(true); }

struct CaptureOptions {
  ViewOptions view;
  DetailOptions detail;
  CapturePathOptions capture;
  std::string output;
  std::string metrics;
  std::string stats;
  std::string svg;
  std::string pops;
  std::string context = "auto";
};

int runCapture(CLI::App& cmd, CaptureOptions& o) {
  if (o.output.empty()) return reportError(Error::usage("capture: -o out.mp4 or -o DIR/ is required"));
  CaptureRequest rq;
  rq.png_sequence = o.output.back() == '/' || std::filesystem::is_directory(o.output);
  rq.output = o.output;
  if (!rq.png_sequence && rq.output.extension() != ".mp4")
    return reportError(Error::usage("-o: expected a .mp4 file or a directory ending in '/', got '" + o.output + "'"));
  for (const std::string* p : {&o.metrics, &o.stats})
    if (!p->empty())
      if (Status s = checkWritable(*p); !s) return reportError(s.error());
  if (!rq.png_sequence) {
    if (Status s = checkWritable(rq.output); !s) return reportError(s.error());
    if (!ffmpegAvailable())
      return reportError(Error::runtime(o.output + ": ffmpeg not found (install Debian's ffmpeg, or write a "
                                        "PNG sequence with -o DIR/)"));
  }
  auto loaded = loadInput(cmd, o.view, o.detail);
  if (!loaded) return reportError(loaded.error());
  // Options the scene's settings may have set are read from here on.
  auto context = parseContextBackend(o.context);
  if (!context) return reportError(context.error());
  if (rq.png_sequence) {
    std::error_code ec;
    std::filesystem::create_directories(rq.output, ec);
    if (ec) return reportError(Error::runtime(o.output + ": cannot create directory: " + ec.message()));
  }
  for (const std::string* dir : {&o.svg, &o.pops}) {
    if (dir->empty()) continue;
    std::error_code ec;
    std::filesystem::create_directories(*dir, ec);
    if (ec || !std::filesystem::is_directory(*dir))
      return reportError(Error::runtime(*dir + ": cannot create directory" + (ec ? ": " + ec.message() : "")));
  }
  const LoadedScene& l = **loaded;
  const CapturePathOptions& c = o.capture;
  auto path = scenePath({c.path, givenOnCommandLine(cmd, "path"), c.duration}, l.drawing.bounds(), l.camera,
                        l.view.fov_deg, l.view.frame.aspect(), l.view.orbit);
  if (!path) return reportError(path.error());
  if (Status s = resolveCaptureOptions(c, std::move(path.value()), rq); !s) return reportError(s.error());
  rq.context = *context;
  rq.metrics = o.metrics;
  rq.stats = o.stats;
  rq.svg_dir = o.svg;
  rq.pop_dir = o.pops;
  rq.interrupted = &g_interrupted;
  rq.progress = isatty(STDERR_FILENO);
  std::signal(SIGINT, onInterrupt);
  std::signal(SIGTERM, onInterrupt);
  auto outcome = captureFrames(**loaded, rq);
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  if (!outcome) return reportError(outcome.error());
  if (outcome->measured)
    std::cout << "frames " << outcome->frames << "  churn mean " << outcome->churn_mean << " p95 " << outcome->churn_p95
              << "  churn_raw mean " << outcome->churn_raw_mean << "  specks mean " << outcome->specks_mean
              << "  texture drift mean " << outcome->texture_drift_mean << " px\n";
  if (outcome->interrupted) {
    std::cerr << "lodline: interrupted after " << outcome->frames << " frame(s); outputs hold the frames done\n";
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
  addCaptureOptions(*cmd, o->capture);
  cmd->add_option("-o,--output", o->output, "out.mp4 (through ffmpeg) or DIR/ for frame_NNNNN.png files")
      ->required();
  cmd->add_option("--metrics", o->metrics, "Per-frame temporal-coherence metrics as CSV (docs/capture.md)");
  cmd->add_option("--stats", o->stats, "Summary statistics as JSON");
  cmd->add_option("--svg", o->svg,
                  "DIR/: one SVG per frame (frame_NNNNN.svg), each stroke with an id it keeps while it "
                  "persists from frame to frame (docs/capture.md)");
  cmd->add_option("--pop-frames", o->pops,
                  "DIR/: one PNG per frame after the first (pop_NNNNN.png): the frame faded, with the line pixels "
                  "that appeared since the previous frame in green and those that vanished in red, as the churn "
                  "counts them (motion-compensated, by opacity; docs/capture.md)");
  cmd->add_option("--context", o->context, "OpenGL context: auto, egl or osmesa")->capture_default_str();
  return {cmd, [o, cmd] { return runCapture(*cmd, *o); }};
}

}  // namespace lodline
