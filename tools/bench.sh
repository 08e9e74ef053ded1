#!/usr/bin/env bash
# An honest bench: the working tree against a baseline commit, measured in one run on one machine.
#
#   tools/bench.sh [--baseline REV] [--runs N] [--threads LIST] [--out DIR] [--quick]
#                  [--reference-size WxH]
#
# Builds the baseline (default: the newest tag reachable from HEAD, else commit 604a183, the
# reference point of issue 16) in build-bench/baseline-<sha> from a temporary git worktree
# (removed at exit; the build is cached by sha, so a rerun does not rebuild it) and the working
# tree in build-bench/current (Release, like tools/build.sh, without tests or the Python module;
# build/ is never used, so a Debug build there cannot spoil the numbers). Then
# tools/bench_runner.py times whole processes, alternating the two builds run by run (ABAB…):
#
#   synthesis         `oceanref fields waves_default.json -o X.exr` (each revision's scene),
#                     and the KissFFT frame time `oceanref bench synthesis` prints (its own
#                     in-process median of 20 frames: the FFT pipeline without the file)
#   fast render       each revision's default scene in fast mode, 1280x720, 4 spp, 2 threads
#   reference render  reference vs fast mode of the default scene at 320x180 (--reference-size),
#                     4 spp, 2 threads; the current build only when the baseline has no
#                     reference mode (604a183 has none)
#   thread scaling    the current fast render at 1 thread and each of --threads (default 2,nproc)
#
# each as median, min and max of N runs (default 5) with peak RSS, and writes DIR (default
# build-bench/results): bench.json (machine, compilers, both shas, every run), bench.md (the
# table, also printed on stdout) and bench.svg (ratios and scaling). Progress goes to stderr.
# --quick: 3 runs, 640x360 and 96x54, a smoke run. Not a test: nothing here fails on a slow
# result. Builds use at most BENCH_JOBS (default 2) parallel jobs.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD

usage() { sed -n '2,/^set -euo/{/^set -euo/d;s/^# \{0,1\}//;p}' "$0"; }

baseline=""
runs=""
threads=""
out="build-bench/results"
quick=0
reference_size=""
while [ $# -gt 0 ]; do
  case "$1" in
    --baseline) baseline=${2:?--baseline needs a revision}; shift 2 ;;
    --baseline=*) baseline=${1#*=}; shift ;;
    --runs) runs=${2:?--runs needs a number}; shift 2 ;;
    --runs=*) runs=${1#*=}; shift ;;
    --threads) threads=${2:?--threads needs a list}; shift 2 ;;
    --threads=*) threads=${1#*=}; shift ;;
    --out) out=${2:?--out needs a directory}; shift 2 ;;
    --out=*) out=${1#*=}; shift ;;
    --quick) quick=1; shift ;;
    --reference-size) reference_size=${2:?--reference-size needs WxH}; shift 2 ;;
    --reference-size=*) reference_size=${1#*=}; shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "bench.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
if [ -n "$runs" ] && ! [[ "$runs" =~ ^[1-9][0-9]*$ ]]; then
  echo "bench.sh: --runs: expected a positive integer, got '$runs'" >&2; exit 2
fi
if [ -n "$threads" ] && ! [[ "$threads" =~ ^[1-9][0-9]*(,[1-9][0-9]*)*$ ]]; then
  echo "bench.sh: --threads: expected a comma-separated list of positive integers, got '$threads'" >&2
  exit 2
fi
if [ -n "$reference_size" ] && ! [[ "$reference_size" =~ ^[1-9][0-9]*x[1-9][0-9]*$ ]]; then
  echo "bench.sh: --reference-size: expected WxH, got '$reference_size'" >&2; exit 2
fi
jobs=${BENCH_JOBS:-2}
if ! [[ "$jobs" =~ ^[1-9][0-9]*$ ]]; then
  echo "bench.sh: BENCH_JOBS: expected a positive integer, got '$jobs'" >&2; exit 2
fi

start=$SECONDS
log() { printf '[bench %4ds] %s\n' "$((SECONDS - start))" "$*" >&2; }

if [ -z "$baseline" ]; then
  baseline=$(git describe --tags --abbrev=0 HEAD 2>/dev/null || true)
  baseline=${baseline:-604a183}
fi
if ! sha=$(git rev-parse --verify --quiet "$baseline^{commit}"); then
  echo "bench.sh: --baseline: '$baseline' is not a commit of this repository" >&2; exit 2
fi
short=$(git rev-parse --short=12 "$sha")
log "baseline $baseline = $short; current = working tree at $(git rev-parse --short=12 HEAD)"

bench_dir="$root/build-bench"
mkdir -p "$bench_dir"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/oceanref-bench.XXXXXX")
worktree=""
cleanup() {
  if [ -n "$worktree" ] && [ -d "$worktree" ]; then
    git -C "$root" worktree remove --force "$worktree" >/dev/null 2>&1 || rm -rf "$worktree"
    git -C "$root" worktree prune >/dev/null 2>&1 || true
  fi
  rm -rf "$tmp"
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

# KissFFT source (Debian's source package, compiled by CMake with double scalars): the one of
# this tree's build/, else the main worktree's, else fetched by tools/setup.sh into build-bench/.
kissfft=${OCEANREF_KISSFFT_DIR:-}
if [ -z "$kissfft" ]; then
  common=$(cd "$(git rev-parse --git-common-dir)" && pwd)
  for d in "$root/build/_deps/kissfft-src" "$(dirname "$common")/build/_deps/kissfft-src" \
           "$bench_dir/_deps/kissfft-src"; do
    if [ -f "$d/kiss_fft.c" ]; then kissfft=$d; break; fi
  done
fi
if [ -z "$kissfft" ]; then
  bash tools/setup.sh "$bench_dir" >&2
  kissfft="$bench_dir/_deps/kissfft-src"
fi

generator=()
command -v ninja >/dev/null && generator=(-G Ninja)

# configure_args SRC_DIR: the options this revision's CMake accepts (BUILD_TESTING through
# include(CTest); OCEANREF_PYTHON only where the revision has the Python module).
configure_args() {
  local src=$1
  local args=(-DCMAKE_BUILD_TYPE=Release -DCMAKE_EXPORT_COMPILE_COMMANDS=ON
              "-DOCEANREF_KISSFFT_DIR=$kissfft")
  if grep -q -E 'include\(CTest\)|BUILD_TESTING' "$src/CMakeLists.txt"; then
    args+=(-DBUILD_TESTING=OFF)
  fi
  if grep -q 'OCEANREF_PYTHON' "$src/CMakeLists.txt"; then
    args+=(-DOCEANREF_PYTHON=OFF)
  fi
  printf '%s\n' "${args[@]}"
}

# build SRC_DIR BUILD_DIR NAME: configure (once) and build the program; its log in BUILD_DIR.
build() {
  local src=$1 dir=$2 name=$3 args
  mapfile -t args < <(configure_args "$src")
  mkdir -p "$dir"
  if [ ! -f "$dir/CMakeCache.txt" ]; then
    log "$name: configuring in ${dir#"$root"/} (${args[*]})"
    if ! cmake -S "$src" -B "$dir" "${generator[@]}" "${args[@]}" >"$dir/bench-configure.log" 2>&1; then
      tail -n 30 "$dir/bench-configure.log" >&2
      echo "bench.sh: configuring $name failed; log: $dir/bench-configure.log" >&2
      exit 1
    fi
  fi
  log "$name: building (-j$jobs; log ${dir#"$root"/}/bench-build.log)"
  if ! cmake --build "$dir" --target oceanref --parallel "$jobs" >"$dir/bench-build.log" 2>&1; then
    tail -n 30 "$dir/bench-build.log" >&2
    echo "bench.sh: building $name failed; log: $dir/bench-build.log" >&2
    exit 1
  fi
}

# The baseline, cached by sha: built once from a temporary worktree, which is removed at exit.
base_build="$bench_dir/baseline-$short"
if [ -x "$base_build/src/oceanref" ] && [ -f "$base_build/bench-built" ]; then
  log "baseline: cached build ${base_build#"$root"/}"
else
  rm -rf "$base_build"
  worktree="$bench_dir/src-$short"
  if [ -e "$worktree" ]; then
    git worktree remove --force "$worktree" >/dev/null 2>&1 || rm -rf "$worktree"
    git worktree prune
  fi
  git worktree add --detach --quiet "$worktree" "$sha"
  build "$worktree" "$base_build" "baseline $short"
  touch "$base_build/bench-built"
  git worktree remove --force "$worktree"
  worktree=""
fi

build "$root" "$bench_dir/current" "current"

# Each revision's own scenes (the baseline may not know keys the current parser wants).
mkdir -p "$tmp/baseline" "$tmp/current"
for scene in default waves_default; do
  git show "$sha:reference/scenes/$scene.json" >"$tmp/baseline/$scene.json"
  cp "reference/scenes/$scene.json" "$tmp/current/$scene.json"
done

runner_args=(--baseline-bin "$base_build/src/oceanref" --current-bin "$bench_dir/current/src/oceanref"
             --baseline-scenes "$tmp/baseline" --current-scenes "$tmp/current"
             --baseline-rev "$baseline" --baseline-sha "$sha" --work "$tmp/work" --out "$out")
[ -n "$runs" ] && runner_args+=(--runs "$runs")
[ -n "$threads" ] && runner_args+=(--threads "$threads")
[ -n "$reference_size" ] && runner_args+=(--reference-size "$reference_size")
[ "$quick" -eq 1 ] && runner_args+=(--quick)
/usr/bin/python3 tools/bench_runner.py "${runner_args[@]}" --elapsed-offset "$((SECONDS - start))"
log "done"
