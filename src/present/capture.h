// A capture: a camera path rendered frame by frame at a fixed simulated frame rate (so the
// result does not depend on the machine's speed) into an MP4 (through ffmpeg) or a PNG
// sequence, with per-frame temporal-coherence metrics (docs/capture.md). What `lodline
// capture` does after parsing its options.
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "core/camera.h"
#include "core/image.h"
#include "core/result.h"
#include "export/coherence.h"
#include "frame/camera_path.h"
#include "frame/scene_builder.h"
#include "gl/context.h"
#include "present/presenter.h"

namespace lodline {

/// Frames [first, end) of a capture.
struct FrameRange {
  int64_t first = 0;
  int64_t end = 0;  ///< exclusive
};

/// Frames of `path` at `fps` (at least 1).
int64_t captureFrameCount(const CameraPath& path, double fps);

struct CaptureRequest {
  ContextBackend context = ContextBackend::kAuto;
  CameraPath path;
  std::string path_name;  ///< as given (for the stats)
  double fps = 30.0;
  /// The frames rendered; frames before `first` are simulated only, so frame k is the same
  /// whichever range renders it. Within [0, captureFrameCount()).
  FrameRange range;
  std::filesystem::path output;  ///< an .mp4 file, or a folder for frame_NNNNN.png
  bool png_sequence = false;
  std::filesystem::path metrics;  ///< per-frame CSV; empty: none
  std::filesystem::path stats;    ///< summary JSON; empty: none
  /// A folder for frame_NNNNN.svg, one per frame, strokes with stable ids
  /// (present/stroke_ids.h); empty: none. Must exist.
  std::filesystem::path svg_dir;
  /// A folder for pop_NNNNN.png, one per frame after the first: the frame faded, with the
  /// line pixels that appeared since the previous frame in green and those that vanished in
  /// red, by how much they popped (export/coherence.h, PopMap); empty: none. Must exist.
  std::filesystem::path pop_dir;
  /// Set (by a signal handler) to stop after the current frame; outputs are finished.
  const std::atomic<bool>* interrupted = nullptr;
  bool progress = false;  ///< a progress bar on stderr
  /// Coherent stroke parameterisation (present/stroke_parameterization.h). Default on.
  bool stroke_coherence = true;
  /// Seconds over which a line that appears fades in (present/stroke_fade.h); 0: off (the
  /// default: it did not lower the churn of the captures measured).
  float fade_in = 0.0f;
};

struct CaptureOutcome {
  int64_t frames = 0;  ///< frames written
  bool interrupted = false;
  /// Means over the frames after the first: churn (opacity-weighted, export/coherence.h),
  /// its 95th percentile, the binary churn and the uncompensated one; visible strokes.
  double churn_mean = 0.0, churn_p95 = 0.0, churn_binary_mean = 0.0, churn_raw_mean = 0.0, specks_mean = 0.0;
  double texture_drift_mean = 0.0;  ///< mean of the frames' texture_drift (frames after the first)
  bool measured = false;  ///< metrics were computed (metrics or stats requested)
};

/// One frame of a capture as CaptureRun::next() gives it.
struct CapturedFrame {
  int64_t index = 0;        ///< the frame's number on the path
  Camera camera;
  Image image;              ///< the colour image, row 0 = top
  bool measured = false;    ///< `metrics_row` and `coherence` were computed
  FrameCoherence coherence;  ///< against the previous frame (compared = false for frame 0)
  /// Where lines popped against the previous frame (measured frames of a capture whose request
  /// names a pop_dir; empty otherwise).
  PopMap pops;
  std::string metrics_row;  ///< the frame's line of the `--metrics` CSV (metricsCsvHeader())
  double specks = 0.0;
  double texture_drift = 0.0;
};

/// A capture advanced frame by frame (what captureFrames() writes, and the Python module's
/// frame iterator yields): the path, the simulation at the capture's rate, the drawing and
/// the coherence measure, without the outputs. `presenter` and `loaded` must outlive it.
class CaptureRun {
 public:
  /// Converges frame 0's detail and simulates (and draws, for the outline's hysteresis) the
  /// frames before request.range.first. `measure`: compute each frame's metrics.
  /// `pipeline` (ignored when measuring): simulate frame k + 1 while frame k is drawn
  /// (ScenePresenter::present's overlap); the frames are the same, but after next() the
  /// scene already holds the following frame, so only a caller that reads nothing of the
  /// scene between frames may ask for it.
  static Result<std::unique_ptr<CaptureRun>> start(LoadedScene& loaded, ScenePresenter& presenter,
                                                   const CaptureRequest& request, bool measure, bool pipeline = false);
  /// True when every frame of the range was given.
  bool done() const { return next_ >= range_.end; }
  /// Draws the next frame of the range. Errors: a failed draw or surface readback.
  Result<CapturedFrame> next();
  /// The presenter that draws the frames (for SVG output and stroke ids).
  ScenePresenter& presenter() { return presenter_; }

 private:
  CaptureRun(LoadedScene& loaded, ScenePresenter& presenter, const CaptureRequest& request, bool measure);
  Camera cameraAt(int64_t k) const;
  Camera simulate(int64_t k, bool while_drawing = false);
  LoadedScene& loaded_;
  ScenePresenter& presenter_;
  CameraPath path_;
  double fps_ = 30.0;
  FrameRange range_;
  bool measure_ = false;
  bool want_pops_ = false;  ///< request.pop_dir set: measured frames carry their PopMap
  bool pipeline_ = false;
  bool simulated_ahead_ = false;  ///< frame next_ was simulated during the last present()
  int64_t next_ = 0;
  float smoothing_w_ = 1.0f;
  double t0_ = 0.0;
  CoherenceMeter meter_;
  LineMask mask_;
  SurfaceImage surface_;
  ChangeZones zones_;  // where this frame's level of detail changed the mesh (measured frames)
};

/// Runs the capture; every output is finished (a valid video, complete PNGs, the CSV and
/// JSON of the frames done) even when a frame fails, which is then the error returned.
Result<CaptureOutcome> captureFrames(LoadedScene& loaded, const CaptureRequest& request);

}  // namespace lodline
