#!/usr/bin/env bash
# Accuracy of the portable libm (src/core/math.h) against MPFR: builds tests/math_accuracy.cpp
# with the portable implementations (src/core/math_exp_log.cpp, math_trig.cpp, math_special.cpp)
# into build/math_accuracy/ (independent of the CMake tree) and runs it. Needs g++ and
# libmpfr-dev. MATH_SOURCES="src/core/math_libm.cpp" tools/math_accuracy.sh ... measures the
# glibc-forwarding build instead (both columns then agree: a sanity check of the harness).
#
#   tools/math_accuracy.sh                      10^7 random arguments per function plus hard
#                                               cases, 2 threads, markdown table (the figures
#                                               of reference/ACCURACY.md)
#   tools/math_accuracy.sh --samples 20000 --max-ulp 0.5005   the quick check ctest runs
#   tools/math_accuracy.sh --function erfc,lgamma --samples 1e5
#   tools/math_accuracy.sh --near-midpoints 8 --samples 200000 >nm.inc &&
#     mv nm.inc tests/math_near_midpoints.inc   regenerate the near-midpoint arguments (~6 min
#                                               of CPU; after a change to the argument
#                                               distributions or a function's rounding)
#
# Arguments are passed to the harness (see `--help`); the defaults above apply only when none
# are given. Run time: the MPFR reference values dominate (about half of it mpfr_erfc for
# 10 < x < 30, then Γ and ln|Γ|), ~0.4 ms of CPU per random argument summed over the 23
# functions. Measured on the 2-core AMD EPYC VM (g++ 12, MPFR 4.2.0, 256 bits), CPU time and
# the wall time it means on 2 idle cores:
#   --samples 20000 (ctest)   8.3 s CPU   ~4 s
#   --samples 1e5             39 s CPU    ~20 s
#   default, 10^7             ~65 min CPU ~33 min (extrapolated ×100 from the 10^5 run)
set -euo pipefail
cd "$(dirname "$0")/.."

sources=${MATH_SOURCES:-src/core/math_exp_log.cpp src/core/math_trig.cpp src/core/math_special.cpp}
out=build/math_accuracy
mkdir -p "$out"
# shellcheck disable=SC2086  # $sources is a list of paths
g++ -std=c++20 -O2 -ffp-contract=off -Wall -Wextra -Wpedantic -Isrc \
  tests/math_accuracy.cpp $sources -o "$out/math_accuracy" -lmpfr -lgmp -pthread

if [ $# -eq 0 ]; then
  set -- --samples 10000000 --threads 2 --markdown
fi
exec "$out/math_accuracy" "$@"
