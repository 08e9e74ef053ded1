#!/usr/bin/env bash
# Peak memory of a render streamed to its files (issue 16, point 3): renders the default scene
# (reference/scenes/default.json, fast accuracy, 1 sample per pixel) at WIDTHxHEIGHT (default
# 16384x16384) with a PNG preview, and prints the peak resident set size of the oceanref
# process, the time and the file sizes. The goal: under 1 GiB at 16384x16384, about the same at
# any height (memory is one band of rows, not the image).
#
#   bash tools/streaming_memory.sh [WIDTHxHEIGHT] [--threads N]
#
# OCEANREF (default build/src/oceanref) names the binary. 16384x16384 takes about ten minutes
# on 2 cores and writes ~2 GB to a temporary folder (removed afterwards).
set -euo pipefail
cd "$(dirname "$0")/.."
size=16384x16384
threads=0
while [[ $# -gt 0 ]]; do
  case "$1" in
    --threads) threads=$2; shift 2 ;;
    -h | --help) sed -n '2,12p' "$0"; exit 0 ;;
    *x*) size=$1; shift ;;
    *) echo "streaming_memory.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
bin=${OCEANREF:-build/src/oceanref}
[[ -x "$bin" ]] || { echo "streaming_memory.sh: no binary at $bin (build first)" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
/usr/bin/python3 - "$bin" "$size" "$threads" "$tmp" <<'PY'
import json, platform, resource, subprocess, sys, time, os
binary, size, threads, tmp = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4]
width, height = (int(v) for v in size.split("x"))
scene = json.load(open("reference/scenes/default.json"))
scene["render"].update(width=width, height=height, samples_per_pixel=1)
scene["shading"]["accuracy"] = "fast"
scene["shading"].pop("tolerance", None)
path = os.path.join(tmp, "scene.json")
json.dump(scene, open(path, "w"))
exr, png = os.path.join(tmp, "out.exr"), os.path.join(tmp, "out.png")
start = time.time()
result = subprocess.run([binary, "render", path, "-o", exr, "--png", png, "--threads", threads,
                         "--max-memory", "64G"], stdout=subprocess.PIPE, text=True, check=True)
seconds = time.time() - start
peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss * 1024  # Linux: KiB
report = dict(line.split(",", 1) for line in result.stdout.splitlines())
commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], stdout=subprocess.PIPE,
                        text=True).stdout.strip()
print(f"# streamed render, default scene fast, {width}x{height}, 1 spp")
model = platform.machine()
for line in open("/proc/cpuinfo") if os.path.exists("/proc/cpuinfo") else []:
    if line.startswith("model name"):
        model = line.split(":", 1)[1].strip()
        break
print(f"# {time.strftime('%Y-%m-%d')}, {model}, {os.cpu_count()} cores, commit {commit}")
print(f"peak_rss_bytes,{peak}")
print(f"peak_rss_mib,{peak / 2**20:.1f}")
print(f"memory_estimate_bytes,{report['memory_estimate_bytes']}")
print(f"seconds,{seconds:.1f}")
print(f"exr_bytes,{os.path.getsize(exr)}")
print(f"png_bytes,{os.path.getsize(png)}")
PY
