#!/usr/bin/env bash
# Error versus cost of the pixel integral (reference/ACCURACY.md, "Converged pixels"): the
# default scene at a reduced size with fast lighting (the same lighting in every render, so only
# the pixel integral differs), rendered with the fixed grid at 1, 4, 16 and 64 spp and with
# adaptive sampling at several tolerances, each compared with a 1024-spp render of the same
# scene. Per render: wall-clock seconds and samples per pixel (the cost), the relative error
# against 1024 spp (median, p99 over pixels, the largest channel per pixel), and the share of
# pixels within the reported pixel_error (alone, and plus the 1024-spp render's own estimate).
#
#   tools/pixel_convergence.sh [WIDTHxHEIGHT] [THREADS]   (default 160x90, 2; builds build/)
#
# About 4 minutes at 160x90 on 2 cores (the 1024-spp render is most of it). Markdown on stdout.
set -euo pipefail
cd "$(dirname "$0")/.."

size=${1:-160x90}
threads=${2:-2}
[[ "$size" =~ ^([0-9]+)x([0-9]+)$ ]] || {
  echo "usage: tools/pixel_convergence.sh [WxH] [THREADS]" >&2
  exit 2
}
width=${BASH_REMATCH[1]}
height=${BASH_REMATCH[2]}
[ -x build/src/oceanref ] || bash tools/build.sh build >&2
bin=$PWD/build/src/oceanref
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# name → render settings; the scene otherwise the default one, fast lighting. Prints the names.
names=$(python3 - "$width" "$height" "$tmp" <<'EOF'
import json, sys
width, height, out = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
base = json.load(open("reference/scenes/default.json"))
base["shading"]["accuracy"] = "fast"
base["shading"].pop("tolerance", None)
runs = {"fixed_1": {"samples_per_pixel": 1}, "fixed_4": {"samples_per_pixel": 4},
        "fixed_16": {"samples_per_pixel": 16}, "fixed_64": {"samples_per_pixel": 64},
        "adaptive_0.1": {"samples_per_pixel": 4, "pixel_tolerance": 0.1},
        "adaptive_0.03": {"samples_per_pixel": 4, "pixel_tolerance": 0.03},
        "adaptive_0.01": {"samples_per_pixel": 4, "pixel_tolerance": 0.01},
        "adaptive_0.01_cap2916": {"samples_per_pixel": 4, "pixel_tolerance": 0.01,
                                  "max_samples_per_pixel": 2916},
        "dense_1024": {"samples_per_pixel": 1024}}
for name, settings in runs.items():
    scene = json.loads(json.dumps(base))
    scene["render"] = dict(width=width, height=height, **settings)
    json.dump(scene, open(f"{out}/{name}.json", "w"))
print(" ".join(runs))
EOF
)
for name in $names; do
  start=$(date +%s%N)
  "$bin" render "$tmp/$name.json" -o "$tmp/$name.exr" --aov --threads "$threads" \
    >"$tmp/$name.out" 2>/dev/null
  echo "$name $((($(date +%s%N) - start) / 1000000))" >>"$tmp/times"  # milliseconds
done

echo "**Pixel integral, error versus cost** (\`tools/pixel_convergence.sh ${size} ${threads}\`;"
echo "$(date -u +%Y-%m-%d), $(lscpu | sed -n 's/^Model name: *//p' | head -1), $(nproc) cores,"
echo "$threads threads, commit $("$bin" --version | sed -n 's/.*(commit \(.*\))$/\1/p')): the default"
echo "scene at ${width}×${height} with fast lighting, against a 1024-spp render of it. Error: per"
echo "pixel the largest over R, G, B of |x − x₁₀₂₄| / x₁₀₂₄; \"within\": pixels whose every channel"
echo "is within its pixel_error (and within pixel_error + the 1024-spp render's own estimate)."
echo
# Debian's OpenImageIO module (python3-openimageio) lives in /usr/bin/python3.
/usr/bin/python3 - "$tmp" $names <<'EOF'
import sys
import numpy as np
import OpenImageIO as oiio

out, names = sys.argv[1], sys.argv[2:]
times = dict(line.split() for line in open(f"{out}/times"))


def read(name):
    image = oiio.ImageBuf(f"{out}/{name}.exr")
    spec = image.spec()
    pixels = image.get_pixels(oiio.FLOAT).reshape(-1, spec.nchannels).astype(float)
    index = {n: i for i, n in enumerate(spec.channelnames)}
    rgb = pixels[:, [index["R"], index["G"], index["B"]]]
    error = pixels[:, [index["pixel_error.R"], index["pixel_error.G"], index["pixel_error.B"]]]
    samples = pixels[:, index["samples"]] if "samples" in index else None
    return rgb, error, samples


dense, dense_error, _ = read("dense_1024")
print("| render | samples per pixel (mean) | seconds | error p50 | error p99 | within pixel_error "
      "| within, + 1024-spp estimate | capped pixels |")
print("|---|---:|---:|---:|---:|---:|---:|---:|")
for name in names[:-1]:
    rgb, error, samples = read(name)
    spp = samples.mean() if samples is not None else float(name.split("_")[1])
    report = dict(line.strip().split(",", 1) for line in open(f"{out}/{name}.out"))
    d = np.abs(rgb - dense)
    relative = (d / np.maximum(np.abs(dense), 1e-30)).max(axis=1)
    slack = 1e-6 * np.abs(dense)  # float32 rounding of equal values
    within = (d <= error + slack).all(axis=1).mean()
    within_both = (d <= error + dense_error + slack).all(axis=1).mean()
    print(f"| {name} | {spp:.1f} | {float(times[name]) / 1000:.1f} | {np.percentile(relative, 50):.2g} | "
          f"{np.percentile(relative, 99):.2g} | {100 * within:.1f}% | {100 * within_both:.1f}% | "
          f"{report.get('capped_pixels', '–')} |")
print(f"| dense_1024 | 1024 | {float(times['dense_1024']) / 1000:.1f} | – | – | – | – | – |")
EOF
