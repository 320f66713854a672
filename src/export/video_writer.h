// Video output through an ffmpeg process fed raw RGBA frames by a pipe (Debian's ffmpeg).
// The file is written under a temporary name as fragmented MP4, so it is playable even if
// the capture stops early, and renamed to the target by finish(). ffmpeg runs in its own
// process group so a Ctrl-C in the terminal reaches lodline only, which then finishes the
// file cleanly.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

#include <sys/types.h>

#include "core/result.h"

namespace lodline {

struct VideoParams {
  int width = 1280;   ///< px (even sizes are required by yuv420p; odd sizes are padded)
  int height = 720;
  double fps = 30.0;  ///< frames per second of the output
  int crf = 18;       ///< x264 quality (lower is better; 18 ≈ visually lossless)
};

class VideoWriter {
 public:
  /// Starts ffmpeg writing `path` (.mp4). Error if ffmpeg is missing (suggesting a PNG
  /// sequence instead) or cannot start.
  static Result<VideoWriter> open(const std::filesystem::path& path, const VideoParams& params);
  ~VideoWriter();
  VideoWriter(VideoWriter&& o) noexcept;
  VideoWriter& operator=(VideoWriter&&) = delete;
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  /// Sends one frame: width·height·4 bytes, RGBA, top row first.
  Status write(std::span<const uint8_t> rgba);
  /// Closes the pipe, waits for ffmpeg and renames the file into place. With no frame
  /// written, or when ffmpeg failed (a non-zero exit, or any error it printed: ffmpeg exits
  /// with 0 when closing the file fails, e.g. on a full disk), removes it and returns an
  /// error quoting ffmpeg's first error line. ffmpeg's messages never reach stderr.
  Status finish();

 private:
  VideoWriter() = default;
  void abandon();
  std::filesystem::path path_, tmp_;
  VideoParams params_;
  int fd_ = -1;
  int log_fd_ = -1;  ///< ffmpeg's stderr (an anonymous in-memory file)
  pid_t pid_ = -1;
  int frames_ = 0;
};

/// True when an `ffmpeg` executable is on PATH.
bool ffmpegAvailable();

}  // namespace lodline
