#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz, clang, ASan + UBSan) in build-fuzz/ and runs each
# for SECONDS (default 30) from its seed corpus (tests/fuzz/corpus/<target>) and its regression
# inputs (tests/fuzz/regressions/<target>). Exits nonzero on any crash, sanitizer report, leak,
# timeout (10 s for one input) or out-of-memory (2 GB), leaving the input that caused it in
# build-fuzz/findings/<target>/ (crash-*, timeout-*, oom-*, leak-*): replay it with
#   build-fuzz/tests/fuzz/oceanref_fuzz_<target> FILE
# and, once fixed, add it to tests/fuzz/regressions/<target>/ (tests/fuzz/README.md).
#
#   tools/fuzz.sh [SECONDS] [TARGET...]     (targets: scene cli exr piece; default all four)
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${1:-30}
shift $(($# > 0 ? 1 : 0))
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(scene cli exr piece)
case $seconds in '' | *[!0-9]*) echo "fuzz.sh: SECONDS must be a whole number, got '$seconds'" >&2; exit 2 ;; esac

kiss=${OCEANREF_KISSFFT_DIR:-$PWD/build/_deps/kissfft-src}
if [ ! -f "$kiss/kiss_fft.c" ]; then bash tools/setup.sh build; fi
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
if [ ! -f build-fuzz/CMakeCache.txt ]; then
  cmake -S . -B build-fuzz "${generator[@]}" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
    -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g" -DOCEANREF_FUZZ=ON -DBUILD_TESTING=OFF \
    -DOCEANREF_PYTHON=OFF -DOCEANREF_KISSFFT_DIR="$kiss" >/dev/null
fi
cmake --build build-fuzz --parallel "$(nproc)" --target "${targets[@]/#/oceanref_fuzz_}"

export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1
status=0
for t in "${targets[@]}"; do
  findings=build-fuzz/findings/$t
  work=build-fuzz/corpus-work/$t  # new inputs found while fuzzing (the checked-in corpus stays)
  mkdir -p "$findings" "$work"
  echo "fuzz.sh: $t for ${seconds}s"
  if ! build-fuzz/tests/fuzz/oceanref_fuzz_"$t" -max_total_time="$seconds" -timeout=10 \
      -rss_limit_mb=2048 -max_len=65536 -print_final_stats=1 \
      -artifact_prefix="$findings/" "$work" tests/fuzz/corpus/"$t" tests/fuzz/regressions/"$t" \
      >"build-fuzz/fuzz-$t.log" 2>&1; then
    echo "fuzz.sh: $t FOUND A PROBLEM: input in $findings/, log build-fuzz/fuzz-$t.log" >&2
    tail -n 40 "build-fuzz/fuzz-$t.log" >&2
    status=1
  fi
  grep -E '^stat::number_of_executed_units|^Done [0-9]+ runs' "build-fuzz/fuzz-$t.log" || true
done
[ $status -eq 0 ] && echo "fuzz.sh: no crash in ${targets[*]} (${seconds}s each)"
exit $status
