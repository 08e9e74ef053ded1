#!/usr/bin/env bash
# The cost of one error budget per pixel (issue 50; reference/ACCURACY.md "One error budget per
# pixel"): the default scene at WxH, adaptive sampling to render.pixel_tolerance 0.01, rendered
#   fast          fast lighting, the pixel integral only (no lighting bound: what it costs alone);
#   every_sample  the reference at every sample (the design before the two-level estimate): its
#                 cost measured as the fast render with --lighting-error, which lights every one
#                 of the same samples by the reference as well;
#   two_level_N   the two-level estimate, its samples lit by the fast rules at sky_order N and
#                 each pixel corrected by the reference (shading.tolerance derived: 1e-3);
# all on the nested grid (render.pixel_pattern grid, cap 324 samples), and with SOBOL=1 (the
# default) also on the Sobol' pattern (pixel_pattern sobol, cap 256): sobol_fast and
# sobol_two_level_N.
# For each: wall and CPU seconds, samples per pixel, reference-lit samples, integrand
# evaluations, and over the sea pixels the bound's parts relative to the largest channel
# (pixel part, lighting part: p50, p99) and the share of sea pixels whose total bound is within
# the tolerance. Prints a Markdown table with the machine, date and commit.
#
#   bash tools/two_level_study.sh [WxH] [THREADS] [SKY_ORDERS]   (default 48x27 2 "4 16 64")
#   SOBOL=0 bash tools/two_level_study.sh ...                      (the grid's rows only)
set -euo pipefail
cd "$(dirname "$0")/.."

size=${1:-48x27}
threads=${2:-2}
orders=${3:-4 16 64}
width=${size%x*}
height=${size#*x}
bin=${OCEANREF_BIN:-build/src/oceanref}
[ -x "$bin" ] || bash tools/build.sh build >/dev/null
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# scene NAME ACCURACY [SKY_ORDER]: the default scene at the size, tolerance 0.01.
scene() {
  /usr/bin/python3 - "$work/$1.json" "$width" "$height" "$2" "${3:-}" "${4:-grid}" <<'EOF'
import json, sys
path, width, height, accuracy, order, pattern = sys.argv[1:7]
s = json.load(open("reference/scenes/default.json"))
s["shading"]["accuracy"] = accuracy
s["shading"].pop("tolerance", None)
if order:
    s["shading"]["sky_order"] = int(order)
s["render"].update(width=int(width), height=int(height), pixel_tolerance=0.01,
                   pixel_pattern=pattern, max_samples_per_pixel=324 if pattern == "grid" else 256)
json.dump(s, open(path, "w"))
EOF
}

run() {  # NAME [render flags...]: renders NAME.json, keeps the report and the times
  local name=$1
  shift
  echo "two_level_study: $name" >&2
  /usr/bin/time -f "%e %U %S" -o "$work/$name.time" \
    "$bin" render "$work/$name.json" -o "$work/$name.exr" --aov --threads "$threads" "$@" \
    >"$work/$name.report" 2>"$work/$name.log" || { cat "$work/$name.log" >&2; exit 1; }
}

scene fast fast
run fast
cp "$work/fast.json" "$work/every_sample.json"
run every_sample --lighting-error
names="fast every_sample"
for o in $orders; do
  scene "two_level_$o" reference "$o"
  run "two_level_$o"
  names="$names two_level_$o"
done
if [ "${SOBOL:-1}" = 1 ]; then
  scene sobol_fast fast "" sobol
  run sobol_fast
  names="$names sobol_fast"
  for o in $orders; do
    scene "sobol_two_level_$o" reference "$o" sobol
    run "sobol_two_level_$o"
    names="$names sobol_two_level_$o"
  done
fi

PYTHONPATH="$PWD/build/python${PYTHONPATH:+:$PYTHONPATH}" /usr/bin/python3 - "$work" "$names" "$size" "$threads" "$(git rev-parse --short HEAD)$(git diff --quiet HEAD || echo -dirty)" \
  "$(lscpu | sed -n 's/^Model name: *//p' | head -n1)" "$orders" <<'EOF'
import datetime, sys
import numpy as np
sys.path.insert(0, "tools")
from image_difference import channels as read, layer

work, names, size, threads, commit, cpu, orders = sys.argv[1:8]
tolerance = 0.01

def report(name):
    out = {}
    for line in open(f"{work}/{name}.report"):
        key, _, value = line.strip().partition(",")
        out[key] = value
    return out

print(f"Default scene at {size}, render.pixel_tolerance {tolerance}, cap 324 samples (the "
      f"Sobol' pattern's rows: 256), "
      f"{threads} threads; {cpu}, {datetime.datetime.utcnow():%Y-%m-%d %H:%M} UTC, commit {commit}, "
      f"`bash tools/two_level_study.sh {size} {threads} \"{orders}\"`.\n")
print("| design | wall s | CPU s | samples/pixel | reference-lit samples | integrand evaluations "
      "| pixel part p50 / p99 | lighting part p50 / p99 | sea pixels within 1% |")
print("|---|---:|---:|---:|---:|---:|---|---|---:|")
for name in names.split():
    d = read(f"{work}/{name}.exr")
    r = report(name)
    wall, user, system = (float(x) for x in open(f"{work}/{name}.time").read().split())
    radiance = layer(d)
    largest = radiance.max(axis=-1)
    sea = d["coverage"] > 0
    scale = np.where(largest > 0, largest, np.inf)
    pixel = (layer(d, "pixel_error").max(axis=-1) / scale)[sea]
    lighting = (layer(d, "lighting_error").max(axis=-1) / scale)[sea]
    total = ((layer(d, "pixel_error") + layer(d, "lighting_error")).max(axis=-1) / scale)[sea]
    reference_lit = r.get("corrected_samples", "")
    if name == "every_sample":
        reference_lit = f"{float(r['pixel_samples_mean']) * radiance.shape[0] * radiance.shape[1]:.0f} (all)"
    if name.endswith("fast"):
        lighting_text = "not bounded"
        within = "–"
    elif name == "every_sample":  # a cost measurement: its pixels are the fast ones
        lighting_text = "(cost only)"
        within = "–"
    else:
        lighting_text = f"{np.percentile(lighting, 50):.2g} / {np.percentile(lighting, 99):.2g}"
        within = f"{100 * np.mean(total <= tolerance):.1f}%"
    print(f"| {name} | {wall:.1f} | {user + system:.1f} | {float(r['pixel_samples_mean']):.0f} "
          f"| {reference_lit or '–'} | {int(r['integrand_evaluations']):.3g} "
          f"| {np.percentile(pixel, 50):.2g} / {np.percentile(pixel, 99):.2g} "
          f"| {lighting_text} | {within} |")
EOF
