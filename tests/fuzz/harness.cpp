#include "harness.h"

#include <cstdio>
#include <cstdlib>
#include <system_error>

#include <unistd.h>

namespace lodline::fuzz {
namespace {

std::vector<std::pair<std::string, TargetFn>>& registry() {
  static std::vector<std::pair<std::string, TargetFn>> targets;
  return targets;
}

// One private directory per process, removed at exit.
const std::filesystem::path& workDir() {
  static const std::filesystem::path dir = [] {
    std::error_code ec;
    std::filesystem::path base = "/dev/shm";
    if (!std::filesystem::is_directory(base, ec) || access(base.c_str(), W_OK) != 0)
      base = std::filesystem::temp_directory_path();
    std::string tmpl = (base / "lodline-fuzz-XXXXXX").string();
    if (!mkdtemp(tmpl.data())) fail("cannot create a temporary directory under " + base.string());
    std::atexit([] {
      std::error_code ignored;
      std::filesystem::remove_all(workDir(), ignored);
    });
    return std::filesystem::path(tmpl);
  }();
  return dir;
}

}  // namespace

bool registerTarget(const char* name, TargetFn fn) {
  registry().emplace_back(name, fn);
  return true;
}

const std::vector<std::pair<std::string, TargetFn>>& registeredTargets() { return registry(); }

InputFile::InputFile(std::string_view extension, std::string_view prefix, const uint8_t* data, size_t size)
    : path_(workDir() / ("input" + std::string(extension))) {
  FILE* f = std::fopen(path_.c_str(), "wb");
  if (!f) fail("cannot write " + path_.string());
  const bool ok = std::fwrite(prefix.data(), 1, prefix.size(), f) == prefix.size() &&
                  (size == 0 || std::fwrite(data, 1, size, f) == size);
  if (std::fclose(f) != 0 || !ok) fail("cannot write " + path_.string());
}

void fail(const std::string& what) {
  std::fprintf(stderr, "lodline fuzz finding: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

void expectCleanError(const Error& error, const std::filesystem::path& path) {
  if (error.message.find(path.string()) == std::string::npos)
    fail("error does not name the file: " + error.message);
  if (error.message.find('\n') != std::string::npos) fail("error is not one line: " + error.message);
  for (unsigned char c : error.message)
    if (c < 0x20 || c == 0x7f) fail("error holds a control character (byte " + std::to_string(c) + "): " + error.message);
  if (error.message.size() > 1000) fail("error line is too long (" + std::to_string(error.message.size()) + " chars)");
}

}  // namespace lodline::fuzz
