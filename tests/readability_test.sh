#!/usr/bin/env bash
# Every kind of file oceanref writes opens in common tools (issue 13): OpenImageIO's oiiotool
# (`--info -v -a`, every subimage), OpenImageIO's Python module (every subimage's pixels) and
# OpenEXR's exrheader, with the expected parts, channels and header attributes. All come from
# Debian (openimageio-tools, python3-openimageio, openexr; tools/setup.sh); the test is skipped
# (exit 77) only when one of them is missing.
#
#   tests/readability_test.sh PATH/TO/oceanref SOURCE_DIR
set -uo pipefail

bin=${1:?usage: readability_test.sh PATH/TO/oceanref SOURCE_DIR}
src=${2:?usage: readability_test.sh PATH/TO/oceanref SOURCE_DIR}
for tool in oiiotool exrheader; do
  if ! command -v "$tool" >/dev/null; then
    echo "SKIP: $tool not installed (tools/setup.sh installs it)"
    exit 77
  fi
done
if ! /usr/bin/python3 -c 'import OpenImageIO' 2>/dev/null; then
  echo "SKIP: OpenImageIO's Python module not installed (tools/setup.sh installs python3-openimageio)"
  exit 77
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
checks=0
fail() {
  echo "FAIL: $*" >&2
  failures=$((failures + 1))
  # tools/mutation.py: the first failure is enough.
  if [ -n "${OCEANREF_TESTS_FAIL_FAST:-}" ]; then exit 1; fi
}
run() {  # run oceanref, failing the test if it does not exit 0
  "$bin" "$@" >"$tmp/run.out" 2>"$tmp/run.err" || fail "oceanref $* exited $?: $(cat "$tmp/run.err")"
}

# readable FILE SUBIMAGES PATTERN... : oiiotool reads every subimage of FILE without an error or
# warning, FILE has SUBIMAGES subimages (parts and levels), and its `oiiotool --info -v -a`
# output matches every extended regex PATTERN (a channel list, an attribute line, …);
# exrheader reads it too.
readable() {
  local file=$1 subimages=$2
  shift 2
  checks=$((checks + 1))
  # --printstats decodes every pixel of every subimage.
  if ! oiiotool --info -v -a "$file" --printstats >"$tmp/info" 2>&1; then
    fail "oiiotool cannot read $file: $(head -c 400 "$tmp/info")"
    return
  fi
  local problems='(^|oiiotool )(ERROR|[Ee]rror:|WARNING|[Ww]arning:)|[Nn]ot supported|[Uu]nsupported'
  if grep -Eq "$problems" "$tmp/info"; then
    fail "oiiotool --info $file: $(grep -E "$problems" "$tmp/info" | head -3)"
  fi
  local got
  got=$(grep -c 'Stats Avg:' "$tmp/info")  # one line per subimage (part or level)
  [ "$got" -eq "$subimages" ] || fail "$file: $got subimages, expected $subimages"
  local p
  for p in "$@"; do
    grep -Eq -- "$p" "$tmp/info" || fail "$file: oiiotool --info -v -a shows no /$p/"
  done
  if [[ $file == *.exr ]]; then
    exrheader "$file" >"$tmp/header" 2>&1 || fail "exrheader cannot read $file: $(head -c 400 "$tmp/header")"
  fi
  # OpenImageIO's Python module: every subimage (part or level), every pixel as float.
  local py
  py=$(/usr/bin/python3 - "$file" <<'PY' 2>&1
import sys
import OpenImageIO as oiio
inp = oiio.ImageInput.open(sys.argv[1])
if not inp:
    sys.exit("cannot open: " + oiio.geterror())
count = 0
while inp.seek_subimage(count, 0):
    spec = inp.spec()
    pixels = inp.read_image(count, 0, 0, spec.nchannels, "float")
    if pixels is None or pixels.size != spec.width * spec.height * spec.nchannels:
        sys.exit("subimage %d: cannot read its pixels: %s" % (count, inp.geterror()))
    count += 1
inp.close()
print(count)
PY
  )
  [ "$py" = "$subimages" ] || fail "OpenImageIO's Python module on $file: $py (expected $subimages subimages)"
}

commit=$("$bin" --version | sed -n '1s/.*(commit \(.*\))$/\1/p')
[ -n "$commit" ] || fail "oceanref --version names no commit"

# A small multi-resolution scene (N_h 32, N_l 16, four cascades) with the default scene's
# settings and a tiny image.
sed -e 's/"resolution": 128/"resolution": 32/' -e 's/"low_resolution": 64/"low_resolution": 16/' \
  -e 's/"width": 96, "height": 54/"width": 24, "height": 14/' \
  -e 's/"columns": 256, "rows": 256/"columns": 64, "rows": 64/' \
  "$src/reference/scenes/golden/default_small.json" >"$tmp/scene.json"
grep -q '"low_resolution": 16' "$tmp/scene.json" || fail "could not derive the small scene"

# 1. The render, without and with the AOV layers.
run render "$tmp/scene.json" -o "$tmp/render.exr" --png "$tmp/preview.png" --threads 2
matrix='-?[0-9.e+-]+(, -?[0-9.e+-]+){15}'
render_attributes=("channel list: R, G, B$" "worldToCamera: $matrix" "worldToNDC: $matrix"
  "oceanref.commit: \"$commit\"" 'oceanref.scene_sha256: "[0-9a-f]{64}"'
  'oceanref.version: "oceanref [0-9.]+"' 'oceanref.pixel_sha256: "[0-9a-f]{64}"'
  'chromaticities: 0.64, 0.33, 0.3, 0.6, 0.15, 0.06, 0.3127, 0.329')
readable "$tmp/render.exr" 1 "${render_attributes[@]}"
run render "$tmp/scene.json" -o "$tmp/aov.exr" --aov --threads 2
readable "$tmp/aov.exr" 1 "${render_attributes[@]:1}" \
  'channel list: R, G, B, depth, coverage, foam.R, foam.G, foam.B, lighting_error.R, '
readable "$tmp/preview.png" 1 '24 x +14, 3 channel, uint8 png'

# 2. The fields: parts c<i> (N_h) and c<i>.low (N_l) per cascade, and sum; every channel is a
# field name plus ".V", every unit attribute is named by the field (docs/FILES.md).
run fields "$tmp/scene.json" -o "$tmp/fields.exr" --threads 2
fields_common=("oceanref.commit: \"$commit\"" 'oceanref.scene_sha256: "[0-9a-f]{64}"'
  'oceanref.scene: "\{"atmosphere"' 'oceanref.seed: "1"' 'oceanref.time_s: "0"'
  'oceanref.choppiness: "-0.8' 'oceanref.units.c0.height: "m"' 'oceanref.units.c3.slope_x: "1"'
  'oceanref.index_convention: "pixel \(column m, row n\)')
readable "$tmp/fields.exr" 9 "${fields_common[@]}" \
  'subimage +0: +32 x +32, 7 channel' \
  'channel list: c0.ddx_dx.V, c0.ddx_dz.V, c0.ddz_dz.V, c0.foam.V, c0.jacobian.V, c0.slope_x.V, c0.slope_z.V$' \
  'subimage +1: +16 x +16, 3 channel' 'channel list: c0.disp_x.V, c0.disp_z.V, c0.height.V$' \
  'name: "c3.low"' 'oceanref.L_m: "800"' 'oceanref.N: "16"' \
  'subimage +8: +32 x +32, 8 channel' \
  'channel list: sum.foam.V, sum.height.V, sum.jacobian.V, sum.normal_x.V, sum.normal_y.V, sum.normal_z.V, sum.slope_x.V, sum.slope_z.V$'

# 3. Every earlier stage, one part per cascade and grid.
for stage in spectrum h0 omega hkt fields; do
  run fields "$tmp/scene.json" --stage "$stage" --time 2.5 -o "$tmp/$stage.exr" --threads 2
done
stage_common=("oceanref.commit: \"$commit\"" 'oceanref.time_s: "2.5"'
  'oceanref.index_convention: "pixel \(column a, row b\) holds the integer wavevector'
  'oceanref.band_rad_per_m: "0,0.12566370614359174"' 'subimage +1: +16 x +16')
readable "$tmp/spectrum.exr" 8 "${stage_common[@]}" 'oceanref.stage: "spectrum"' \
  'channel list: c0.in_band.V, c0.theta.V, c0.variance.V$' 'oceanref.units.c0.low.variance: "m\^2"' \
  'oceanref.units.c0.theta: "m\^4"'
readable "$tmp/h0.exr" 8 "${stage_common[@]}" 'channel list: c2.h0.im.V, c2.h0.re.V$' \
  'oceanref.units.c2.h0.re: "m"'
readable "$tmp/omega.exr" 8 "${stage_common[@]}" 'channel list: c1.k.V, c1.kx.V, c1.kz.V, c1.omega.V$' \
  'oceanref.units.c1.omega: "rad/s"'
readable "$tmp/hkt.exr" 8 "${stage_common[@]}" 'channel list: c3.low.hkt.im.V, c3.low.hkt.re.V$'
readable "$tmp/fields.exr" 9 'oceanref.time_s: "2.5"' 'oceanref.stage: "fields"'

# The worked example of docs/BACKENDS.md: one wave component reproduced by hand from the stages.
mkdir -p "$tmp/example"
for stage in spectrum h0 omega hkt fields; do
  run fields "$src/reference/scenes/backend_example.json" --stage "$stage" -o "$tmp/example/$stage.exr"
done
checks=$((checks + 1))
python3 "$src/docs/backend_example.py" "$tmp/example" >"$tmp/example.out" 2>&1 ||
  fail "docs/backend_example.py: $(cat "$tmp/example.out")"

# 4. The sky hemisphere.
run sky --sun-zenith-deg 60 --size 16 -o "$tmp/sky.exr"
readable "$tmp/sky.exr" 1 'channel list: R, G, B'

# 5. compare's report (diff.exr and the PNGs), when compare writes one.
run compare "$tmp/render.exr" "$tmp/render.exr" --report "$tmp/report"
for f in "$tmp"/report/*.exr "$tmp"/report/*.png; do
  [ -e "$f" ] && readable "$f" 1
done
[ -e "$tmp/report/diff.exr" ] || fail "compare --report wrote no diff.exr"

# 6. The checked-in goldens: a fields file has 2 parts per cascade with multi-resolution (1
# without) and the part sum, as its own attributes describe; a converged golden's render holds
# its error layers.
for f in "$src"/reference/golden/*.exr; do
  case $f in
    *.fields.exr)
      info=$(oiiotool --info -v "$f" 2>&1)
      attribute() { sed -n "s/^ *oceanref.$1: \"\(.*\)\"$/\1/p" <<<"$info" | head -n1; }
      cascades=$(attribute cascade_sizes_m | tr ',' '\n' | grep -c .)
      per_cascade=$([ "$(attribute resolution)" = "$(attribute low_resolution)" ] && echo 1 || echo 2)
      readable "$f" $((cascades * per_cascade + 1)) 'name: "sum"' 'name: "c0"' \
        'oceanref.scene_sha256: "[0-9a-f]{64}"' 'oceanref.units.sum.height: "m"' ;;
    *)
      # A converged golden (render.pixel_tolerance) carries its layers, the others R, G, B only.
      if oiiotool --info -v "$f" 2>&1 | grep -q 'oceanref.pixel_error: "3 standard errors of the pixel mean, adaptive'; then
        readable "$f" 1 'channel list: R, G, B, .*samples.*lighting_error.R.*pixel_error.R' \
          'worldToCamera: ' 'worldToNDC: ' 'oceanref.commit: '
      else
        readable "$f" 1 'channel list: R, G, B$' 'worldToCamera: ' 'worldToNDC: ' 'oceanref.commit: '
      fi ;;
  esac
done

echo "$checks files read, $failures failures"
[ "$failures" -eq 0 ]
