#!/usr/bin/env bash
# Determinism across compilers: builds oceanref with clang -O2 in build-clang/ and checks that a
# set of commands prints byte-identical output from the gcc -O3 build (build/) and the clang one.
set -euo pipefail
cd "$(dirname "$0")/.."

bash tools/build.sh build
# The program only: clang runs the unit tests in the sanitizer build (tools/test.sh --sanitize),
# the Python module is the gcc build's. tools/determinism_matrix.sh configures it the same way.
CC=clang CXX=clang++ bash tools/build.sh build-clang -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DOCEANREF_PYTHON=OFF -DBUILD_TESTING=OFF  # -O2 -g
commands=(
  "spectrum --model pierson-moskowitz --omega 0.3,0.5,0.8766,1.2,2,5,40"
  "spectrum --model jonswap --gamma 5 --omega 0.5,0.9,1.3 --theta-deg -170,-45,0,10,90,180"
  "spectrum --model tma --depth 4 --wind-speed 18 --fetch 30000 --omega 0.4,0.7,1,2"
  "spectrum --model donelan --spreading donelan-banner --wavevector 0.05:0.01,0.3:-0.2,2:1"
  "spectrum --model unified --wind-speed 7 --wavevector 0.01:0,0.2:-0.1,3:4,370:0,1e4:1"
  "spectrum --model phillips --spreading cos4 --wavevector 0.02:0.03,1:-1"
  "spectrum --model jonswap --spreading mitsuyasu --swell 0.6 --spread-blend 0.3 --omega 1 --theta-deg 0,30,120"
  "spectrum --model pierson-moskowitz --moments"
  "spectrum --model unified --moments"
  "fields reference/scenes/waves_default.json --at 0,0 --time 3"
  "fields reference/scenes/waves_default.json --at 123.4,-56.7 --time 1000"
  "sky --sun-zenith-deg 37 --sun-azimuth-deg 20 --turbidity 3.5 --dir 0,1,0;0.3,0.2,0.9;-1,0.05,0"
  "sky --sun-zenith-deg 71 --sun"
  "sky --sun-zenith-deg 50 --irradiance"
  "brdf --view -0.6,0.5,0.1 --sun 0.6,0.5,0 --sigma2 0.02,0.01 --wind-deg 15"
)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
for c in "${commands[@]}"; do
  # shellcheck disable=SC2086
  if ! build/src/oceanref $c >"$tmp/gcc" || ! build-clang/src/oceanref $c >"$tmp/clang" ||
    [ ! -s "$tmp/gcc" ] || ! cmp -s "$tmp/gcc" "$tmp/clang"; then
    echo "FAIL: gcc and clang builds differ (or fail) for: oceanref $c" >&2
    failures=$((failures + 1))
  fi
done
# The default scene at 96x54 (reference lighting, ~1 ms per sea sample).
scene=reference/scenes/golden/default_small.json
if ! build/src/oceanref render "$scene" -o "$tmp/gcc_r.exr" >"$tmp/gcc_h" ||
  ! build-clang/src/oceanref render "$scene" -o "$tmp/clang_r.exr" >"$tmp/clang_h" ||
  ! cmp -s "$tmp/gcc_h" "$tmp/clang_h"; then
  echo "FAIL: gcc and clang builds render different pixels" >&2
  failures=$((failures + 1))
fi
# The fields EXR: identical files imply identical decoded pixels.
build/src/oceanref fields reference/scenes/waves_default.json -o "$tmp/gcc.exr"
build-clang/src/oceanref fields reference/scenes/waves_default.json -o "$tmp/clang.exr"
if ! cmp -s "$tmp/gcc.exr" "$tmp/clang.exr"; then
  echo "FAIL: gcc and clang builds write different fields EXR files" >&2
  failures=$((failures + 1))
fi
echo "compare_compilers: $((${#commands[@]} + 2)) outputs, $failures differ between gcc and clang"
[ "$failures" -eq 0 ]
