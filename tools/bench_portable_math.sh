#!/usr/bin/env bash
# What the portable elementary functions cost: the default scene rendered by the normal build
# (build/, src/core/math.h) and by a build that forwards core/math.h to glibc's libm
# (build-libm/, -DOCEANREF_LIBM_MATH=ON: for this measurement only, not bit-reproducible across
# machines), alternately, the same number of times; prints the median CPU time of each and
# their ratio (goal ≤ 1.3, reference/ACCURACY.md).
#
#   tools/bench_portable_math.sh [RUNS] [SCENE] [extra render flags...]
#       RUNS default 5, SCENE default reference/scenes/default.json; one thread unless
#       --threads is among the extra flags
set -euo pipefail
cd "$(dirname "$0")/.."

runs=${1:-5}
scene=${2:-reference/scenes/default.json}
shift $(($# > 2 ? 2 : $#))
extra=("$@")
[[ " ${extra[*]} " == *" --threads "* ]] || extra+=(--threads 1)

bash tools/build.sh build >/dev/null
bash tools/build.sh build-libm -DOCEANREF_LIBM_MATH=ON >/dev/null
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# cpu_seconds BUILD: user + system CPU time of one render.
cpu_seconds() {
  /usr/bin/time -f '%U %S' -o "$tmp/time" "$1/src/oceanref" render "$scene" -o "$tmp/out.exr" \
    "${extra[@]}" >/dev/null 2>&1
  awk '{print $1 + $2}' "$tmp/time"
}
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
for ((i = 0; i < runs; ++i)); do
  cpu_seconds build >>"$tmp/portable"
  cpu_seconds build-libm >>"$tmp/libm"
done
portable=$(median <"$tmp/portable")
libm=$(median <"$tmp/libm")
echo "# $(date -u +%Y-%m-%d), $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores, $(g++ --version | head -1)"
echo "# $scene, render ${extra[*]}, median of $runs runs each, CPU seconds (user + system)"
echo "portable_math_s,glibc_libm_s,ratio"
awk -v p="$portable" -v l="$libm" 'BEGIN {printf "%.2f,%.2f,%.2f\n", p, l, p / l}'
