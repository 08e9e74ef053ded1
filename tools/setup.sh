#!/usr/bin/env bash
# Installs the Debian packages oceanref needs (only the missing ones) and fetches Debian's
# `kissfft` source package into the build tree, so CMake can compile it with double scalars.
#
#   tools/setup.sh [--image] [BUILD_DIR]      (default BUILD_DIR: build)
#
# --image: only what building the `oceanref` program needs (the quick start's first image);
# without it also what the tests, the Python module and the tools use.
#
# No system file is modified: the source package comes through a private apt configuration
# (its own sources list derived from the system's, its own lists and cache) in a temporary
# directory that is removed afterwards. Nothing is written when everything is already present.
set -euo pipefail

image_only=0
if [ "${1:-}" = "--image" ]; then
  image_only=1
  shift
fi
build_dir=${1:-build}
# What CMake's configure step finds and the program links (doctest: the test targets are
# configured, not built; FFTW: `oceanref bench synthesis`'s peer).
packages=(build-essential cmake ninja-build dpkg-dev pkg-config libglm-dev libopenexr-dev
          libtinyobjloader-dev doctest-dev nlohmann-json3-dev libcli11-dev libfftw3-dev zlib1g-dev)
if [ "$image_only" -eq 0 ]; then
  packages+=(clang libclang-rt-dev clang-format libmpfr-dev
             chromium openimageio-tools python3-openimageio openexr python3-jsonschema
             pybind11-dev python3-dev python3-numpy python3-pytest parallel)
fi

as_root() { if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi; }

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  as_root apt-get update -qq
  as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
    "${missing[@]}" >/dev/null
fi

kiss_dir="$build_dir/_deps/kissfft-src"
if [ -f "$kiss_dir/kiss_fft.c" ]; then exit 0; fi

echo "setup: fetching Debian's kissfft source package into $kiss_dir"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/sources.list.d" "$tmp/lists/partial" "$tmp/cache/archives/partial" "$tmp/src"
# Derive deb-src entries from the system's own entries (one-line and deb822 formats).
if [ -f /etc/apt/sources.list ]; then
  sed -n 's/^[[:space:]]*deb[[:space:]]/deb-src /p' /etc/apt/sources.list >"$tmp/sources.list"
else
  : >"$tmp/sources.list"
fi
for f in /etc/apt/sources.list.d/*.list; do
  [ -f "$f" ] && sed -n 's/^[[:space:]]*deb[[:space:]]/deb-src /p' "$f" >>"$tmp/sources.list"
done
for f in /etc/apt/sources.list.d/*.sources; do
  [ -f "$f" ] && sed 's/^Types:.*/Types: deb-src/' "$f" >"$tmp/sources.list.d/$(basename "$f")"
done
apt_private=(-o "Dir::Etc::SourceList=$tmp/sources.list"
             -o "Dir::Etc::SourceParts=$tmp/sources.list.d"
             -o "Dir::State::Lists=$tmp/lists"
             -o "Dir::Cache=$tmp/cache"
             -o "APT::Sandbox::User=$(id -un)"
             -o "Debug::NoLocking=1")
apt-get "${apt_private[@]}" -qq update
(cd "$tmp/src" && apt-get "${apt_private[@]}" -qq source kissfft >/dev/null 2>&1)
src=$(find "$tmp/src" -maxdepth 2 -name kiss_fft.c -printf '%h\n' | head -n1)
if [ -z "$src" ]; then
  echo "setup: could not unpack the kissfft source package" >&2
  exit 1
fi
mkdir -p "$(dirname "$kiss_dir")"
rm -rf "$kiss_dir.partial"
cp -r "$src" "$kiss_dir.partial"
mv "$kiss_dir.partial" "$kiss_dir"
