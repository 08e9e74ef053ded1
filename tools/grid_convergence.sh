#!/usr/bin/env bash
# What the projected grid's triangulation costs at grazing views (reference/ACCURACY.md, "Two
# renderers": both renderers share the grid's surface, so only a finer grid shows its error):
# the two grazing golden scenes rendered with grid.columns = grid.rows = 96 … 3072, each compared
# with the same scene on a 6144 × 6144 grid (the continuous surface's stand-in until the ray
# tracer intersects it directly, issue 17). Fast lighting and 4 spp in every render, so the
# renders differ only in the grid; per render the relative difference per pixel (largest over
# R, G, B of |c − f|/s, f the 6144 render, s = max(|f|, 0.01·RMS of f's channel) as `oceanref
# compare` scales it, so near-black pixels do not dominate) at p50 and p99, the relative RMS over
# the image
# (√Σ|c − f|² / √Σ|f|²), the pixels whose sea coverage differs, and the wall-clock seconds.
#
#   tools/grid_convergence.sh [THREADS]   (default 2; builds build/ when missing)
#
# About 4 minutes on 2 cores; the 6144 grid needs about 4 GB. Markdown on stdout.
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
  for n in "${levels[@]}"; do
    echo "grid_convergence.sh: $name, grid $n" >&2
    python3 - "reference/scenes/golden/$name.json" "$tmp/$name.$n.json" "$n" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
s.setdefault("shading", {})["accuracy"] = "fast"
s["render"]["samples_per_pixel"] = 4
s.setdefault("grid", {})["columns"] = s["grid"]["rows"] = int(sys.argv[3])
json.dump(s, open(sys.argv[2], "w"))
PY
    start=$(date +%s%N)
    "$bin" render "$tmp/$name.$n.json" -o "$tmp/$name.$n.exr" --aov --threads "$threads" \
      >/dev/null 2>&1
    echo "$name $n $((($(date +%s%N) - start) / 1000000))" >>"$tmp/times"
  done
done

commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
cpu=$(lscpu | sed -n 's/^Model name: *//p' | head -1)
# The EXRs are read by oceanref's own Python module (build/python).
PYTHONPATH=$PWD/build/python /usr/bin/python3 - "$tmp" "$commit" "$cpu" "$(nproc)" "$threads" "${levels[*]}" \
  "${scenes[*]}" <<'PY'
import datetime, sys
import numpy as np
import oceanref

tmp, commit, cpu, cores, threads, levels, scenes = sys.argv[1:8]
levels = [int(n) for n in levels.split()]
times = {}
for line in open(f"{tmp}/times"):
    name, n, ms = line.split()
    times[(name, int(n))] = int(ms) / 1000.0

def read(path):
    channels = {}
    for part in oceanref.read_exr(path):
        channels.update(part["channels"])
    rgb = np.stack([channels[c].astype(np.float64) for c in "RGB"], axis=2)
    coverage = channels.get("coverage")
    return rgb, coverage

print(f"**Grid convergence at grazing views** (`tools/grid_convergence.sh {threads}`; "
      f"{datetime.date.today()}, {cpu}, {cores} cores, {threads} threads, commit {commit}): "
      f"each scene with fast lighting and 4 spp on an N × N projected grid against the same on "
      f"{levels[-1]} × {levels[-1]}.")
print()
print("| scene | N | p50 | p99 | relative RMS | coverage differs | seconds |")
print("|---|---:|---:|---:|---:|---:|---:|")
for name in scenes.split():
    finest, finest_cov = read(f"{tmp}/{name}.{levels[-1]}.exr")
    for n in levels:
        rgb, cov = read(f"{tmp}/{name}.{n}.exr")
        diff = np.abs(rgb - finest)
        channel_rms = np.sqrt((finest ** 2).mean(axis=(0, 1)))
        scale = np.maximum(np.abs(finest), 0.01 * channel_rms)
        per_pixel = (diff / scale).max(axis=2).ravel()
        rms = np.sqrt((diff ** 2).sum()) / np.sqrt((finest ** 2).sum())
        covd = int((cov != finest_cov).sum()) if cov is not None else 0
        label = f"{n} (reference)" if n == levels[-1] else str(n)
        print(f"| {name} | {label} | {np.percentile(per_pixel, 50):.2g} | "
              f"{np.percentile(per_pixel, 99):.2g} | {rms:.2g} | {covd} | {times[(name, n)]:.1f} |")
PY
