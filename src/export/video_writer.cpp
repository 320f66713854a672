#include "export/video_writer.h"

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <utility>
#include <vector>

#include <fcntl.h>
#include <sys/mman.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "io/atomic_file.h"
#include "core/printable.h"

extern char** environ;

namespace lodline {

bool ffmpegAvailable() { return std::system("command -v ffmpeg >/dev/null 2>&1") == 0; }

Result<VideoWriter> VideoWriter::open(const std::filesystem::path& path, const VideoParams& params) {
  if (Status s = checkWritable(path); !s) return s.error();
  if (!ffmpegAvailable())
    return Error::runtime(path.string() + ": ffmpeg not found (install Debian's ffmpeg, or write a PNG "
                          "sequence with -o DIR/)");
  VideoWriter w;
  w.path_ = path;
  w.params_ = params;
  removeStaleTemporaries(path);  // parts of captures that were killed (SIGKILL) before
  const auto dir = path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path();
  std::string tmp_name(".");  // append(): see io/atomic_file.cpp on GCC 12's -Wrestrict
  tmp_name.append(path.filename().string()).append(".part").append(std::to_string(getpid())).append(".mp4");
  w.tmp_ = dir / tmp_name;

  int pipe_fds[2];
  if (pipe(pipe_fds) != 0) return Error::runtime(path.string() + ": pipe failed: " + std::strerror(errno));
  // ffmpeg's stderr goes to an in-memory file read by finish(): its messages become part of
  // our one-line error, and a file (unlike a pipe) never blocks ffmpeg however much it says.
  const int log_fd = memfd_create("lodline-ffmpeg-log", MFD_CLOEXEC);
  if (log_fd < 0) {
    close(pipe_fds[0]);
    close(pipe_fds[1]);
    return Error::runtime(path.string() + ": cannot create ffmpeg's log: " + std::strerror(errno));
  }
  const std::string size = std::to_string(params.width) + "x" + std::to_string(params.height);
  const std::string rate = std::to_string(params.fps);
  const std::string crf = std::to_string(params.crf);
  std::vector<std::string> args = {"ffmpeg", "-hide_banner", "-loglevel", "error", "-nostdin", "-y",
                                   "-f", "rawvideo", "-pix_fmt", "rgba", "-s", size, "-r", rate,
                                   "-i", "pipe:0",
                                   // yuv420p needs even sizes: pad odd ones by a pixel.
                                   "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                                   "-c:v", "libx264", "-preset", "medium", "-crf", crf,
                                   "-pix_fmt", "yuv420p",
                                   "-movflags", "+frag_keyframe+empty_moov+default_base_moof",
                                   "-f", "mp4", w.tmp_.string()};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[0], STDIN_FILENO);
  posix_spawn_file_actions_adddup2(&actions, log_fd, STDERR_FILENO);
  posix_spawn_file_actions_addclose(&actions, pipe_fds[1]);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK);
  posix_spawnattr_setpgroup(&attr, 0);  // own process group: terminal Ctrl-C reaches us only
  sigset_t none;
  sigemptyset(&none);
  posix_spawnattr_setsigmask(&attr, &none);
  const int rc = posix_spawnp(&w.pid_, "ffmpeg", &actions, &attr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  close(pipe_fds[0]);
  if (rc != 0) {
    close(pipe_fds[1]);
    close(log_fd);
    w.pid_ = -1;
    return Error::runtime(path.string() + ": cannot start ffmpeg: " + std::strerror(rc));
  }
  w.fd_ = pipe_fds[1];
  w.log_fd_ = log_fd;
  fcntl(w.fd_, F_SETFD, FD_CLOEXEC);
  return w;
}

VideoWriter::VideoWriter(VideoWriter&& o) noexcept
    : path_(std::move(o.path_)), tmp_(std::move(o.tmp_)), params_(o.params_),
      fd_(std::exchange(o.fd_, -1)), log_fd_(std::exchange(o.log_fd_, -1)), pid_(std::exchange(o.pid_, -1)),
      frames_(o.frames_) {}

VideoWriter::~VideoWriter() { abandon(); }

void VideoWriter::abandon() {
  if (fd_ >= 0) close(fd_);
  fd_ = -1;
  if (pid_ > 0) {
    int status = 0;
    waitpid(pid_, &status, 0);
  }
  pid_ = -1;
  if (log_fd_ >= 0) close(log_fd_);
  log_fd_ = -1;
  std::error_code ec;
  if (!tmp_.empty()) std::filesystem::remove(tmp_, ec);
}

Status VideoWriter::write(std::span<const uint8_t> rgba) {
  if (fd_ < 0) return Error::runtime(path_.string() + ": video already finished");
  if (rgba.size() != static_cast<size_t>(params_.width) * params_.height * 4)
    return Error::runtime(path_.string() + ": internal error: frame size mismatch");
  // A dead ffmpeg must give an error, not kill us with SIGPIPE.
  struct sigaction ignore{}, old{};
  ignore.sa_handler = SIG_IGN;
  sigaction(SIGPIPE, &ignore, &old);
  size_t done = 0;
  while (done < rgba.size()) {
    const ssize_t n = ::write(fd_, rgba.data() + done, rgba.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string why = std::strerror(n < 0 ? errno : EPIPE);
      sigaction(SIGPIPE, &old, nullptr);
      // ffmpeg's own reason, when it gave one (e.g. "No space left on device").
      std::string log;
      if (log_fd_ >= 0) {
        char buf[1024];
        const ssize_t m = pread(log_fd_, buf, sizeof(buf), 0);
        if (m > 0) log.assign(buf, static_cast<size_t>(m));
      }
      log = printableText(log.substr(0, log.find('\n')));
      return Error::runtime(path_.string() + ": ffmpeg stopped accepting frames (" + why + ")" +
                            (log.empty() ? std::string() : ": " + log));
    }
    done += static_cast<size_t>(n);
  }
  sigaction(SIGPIPE, &old, nullptr);
  ++frames_;
  return {};
}

Status VideoWriter::finish() {
  if (fd_ >= 0) close(fd_);
  fd_ = -1;
  int status = 0;
  if (pid_ > 0) {
    while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
  }
  pid_ = -1;
  // ffmpeg runs with -loglevel error: anything it printed is an error.
  std::string log;
  if (log_fd_ >= 0) {
    char buf[4096];
    const ssize_t n = pread(log_fd_, buf, sizeof(buf), 0);
    if (n > 0) log.assign(buf, static_cast<size_t>(n));
    close(log_fd_);
    log_fd_ = -1;
  }
  const std::string first_line = printableText(log.substr(0, log.find('\n')));
  std::error_code ec;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !log.empty()) {
    std::filesystem::remove(tmp_, ec);
    tmp_.clear();
    return Error::runtime(path_.string() + ": ffmpeg failed (exit status " +
                          std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) +
                          (first_line.empty() ? std::string(")") : "): " + first_line));
  }
  if (frames_ == 0) {
    std::filesystem::remove(tmp_, ec);
    return Error::runtime(path_.string() + ": no frame was rendered; no video written");
  }
  std::filesystem::rename(tmp_, path_, ec);
  if (ec) {
    std::filesystem::remove(tmp_, ec);
    return Error::runtime(path_.string() + ": cannot write: " + ec.message());
  }
  tmp_.clear();
  return {};
}

}  // namespace lodline
