#!/usr/bin/env bash
# Error versus cost of the pixel integral (reference/ACCURACY.md, "Converged pixels"): the
# default scene at a reduced size with fast lighting (the same lighting in every render, so only
# the pixel integral differs), rendered with the fixed grid at 1, 4, 16 and 64 spp, footprint-filtered at 1 and 4 spp, and with
# adaptive sampling at several tolerances on each pixel pattern (render.pixel_pattern: the nested
# grid, cap 324, "adaptive_*"; the Sobol' pattern, cap 256, "sobol_*"; each also at a higher
# cap), each compared with a 1024-spp render of the same scene. Per render: wall-clock seconds and samples per pixel (the cost), the relative error
# against 1024 spp (median, p99 over pixels, the largest channel per pixel), and the share of
# pixels within the reported pixel_error (alone, and plus the 1024-spp render's own estimate);
# over the pixels the sea covers, the RMS error relative to the mean and the light relative to
# 1024 spp. Footprint filtering (render.footprint_filtering) at 1 and 4 spp is one family.
#
#   tools/pixel_convergence.sh [WIDTHxHEIGHT] [THREADS]   (default 160x90, 2; builds build/)
#
# Outputs: the Markdown table on stdout (for reference/ACCURACY.md, followed by the line that
# embeds the plot), and two files, each written to a temporary file and renamed into place so
# a failed run leaves the previous ones as they were:
#   reference/pixel_convergence.csv  one row per render: render, family (the name's prefix before
#       the first "_": fixed, adaptive, dense, ...), samples_per_pixel_mean, seconds, error_p50,
#       error_p99, within_pixel_error and within_with_dense_estimate (fractions of the pixels),
#       capped_pixels (empty where none are reported; errors empty for dense_1024 itself);
#   reference/pixel_convergence.svg  error p99 (filled) and p50 (hollow) versus seconds (left)
#       and versus mean samples per pixel (right), log-log, one series per family.
# Environment:
#   OCEANREF_BIN=PATH           the oceanref binary to run (default build/src/oceanref, built by
#                               tools/build.sh when missing; not built when this is set)
#   PIXEL_CONVERGENCE_OUT=DIR   write the CSV and SVG to DIR instead of reference/ (trial runs)
#
# About 6 minutes at 160x90 on 2 cores (the 1024-spp render and the high caps are most of it).
set -euo pipefail
# The caller's paths are relative to the caller's directory: resolved before the cd.
bin=${OCEANREF_BIN:+$(realpath -m -- "$OCEANREF_BIN")}
out_dir=${PIXEL_CONVERGENCE_OUT:+$(realpath -m -- "$PIXEL_CONVERGENCE_OUT")}
cd "$(dirname "$0")/.."

size=${1:-160x90}
threads=${2:-2}
[[ "$size" =~ ^([0-9]+)x([0-9]+)$ ]] || {
  echo "usage: tools/pixel_convergence.sh [WxH] [THREADS]" >&2
  exit 2
}
width=${BASH_REMATCH[1]}
height=${BASH_REMATCH[2]}
if [ -n "$bin" ]; then
  if [ ! -f "$bin" ] || [ ! -x "$bin" ]; then
    echo "pixel_convergence.sh: OCEANREF_BIN=$OCEANREF_BIN is not an executable file" >&2
    exit 2
  fi
else
  [ -x build/src/oceanref ] || bash tools/build.sh build >&2
  bin=$PWD/build/src/oceanref
fi
out_dir=${out_dir:-$PWD/reference}
mkdir -p "$out_dir"
[ -w "$out_dir" ] || { echo "pixel_convergence.sh: cannot write to $out_dir" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# name → render settings; the scene otherwise the default one, fast lighting. Prints the names.
names=$(python3 - "$width" "$height" "$tmp" <<'EOF'
import json, sys
width, height, out = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
base = json.load(open("reference/scenes/default.json"))
base["shading"]["accuracy"] = "fast"
base["shading"].pop("tolerance", None)
# Footprint filtering cannot read accumulated foam (waves.foam.steps): every render of the study
# shows the instant's whitecaps only, so that all see the same image.
base.get("waves", {}).pop("foam", None)
runs = {"fixed_1": {"samples_per_pixel": 1}, "fixed_4": {"samples_per_pixel": 4},
        "fixed_16": {"samples_per_pixel": 16}, "fixed_64": {"samples_per_pixel": 64},
        "footprint_1": {"samples_per_pixel": 1, "footprint_filtering": True},
        "footprint_4": {"samples_per_pixel": 4, "footprint_filtering": True},
        "adaptive_0.1": {"samples_per_pixel": 4, "pixel_tolerance": 0.1, "pixel_pattern": "grid"},
        "adaptive_0.03": {"samples_per_pixel": 4, "pixel_tolerance": 0.03, "pixel_pattern": "grid"},
        "adaptive_0.01": {"samples_per_pixel": 4, "pixel_tolerance": 0.01, "pixel_pattern": "grid"},
        "adaptive_0.01_cap2916": {"samples_per_pixel": 4, "pixel_tolerance": 0.01,
                                  "pixel_pattern": "grid", "max_samples_per_pixel": 2916},
        "sobol_0.1": {"samples_per_pixel": 4, "pixel_tolerance": 0.1, "pixel_pattern": "sobol",
                      "max_samples_per_pixel": 256},
        "sobol_0.03": {"samples_per_pixel": 4, "pixel_tolerance": 0.03, "pixel_pattern": "sobol",
                       "max_samples_per_pixel": 256},
        "sobol_0.01": {"samples_per_pixel": 4, "pixel_tolerance": 0.01, "pixel_pattern": "sobol",
                       "max_samples_per_pixel": 256},
        "sobol_0.01_cap2048": {"samples_per_pixel": 4, "pixel_tolerance": 0.01,
                               "pixel_pattern": "sobol", "max_samples_per_pixel": 2048},
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
    >"$tmp/$name.out" 2>"$tmp/$name.err" || { cat "$tmp/$name.err" >&2; exit 1; }
  echo "$name $((($(date +%s%N) - start) / 1000000))" >>"$tmp/times"  # milliseconds
done

# The facts of the Markdown header, also the SVG's title line.
day=$(date -u +%Y-%m-%d)
cpu=$(lscpu | sed -n 's/^Model name: *//p' | head -1) || cpu=
cores=$(nproc)
commit=$("$bin" --version | sed -n 's/.*(commit \(.*\))$/\1/p') || commit=
echo "**Pixel integral, error versus cost** (\`tools/pixel_convergence.sh ${size} ${threads}\`;"
echo "$day, $cpu, $cores cores,"
echo "$threads threads, commit $commit): the default"
echo "scene at ${width}×${height} with fast lighting, against a 1024-spp render of it. Error: per"
echo "pixel the largest over R, G, B of |x − x₁₀₂₄| / x₁₀₂₄; \"within\": pixels whose every channel"
echo "is within its pixel_error (and within pixel_error + the 1024-spp render's own estimate). Sea: over"
echo "the pixels the sea covers, the RMS error relative to the mean radiance, and the light relative"
echo "to 1024 spp."
echo
# Debian's OpenImageIO module (python3-openimageio) lives in /usr/bin/python3. Also writes the
# rows, unrounded, to $tmp/rows.json for the CSV and the plot.
/usr/bin/python3 - "$tmp" $names <<'EOF'
import json
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
    return rgb, error, samples, pixels[:, index["coverage"]]


dense, dense_error, _, coverage = read("dense_1024")
sea = coverage == 1.0  # pixels the sea covers entirely (in the 1024-spp render)
rows = []
print("| render | samples per pixel (mean) | seconds | error p50 | error p99 | within pixel_error "
      "| within, + 1024-spp estimate | capped pixels | sea RMS | sea light |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for name in names[:-1]:
    rgb, error, samples, _ = read(name)
    spp = samples.mean() if samples is not None else float(name.split("_")[1])
    report = dict(line.strip().split(",", 1) for line in open(f"{out}/{name}.out"))
    d = np.abs(rgb - dense)
    relative = (d / np.maximum(np.abs(dense), 1e-30)).max(axis=1)
    slack = 1e-6 * np.abs(dense)  # float32 rounding of equal values
    within = (d <= error + slack).all(axis=1).mean()
    within_both = (d <= error + dense_error + slack).all(axis=1).mean()
    # Over the sea: the RMS difference relative to the mean, and the light relative to 1024 spp.
    sea_rms = np.sqrt(((rgb[sea] - dense[sea]) ** 2).mean()) / dense[sea].mean()
    sea_light = rgb[sea].sum() / dense[sea].sum()
    print(f"| {name} | {spp:.1f} | {float(times[name]) / 1000:.1f} | {np.percentile(relative, 50):.2g} | "
          f"{np.percentile(relative, 99):.2g} | {100 * within:.1f}% | {100 * within_both:.1f}% | "
          f"{report.get('capped_pixels', '–')} | {sea_rms:.2g} | {sea_light:.3f} |")
    rows.append(dict(render=name, samples_per_pixel_mean=float(spp),
                     seconds=float(times[name]) / 1000,
                     error_p50=float(np.percentile(relative, 50)),
                     error_p99=float(np.percentile(relative, 99)),
                     within_pixel_error=float(within), within_with_dense_estimate=float(within_both),
                     capped_pixels=report.get("capped_pixels")))
print(f"| dense_1024 | 1024 | {float(times['dense_1024']) / 1000:.1f} | – | – | – | – | – | – | 1 |")
rows.append(dict(render="dense_1024", samples_per_pixel_mean=1024.0,
                 seconds=float(times["dense_1024"]) / 1000))
json.dump(rows, open(f"{out}/rows.json", "w"))
EOF

# The CSV and the SVG plot, both built in memory, then each written to a temporary file in the
# output directory and renamed into place (stdlib only: no matplotlib).
/usr/bin/python3 - "$tmp" "$out_dir" "$width" "$height" "$threads" "$day" "$cpu" "$cores" \
  "$commit" <<'EOF'
import csv
import io
import json
import math
import os
import sys
import tempfile
from xml.sax.saxutils import escape, quoteattr

tmp, out_dir, width, height, threads, day, cpu, cores, commit = sys.argv[1:10]
rows = json.load(open(f"{tmp}/rows.json"))
for row in rows:
    row["family"] = row["render"].split("_", 1)[0]

# --- CSV ------------------------------------------------------------------------------------
columns = ["render", "family", "samples_per_pixel_mean", "seconds", "error_p50", "error_p99",
           "within_pixel_error", "within_with_dense_estimate", "capped_pixels"]
text = io.StringIO()
table = csv.writer(text, lineterminator="\n")
table.writerow(columns)
for row in rows:
    table.writerow(["" if row.get(c) is None else row[c] for c in columns])
csv_text = text.getvalue()

# --- SVG ------------------------------------------------------------------------------------
W, H = 900, 400
TOP, BOTTOM = 50, 310  # the panels' frame, y
PANELS = [  # (x field, panel title, x axis title, frame left, frame right)
    ("seconds", "error versus time", f"seconds (wall clock, {threads} threads)", 70, 420),
    ("samples_per_pixel_mean", "error versus samples", "samples per pixel (mean)", 530, 880),
]
KNOWN = {"fixed": "#1f77b4", "adaptive": "#ff7f0e", "footprint": "#2ca02c", "dense": "#7f7f7f"}
PALETTE = ["#d62728", "#9467bd", "#8c564b", "#e377c2", "#17becf", "#bcbd22"]
SHAPES = ["circle", "square", "diamond", "triangle", "triangle_down"]

# Runs with an error (not the 1024-spp reference itself) and positive coordinates (log axes).
points = []
for row in rows:
    if row.get("error_p99") is None:
        continue
    values = [row[p[0]] for p in PANELS] + [row["error_p99"], row["error_p50"]]
    if min(values) <= 0:
        print(f"pixel_convergence.sh: {row['render']} left out of the plot (a value <= 0 on a "
              "log axis)", file=sys.stderr)
        continue
    points.append(row)
if not points:
    sys.exit("pixel_convergence.sh: nothing to plot")

families = list(dict.fromkeys(row["family"] for row in points))  # in order of first appearance
spare = [c for c in PALETTE if c not in KNOWN.values()]
colour, shape = {}, {}
for i, family in enumerate(families):
    if family in KNOWN:
        colour[family] = KNOWN[family]
    else:
        colour[family] = spare[sum(f not in KNOWN for f in families[:i]) % len(spare)]
    shape[family] = SHAPES[i % len(SHAPES)]


def decades(values):
    lo = math.floor(math.log10(min(values)) + 1e-9)
    hi = math.ceil(math.log10(max(values)) - 1e-9)
    return lo, max(hi, lo + 1)


def scale(lo, hi, a, b):
    pad = 0.04 * (hi - lo)  # keeps markers on a decade off the frame
    return lambda v: a + (math.log10(v) - (lo - pad)) / (hi - lo + 2 * pad) * (b - a)


def decade_label(e):  # 10 with the exponent raised
    return f'10<tspan dy="-5" font-size="8">{str(e).replace("-", "−")}</tspan>'


def num(v):
    return f"{v:.1f}".rstrip("0").rstrip(".")


def attr(value):
    return quoteattr(str(value))


def marker(kind, x, y, fill, stroke, r=4.0):
    style = f'fill="{fill}" stroke="{stroke}" stroke-width="1.4"'
    if kind == "circle":
        return f'<circle cx="{num(x)}" cy="{num(y)}" r="{r}" {style}/>'
    if kind == "square":
        s = 0.85 * r
        return f'<rect x="{num(x - s)}" y="{num(y - s)}" width="{num(2 * s)}" height="{num(2 * s)}" {style}/>'
    r *= 1.2
    corners = {"diamond": [(0, -r), (r, 0), (0, r), (-r, 0)],
               "triangle": [(0, -r), (0.9 * r, 0.6 * r), (-0.9 * r, 0.6 * r)],
               "triangle_down": [(0, r), (0.9 * r, -0.6 * r), (-0.9 * r, -0.6 * r)]}[kind]
    xy = " ".join(f"{num(x + dx)},{num(y + dy)}" for dx, dy in corners)
    return f'<polygon points="{xy}" {style}/>'


def text_width(s, size):
    return 0.6 * size * len(s)  # sans-serif (DejaVu Sans), roughly


def overlap(a, b):
    return max(0.0, min(a[2], b[2]) - max(a[0], b[0])) * max(0.0, min(a[3], b[3]) - max(a[1], b[1]))


svg = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" '
       f'viewBox="0 0 {W} {H}" font-family="sans-serif" font-size="11">',
       '<rect width="100%" height="100%" fill="white"/>']
title = (f"Pixel integral, error versus cost: default scene {width}×{height}, fast lighting, "
         f"{threads} threads; {day}, {cpu or 'unknown CPU'}, commit {commit or 'unknown'}")
fit = f' textLength="{W - 20}" lengthAdjust="spacingAndGlyphs"' if text_width(title, 12) > W - 20 else ""
svg.append(f'<text x="{W / 2}" y="20" text-anchor="middle" font-size="12"{fit}>{escape(title)}</text>')

y_lo, y_hi = decades([r[k] for r in points for k in ("error_p99", "error_p50")])
y_of = scale(y_lo, y_hi, BOTTOM, TOP)
for field, panel_title, x_title, left, right in PANELS:
    x_lo, x_hi = decades([r[field] for r in points])
    x_of = scale(x_lo, x_hi, left, right)
    mid = (left + right) / 2
    svg.append("<g>")
    svg.append(f'<text x="{mid}" y="{TOP - 8}" text-anchor="middle" font-size="12">{panel_title}</text>')
    # Grid, ticks (decades labelled, 2..9 as short marks) and the axis titles.
    for e in range(x_lo, x_hi + 1):
        x = num(x_of(10.0 ** e))
        svg.append(f'<line x1="{x}" y1="{TOP}" x2="{x}" y2="{BOTTOM}" stroke="#e2e2e2"/>')
        svg.append(f'<text x="{x}" y="{BOTTOM + 16}" text-anchor="middle">{decade_label(e)}</text>')
        for m in range(2, 10):
            if e < x_hi:
                xm = num(x_of(m * 10.0 ** e))
                svg.append(f'<line x1="{xm}" y1="{BOTTOM}" x2="{xm}" y2="{BOTTOM - 4}" stroke="#666"/>')
    for e in range(y_lo, y_hi + 1):
        y = num(y_of(10.0 ** e))
        svg.append(f'<line x1="{left}" y1="{y}" x2="{right}" y2="{y}" stroke="#e2e2e2"/>')
        svg.append(f'<text x="{left - 5}" y="{num(y_of(10.0 ** e) + 4)}" text-anchor="end">'
                   f'{decade_label(e)}</text>')
        for m in range(2, 10):
            if e < y_hi:
                ym = num(y_of(m * 10.0 ** e))
                svg.append(f'<line x1="{left}" y1="{ym}" x2="{left + 4}" y2="{ym}" stroke="#666"/>')
    svg.append(f'<rect x="{left}" y="{TOP}" width="{right - left}" height="{BOTTOM - TOP}" '
               'fill="none" stroke="#444"/>')
    svg.append(f'<text x="{mid}" y="{BOTTOM + 32}" text-anchor="middle">{escape(x_title)}</text>')
    yx, ym = left - 42, (TOP + BOTTOM) / 2
    svg.append(f'<text x="{yx}" y="{ym}" text-anchor="middle" transform="rotate(-90 {yx} {ym})">'
               'relative error against 1024 spp</text>')
    # Per family: p50 (hollow, dashed) under p99 (filled, solid), each joined in the run order.
    busy = []  # boxes of markers and labels, for placing the labels
    for family in families:
        run = [r for r in points if r["family"] == family]
        c = colour[family]
        for key, dash in (("error_p50", ' stroke-dasharray="4 3" stroke-opacity="0.7"'),
                          ("error_p99", "")):
            xy = [(x_of(r[field]), y_of(r[key])) for r in run]
            if len(xy) > 1:
                line = " ".join(f"{num(x)},{num(y)}" for x, y in xy)
                svg.append(f'<polyline points="{line}" fill="none" stroke="{c}" stroke-width="1.2"{dash}/>')
            for x, y in xy:
                filled = key == "error_p99"
                svg.append(marker(shape[family], x, y, c if filled else "white", c))
                busy.append((x - 5, y - 5, x + 5, y + 5))
    # Each p99 point labelled with its run name, at the first free place around it (else the
    # least crowded one), near places first.
    size = 9
    PLACES = [(7, 3, "start"), (-7, 3, "end"), (0, -8, "middle"), (0, 14, "middle"),
              (6, -7, "start"), (6, 12, "start"), (-6, -7, "end"), (-6, 12, "end"),
              (0, -18, "middle"), (0, 24, "middle"), (6, -17, "start"), (6, 22, "start"),
              (-6, -17, "end"), (-6, 22, "end")]
    for r in points:
        x, y = x_of(r[field]), y_of(r["error_p99"])
        name = r["render"]
        w, h = text_width(name, size), size
        best = None
        for dx, dy, anchor in PLACES:
            x0 = x + dx - {"start": 0, "middle": w / 2, "end": w}[anchor]
            box = (x0 - 1, y + dy - h, x0 + w + 1, y + dy + 2)
            outside = box[0] < left + 1 or box[2] > right - 1 or box[1] < TOP + 1 or box[3] > BOTTOM - 1
            cost = sum(overlap(box, b) for b in busy) + (1e6 if outside else 0)
            if best is None or cost < best[0]:
                best = (cost, dx, dy, anchor, box)
            if cost == 0:
                break
        _, dx, dy, anchor, box = best
        busy.append(box)
        svg.append(f'<text x="{num(x + dx)}" y="{num(y + dy)}" text-anchor="{anchor}" '
                   f'font-size="{size}" fill="#333">{escape(name)}</text>')
    svg.append("</g>")

# Legend: one entry per family, then what filled and hollow mean.
x, y = 70, H - 18
svg.append("<g>")
for family in families:
    svg.append(marker(shape[family], x, y - 4, colour[family], colour[family]))
    svg.append(f'<text x="{x + 9}" y="{y}">{escape(family)}</text>')
    x += 9 + text_width(family, 11) + 16
x += 24
svg.append(marker("circle", x, y - 4, "#555", "#555"))
svg.append(f'<text x="{x + 9}" y="{y}">filled = error p99 (solid line)</text>')
x += 9 + text_width("filled = error p99 (solid line)", 11) + 16
svg.append(marker("circle", x, y - 4, "white", "#555"))
svg.append(f'<text x="{x + 9}" y="{y}">hollow = error p50 (dashed line)</text>')
svg.append("</g>")
svg.append("</svg>")
svg_text = '<?xml version="1.0" encoding="UTF-8"?>\n' + "\n".join(svg) + "\n"

# --- Write: both to temporary files first, then both renamed ----------------------------------
umask = os.umask(0)
os.umask(umask)
written = []
try:
    for name, content in (("pixel_convergence.csv", csv_text), ("pixel_convergence.svg", svg_text)):
        fd, path = tempfile.mkstemp(dir=out_dir, prefix=f".{name}.", suffix=".tmp")
        written.append((path, os.path.join(out_dir, name)))
        with os.fdopen(fd, "w", encoding="utf-8", newline="") as f:
            f.write(content)
        os.chmod(path, 0o666 & ~umask)
    for path, final in written:
        os.replace(path, final)
        print(f"pixel_convergence.sh: wrote {final}", file=sys.stderr)
except BaseException:
    for path, _ in written:
        if os.path.exists(path):
            os.unlink(path)
    raise
EOF
echo
echo "![Pixel integral: error p99 and p50 versus seconds and samples per pixel](pixel_convergence.svg)"
