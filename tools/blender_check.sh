#!/usr/bin/env bash
# Does Blender read these EXR files fully? (issue 13: "readable by ... Blender")
#
#   tools/blender_check.sh FILE.exr...
#
# For each FILE, runs Blender headless (blender -b --factory-startup) with
# tools/blender_read_exr.py, which loads the file as an image and writes out what Blender sees:
# its type (MULTILAYER or IMAGE), its layers and passes, and every pass's pixels (through a
# compositor File Output node) or, for a single-layer image, image.pixels. Then compares with
# what OpenImageIO's Python module reads from FILE: every channel of every part must be in
# Blender with bit-identical values, at its own size or, for a part smaller than part 0 (a
# `c<i>.low` part), padded to part 0's size (Blender sizes every pass like part 0) with the
# values in the top-left block. Prints one line per file, a PADDED line per padded channel and a
# FAIL line per missing or wrong channel.
#
# Exit 0 when Blender sees every channel of every FILE with the right values, 1 when it does
# not (or Blender fails), 2 on bad usage, 77 (skip) when blender or OpenImageIO's Python module
# is not installed. Blender is not installed by tools/setup.sh (Debian bookworm's `blender`,
# 3.4.1, is ~1 GB): `apt-get install blender`. Set BLENDER to use another binary.
set -uo pipefail

if [ $# -eq 0 ]; then
  echo "usage: tools/blender_check.sh FILE.exr..." >&2
  exit 2
fi
blender=${BLENDER:-blender}
if ! command -v "$blender" >/dev/null; then
  echo "SKIP: blender not installed (apt-get install blender; not in tools/setup.sh)"
  exit 77
fi
if ! /usr/bin/python3 -c 'import OpenImageIO, numpy' 2>/dev/null; then
  echo "SKIP: OpenImageIO's Python module not installed (tools/setup.sh installs python3-openimageio)"
  exit 77
fi
harness="$(cd "$(dirname "$0")" && pwd)/blender_read_exr.py"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

status=0
n=0
for file in "$@"; do
  n=$((n + 1))
  if [ ! -f "$file" ]; then
    echo "FAIL: $file: no such file" >&2
    status=1
    continue
  fi
  out="$tmp/$n"
  mkdir -p "$out"
  TMPDIR="$out" "$blender" -b --factory-startup --python-exit-code 3 --python "$harness" -- "$(realpath "$file")" "$out" \
    >"$out/blender.log" 2>&1
  rc=$?
  if [ $rc -ne 0 ] || [ ! -f "$out/blender.json" ]; then
    echo "FAIL: $file: blender exited $rc; last lines of its output:" >&2
    tail -n 15 "$out/blender.log" >&2
    if [ $rc -ge 128 ]; then
      echo "  (Blender 3.4 crashes on a multi-part file whose part 0 is smaller than a later part:" >&2
      echo "   it sizes every pass like part 0 and reads the larger part past the buffer's end)" >&2
    fi
    status=1
    continue
  fi
  /usr/bin/python3 "$harness" compare "$file" "$out" "$out/blender.log" || status=1
done
exit $status
