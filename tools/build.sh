#!/usr/bin/env bash
# Installs what is missing (tools/setup.sh), configures and builds oceanref.
#
#   tools/build.sh [BUILD_DIR] [extra CMake arguments...]     (default BUILD_DIR: build)
#
# Every build directory shares the KissFFT source fetched into build/_deps, so a second build
# (sanitizers, clang) does not download it again. The configure step runs for a new build
# directory, and again whenever CMake arguments are given (they change its cache).
set -euo pipefail
cd "$(dirname "$0")/.."

build_dir=${1:-build}
shift $(($# > 0 ? 1 : 0))
bash tools/setup.sh build
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
if [ ! -f "$build_dir/CMakeCache.txt" ] || [ $# -gt 0 ]; then
  cmake -S . -B "$build_dir" "${generator[@]}" \
    -DOCEANREF_KISSFFT_DIR="$PWD/build/_deps/kissfft-src" "$@" >/dev/null
fi
cmake --build "$build_dir" --parallel "$(nproc)"
