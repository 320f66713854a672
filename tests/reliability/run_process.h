// The `lodline` program run as a child process for the reliability tests: exit status or
// signal, stdout and stderr apart, peak resident memory (wait4's ru_maxrss), resource limits
// (file size, address space) and a timeout, so a hang or a runaway allocation is a failure
// with a message rather than a stuck test.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <sys/types.h>

#include "test_util.h"

namespace lodline::test {

struct ProcessOptions {
  std::vector<std::string> env;         ///< extra NAME=value entries
  uint64_t file_size_limit = 0;         ///< RLIMIT_FSIZE in bytes (0: none); SIGXFSZ ignored, so writes fail
  uint64_t address_space_limit = 0;     ///< RLIMIT_AS in bytes (0: none); ignored in sanitizer builds
  double timeout_s = 120.0;             ///< then SIGKILL, and the result says timed_out
};

struct ProcessResult {
  int exit_code = -1;     ///< exit status, -1 when ended by a signal
  int signal = 0;         ///< the signal that ended it, 0 when it exited
  bool timed_out = false;
  std::string out;        ///< stdout (its first MiB)
  std::string err;        ///< stderr (its first MiB)
  /// Largest resident set, KiB (wait4's ru_maxrss: Linux counts the parent's resident
  /// size at fork() in it too, so it is an upper bound; this process stays small).
  long peak_rss_kb = 0;
  double seconds = 0.0;
  /// "exit 1", "signal 11", "timed out": for failure messages.
  std::string describe() const;
};

/// A running child. The destructor kills (SIGKILL) and reaps it if it is still running.
class Process {
 public:
  Process(const std::vector<std::string>& argv, const ProcessOptions& options = {});
  ~Process();
  Process(const Process&) = delete;
  Process& operator=(const Process&) = delete;
  pid_t pid() const { return pid_; }
  /// Sends `sig` to the child.
  void signal(int sig) const;
  /// Waits for the end (or the timeout) and collects the result. Call once.
  ProcessResult wait();
  /// Bytes written to stderr so far.
  std::string stderrSoFar() const;

 private:
  TempDir logs_;
  pid_t pid_ = -1;
  double timeout_s_ = 0.0;
  double start_ = 0.0;
  bool reaped_ = false;
};

/// Runs `argv` to its end.
ProcessResult runProcess(const std::vector<std::string>& argv, const ProcessOptions& options = {});

/// The built `lodline` binary with `args`.
std::vector<std::string> lodlineArgs(const std::vector<std::string>& args);

/// True when this test binary (and so the lodline binary beside it) has AddressSanitizer.
bool sanitizerBuild();

/// Lines of `text` (without line ends; a last line without "\n" counts).
std::vector<std::string> linesOf(const std::string& text);

}  // namespace lodline::test
