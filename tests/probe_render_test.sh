#!/usr/bin/env bash
# `oceanref probe` prints the pixel `oceanref render` writes, bit for bit (issue 14 point 6): the
# default scene (reference accuracy) at 24 × 14 pixels and 9 samples per pixel (a count whose
# 1/S² is not a power of two, so dividing each sample by S² and multiplying by 1/S² differ),
# rendered once; then for a corner, the opposite edge, a pixel on the horizon (partly sea, partly
# sky) and a pixel of open sea, the probe's printed pixel (17 significant digits, so the double
# round-trips), rounded to float32, equals the EXR's R, G and B exactly. The EXR is read with
# OpenImageIO's Python module (python3-openimageio, tools/setup.sh); skipped (exit 77) only when
# it is missing.
#
#   tests/probe_render_test.sh PATH/TO/oceanref SOURCE_DIR
set -uo pipefail

bin=${1:?usage: probe_render_test.sh PATH/TO/oceanref SOURCE_DIR}
src=${2:?usage: probe_render_test.sh PATH/TO/oceanref SOURCE_DIR}
if ! /usr/bin/python3 -c 'import OpenImageIO, numpy' 2>/dev/null; then
  echo "SKIP: OpenImageIO's Python module not installed (tools/setup.sh installs python3-openimageio)"
  exit 77
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

/usr/bin/python3 - "$src/reference/scenes/default.json" "$tmp/scene.json" <<'EOF' || exit 1
import json, sys
scene = json.load(open(sys.argv[1]))
scene["render"].update({"width": 24, "height": 14, "samples_per_pixel": 9})
json.dump(scene, open(sys.argv[2], "w"))
EOF
if ! "$bin" render "$tmp/scene.json" -o "$tmp/render.exr" --threads 2 >"$tmp/render.out" \
  2>"$tmp/render.err"; then
  echo "FAIL: oceanref render exited $?: $(cat "$tmp/render.err")" >&2
  exit 1
fi
# The pixels: the corners (0, 0) (sky) and (23, 13) (sea), and in column 12 the rows around the
# horizon (6.4 rows from the top: the camera looks 2.3° down with 50°/14 rows) and open sea.
for pixel in 0,0 23,13 12,5 12,6 12,7 12,12; do
  if ! "$bin" probe "$tmp/scene.json" --pixel "$pixel" --threads 2 >"$tmp/pixel.$pixel.csv" \
    2>"$tmp/probe.err"; then
    echo "FAIL: oceanref probe --pixel $pixel exited $?: $(cat "$tmp/probe.err")" >&2
    exit 1
  fi
done
/usr/bin/python3 - "$tmp" <<'EOF'
import glob, os, sys
import numpy as np
import OpenImageIO as oiio

tmp = sys.argv[1]
image = oiio.ImageInput.open(os.path.join(tmp, "render.exr"))
spec = image.spec()
names = list(spec.channelnames)
pixels = image.read_image(0, 0, 0, spec.nchannels, "float")
image.close()
failures = 0
kinds = set()
for path in sorted(glob.glob(os.path.join(tmp, "pixel.*.csv"))):
    x, y = (int(v) for v in os.path.basename(path).split(".")[1].split(","))
    lines = open(path).read().splitlines()
    assert lines[-2] == "pixel,R,G,B", lines[-2]
    probe = [float(v) for v in lines[-1].split(",")[1:]]
    header = lines[0].split(",")
    hits = [int(row.split(",")[header.index("hit")]) for row in lines[1:-2]]
    assert len(hits) == 9, len(hits)
    kinds.add("sky" if sum(hits) == 0 else "sea" if sum(hits) == 9 else "horizon")
    for c, name in enumerate("RGB"):
        written = pixels[y, x, names.index(name)]
        probed = np.float32(probe[c])
        if probed.tobytes() != written.tobytes():
            print(f"FAIL: pixel {x},{y} {name}: probe {probe[c]!r} -> {probed!r}, render wrote "
                  f"{written!r}", file=sys.stderr)
            failures += 1
# The chosen pixels must include the horizon (part sea, part sky), open sea and sky.
if kinds != {"sky", "sea", "horizon"}:
    print(f"FAIL: the probed pixels cover {sorted(kinds)}, not sky, sea and horizon",
          file=sys.stderr)
    failures += 1
print(f"probe_render: {failures} failures")
sys.exit(1 if failures else 0)
EOF
