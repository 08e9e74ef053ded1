#!/usr/bin/env bash
# Ground truth of visibility on every golden scene (reference/ACCURACY.md, "Two renderers"):
# each rendered by the rasterizer (on the projected grid's triangles) and by the ray tracer
# against the continuous surface (`--renderer raytrace_surface`), both with the golden's own
# settings except adaptive sampling (render.pixel_tolerance dropped: the fixed S×S grid, so that
# both shade the same sample positions), compared per pixel as tools/image_difference.py does,
# with each renderer's wall-clock time. Where they differ the grid under-samples the surface
# (crests cut at grazing views) or a sample is shaded at another x0 (the grid's interpolated one
# against the true hit's).
#
#   tools/surface_truth.sh [THREADS]   (default 2; builds build/ when missing)
#
# About 10 minutes on 2 cores. Markdown on stdout.
set -euo pipefail
cd "$(dirname "$0")/.."
threads=${1:-2}
[ -x build/src/oceanref ] || bash tools/build.sh build >&2
bin=$PWD/build/src/oceanref
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

for scene in reference/scenes/golden/*.json; do
  name=$(basename "$scene" .json)
  # The golden without adaptive sampling, its object paths made absolute.
  python3 - "$scene" "$tmp/$name.json" <<'PY'
import json, os, sys
s = json.load(open(sys.argv[1]))
for key in ("pixel_tolerance", "max_samples_per_pixel"):
    s.get("render", {}).pop(key, None)
for o in s.get("objects", []):
    o["obj"] = os.path.abspath(os.path.join(os.path.dirname(sys.argv[1]), o["obj"]))
json.dump(s, open(sys.argv[2], "w"))
PY
  for renderer in raster raytrace_surface; do
    echo "surface_truth.sh: $name, $renderer" >&2
    start=$(date +%s%N)
    "$bin" render "$tmp/$name.json" -o "$tmp/$name.$renderer.exr" --aov --renderer "$renderer" \
      --threads "$threads" >/dev/null 2>&1
    echo "$name $renderer $((($(date +%s%N) - start) / 1000000))" >>"$tmp/times"
  done
done

commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
cpu=$(lscpu | sed -n 's/^Model name: *//p' | head -1)
PYTHONPATH=$PWD/build/python:$PWD/tools /usr/bin/python3 - "$tmp" "$commit" "$cpu" "$(nproc)" \
  "$threads" <<'PY'
import datetime, sys
from image_difference import differences, read

tmp, commit, cpu, cores, threads = sys.argv[1:6]
times = {}
for line in open(f"{tmp}/times"):
    name, renderer, ms = line.split()
    times[(name, renderer)] = int(ms) / 1000.0

print(f"**The rasterizer against the continuous surface** (`tools/surface_truth.sh {threads}`; "
      f"{datetime.date.today()}, {cpu}, {cores} cores, {threads} threads, commit {commit}): "
      f"each golden scene (fixed S×S samples) rasterized, against the same ray traced on the "
      f"continuous surface (`raytrace_surface`).")
print()
print("| scene | pixels | p50 | p99 | relative RMS | depth RMS | coverage differs | raster | "
      "raytrace_surface |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
for name in sorted({n for n, _ in times}):
    truth = read(f"{tmp}/{name}.raytrace_surface.exr")
    d = differences(read(f"{tmp}/{name}.raster.exr"), truth)
    print(f"| {name} | {truth[1].size} | {d['p50']:.2g} | {d['p99']:.2g} | {d['rms']:.2g} | "
          f"{d['depth_rms']:.2g} | {d['coverage']} | {times[(name, 'raster')]:.1f} s | "
          f"{times[(name, 'raytrace_surface')]:.1f} s |")
PY
