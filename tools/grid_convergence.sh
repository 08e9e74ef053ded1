#!/usr/bin/env bash
# What the projected grid's triangulation costs at grazing views (reference/ACCURACY.md, "Two
# renderers"): the two grazing golden scenes rasterized with grid.columns = grid.rows = 96 …
# 6144, each compared with the same scene ray traced against the continuous surface
# (`--renderer raytrace_surface`, the ground truth of visibility; its grid is the scene's, which
# only sets the area of sea it covers). Fast lighting and 4 spp in every render, so the renders
# differ only in visibility and where a sample is shaded; per render the relative difference
# per pixel (largest over R, G, B of |c − f|/s, f the surface render, s = max(|f|, 0.01·RMS of
# f's channel) as `oceanref compare` scales it, so near-black pixels do not dominate) at p50 and
# p99, the relative RMS over the image (√Σ|c − f|² / √Σ|f|²), the RMS of the relative difference
# of the view depth (AOV) over pixels that see the sea in both, the pixels whose sea coverage
# differs, and the wall-clock seconds.
#
#   tools/grid_convergence.sh [THREADS]   (default 2; builds build/ when missing)
#
# About 6 minutes on 2 cores; the 6144 grid needs about 4 GB. Markdown on stdout.
set -euo pipefail
cd "$(dirname "$0")/.."
threads=${1:-2}
[ -x build/src/oceanref ] || bash tools/build.sh build >&2
bin=$PWD/build/src/oceanref
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

scenes=(long_horizon_many_cascades_grazing_sun tma_shallow_grazing)
levels=(96 192 384 768 1536 3072 6144)
for name in "${scenes[@]}"; do
  for n in surface "${levels[@]}"; do
    echo "grid_convergence.sh: $name, grid $n" >&2
    python3 - "reference/scenes/golden/$name.json" "$tmp/$name.$n.json" "$n" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
s.setdefault("shading", {})["accuracy"] = "fast"
s["render"]["samples_per_pixel"] = 4
if sys.argv[3] != "surface":
    s.setdefault("grid", {})["columns"] = s["grid"]["rows"] = int(sys.argv[3])
json.dump(s, open(sys.argv[2], "w"))
PY
    renderer=raster
    [ "$n" = surface ] && renderer=raytrace_surface
    start=$(date +%s%N)
    "$bin" render "$tmp/$name.$n.json" -o "$tmp/$name.$n.exr" --aov --threads "$threads" \
      --renderer "$renderer" >/dev/null 2>&1
    echo "$name $n $((($(date +%s%N) - start) / 1000000))" >>"$tmp/times"
  done
done

commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
cpu=$(lscpu | sed -n 's/^Model name: *//p' | head -1)
# The EXRs are read by oceanref's own Python module (build/python).
PYTHONPATH=$PWD/build/python:$PWD/tools /usr/bin/python3 - "$tmp" "$commit" "$cpu" "$(nproc)" \
  "$threads" "${levels[*]}" "${scenes[*]}" <<'PY'
import datetime, sys
from image_difference import differences, read

tmp, commit, cpu, cores, threads, levels, scenes = sys.argv[1:8]
times = {}
for line in open(f"{tmp}/times"):
    name, n, ms = line.split()
    times[(name, n)] = int(ms) / 1000.0

print(f"**Grid convergence at grazing views** (`tools/grid_convergence.sh {threads}`; "
      f"{datetime.date.today()}, {cpu}, {cores} cores, {threads} threads, commit {commit}): "
      f"each scene with fast lighting and 4 spp, rasterized on an N × N projected grid, against "
      f"the same ray traced on the continuous surface (`raytrace_surface`, its time in the last "
      f"row).")
print()
print("| scene | N | p50 | p99 | relative RMS | depth RMS | coverage differs | seconds |")
print("|---|---:|---:|---:|---:|---:|---:|---:|")
for name in scenes.split():
    truth = read(f"{tmp}/{name}.surface.exr")
    for n in levels.split() + ["surface"]:
        d = differences(read(f"{tmp}/{name}.{n}.exr"), truth)
        label = "continuous surface" if n == "surface" else n
        print(f"| {name} | {label} | {d['p50']:.2g} | {d['p99']:.2g} | {d['rms']:.2g} | "
              f"{d['depth_rms']:.2g} | {d['coverage']} | {times[(name, n)]:.1f} |")
PY
