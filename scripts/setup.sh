#!/usr/bin/env bash
# lodline set-up: installs the Debian 12 packages lodline needs (idempotent),
# extracts the CGAL demo meshes used by tests and benchmarks into data/ (ignored
# by git) and builds into build/ (ccache when available).
#
#   scripts/setup.sh [--no-build] [--build-dir DIR] [--sanitize]
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir="$here/build"
do_build=1
sanitize=OFF
while [ $# -gt 0 ]; do
  case "$1" in
    --no-build) do_build=0 ;;
    --build-dir) build_dir=$2; shift ;;
    --sanitize) sanitize=ON ;;
    -h|--help) sed -n '2,6p' "$0"; exit 0 ;;
    *) echo "setup.sh: unknown option '$1'" >&2; exit 2 ;;
  esac
  shift
done

packages=(
  build-essential cmake ninja-build ccache pkg-config git
  libopenmesh-dev libeigen3-dev libglm-dev libcgal-dev libcgal-demo
  libglfw3-dev libegl-dev libgl-dev libosmesa6-dev libegl-mesa0 libgl1-mesa-dri
  libgtest-dev libgmock-dev libbenchmark-dev libmeshoptimizer-dev
  libcli11-dev nlohmann-json3-dev libstb-dev libpng-dev
  glslang-tools ffmpeg xvfb xauth librsvg2-bin fonts-dejavu-core
  libimgui-dev libtinygltf-dev xdotool
  clang-14 libclang-rt-14-dev util-linux
  pybind11-dev python3-dev python3-numpy python3-pytest parallel dpkg-dev
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup.sh: installing ${missing[*]}" >&2
  sudo_cmd=""
  [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo_cmd apt-get update -qq
  $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# CGAL demo meshes (armadillo, bunny00, refined_elephant, fandisk, ...): tests and
# benchmarks look for them in data/meshes; they are never committed.
data_tar=/usr/share/doc/libcgal-dev/data.tar.gz
[ -f "$data_tar" ] || data_tar=$(dpkg -L libcgal-demo 2>/dev/null | grep -m1 'data\.tar\.gz$' || true)
if [ -n "$data_tar" ] && [ -f "$data_tar" ] && [ ! -f "$here/data/meshes/armadillo.off" ]; then
  mkdir -p "$here/data"
  tar -xzf "$data_tar" -C "$here/data" --strip-components=0 'data/meshes' 2>/dev/null ||
    tar -xzf "$data_tar" -C "$here/data"
  # The archive holds data/meshes/...: flatten to data/meshes.
  if [ -d "$here/data/data/meshes" ]; then
    rm -rf "$here/data/meshes"; mv "$here/data/data/meshes" "$here/data/meshes"; rm -rf "$here/data/data"
  fi
fi

if [ $do_build -eq 1 ]; then
  launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
  build_type=Release
  extra=()
  if [ "$sanitize" = ON ]; then build_type=RelWithDebInfo; extra=(-DLODLINE_BUILD_BENCH=OFF -DLODLINE_BUILD_VIEWER=OFF -DLODLINE_BUILD_PYTHON=OFF); fi
  cmake -S "$here" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=$build_type \
    -DLODLINE_SANITIZE=$sanitize "${launcher[@]}" "${extra[@]}" >/dev/null
  cmake --build "$build_dir" -j "$(nproc)"
fi
