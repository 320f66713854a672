// A child process whose stdout and stderr go to one pipe that the parent reads without
// blocking, so several can run at once under one poll() loop (`lodline sweep --jobs N`).
#pragma once

#include <string>
#include <vector>

#include <sys/types.h>

#include "core/result.h"

namespace lodline {

struct ChildExit {
  int code = -1;       ///< exit status, or -1 when killed by a signal
  int signal = 0;      ///< the signal that killed it, 0 otherwise
  std::string output;  ///< everything it wrote to stdout and stderr
};

/// Move-only owner of a running child. The destructor kills (SIGKILL) and reaps a child that
/// was not waited for, so no zombie or orphan outlives it.
class ChildProcess {
 public:
  /// Starts `exe` with `args` (argv[1]...), stdin from /dev/null, stdout and stderr into a
  /// pipe. Errors name `exe`.
  static Result<ChildProcess> spawn(const std::string& exe, const std::vector<std::string>& args);

  ChildProcess(ChildProcess&& other) noexcept;
  ChildProcess& operator=(ChildProcess&& other) noexcept;
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;
  ~ChildProcess();

  pid_t pid() const { return pid_; }
  /// The read end of the output pipe (for poll()); -1 once it reached end of file.
  int fd() const { return fd_; }
  /// Reads what the pipe holds now without blocking; returns false once it is at end of file
  /// (the child closed its output, normally because it exited).
  bool readAvailable();
  /// Sends `sig` to the child (no-op once reaped).
  void signal(int sig) const;
  /// Reads the rest of the output, then waits for the child to exit.
  ChildExit wait();

 private:
  ChildProcess(pid_t pid, int fd) : pid_(pid), fd_(fd) {}
  void release();
  pid_t pid_ = -1;
  int fd_ = -1;
  std::string output_;
};

}  // namespace lodline
