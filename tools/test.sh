#!/usr/bin/env bash
# The README's second command: builds and runs every test.
#
#   tools/test.sh              ctest (unit, property and CLI tests) on the gcc build in build/,
#                              then the gcc/clang determinism comparison (tools/compare_compilers.sh)
#   tools/test.sh --sanitize   ctest on an AddressSanitizer + UndefinedBehaviorSanitizer build
#                              in build-asan/ (Debug, i.e. with assertions, at -O1 as the
#                              sanitizers' documentation recommends: -O0 made the tests ~3x
#                              slower; the golden test on default_small only)
set -euo pipefail
cd "$(dirname "$0")/.."

if [ "${1:-}" = "--sanitize" ]; then
  bash tools/build.sh build-asan -DOCEANREF_SANITIZE=ON -DCMAKE_BUILD_TYPE=Debug \
    "-DCMAKE_CXX_FLAGS_DEBUG=-g -O1" "-DCMAKE_C_FLAGS_DEBUG=-g -O1" -DOCEANREF_GOLDEN_ONLY=default_small
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1
  ctest --test-dir build-asan --output-on-failure
  exit
fi
bash tools/build.sh build
ctest --test-dir build --output-on-failure
bash tools/compare_compilers.sh
