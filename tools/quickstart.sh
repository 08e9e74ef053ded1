#!/usr/bin/env bash
# The README's first command: installs what is missing, builds oceanref and runs the main job,
# which for now prints a default spectrum table (JONSWAP, U10 = 10 m/s, fetch 100 km: S(ω) around
# the peak, and the moments m0, Hs and mean square slopes).
set -euo pipefail
cd "$(dirname "$0")/.."

bash tools/build.sh build
echo
echo "== oceanref spectrum --model jonswap --omega 0.4,...,3 (S in m^2 s)"
build/src/oceanref spectrum --model jonswap --omega 0.4,0.5,0.6,0.7,0.8,0.9,1,1.2,1.5,2,3
echo
echo "== oceanref spectrum --model jonswap --moments"
build/src/oceanref spectrum --model jonswap --moments
