#!/usr/bin/env bash
# The README's second command: builds and runs every test.
#
#   tools/test.sh              ctest (unit, property and CLI tests; two at a time) on the gcc
#                              build in build/, then the gcc/clang comparison
#                              (tools/compare_compilers.sh)
#   tools/test.sh --sanitize   ctest on an AddressSanitizer + UndefinedBehaviorSanitizer build
#                              in build-asan/: clang (with the sanitizers it builds ~2.3x faster
#                              than gcc; it is also the clang build that runs the unit tests), Debug
#                              (assertions on) at -O1 as the sanitizers' documentation recommends;
#                              the golden test on default_small only. The same build holds the
#                              libFuzzer targets (tools/fuzz.sh --build build-asan).
set -euo pipefail
cd "$(dirname "$0")/.."

jobs=$(nproc)
if [ "${1:-}" = "--sanitize" ]; then
  CC=clang CXX=clang++ bash tools/build.sh build-asan -DOCEANREF_SANITIZE=ON -DOCEANREF_FUZZ=ON \
    -DCMAKE_BUILD_TYPE=Debug "-DCMAKE_CXX_FLAGS_DEBUG=-g -O1" "-DCMAKE_C_FLAGS_DEBUG=-g -O1" \
    -DOCEANREF_GOLDEN_ONLY=default_small
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1
  ctest --test-dir build-asan --output-on-failure -j "$jobs"
  exit
fi
# The Python module on: build/ may have been configured by the quick start, before its packages.
bash tools/build.sh build -DOCEANREF_PYTHON=ON
ctest --test-dir build --output-on-failure -j "$jobs"
bash tools/compare_compilers.sh
