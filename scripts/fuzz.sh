#!/usr/bin/env bash
# Runs every libFuzzer target of tests/fuzz for a bounded time (docs/reliability.md).
#
#   scripts/fuzz.sh SECONDS [--jobs N] [--build-dir DIR] [--no-build] [TARGET...]
#
# Builds the targets in DIR (default build-fuzz: clang-14, -DLODLINE_FUZZ=ON, ASan + UBSan +
# libFuzzer), writes the seed corpora (small generated meshes in every format, the CGAL demo
# meshes of data/meshes up to 8 KiB converted to every format, caches, camera paths, PNGs)
# into DIR/corpus/TARGET, then runs each target (all of them, or the TARGETs named, e.g.
# mesh_off) for SECONDS seconds, N at a time (default 1). The committed inputs of
# tests/fuzz/regressions/TARGET (past findings) are replayed first. A finding (crash,
# sanitizer report, leak, allocation over 256 MiB, input taking over 10 s, or a broken error
# contract, see tests/fuzz/harness.h) is saved as DIR/findings/TARGET/*. Prints one line per
# target: executions, corpus size, findings. Exit status 1 when anything was found.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
seconds=""
jobs=1
build_dir="$here/build-fuzz"
build=1
targets=()
while [ $# -gt 0 ]; do
  case "$1" in
    --jobs) jobs=$2; shift ;;
    --build-dir) build_dir=$2; shift ;;
    --no-build) build=0 ;;
    -h|--help) sed -n '2,16p' "$0"; exit 0 ;;
    -*) echo "fuzz.sh: unknown option '$1'" >&2; exit 2 ;;
    *) if [ -z "$seconds" ]; then seconds=$1; else targets+=("$1"); fi ;;
  esac
  shift
done
if ! [[ "$seconds" =~ ^[0-9]+$ ]] || [ "$seconds" -lt 1 ]; then
  echo "usage: scripts/fuzz.sh SECONDS [--jobs N] [--build-dir DIR] [--no-build] [TARGET...]" >&2
  exit 2
fi

if [ $build -eq 1 ]; then
  launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
  CC=clang-14 CXX=clang++-14 cmake -S "$here" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DLODLINE_FUZZ=ON -DLODLINE_BUILD_TESTS=OFF -DLODLINE_BUILD_BENCH=OFF -DLODLINE_BUILD_VIEWER=OFF \
    "${launcher[@]}" >/dev/null
  cmake --build "$build_dir" --target lodline_fuzz -j "$(nproc)"
fi
if [ ${#targets[@]} -eq 0 ]; then
  for exe in "$build_dir"/fuzz/fuzz_*; do targets+=("$(basename "$exe" | sed 's/^fuzz_//')"); done
fi

# OpenMesh keeps one allocation for the life of the process: suppress that leak only.
export LSAN_OPTIONS="suppressions=$here/scripts/lsan.supp:print_suppressions=0"
export ASAN_OPTIONS="detect_odr_violation=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
"$build_dir/fuzz/lodline_fuzz_seeds" "$build_dir/corpus" "$here/data/meshes" >/dev/null

run_target() {
  local t=$1 exe="$build_dir/fuzz/fuzz_$1" log="$build_dir/findings/$1.log"
  local corpus="$build_dir/corpus/$t" findings="$build_dir/findings/$t"
  [ -x "$exe" ] || { echo "fuzz.sh: no target '$t' in $build_dir/fuzz" >&2; return 2; }
  mkdir -p "$corpus" "$findings"
  # New inputs go to the first corpus directory only; the committed ones are read.
  local flags=() dirs=("$corpus")
  [ -f "$here/tests/fuzz/dict/$t.dict" ] && flags+=("-dict=$here/tests/fuzz/dict/$t.dict")
  [ -d "$here/tests/fuzz/regressions/$t" ] && dirs+=("$here/tests/fuzz/regressions/$t")
  local status=0
  "$exe" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=256 -max_len=8192 \
    -print_final_stats=1 -artifact_prefix="$findings/" "${flags[@]}" "${dirs[@]}" >"$log" 2>&1 || status=$?
  local execs units found
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo 0)
  units=$(find "$corpus" -type f | wc -l)
  found=$(find "$findings" -type f | wc -l)
  printf '%-18s %10s execs in %ss  corpus %5s  findings %s\n' "$t" "${execs:-0}" "$seconds" "$units" "$found"
  if [ "$status" -ne 0 ] || [ "$found" -ne 0 ]; then
    echo "  $t: finding, see $log and $findings/" >&2
    return 1
  fi
}

mkdir -p "$build_dir/findings"
failed=0
pids=()
for t in "${targets[@]}"; do
  if [ "$jobs" -le 1 ]; then
    run_target "$t" || failed=1
  else
    run_target "$t" &
    pids+=($!)
    if [ ${#pids[@]} -ge "$jobs" ]; then
      wait "${pids[0]}" || failed=1
      pids=("${pids[@]:1}")
    fi
  fi
done
for p in "${pids[@]}"; do wait "$p" || failed=1; done
exit $failed
