#!/usr/bin/env bash
# The determinism matrix: the golden suite must be bit-identical (SHA-256 of the decoded pixels
# and fields, reference/golden/manifest.json) from gcc -O2, clang -O2 and gcc -O0 builds, each
# with 1 and 2 threads.
set -euo pipefail
cd "$(dirname "$0")/.."

bash tools/build.sh build
CC=clang CXX=clang++ bash tools/build.sh build-clang
bash tools/build.sh build-O0 -DCMAKE_BUILD_TYPE=Debug  # CMake's Debug: -g, no optimization
failures=0
for dir in build build-clang build-O0; do
  for threads in 1 2; do
    if "$dir/src/oceanref" golden verify --threads "$threads" >"/tmp/oceanref-golden-$$.log"; then
      echo "determinism: $dir, $threads threads: identical"
    else
      echo "FAIL: $dir with $threads threads differs from reference/golden:" >&2
      grep -v ',identical,' "/tmp/oceanref-golden-$$.log" >&2 || true
      failures=$((failures + 1))
    fi
  done
done
rm -f "/tmp/oceanref-golden-$$.log"
[ "$failures" -eq 0 ]
