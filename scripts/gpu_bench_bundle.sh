#!/usr/bin/env bash
# The frame benchmarks on a machine with a GPU and nothing installed (docs/performance.md,
# "On a GPU"): packs the Release `lodline`, `detail_frame_bench` and the shared libraries
# they need (not glibc, not the GL/EGL stack: the target's driver provides those) with the
# armadillo into one archive (at most 64 MiB), which runs there through EGL on the GPU
# without a display (EGL_EXT_platform_device: NVIDIA's driver through libglvnd's vendor file).
#
#   scripts/gpu_bench_bundle.sh pack [OUT.tar.gz]   # default build/lodline-gpu-bench.tar.gz
#   scripts/gpu_bench_bundle.sh selftest            # pack, unpack elsewhere, run it here
#
# On the target: tar xzf lodline-gpu-bench.tar.gz && lodline-gpu-bench/run.sh [FILTER]
# writes lodline-gpu-bench/results.txt: the GL renderer, then one table (medians per stage,
# ms; Google Benchmark's tabular counters). FILTER defaults to the detail_frame and
# pipelined cases (frames in turn, and with the next frame's CPU stages run during the draw).
# Needs a target glibc at least as new as the build machine's (Debian 12: 2.36).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${LODLINE_BUILD_DIR:-$here/build}  # the Release build to pack
mode=${1:-}
cleanup=()  # temporary directories, removed however the script ends
trap 'rm -rf "${cleanup[@]}"' EXIT

pack() {
  local out=$1
  local bin="$build/lodline" bench="$build/tests/bench/detail_frame_bench"
  for f in "$bin" "$bench"; do
    [ -x "$f" ] || { echo "gpu_bench_bundle: $f is missing (build Release with benchmarks: scripts/setup.sh)" >&2; exit 1; }
  done
  [ -f "$here/data/meshes/armadillo.off" ] || { echo "gpu_bench_bundle: data/meshes/armadillo.off is missing (scripts/setup.sh)" >&2; exit 1; }
  local stage
  stage=$(mktemp -d)
  cleanup+=("$stage")
  local root="$stage/lodline-gpu-bench"
  mkdir -p "$root/bin" "$root/lib" "$root/lib/glvnd" "$root/data"
  cp "$bin" "$bench" "$root/bin/"
  cp "$here/data/meshes/armadillo.off" "$root/data/"
  # Shared libraries: everything ldd names except glibc's own and the GL/EGL dispatch, which
  # must be the target's (they load its driver). libglvnd's libEGL and libGLdispatch go in
  # lib/glvnd, used only where the target has no libEGL.so.1 of its own.
  ldd "$bin" "$bench" | awk '$3 ~ /^\// {print $1, $3}' | sort -u | while read -r name path; do
    case "$name" in
      libc.so.*|libm.so.*|libdl.so.*|libpthread.so.*|librt.so.*|ld-linux*|libresolv.so.*) ;;
      libEGL.so.*|libGLdispatch.so.*) cp -L "$path" "$root/lib/glvnd/$name" ;;
      libGL.so.*|libGLX*.so.*|libOpenGL.so.*|libglapi.so.*|libEGL_mesa*|libgbm.so.*) ;;
      *) cp -L "$path" "$root/lib/$name" ;;
    esac
  done
  cat > "$root/run.sh" <<'RUN'
#!/bin/sh
# Runs lodline's frame benchmarks here through EGL (see scripts/gpu_bench_bundle.sh).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
filter=${1:-(detail_frame|pipelined)/}
lib="$here/lib"
# libglvnd's libEGL from the bundle only where the system has none (ldconfig is often not on
# a user's PATH).
if ! ( (ldconfig -p 2>/dev/null || /sbin/ldconfig -p 2>/dev/null) | grep -q 'libEGL\.so\.1 '); then
  lib="$lib:$here/lib/glvnd"
fi
export LD_LIBRARY_PATH="$lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export LODLINE_DATA_MESHES="$here/data"
unset DISPLAY WAYLAND_DISPLAY
out="$here/results.txt"
{
  echo "# lodline frame benchmarks, $(date -u +%Y-%m-%dT%H:%M:%SZ), $(uname -m), $(nproc) cores"
  "$here/bin/lodline" render "$here/data/armadillo.off" --size 320x240 -o "$here/check.png" --stats "$here/check.json" >/dev/null
  echo "# EGL platform: ${LODLINE_EGL_PLATFORM:-auto (surfaceless, else the first EGL device)}"
  printf '# GL: '; grep -o '"gl": *"[^"]*"' "$here/check.json" | sed 's/"gl": *//; s/"//g'
  "$here/bin/detail_frame_bench" --benchmark_filter="$filter" --benchmark_counters_tabular=true 2>"$here/bench.log"
} > "$out"
cat "$out"
RUN
  chmod +x "$root/run.sh"
  mkdir -p "$(dirname "$out")"
  tar -C "$stage" -czf "$out.tmp" lodline-gpu-bench
  mv "$out.tmp" "$out"
  local size
  size=$(stat -c %s "$out")
  if [ "$size" -gt $((64 * 1024 * 1024)) ]; then
    echo "gpu_bench_bundle: $out is $size bytes, over 64 MiB" >&2
    exit 1
  fi
  echo "gpu_bench_bundle: wrote $out ($((size / 1024)) KiB)" >&2
}

case "$mode" in
  pack)
    pack "${2:-$build/lodline-gpu-bench.tar.gz}"
    ;;
  selftest)
    [ -f "$here/data/meshes/armadillo.off" ] || { echo "gpu_bench_bundle: no data/meshes/armadillo.off: skipped" >&2; exit 77; }
    # Unpacked in another directory and run from there, on this machine's GL (llvmpipe
    # here): the bundle must not read the source tree or the build tree.
    tmp=$(mktemp -d)
    cleanup+=("$tmp")
    pack "$tmp/bundle.tar.gz"
    mkdir "$tmp/target"
    tar -C "$tmp/target" -xzf "$tmp/bundle.tar.gz"
    # Through an EGL device, as on a GPU machine (Mesa's software device here).
    (cd / && LODLINE_EGL_PLATFORM=device "$tmp/target/lodline-gpu-bench/run.sh" 'detail_frame/armadillo.off/T:16/iter') > "$tmp/log"
    r="$tmp/target/lodline-gpu-bench/results.txt"
    grep -q '^# GL: .' "$r" || { echo "gpu_bench_bundle: no GL line in results" >&2; cat "$r" >&2; exit 1; }
    grep -q 'controlled_ms' "$r" || { echo "gpu_bench_bundle: no benchmark table in results" >&2; cat "$r" >&2; exit 1; }
    grep -q 'detail_frame/armadillo.off/T:16' "$r" || { echo "gpu_bench_bundle: the armadillo case did not run" >&2; cat "$r" >&2; exit 1; }
    cat "$r"
    ;;
  *)
    sed -n '2,14p' "$0" >&2
    exit 2
    ;;
esac
