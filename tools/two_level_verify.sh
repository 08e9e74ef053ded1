#!/usr/bin/env bash
# Do the two-level estimate's bounds hold? (issue 50; reference/ACCURACY.md, "One error budget per
# pixel".) Each scene at WxH is rendered twice, both with the reference lighting at tolerance
# 1e-3: the two-level estimate to render.pixel_tolerance TOL (4 spp, the default cap), and an
# independent dense render of the fixed grid (DENSE spp, every sample lit by the reference). Per
# sea pixel, the two-level pixel is within its bound when, in every channel, |two-level − dense|
# ≤ pixel_error + lighting_error + the dense render's own pixel_error + lighting_error. Prints a
# Markdown table with the machine, date and commit. The two-level estimate is rendered with each
# pixel pattern of PATTERNS (render.pixel_pattern, default "grid sobol"), at its default cap,
# against the same dense render.
#
#   bash tools/two_level_verify.sh [WxH] [DENSE] [TOL]     (default 16x9 1024 0.05)
#   PATTERNS=sobol bash tools/two_level_verify.sh ...
set -euo pipefail
cd "$(dirname "$0")/.."

size=${1:-16x9}
dense=${2:-1024}
tolerance=${3:-0.05}
threads=${THREADS:-2}
patterns=${PATTERNS:-grid sobol}
bin=${OCEANREF_BIN:-build/src/oceanref}
[ -x "$bin" ] || bash tools/build.sh build >/dev/null
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scenes=(reference/scenes/default.json
        reference/scenes/golden/pm_high_sun.json
        reference/scenes/golden/long_horizon_many_cascades_grazing_sun.json)
common=(--set shading.accuracy=reference --set shading.tolerance=1e-3 --set shading.sky_order=null
        --set shading.sun_order=null --set "render.width=${size%x*}" --set "render.height=${size#*x}"
        --set render.max_samples_per_pixel=null --set render.footprint_filtering=null
        --aov --threads "$threads")
names=()
for scene in "${scenes[@]}"; do
  name=$(basename "$scene" .json)
  names+=("$name")
  echo "two_level_verify: $name" >&2
  for pattern in $patterns; do
    /usr/bin/time -f "%e" -o "$work/$name.$pattern.time" "$bin" render "$scene" "${common[@]}" \
      --set render.samples_per_pixel=4 --set "render.pixel_tolerance=$tolerance" \
      --set "render.pixel_pattern=$pattern" -o "$work/$name.$pattern.exr" >/dev/null
  done
  /usr/bin/time -f "%e" -o "$work/$name.dense.time" "$bin" render "$scene" "${common[@]}" \
    --set "render.samples_per_pixel=$dense" --set render.pixel_tolerance=null \
    -o "$work/$name.dense.exr" >/dev/null
done

PYTHONPATH="$PWD/build/python${PYTHONPATH:+:$PYTHONPATH}" /usr/bin/python3 - "$work" "${names[*]}" "$size" "$dense" "$tolerance" "$threads" "$patterns" \
  "$(git rev-parse --short HEAD)$(git diff --quiet HEAD || echo -dirty)" \
  "$(lscpu | sed -n 's/^Model name: *//p' | head -n1)" <<'EOF'
import datetime, sys
import numpy as np
sys.path.insert(0, "tools")
from image_difference import channels as read, layer

work, names, size, dense, tolerance, threads, patterns, commit, cpu = sys.argv[1:10]

print(f"Each scene at {size}: the two-level estimate (4 spp, render.pixel_tolerance {tolerance}) "
      f"against a dense render ({dense} spp, the reference at every sample), both with the "
      f"reference at 1e-3; {threads} threads; {cpu}, {datetime.datetime.utcnow():%Y-%m-%d %H:%M} "
      f"UTC, commit {commit}, `bash tools/two_level_verify.sh {size} {dense} {tolerance}`.\n")
print("| scene | pixel pattern | sea pixels | within their bound | within the tolerance "
      "| actual error p50 / p99 | bound p50 / p99 | two-level s | dense s |")
print("|---|---|---:|---:|---:|---|---|---:|---:|")
for name, pattern in ((n, p) for n in names.split() for p in patterns.split()):
    two = read(f"{work}/{name}.{pattern}.exr")
    den = read(f"{work}/{name}.dense.exr")
    sea = two["coverage"] > 0
    actual = np.abs(layer(two) - layer(den))
    bound = layer(two, "pixel_error") + layer(two, "lighting_error")
    allowance = bound + layer(den, "pixel_error") + layer(den, "lighting_error")
    within = np.all(actual <= allowance, axis=-1)[sea]
    largest = layer(two).max(axis=-1)[sea]
    relative_actual = actual.max(axis=-1)[sea] / largest
    relative_bound = bound.max(axis=-1)[sea] / largest
    meets = relative_bound <= float(tolerance)
    t2 = float(open(f"{work}/{name}.{pattern}.time").read())
    td = float(open(f"{work}/{name}.dense.time").read())
    print(f"| {name} | {pattern} | {sea.sum()} | {100 * within.mean():.1f}% | {100 * meets.mean():.1f}% "
          f"| {np.percentile(relative_actual, 50):.2g} / {np.percentile(relative_actual, 99):.2g} "
          f"| {np.percentile(relative_bound, 50):.2g} / {np.percentile(relative_bound, 99):.2g} "
          f"| {t2:.1f} | {td:.1f} |")
EOF
