#!/usr/bin/env bash
# lodline test command (README, .ci/run): set-up (packages, CGAL meshes, Release build),
# the whole CTest suite, then the same suite built with AddressSanitizer + UBSan, a short
# soak under it, and every fuzz target for a short bounded time (docs/reliability.md).
#
#   scripts/test.sh [--no-sanitize] [--no-fuzz]
#
# LODLINE_CI_FUZZ_SECONDS (default 10) sets the time per fuzz target, LODLINE_CI_SOAK_FRAMES
# (default 300) the soak's length.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
sanitize=1
fuzz=1
for arg in "$@"; do
  case "$arg" in
    --no-sanitize) sanitize=0 ;;
    --no-fuzz) fuzz=0 ;;
    *) echo "test.sh: unknown option '$arg'" >&2; exit 2 ;;
  esac
done
jobs=$(nproc)

"$here/scripts/setup.sh"
# Headless GL in tests: Mesa's surfaceless EGL platform, never a display.
unset DISPLAY WAYLAND_DISPLAY
export EGL_PLATFORM=surfaceless
ctest --test-dir "$here/build" --output-on-failure -j "$jobs"

if [ $sanitize -eq 1 ]; then
  "$here/scripts/setup.sh" --sanitize --build-dir "$here/build-asan"
  # Mesa/LLVM keep some allocations for the life of the process: suppress those leaks only.
  export LSAN_OPTIONS="suppressions=$here/scripts/lsan.supp:print_suppressions=0"
  export ASAN_OPTIONS="detect_odr_violation=0:abort_on_error=0"
  export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
  ctest --test-dir "$here/build-asan" --output-on-failure -j "$jobs"
  # A short soak: a randomised capture under the sanitizers, memory sampled.
  "$here/scripts/soak.sh" "${LODLINE_CI_SOAK_FRAMES:-300}" --build-dir "$here/build-asan"
fi

if [ $fuzz -eq 1 ]; then
  # clang + libFuzzer build (build-fuzz), then each target for a short bounded time.
  "$here/scripts/fuzz.sh" "${LODLINE_CI_FUZZ_SECONDS:-10}" --jobs "$jobs"
fi
