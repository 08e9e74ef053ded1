#!/usr/bin/env bash
# Cross-builds oceanref for aarch64 (arm64) on an x86-64 Debian host and runs it under qemu-user.
#
#   tools/cross_aarch64.sh [BUILD_DIR]                  build (default BUILD_DIR: build-aarch64)
#   tools/cross_aarch64.sh [BUILD_DIR] --run ARGS...    run BUILD_DIR/src/oceanref ARGS under qemu
#
# Installs what is missing on the host (g++-aarch64-linux-gnu, qemu-user), creates an arm64
# sysroot once in build/_deps/aarch64-sysroot (Debian's arm64 .debs of the -dev packages and
# their dependencies, fetched through a private apt configuration in a temporary directory and
# unpacked with dpkg-deb; no system file is written, no foreign architecture is added), fetches
# KissFFT (tools/setup.sh), then configures with tools/aarch64-toolchain.cmake and builds
# `oceanref` (the unit tests run threads, which hang under qemu-user: they are not built). The C library and libstdc++ are the cross
# toolchain's (/usr/aarch64-linux-gnu). Threaded programs can hang under qemu-user: pass
# `--threads 1` to the commands that take it. Relative paths (BUILD_DIR, ARGS) are taken from
# the repository root, e.g.
#
#   tools/cross_aarch64.sh --run render reference/scenes/golden/default_small.json -o /tmp/a64.exr --threads 1
set -euo pipefail
cd "$(dirname "$0")/.."

build_dir=build-aarch64
if [ $# -gt 0 ] && [ "$1" != "--run" ]; then
  build_dir=$1
  shift
fi
sysroot="$PWD/build/_deps/aarch64-sysroot"
triple=aarch64-linux-gnu
lib_path="$sysroot/usr/lib/$triple:$sysroot/lib/$triple:/usr/$triple/lib"

if [ $# -gt 0 ] && [ "$1" = "--run" ]; then
  shift
  if [ ! -x "$build_dir/src/oceanref" ] || [ ! -d "$sysroot" ]; then
    echo "cross_aarch64: $build_dir/src/oceanref not built; run tools/cross_aarch64.sh first" >&2
    exit 2
  fi
  exec qemu-aarch64 -L "$sysroot" -E "LD_LIBRARY_PATH=$lib_path" "$build_dir/src/oceanref" "$@"
fi
if [ $# -gt 0 ]; then
  echo "usage: tools/cross_aarch64.sh [BUILD_DIR] [--run ARGS...]" >&2
  exit 2
fi

as_root() { if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi; }

# --- host tools -----------------------------------------------------------------------------
missing=()
for p in g++-aarch64-linux-gnu qemu-user; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "cross_aarch64: installing ${missing[*]}"
  as_root apt-get update -qq
  as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
    "${missing[@]}" >/dev/null
fi

# --- arm64 sysroot --------------------------------------------------------------------------
# The -dev packages the build needs (header-only ones are architecture-independent, but CMake
# looks for packages only in the sysroot).
dev_packages=(libopenexr-dev libimath-dev zlib1g-dev libfftw3-dev libtinyobjloader-dev
              nlohmann-json3-dev libglm-dev libcli11-dev doctest-dev)
# Provided by the cross toolchain (/usr/aarch64-linux-gnu) or not needed to link: not followed.
toolchain_re='^(libc6|libc6-dev|libc-dev-bin|libgcc-s1|libgcc-[0-9]+-dev|libstdc\+\+6|libstdc\+\+-[0-9]+-dev|gcc-[0-9]+-base|libcrypt1|libcrypt-dev|libnsl2|libnsl-dev|linux-libc-dev|rpcsvc-proto|libtirpc[0-9a-z-]*|libgomp1|libatomic1|libasan[0-9]+|libubsan[0-9]+|libtsan[0-9]+|liblsan[0-9]+|libhwasan[0-9]+|libitm[0-9]+|debconf|dpkg|perl-base|install-info)$'

make_sysroot() {
  local tmp=$1 partial="$sysroot.partial"
  mkdir -p "$tmp/sources.list.d" "$tmp/lists/partial" "$tmp/cache/archives/partial" "$tmp/debs"
  : >"$tmp/status"
  # The system's binary entries, minus those restricted to other architectures.
  : >"$tmp/sources.list"
  for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.list; do
    [ -f "$f" ] || continue
    grep -E '^[[:space:]]*deb[[:space:]]' "$f" |
      grep -Ev '\[[^]]*arch=' >>"$tmp/sources.list" || true
    grep -E '^[[:space:]]*deb[[:space:]]+\[[^]]*arch=[^] ]*arm64' "$f" >>"$tmp/sources.list" || true
  done
  for f in /etc/apt/sources.list.d/*.sources; do
    [ -f "$f" ] || continue
    awk 'BEGIN { RS = ""; ORS = "\n\n" }
         /(^|\n)Types:[^\n]*deb([ \t]|\n|$)/ && (!/(^|\n)Architectures:/ || /(^|\n)Architectures:[^\n]*arm64/)' \
      "$f" >"$tmp/sources.list.d/$(basename "$f")"
  done
  local apt_private=(-o "Dir::Etc::SourceList=$tmp/sources.list"
                     -o "Dir::Etc::SourceParts=$tmp/sources.list.d"
                     -o "Dir::State::Lists=$tmp/lists"
                     -o "Dir::State::status=$tmp/status"
                     -o "Dir::Cache=$tmp/cache"
                     -o "APT::Architecture=arm64"
                     -o "APT::Architectures::=arm64"
                     -o "APT::Sandbox::User=$(id -un)"
                     -o "Debug::NoLocking=1")
  apt-get "${apt_private[@]}" -qq update

  # Dependency closure (Depends and Pre-Depends; of alternatives the first real package).
  local -A seen=()
  local frontier=("${dev_packages[@]}") closure=() query next p
  while [ ${#frontier[@]} -gt 0 ]; do
    query=()
    for p in "${frontier[@]}"; do
      if [ -n "${seen[$p]:-}" ] || [[ $p =~ $toolchain_re ]]; then continue; fi
      seen[$p]=1
      query+=("$p")
    done
    [ ${#query[@]} -gt 0 ] || break
    closure+=("${query[@]}")
    mapfile -t next < <(
      apt-cache "${apt_private[@]}" depends --no-recommends --no-suggests --no-conflicts \
        --no-breaks --no-replaces --no-enhances "${query[@]}" 2>/dev/null |
      awk '/^[^ ]/ { grp = 0; done = 0; next }
           { alt = ($0 ~ /^ \|/); line = $0; sub(/^ *\|?/, "", line)
             n = index(line, ": "); type = substr(line, 1, n - 1); name = substr(line, n + 2)
             if (type != "Depends" && type != "PreDepends") { grp = 0; done = 0; next }
             if (!grp) done = 0
             if (!done && name !~ /^</) { sub(/:.*/, "", name); print name; done = 1 }
             grp = alt }' | sort -u)
    frontier=()
    for p in "${next[@]}"; do
      [ -z "${seen[$p]:-}" ] && frontier+=("$p")
    done
  done

  (cd "$tmp/debs" && apt-get "${apt_private[@]}" -qq download "${closure[@]}" >/dev/null)
  rm -rf "$partial"
  mkdir -p "$partial"
  local deb
  for deb in "$tmp"/debs/*.deb; do
    dpkg-deb -x "$deb" "$partial"
    dpkg-deb -f "$deb" Package Version Architecture |
      awk '{ v[NR] = $2 } END { print v[1] " " v[2] " " v[3] }' >>"$tmp/packages.txt"
  done
  sort "$tmp/packages.txt" >"$partial/oceanref-packages.txt"
  # Absolute symbolic links (libz.so -> /lib/...) point at the host: make them relative.
  local link target
  while IFS= read -r -d '' link; do
    target=$(readlink "$link")
    if [[ $target == /* ]]; then
      ln -sfn "$(realpath -m --relative-to="$(dirname "$link")" "$partial$target")" "$link"
    fi
  done < <(find "$partial" -type l -print0)
  # qemu -L looks for the program interpreter in the sysroot: the toolchain's (same glibc).
  mkdir -p "$partial/lib"
  cp -L "/usr/$triple/lib/ld-linux-aarch64.so.1" "$partial/lib/ld-linux-aarch64.so.1"
  rm -rf "$partial/usr/share/doc" "$partial/usr/share/man" "$partial/usr/share/lintian"
  mv "$partial" "$sysroot"
}

if [ ! -f "$sysroot/oceanref-packages.txt" ]; then
  echo "cross_aarch64: creating the arm64 sysroot in build/_deps/aarch64-sysroot"
  mkdir -p "$(dirname "$sysroot")"
  rm -rf "$sysroot"   # an incomplete one (no package list) is rebuilt
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp" "$sysroot.partial"' EXIT
  trap 'exit 130' INT
  trap 'exit 143' TERM
  make_sysroot "$tmp"
  rm -rf "$tmp"
  trap - EXIT INT TERM
fi

# --- configure and build --------------------------------------------------------------------
bash tools/setup.sh build
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
if [ ! -f "$build_dir/CMakeCache.txt" ]; then
  mkdir -p "$build_dir"
  if ! cmake -S . -B "$build_dir" "${generator[@]}" \
      -DCMAKE_TOOLCHAIN_FILE="$PWD/tools/aarch64-toolchain.cmake" -DSYSROOT="$sysroot" \
      -DOCEANREF_KISSFFT_DIR="$PWD/build/_deps/kissfft-src" -DBUILD_TESTING=OFF \
      >"$build_dir/configure.log" 2>&1; then
    cat "$build_dir/configure.log" >&2
    rm -f "$build_dir/CMakeCache.txt"
    exit 1
  fi
fi
cmake --build "$build_dir" --parallel 2 --target oceanref
run_dir=
[ "$build_dir" = build-aarch64 ] || run_dir=" $build_dir"
echo "cross_aarch64: built $build_dir/src/oceanref; run it (one thread) with"
echo "  bash tools/cross_aarch64.sh$run_dir --run render SCENE.json -o OUT.exr --threads 1"
echo "  (= qemu-aarch64 -L build/_deps/aarch64-sysroot -E LD_LIBRARY_PATH=... $build_dir/src/oceanref ...)"
