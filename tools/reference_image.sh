#!/usr/bin/env bash
# The quick start's second step: the converged reference image of the default view
# (reference/scenes/default.json), every pixel within a stated total error — the two-level
# estimate to render.pixel_tolerance (README, "One error budget per pixel"): its pixel integral
# and its lighting integrals both bounded, per pixel, in the EXR's pixel_error and lighting_error
# layers. Once the first 2% of its rows (spread over the image) are done it prints its estimated
# total time; then its progress. Writes build/default_reference.exr (with --aov layers) and
# build/default_reference.png, and prints the render's report.
#
#   bash tools/reference_image.sh [TOLERANCE] [WxH] [RENDER FLAGS...]
#       default 0.01 and the scene's 640x360 ("" keeps the size); further arguments go to
#       `oceanref render`, e.g. --set render.pixel_pattern=sobol
set -euo pipefail
cd "$(dirname "$0")/.."

tolerance=${1:-0.01}
size=${2:-}
shift $(($# < 2 ? $# : 2))
bin=build/src/oceanref
[ -x "$bin" ] || bash tools/quickstart.sh >/dev/null
overrides=(--set "render.pixel_tolerance=$tolerance")
if [ -n "$size" ]; then
  overrides+=(--set "render.width=${size%x*}" --set "render.height=${size#*x}")
fi
overrides+=("$@")
echo "== $bin render reference/scenes/default.json ${overrides[*]} --aov" \
  "-o build/default_reference.exr --png build/default_reference.png"
start=$SECONDS
$bin render reference/scenes/default.json "${overrides[@]}" --aov \
  -o build/default_reference.exr --png build/default_reference.png
echo "reference_image: $((SECONDS - start)) s; a pixel is within the tolerance when pixel_error +"
echo "lighting_error <= $tolerance x its largest channel (capped_pixels above counts the others)"
# Over the sea (with OpenImageIO's Python module, which tools/setup.sh installs for the tests).
/usr/bin/python3 - "$tolerance" <<'EOF' 2>/dev/null || true
import sys
import numpy as np
import OpenImageIO as oiio
i = oiio.ImageInput.open("build/default_reference.exr")
spec = i.spec()
a = np.asarray(i.read_image(format="double")).reshape(spec.height, spec.width, -1)
d = {n: a[:, :, k] for k, n in enumerate(spec.channelnames)}
layer = lambda name: np.stack([d[name + c] for c in (".R", ".G", ".B")], -1)
largest = np.stack([d["R"], d["G"], d["B"]], -1).max(-1)
sea = d["coverage"] > 0
part = lambda e: (e.max(-1) / largest)[sea]
total = part(layer("pixel_error") + layer("lighting_error"))
q = lambda x: "p50 %.2g, p99 %.2g" % tuple(np.percentile(x, [50, 99]))
print("sea pixels %d: within the tolerance %.1f%%; total bound %s; pixel part %s; lighting part %s"
      % (sea.sum(), 100 * (total <= float(sys.argv[1])).mean(), q(total),
         q(part(layer("pixel_error"))), q(part(layer("lighting_error")))))
EOF
