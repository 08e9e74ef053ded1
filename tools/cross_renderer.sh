#!/usr/bin/env bash
# The two renderers against each other (issue 17, point 2; reference/ACCURACY.md, "Two
# renderers"): every golden scene rendered by the rasterizer and by the ray tracer
# (`render --renderer raytrace`), both on the same displaced projected grid and shaded the same
# way, compared per pixel: the share of pixels whose R, G, B are identical in double precision,
# within 1e-12 and 1e-9 relative, the largest relative difference, the pixels whose sea coverage
# differs, whether the double-precision radiance behind the EXR is the same bits
# (radiance_f64_sha256), and each renderer's wall-clock time. A difference is where the two decide visibility
# or the interpolation weights differently (edge rules, depth ties, rounding).
#
#   tools/cross_renderer.sh [THREADS]   (default 2; builds build/ when missing)
#
# About 5 minutes on 2 cores (the goldens' reference lighting). Markdown on stdout.
set -euo pipefail
cd "$(dirname "$0")/.."
threads=${1:-2}
[ -x build/src/oceanref ] || bash tools/build.sh build >&2
bin=$PWD/build/src/oceanref
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

milliseconds() { echo $((($(date +%s%N) - $1) / 1000000)); }
for scene in reference/scenes/golden/*.json; do
  name=$(basename "$scene" .json)
  echo "cross_renderer.sh: $name" >&2
  for renderer in raster raytrace; do
    start=$(date +%s%N)
    "$bin" render "$scene" -o "$tmp/$name.$renderer.exr" --aov --renderer "$renderer" \
      --threads "$threads" 2>/dev/null >"$tmp/$name.$renderer.out"
    echo "$name $renderer $(milliseconds "$start")" >>"$tmp/times"
  done
done

echo "**Two renderers** (\`tools/cross_renderer.sh ${threads}\`; $(date -u +%Y-%m-%d),"
echo "$(lscpu | sed -n 's/^Model name: *//p' | head -1), $(nproc) cores, $threads threads, commit"
echo "$("$bin" --version | sed -n 's/.*(commit \(.*\))$/\1/p')): each golden scene rendered by the"
echo "rasterizer and by the ray tracer; per pixel the largest over R, G, B of |raytrace − raster| /"
echo "|raster| (the float32 EXR values; 0 where both are 0)."
echo
/usr/bin/python3 - "$tmp" <<'PY'
import sys
import numpy as np
import OpenImageIO as oiio

out = sys.argv[1]
times = {}
for line in open(f"{out}/times"):
    name, renderer, ms = line.split()
    times[(name, renderer)] = int(ms) / 1000


def read(path):
    image = oiio.ImageBuf(path)
    spec = image.spec()
    pixels = image.get_pixels(oiio.FLOAT).reshape(-1, spec.nchannels).astype(float)
    index = {n: i for i, n in enumerate(spec.channelnames)}
    return pixels[:, [index["R"], index["G"], index["B"]]], pixels[:, index["coverage"]]


print("| scene | pixels | identical | within 1e-6 | max relative | coverage differs "
      "| doubles identical | raster | raytrace |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")


def f64_hash(name, renderer):
    for line in open(f"{out}/{name}.{renderer}.out"):
        if line.startswith("radiance_f64_sha256,"):
            return line.strip().split(",")[1]
    raise SystemExit(f"no radiance_f64_sha256 for {name} ({renderer})")

for name in sorted({n for n, _ in times}):
    a, cov_a = read(f"{out}/{name}.raster.exr")
    b, cov_b = read(f"{out}/{name}.raytrace.exr")
    d = np.abs(a - b)
    rel = np.where(d == 0, 0.0, d / np.maximum(np.abs(a), 1e-30)).max(axis=1)
    print(f"| {name} | {len(rel)} | {100 * (rel == 0).mean():.2f}% | {100 * (rel <= 1e-6).mean():.2f}% "
          f"| {rel.max():.2g} | {(cov_a != cov_b).sum()} "
          f"| {'yes' if f64_hash(name, 'raster') == f64_hash(name, 'raytrace') else 'no'} "
          f"| {times[(name, 'raster')]:.1f} s "
          f"| {times[(name, 'raytrace')]:.1f} s |")
PY
