// Fuzz targets (libFuzzer) for everything lodline reads from the outside world, written
// once and built two ways:
//  - with LODLINE_FUZZ=ON (clang, -fsanitize=fuzzer,address,undefined): each fuzz_NAME.cpp
//    becomes the executable fuzz_NAME, run by scripts/fuzz.sh;
//  - in the ordinary test build: every target registers itself and
//    tests/reliability/fuzz_replay_test.cpp replays the committed inputs of
//    tests/fuzz/regressions/NAME/ (past findings) through it, under GCC and the ASan build.
//
// A target is one file: `LODLINE_FUZZ_TARGET(name) { ... data, size ... }`. Besides crashes,
// sanitizer reports and huge allocations, a target checks lodline's error contract and
// reports a violation through fail(): a refused input must give one line that names the file.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/result.h"

namespace lodline::fuzz {

using TargetFn = void (*)(const uint8_t* data, size_t size);

/// Adds a target to the registry of the replay build; returns true (for static init).
bool registerTarget(const char* name, TargetFn fn);
/// The registered targets, by name (replay build; empty in the libFuzzer build).
const std::vector<std::pair<std::string, TargetFn>>& registeredTargets();

/// The fuzz input as a file named "input<extension>" in a private temporary directory
/// (under /dev/shm when there is one), because lodline's readers take paths. The bytes are
/// `prefix` followed by `data`: a prefix steers a target to one variant of a format (binary
/// PLY, binary STL) while the fuzzer mutates the rest. The file is rewritten by each input.
class InputFile {
 public:
  InputFile(std::string_view extension, std::string_view prefix, const uint8_t* data, size_t size);
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// A finding that is not a crash: prints "lodline fuzz finding: <what>" and aborts, which
/// libFuzzer records as a crash input (and which fails the replay test).
[[noreturn]] void fail(const std::string& what);

/// Checks lodline's error contract for a refused input: one line, naming `path`.
void expectCleanError(const Error& error, const std::filesystem::path& path);

}  // namespace lodline::fuzz

#define LODLINE_FUZZ_CAT2(a, b) a##b
#define LODLINE_FUZZ_CAT(a, b) LODLINE_FUZZ_CAT2(a, b)

#ifdef LODLINE_FUZZING
#define LODLINE_FUZZ_TARGET(name)                                                        \
  static void LODLINE_FUZZ_CAT(lodlineFuzz_, name)(const uint8_t* data, size_t size);   \
  extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {             \
    LODLINE_FUZZ_CAT(lodlineFuzz_, name)(data, size);                                    \
    return 0;                                                                            \
  }                                                                                      \
  static void LODLINE_FUZZ_CAT(lodlineFuzz_, name)(const uint8_t* data, size_t size)
#else
#define LODLINE_FUZZ_TARGET(name)                                                        \
  static void LODLINE_FUZZ_CAT(lodlineFuzz_, name)(const uint8_t* data, size_t size);   \
  [[maybe_unused]] static const bool LODLINE_FUZZ_CAT(lodlineFuzzRegistered_, name) =   \
      ::lodline::fuzz::registerTarget(#name, LODLINE_FUZZ_CAT(lodlineFuzz_, name));      \
  static void LODLINE_FUZZ_CAT(lodlineFuzz_, name)(const uint8_t* data, size_t size)
#endif
