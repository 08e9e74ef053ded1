#!/usr/bin/env bash
# The determinism matrix: every golden scene (reference/golden/manifest.json) must give the same
# SHA-256 — of the float32 pixels and fields and of the double buffers behind them — from every
# build, thread count, CPU variant and architecture. Each build is also checked at the
# machine-code level (tools/check_binary.sh: no libm transcendental, no fused multiply-add).
#
#   tools/determinism_matrix.sh --ci     what CI runs on every stop (.ci/run), after tools/test.sh
#       and with no build of its own: the gcc -O3 build (build/) with 1 thread (ctest's golden
#       test ran it with 2), the clang -O2 build (build-clang/, tools/compare_compilers.sh) with 2
#       threads, every scene; the gcc build under glibc's no-FMA/AVX2 variants on the two
#       sensitive scenes.
#   tools/determinism_matrix.sh          the cross-build matrix (five builds and the aarch64
#       sysroot), run by hand before a change to the numerics lands:
#       gcc -O3 (Release) with 1 and 2 threads; clang -O2 (RelWithDebInfo), gcc -O3
#       -march=x86-64-v3 (AVX2 and FMA available to the compiler), clang -O3 -march=native with 2
#       threads; gcc -O0 (Debug) with 2 threads on the two sensitive scenes (default_small, the
#       long horizon); the gcc build again under glibc's no-FMA/AVX2 variants (GLIBC_TUNABLES, as
#       on an older CPU); then aarch64: a cross build (tools/cross_aarch64.sh) run under
#       qemu-user, one thread, on the two sensitive scenes.
#   tools/determinism_matrix.sh --full   every scene on every build at 1, 2, 3 and 8 threads (and
#       on aarch64), and the gcc build under qemu-x86_64 -cpu Nehalem (an x86-64 CPU without AVX,
#       FMA or AVX2), one thread.
#   tools/determinism_matrix.sh --no-aarch64   skips the cross build (e.g. without network).
set -euo pipefail
cd "$(dirname "$0")/.."

full=0
aarch64=1
ci=0
for arg in "$@"; do
  case "$arg" in
    --full) full=1 ;;
    --ci) ci=1 ;;
    --no-aarch64) aarch64=0 ;;
    *) echo "usage: tools/determinism_matrix.sh [--ci | --full] [--no-aarch64]" >&2; exit 2 ;;
  esac
done
threads=(1 2)
[ "$full" -eq 1 ] && threads=(1 2 3 8)

only=()  # golden verify --only NAMES for the next verify calls; empty: every scene
log=$(mktemp)
trap 'rm -f "$log"' EXIT
failures=0
# verify LABEL THREADS COMMAND...: runs `COMMAND golden verify` with THREADS and reports.
verify() {
  local label=$1 t=$2
  shift 2
  if "$@" golden verify --root reference --threads "$t" "${only[@]}" >"$log" 2>&1; then
    echo "determinism: $label: identical ($(grep -c ',identical,' "$log") scenes)"
  else
    echo "FAIL: $label differs from reference/golden:" >&2
    grep -v ',identical,' "$log" >&2 || true
    failures=$((failures + 1))
  fi
}

sensitive=(--only default_small,long_horizon_many_cascades_grazing_sun)
bash tools/build.sh build
# The matrix renders with the program only: neither tests nor the Python module in the extra
# builds (build/ runs the tests: tools/test.sh).
program_only=(-DOCEANREF_PYTHON=OFF -DBUILD_TESTING=OFF)
CC=clang CXX=clang++ bash tools/build.sh build-clang -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  "${program_only[@]}"  # -O2 -g, as tools/compare_compilers.sh configures it
if [ "$ci" -eq 1 ]; then
  for dir in build build-clang; do
    bash tools/check_binary.sh "$dir" || failures=$((failures + 1))
  done
  verify "build, 1 thread" 1 build/src/oceanref
  verify "build-clang, 2 threads" 2 build-clang/src/oceanref
  only=("${sensitive[@]}")
  GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2_Usable,-AVX2,-FMA,-AVX,-FMA4 \
    verify "build, glibc without AVX/AVX2/FMA variants" 2 build/src/oceanref
  [ "$failures" -eq 0 ] &&
    echo "determinism: all identical (CI subset; the cross builds: tools/determinism_matrix.sh)"
  exit $((failures > 0))
fi
bash tools/build.sh build-O0 -DCMAKE_BUILD_TYPE=Debug "${program_only[@]}"  # -g, no optimization
bash tools/build.sh build-gcc-v3 -DCMAKE_C_FLAGS=-march=x86-64-v3 -DCMAKE_CXX_FLAGS=-march=x86-64-v3 \
  "${program_only[@]}"
CC=clang CXX=clang++ bash tools/build.sh build-clang-native \
  -DCMAKE_C_FLAGS=-march=native -DCMAKE_CXX_FLAGS=-march=native "${program_only[@]}"
builds=(build build-clang build-O0 build-clang-native)
# An x86-64-v3 binary needs AVX2, FMA, BMI2 to run; it is still built and checked without them.
if grep -qw avx2 /proc/cpuinfo && grep -qw fma /proc/cpuinfo && grep -qw bmi2 /proc/cpuinfo; then
  builds+=(build-gcc-v3)
else
  echo "determinism: this CPU lacks AVX2/FMA: build-gcc-v3 is checked but not run"
fi

for dir in build build-clang build-O0 build-gcc-v3 build-clang-native; do
  bash tools/check_binary.sh "$dir" || failures=$((failures + 1))
done
# The reference lighting costs ~1 ms per sea sample optimized, ~10x more unoptimized: the main
# build runs every scene at every thread count, the other builds at the last thread count, and
# the -O0 build the two scenes made to be sensitive (--full: everything everywhere).
for dir in "${builds[@]}"; do
  for t in "${threads[@]}"; do
    if [ "$full" -eq 0 ] && [ "$dir" != build ] && [ "$t" != "${threads[-1]}" ]; then continue; fi
    only=()
    [ "$full" -eq 0 ] && [ "$dir" = build-O0 ] && only=("${sensitive[@]}")
    verify "$dir, $t threads" "$t" "$dir/src/oceanref"
  done
done
only=()

# glibc's variants for CPUs without FMA/AVX2 (its ifunc choice; the portable math does not
# depend on it, so nothing may change).
GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2_Usable,-AVX2,-FMA,-AVX,-FMA4 \
  verify "build, glibc without AVX/AVX2/FMA variants" 2 build/src/oceanref


if [ "$aarch64" -eq 1 ]; then
  bash tools/cross_aarch64.sh build-aarch64
  bash tools/check_binary.sh build-aarch64 aarch64-linux-gnu-objdump || failures=$((failures + 1))
  # qemu-user hangs on threaded programs on these machines: one thread.
  # Every stop: the two scenes made to be sensitive (default_small, long horizon with 8 cascades
  # and a grazing sun), ~1 min under qemu; --full: the whole suite (~5 min).
  only=(--only default_small,long_horizon_many_cascades_grazing_sun)
  [ "$full" -eq 1 ] && only=()
  verify "aarch64 (qemu-user), 1 thread" 1 bash tools/cross_aarch64.sh --run
  only=()
fi

if [ "$full" -eq 1 ]; then
  # qemu-user comes with the aarch64 tools (tools/cross_aarch64.sh installs it).
  if command -v qemu-x86_64 >/dev/null; then
    verify "build under qemu-x86_64 -cpu Nehalem, 1 thread" 1 qemu-x86_64 -cpu Nehalem build/src/oceanref
  else
    echo "determinism: qemu-user missing (run without --no-aarch64): Nehalem run skipped"
  fi
fi

[ "$failures" -eq 0 ] && echo "determinism: all identical"
[ "$failures" -eq 0 ]
