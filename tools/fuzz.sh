#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz, clang, ASan + UBSan) in build-fuzz/ and runs each
# for SECONDS (default 30) from its seed corpus (tests/fuzz/corpus/<target>) and its regression
# inputs (tests/fuzz/regressions/<target>). Exits nonzero on any crash, sanitizer report, leak,
# timeout (10 s for one input) or out-of-memory (2 GB), leaving the input that caused it in
# build-fuzz/findings/<target>/ (crash-*, timeout-*, oom-*, leak-*): replay it with
#   build-fuzz/tests/fuzz/oceanref_fuzz_<target> FILE
# and, once fixed, add it to tests/fuzz/regressions/<target>/ (tests/fuzz/README.md).
#
#   tools/fuzz.sh [--build DIR] [SECONDS] [TARGET...]   (targets: scene cli exr piece obj; default
#                                                        all five)
# --build DIR: an existing clang build configured with -DOCEANREF_FUZZ=ON instead of build-fuzz/
# (CI uses the sanitizer build, tools/test.sh --sanitize, which holds the fuzz targets too).
set -euo pipefail
cd "$(dirname "$0")/.."

dir=build-fuzz
if [ "${1:-}" = "--build" ]; then
  dir=${2:?fuzz.sh: --build needs a build directory}
  shift 2
  grep -q '^OCEANREF_FUZZ:BOOL=ON' "$dir/CMakeCache.txt" 2>/dev/null ||
    { echo "fuzz.sh: $dir is not a build configured with -DOCEANREF_FUZZ=ON" >&2; exit 2; }
fi
seconds=${1:-30}
shift $(($# > 0 ? 1 : 0))
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(scene cli exr piece obj)
case $seconds in '' | *[!0-9]*) echo "fuzz.sh: SECONDS must be a whole number, got '$seconds'" >&2; exit 2 ;; esac

kiss=${OCEANREF_KISSFFT_DIR:-$PWD/build/_deps/kissfft-src}
if [ ! -f "$kiss/kiss_fft.c" ]; then bash tools/setup.sh build; fi
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
if [ ! -f "$dir/CMakeCache.txt" ]; then
  cmake -S . -B "$dir" "${generator[@]}" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
    -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g" -DOCEANREF_FUZZ=ON -DBUILD_TESTING=OFF \
    -DOCEANREF_PYTHON=OFF -DOCEANREF_KISSFFT_DIR="$kiss" >/dev/null
fi
cmake --build "$dir" --parallel "$(nproc)" --target "${targets[@]/#/oceanref_fuzz_}"

export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1
status=0
for t in "${targets[@]}"; do
  findings=$dir/findings/$t
  work=$dir/corpus-work/$t  # new inputs found while fuzzing (the checked-in corpus stays)
  mkdir -p "$findings" "$work"
  echo "fuzz.sh: $t for ${seconds}s"
  if ! "$dir"/tests/fuzz/oceanref_fuzz_"$t" -max_total_time="$seconds" -timeout=10 \
      -rss_limit_mb=2048 -max_len=65536 -print_final_stats=1 \
      -artifact_prefix="$findings/" "$work" tests/fuzz/corpus/"$t" tests/fuzz/regressions/"$t" \
      >"$dir/fuzz-$t.log" 2>&1; then
    echo "fuzz.sh: $t FOUND A PROBLEM: input in $findings/, log $dir/fuzz-$t.log" >&2
    tail -n 40 "$dir/fuzz-$t.log" >&2
    status=1
  fi
  grep -E '^stat::number_of_executed_units|^Done [0-9]+ runs' "$dir/fuzz-$t.log" || true
done
[ $status -eq 0 ] && echo "fuzz.sh: no crash in ${targets[*]} (${seconds}s each)"
exit $status
