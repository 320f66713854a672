#include "run_process.h"

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>
#include <thread>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace lodline::test {
namespace {

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// At most the first MiB: a child that floods its output must not grow this process (whose
// resident size at fork() counts in the next child's ru_maxrss).
std::string readFile(const std::filesystem::path& p) {
  constexpr size_t kMax = 1 << 20;
  std::ifstream in(p, std::ios::binary);
  std::string s(kMax, '\0');
  in.read(s.data(), kMax);
  s.resize(static_cast<size_t>(in.gcount()));
  std::error_code ec;
  const auto size = std::filesystem::file_size(p, ec);
  if (!ec && size > kMax) s += "\n[... " + std::to_string(size - kMax) + " more bytes]\n";
  return s;
}

}  // namespace

bool sanitizerBuild() {
#if defined(__SANITIZE_ADDRESS__)
  return true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
  return true;
#else
  return false;
#endif
#else
  return false;
#endif
}

std::string ProcessResult::describe() const {
  if (timed_out) return "timed out after " + std::to_string(seconds) + " s";
  if (signal != 0) return "killed by signal " + std::to_string(signal);
  return "exit " + std::to_string(exit_code);
}

Process::Process(const std::vector<std::string>& argv, const ProcessOptions& options)
    : timeout_s_(options.timeout_s), start_(now()) {
  const std::string out = (logs_ / "stdout").string(), err = (logs_ / "stderr").string();
  std::vector<std::string> env = options.env;
  env.push_back("EGL_PLATFORM=surfaceless");
  pid_ = fork();
  if (pid_ == 0) {
    const int o = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int e = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int in = open("/dev/null", O_RDONLY);
    if (o < 0 || e < 0 || in < 0) _exit(126);
    dup2(in, 0);
    dup2(o, 1);
    dup2(e, 2);
    setpgid(0, 0);  // its own group: a test's signal reaches the child and what it starts
    for (const std::string& kv : env) putenv(const_cast<char*>(kv.c_str()));
    if (options.file_size_limit > 0) {
      const rlimit r{options.file_size_limit, options.file_size_limit};
      setrlimit(RLIMIT_FSIZE, &r);
      std::signal(SIGXFSZ, SIG_IGN);  // over the limit, write() fails with EFBIG, as on a full disk
    }
    if (options.address_space_limit > 0 && !sanitizerBuild()) {
      const rlimit r{options.address_space_limit, options.address_space_limit};
      setrlimit(RLIMIT_AS, &r);
    }
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execvp(args[0], args.data());
    _exit(127);
  }
}

Process::~Process() {
  if (pid_ > 0 && !reaped_) {
    kill(pid_, SIGKILL);
    int status = 0;
    waitpid(pid_, &status, 0);
  }
}

void Process::signal(int sig) const {
  if (pid_ > 0 && !reaped_) kill(pid_, sig);
}

std::string Process::stderrSoFar() const { return readFile(logs_ / "stderr"); }

ProcessResult Process::wait() {
  ProcessResult r;
  if (pid_ <= 0) {
    r.err = "fork failed";
    return r;
  }
  int status = 0;
  rusage usage{};
  for (;;) {
    const pid_t done = wait4(pid_, &status, WNOHANG, &usage);
    if (done == pid_) break;
    if (done < 0 && errno != EINTR) break;
    if (now() - start_ > timeout_s_) {
      r.timed_out = true;
      kill(pid_, SIGKILL);
      wait4(pid_, &status, 0, &usage);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  reaped_ = true;
  r.seconds = now() - start_;
  r.peak_rss_kb = usage.ru_maxrss;
  if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) r.signal = WTERMSIG(status);
  r.out = readFile(logs_ / "stdout");
  r.err = readFile(logs_ / "stderr");
  return r;
}

ProcessResult runProcess(const std::vector<std::string>& argv, const ProcessOptions& options) {
  Process p(argv, options);
  return p.wait();
}

std::vector<std::string> lodlineArgs(const std::vector<std::string>& args) {
  std::vector<std::string> out = {LODLINE_BINARY};
  out.insert(out.end(), args.begin(), args.end());
  return out;
}

std::vector<std::string> linesOf(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

}  // namespace lodline::test
