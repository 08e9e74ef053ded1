#!/usr/bin/env bash
# The installed package works for a consumer: installs the build into a temporary prefix
# (cmake --install), then configures, builds and runs tests/consumer against it with
# find_package(oceanref) — once with oceanref::oceanref (static), once with
# oceanref::oceanref_shared — and checks the install tree's layout.
#
#   tests/consumer_test.sh BUILD_DIR SOURCE_DIR CXX
set -euo pipefail
build=${1:?usage: consumer_test.sh BUILD_DIR SOURCE_DIR CXX}
root=${2:?usage: consumer_test.sh BUILD_DIR SOURCE_DIR CXX}
cxx=${3:?usage: consumer_test.sh BUILD_DIR SOURCE_DIR CXX}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
prefix="$work/prefix"

cmake --install "$build" --prefix "$prefix" >"$work/install.log"
fail() {
  echo "FAIL: $*" >&2
  exit 1
}
libdir=$(find "$prefix" -name liboceanref.a -printf '%h\n' | head -1)
[ -n "$libdir" ] || fail "no liboceanref.a under $prefix"
[ -f "$prefix/include/oceanref/version.h" ] || fail "no include/oceanref/version.h"
for folder in core spectrum waves sky shading raster scene io conformance; do
  [ -n "$(ls "$prefix/include/oceanref/$folder/"*.h 2>/dev/null)" ] ||
    fail "no headers in include/oceanref/$folder"
done
[ ! -e "$prefix/include/oceanref/cli" ] || fail "the program's headers were installed"
so=$(readlink "$libdir/liboceanref.so") || fail "liboceanref.so is not a link to a versioned file"
[ -f "$libdir/$so" ] || fail "liboceanref.so points to a missing $so"
for f in oceanrefConfig.cmake oceanrefConfigVersion.cmake oceanrefTargets.cmake; do
  [ -f "$libdir/cmake/oceanref/$f" ] || fail "no $f in $libdir/cmake/oceanref"
done
soname=$(objdump -p "$libdir/liboceanref.so" | awk '$1 == "SONAME" { print $2 }')
[ -n "$soname" ] && [ -e "$libdir/$soname" ] || fail "liboceanref.so has no soname or no link for it"
echo "consumer_test: installed $(find "$prefix" -type f | wc -l) files; $libdir: liboceanref.a," \
     "liboceanref.so -> $so (soname $soname)"

for kind in static shared; do
  shared=OFF
  [ "$kind" = shared ] && shared=ON
  if ! cmake -S "$root/tests/consumer" -B "$work/$kind" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_PREFIX_PATH="$prefix" -DCONSUMER_SHARED=$shared \
      >"$work/$kind.configure.log" 2>&1; then
    cat "$work/$kind.configure.log" >&2
    fail "$kind: the consumer does not configure against the installed package"
  fi
  if ! cmake --build "$work/$kind" >"$work/$kind.build.log" 2>&1; then
    cat "$work/$kind.build.log" >&2
    fail "$kind: the consumer does not build against the installed package"
  fi
  # The shared consumer must load the installed liboceanref.so (through its RUNPATH), not
  # carry the library's code itself.
  if [ "$kind" = shared ]; then
    # (ldd's output captured first: grep -q closing the pipe early would fail it under pipefail)
    loaded=$(ldd "$work/$kind/consumer")
    grep -q "$soname => $libdir/$soname " <<<"$loaded" ||
      fail "shared: the consumer does not load $libdir/$soname: $loaded"
  else
    ! ldd "$work/$kind/consumer" | grep -q liboceanref ||
      fail "static: the consumer loads a shared liboceanref"
  fi
  echo "consumer_test: $kind:"
  "$work/$kind/consumer" "$root/reference/scenes/default.json" || fail "$kind: the consumer's checks"
done
echo "consumer_test: the installed package builds and runs a consumer, static and shared"
