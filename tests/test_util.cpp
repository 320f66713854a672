#include "test_util.h"

#include <atomic>
#include <random>
#include <system_error>

#include <cstdio>

#include <sys/wait.h>
#include <unistd.h>

namespace lodline::test {

std::filesystem::path dataMesh(const std::string& name) {
  const std::filesystem::path p = std::filesystem::path(LODLINE_DATA_MESHES) / name;
  return std::filesystem::exists(p) ? p : std::filesystem::path();
}

int runCommand(const std::string& command, std::string* output) {
  FILE* pipe = popen(("EGL_PLATFORM=surfaceless " + command + " 2>&1").c_str(), "r");
  if (!pipe) return -1;
  std::string out;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof(buf), pipe)) > 0) out.append(buf, n);
  const int status = pclose(pipe);
  if (output) *output = out;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

int runLodline(const std::string& args, std::string* output) {
#ifdef LODLINE_BINARY
  return runCommand(std::string(LODLINE_BINARY) + " " + args, output);
#else
  (void)args;
  (void)output;
  return -1;
#endif
}

TempDir::TempDir() {
  static std::atomic<int> counter{0};
  std::random_device rd;
  path_ = std::filesystem::temp_directory_path() /
          ("lodline-test-" + std::to_string(getpid()) + "-" + std::to_string(counter++) + "-" +
           std::to_string(rd()));
  std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

}  // namespace lodline::test
