#!/usr/bin/env bash
# lodline test command (README, .ci/run): set-up (packages, CGAL meshes, Release build),
# the whole CTest suite, then the same suite built with AddressSanitizer + UBSan.
#
#   scripts/test.sh [--no-sanitize]
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
sanitize=1
[ "${1:-}" = "--no-sanitize" ] && sanitize=0
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
fi
