#!/usr/bin/env bash
# Where a render's work goes (reference/ACCURACY.md, "Where the time goes"): instruction counts
# under callgrind (repeatable whatever else the machine does), as inclusive shares of the
# program's total, for the default scene at a small size in fast and in reference lighting.
#
#   tools/profile_render.sh [WIDTHxHEIGHT]     (default 160x90; builds build/ if needed)
#
# The fast render runs under callgrind (~20 s at 160x90); the reference render (at tolerances
# 1e-6 and 1e-3), ~50x slower per sample, runs natively: its integrand evaluations per sea
# sample and estimated errors are reported (under callgrind it would take an hour).
set -euo pipefail
cd "$(dirname "$0")/.."

size=${1:-160x90}
[[ "$size" =~ ^([0-9]+)x([0-9]+)$ ]] || { echo "usage: tools/profile_render.sh [WxH]" >&2; exit 2; }
width=${BASH_REMATCH[1]}
height=${BASH_REMATCH[2]}
command -v valgrind >/dev/null || { echo "profile_render: valgrind is needed" >&2; exit 2; }
[ -x build/src/oceanref ] || bash tools/build.sh build >&2
bin=$PWD/build/src/oceanref
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# The default scene at WxH, 4 spp, in both lighting modes.
python3 - "$width" "$height" "$tmp" <<'EOF'
import json, sys
width, height, out = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
scene = json.load(open("reference/scenes/default.json"))
scene["render"].update(width=width, height=height)
json.dump(scene, open(f"{out}/reference.json", "w"))
scene["shading"]["accuracy"] = "fast"
scene["shading"].pop("tolerance", None)
json.dump(scene, open(f"{out}/fast.json", "w"))
EOF

echo "# oceanref render profile: default scene ${width}x${height}, 4 spp, 1 thread"
echo "# $(date -u +%Y-%m-%d), $(lscpu | sed -n 's/^Model name: *//p' | head -1), $(nproc) cores," \
  "commit $("$bin" --version | sed -n 's/.*(commit \(.*\))$/\1/p')"
valgrind --tool=callgrind --callgrind-out-file="$tmp/cg" "$bin" render "$tmp/fast.json" \
  -o "$tmp/fast.exr" --threads 1 >/dev/null 2>"$tmp/valgrind.log"
callgrind_annotate --inclusive=yes --threshold=100 "$tmp/cg" >"$tmp/inclusive.txt" 2>/dev/null
total=$(sed -n 's/^ *\([0-9,]*\) .*PROGRAM TOTALS.*/\1/p' "$tmp/inclusive.txt" | tr -d ,)
echo
echo "fast lighting (sky_order 4, sun_order 2): $total instructions in all"
echo
echo "| stage or function (inclusive) | share of the instructions |"
echo "|---|---:|"
# One row per function: the first line of callgrind's inclusive listing that names it.
row() {
  local label=$1 pattern=$2
  local count
  count=$({ grep -E "$pattern" "$tmp/inclusive.txt" || true; } | head -1 |
    sed 's/^ *\([0-9,]*\) .*/\1/' | tr -d ,)
  if [ -z "$count" ]; then
    echo "| $label | (inlined into its caller) |"
    return
  fi
  awk -v l="$label" -v c="$count" -v t="$total" 'BEGIN { printf "| %s | %.1f%% |\n", l, 100 * c / t }'
}
row "realize the spectrum (h0 of every cascade)" 'oceanref::realize_ocean\('
row "BRDF roughness: the slope variance budget" 'oceanref::slope_budget\('
row "wave synthesis (inverse FFTs; the frame and its foam history)" 'oceanref::synthesize_ocean\('
row "projected grid: displaced vertices" 'build_geometry\('
row "rasterization" 'oceanref::rasterize\('
row "shading (every sample)" 'shade_sample\('
row "  fields at the sample (interpolation)" 'oceanref::combine_shading_at\('
row "  whitecap coverage over the foam history" 'oceanref::foam_coverage_at\('
row "    earlier instants' deformation (interpolation)" 'oceanref::deformation_at\('
row "  reflected sky (Gauss-Hermite)" 'oceanref::reflected_sky\(std::array<double, 3ul> const&, oceanref::SurfaceFrame const&, oceanref::SlopeVariance, oceanref::Sky const&, oceanref::QuadratureRule'
row "    Preetham sky radiance" 'oceanref::sky_radiance_rgb\('
row "  reflected sun (sun disk)" 'oceanref::reflected_sun\('
row "  Smith masking Lambda (erfc, exp)" 'oceanref::smith_lambda\('
row "exp (every caller)" 'oceanref::math::exp\(double\)'
row "erfc (every caller)" 'oceanref::math::erfc\(double\)'

echo
# The reference lighting at two tolerances: its cost does not follow the tolerance.
python3 -c '
import json, sys
scene = json.load(open(sys.argv[1] + "/reference.json"))
scene["shading"]["tolerance"] = 1e-3
json.dump(scene, open(sys.argv[1] + "/reference_1e-3.json", "w"))
' "$tmp"
echo "| reference lighting, tolerance | integrand evaluations per sea sample | estimated error / radiance: median | largest |"
echo "|---|---:|---:|---:|"
for t in 1e-6 1e-3; do
  scene="$tmp/reference.json"
  [ "$t" = 1e-3 ] && scene="$tmp/reference_1e-3.json"
  "$bin" render "$scene" -o "$tmp/reference.exr" --aov --threads 2 >"$tmp/reference.out"
  # Sea samples: the coverage layer summed over the pixels, times the 4 samples per pixel
  # (Debian's OpenImageIO module, python3-openimageio, lives in /usr/bin/python3).
  /usr/bin/python3 -c '
import sys
import OpenImageIO as oiio
tmp, tolerance = sys.argv[1], sys.argv[2]
report = dict(line.split(",", 1) for line in open(tmp + "/reference.out").read().split())
image = oiio.ImageInput.open(tmp + "/reference.exr")
c = image.spec().channelnames.index("coverage")
samples = 4 * float(image.read_image(0, 0, c, c + 1, "float").sum())
per_sample = int(report["integrand_evaluations"]) / samples
median = float(report["lighting_error_median_relative"])
largest = float(report["lighting_error_max_relative"])
print(f"| {tolerance} | {per_sample:.0f} | {median:.2g} | {largest:.2g} |")
' "$tmp" "$t"
done
echo
echo "(fast lighting: 16 sky directions, 16 Fresnel facets and 8 sun-disk nodes per sea sample)"
