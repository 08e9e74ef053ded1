#!/usr/bin/env bash
# Line coverage of src/ by the unit and command-line tests without the golden hashes — the tests
# tools/mutation.py measures (docs/MUTATION.md). A line no test executes is a mutant that cannot
# be killed: this finds such code in one run (~25 min on 2 cores) instead of one mutant at a time.
#
#   tools/coverage.sh [BUILD_DIR]   (default build-cov/: g++ --coverage -O1, no Python module)
#
# Prints each src/ file's executed share and writes BUILD_DIR/uncovered.txt: every line of src/
# that no test executed, as FILE:LINE: SOURCE. The golden suite and the slow whole-render tests
# (golden, probe_render, parameter_sweep_scenes) and the build checks (portable_binary,
# compile_guards, consumer) are left out, as tools/mutation.py leaves out the goldens.
set -euo pipefail
cd "$(dirname "$0")/.."
dir=${1:-build-cov}
kiss=${OCEANREF_KISSFFT_DIR:-$PWD/build/_deps/kissfft-src}
if [ ! -f "$kiss/kiss_fft.c" ]; then bash tools/setup.sh build; fi
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
cmake -S . -B "$dir" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g --coverage" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g" \
  -DCMAKE_EXE_LINKER_FLAGS="--coverage" -DCMAKE_SHARED_LINKER_FLAGS="--coverage" \
  -DOCEANREF_PYTHON=OFF -DOCEANREF_KISSFFT_DIR="$kiss" >/dev/null
cmake --build "$dir" --parallel "$(nproc)"
find "$dir" -name '*.gcda' -delete
# The tests' own verdicts do not matter here (a failing test still executes lines).
(cd "$dir" && OCEANREF_TESTS_NO_GOLDENS=1 ctest --parallel "$(nproc)" \
  -E '^(golden|probe_render|parameter_sweep_scenes|portable_binary|compile_guards|consumer)$' \
  >ctest-coverage.log 2>&1) || echo "coverage.sh: some tests failed (see $dir/ctest-coverage.log)"
gcov_dir=$dir/gcov
rm -rf "$gcov_dir" && mkdir -p "$gcov_dir"
find "$PWD/$dir/src" -name '*.gcda' | while read -r f; do
  (cd "$gcov_dir" && gcov -o "$(dirname "$f")" "$f" >/dev/null 2>&1) || true
done
python3 - "$gcov_dir" "$PWD" "$dir/uncovered.txt" <<'EOF'
import glob, os, sys
gcov_dir, root, out = sys.argv[1], sys.argv[2] + "/", sys.argv[3]
rows, missed = {}, []
for g in glob.glob(os.path.join(gcov_dir, "*.gcov")):
    lines = open(g, errors="replace").read().splitlines()
    source = lines[0].split("Source:")[-1]
    if not source.startswith(root + "src/"):
        continue
    name = source[len(root):]
    total = miss = 0
    for line in lines[1:]:
        count, number, text = (line.split(":", 2) + ["", ""])[:3]
        count = count.strip()
        if count == "-" or not number.strip().isdigit() or int(number) == 0:
            continue
        total += 1
        if count in ("#####", "====="):
            miss += 1
            missed.append(f"{name}:{number.strip()}: {text.strip()}")
    rows[name] = (total, miss)
print("| file | lines | not executed | executed |")
print("|---|---:|---:|---:|")
for name, (total, miss) in sorted(rows.items()):
    if total:
        print(f"| {name} | {total} | {miss} | {100 * (total - miss) / total:.1f}% |")
open(out, "w").write("\n".join(sorted(missed)) + "\n")
print(f"\n{len(missed)} lines not executed: {out}")
EOF
