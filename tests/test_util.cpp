#include "test_util.h"

#include <atomic>
#include <random>
#include <system_error>

#include <unistd.h>

namespace lodline::test {

std::filesystem::path dataMesh(const std::string& name) {
  const std::filesystem::path p = std::filesystem::path(LODLINE_DATA_MESHES) / name;
  return std::filesystem::exists(p) ? p : std::filesystem::path();
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
