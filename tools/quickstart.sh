#!/usr/bin/env bash
# The README's first command: installs what is missing, builds oceanref and renders the default
# scene (reference/scenes/default.json) to build/default.exr (linear, cd/m²) and
# build/default.png (tone-mapped preview).
set -euo pipefail
cd "$(dirname "$0")/.."

bash tools/build.sh build
echo
echo "== oceanref render reference/scenes/default.json -o build/default.exr --png build/default.png"
build/src/oceanref render reference/scenes/default.json -o build/default.exr --png build/default.png
echo "wrote build/default.exr and build/default.png"
