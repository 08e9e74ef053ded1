#!/usr/bin/env bash
# The README's first command: installs only what the program needs (tools/setup.sh --image),
# builds the `oceanref` program alone (the test targets and the Python module belong to the test
# command, tools/test.sh), renders the default scene (reference/scenes/default.json) with the
# fast lighting rules to build/default.exr (linear, cd/m²) and build/default.png (tone-mapped
# preview), and prints what that image's error is, measured:
#   - the pixel integral: the render's pixel_error summary (3 standard errors of each pixel's
#     samples' mean, relative to the pixel);
#   - the lighting: the same view at 64×36, one sample a pixel, rendered with the fast rules and
#     with the converged reference, compared pixel by pixel (`oceanref bench lighting-pixels`).
# The converged reference image of the default view is the named second step,
# tools/reference_image.sh. Prints the time each step took.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$SECONDS

bash tools/setup.sh --image build
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
if [ ! -f build/CMakeCache.txt ]; then
  cmake -S . -B build "${generator[@]}" -DOCEANREF_KISSFFT_DIR="$PWD/build/_deps/kissfft-src" \
    >/dev/null
fi
cmake --build build --parallel "$(nproc)" --target oceanref
echo "quickstart: installed and built in $((SECONDS - start)) s"

bin=build/src/oceanref
fast=(--set shading.accuracy=fast --set shading.tolerance=null)
scene=reference/scenes/default.json
render_start=$SECONDS
echo
echo "== $bin render $scene ${fast[*]} -o build/default.exr --png build/default.png"
$bin render "$scene" "${fast[@]}" -o build/default.exr --png build/default.png \
  >build/default.report
echo "wrote build/default.exr and build/default.png ($((SECONDS - render_start)) s)"
field() { sed -n "s/^$1,//p" build/default.report; }
echo "pixel integral, estimated error relative to each pixel (3 standard errors of its 4 samples):"
printf '  median %.2g, 99%% %.2g\n' "$(field pixel_error_p50_relative)" "$(field pixel_error_p99_relative)"

check_start=$SECONDS
small=(--set render.width=64 --set render.height=36 --set render.samples_per_pixel=1)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
$bin render "$scene" "${small[@]}" "${fast[@]}" --aov -o "$tmp/fast.exr" >/dev/null
$bin render "$scene" "${small[@]}" -o "$tmp/reference.exr" >/dev/null
IFS=, read -r sea _ median p95 max _ < <($bin bench lighting-pixels "$tmp/fast.exr" \
  "$tmp/reference.exr" | tail -n 1)
echo "fast lighting against the reference (tolerance 1e-6), measured on the same view at 64x36,"
printf '  1 spp, %s sea pixels: |fast - reference|/reference median %.2g, 95%% %.2g, max %.2g (%s s)\n' \
  "$sea" "$median" "$p95" "$max" "$((SECONDS - check_start))"
echo
echo "quickstart: $((SECONDS - start)) s in all. The converged reference image of this view, every"
echo "pixel within a stated error: bash tools/reference_image.sh (it prints its estimated time first)."
