// Shared helpers for the test executables.
#pragma once

#include <filesystem>
#include <string>

namespace lodline::test {

/// Path of a CGAL demo mesh (data/meshes/NAME, extracted by scripts/setup.sh), or an empty
/// path when it is not there (tests then GTEST_SKIP with a message).
std::filesystem::path dataMesh(const std::string& name);

/// Runs `command` through the shell with EGL_PLATFORM=surfaceless, stderr merged into
/// `output` (optional); returns the exit status (128 + signal when killed).
int runCommand(const std::string& command, std::string* output = nullptr);

/// Runs the built `lodline` binary with `args` (as runCommand).
int runLodline(const std::string& args, std::string* output = nullptr);

/// A fresh empty directory under the system temp dir, removed by the destructor.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

}  // namespace lodline::test
