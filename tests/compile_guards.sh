#!/usr/bin/env bash
# The compile-time guards of the determinism contract can fail: a translation unit of the
# library must not compile under -ffast-math or -Ofast (__FAST_MATH__) or with x87 arithmetic
# (-mfpmath=387: FLT_EVAL_METHOD == 2), and must compile without them.
#
#   tests/compile_guards.sh CXX SOURCE_DIR
set -euo pipefail
cxx=${1:?usage: compile_guards.sh CXX SOURCE_DIR}
src=${2:?usage: compile_guards.sh CXX SOURCE_DIR}
check() {  # check EXPECTED(pass|fail) FLAGS... : compiles src/core/math.h and the FP guard
  local expected=$1
  shift
  local status=pass
  for f in core/fp_environment.cpp core/math_trig.cpp; do
    "$cxx" -std=c++20 -DOCEANREF_BUILDING -I"$src" "$@" -fsyntax-only "$src/$f" 2>/dev/null ||
      status=fail
  done
  if [ "$status" != "$expected" ]; then
    echo "FAIL: compiling with '$*' should $expected but did $status" >&2
    exit 1
  fi
  echo "compile_guards: '$*': $expected, as it should"
}
check pass -O2 -ffp-contract=off
check fail -O2 -ffast-math
check fail -Ofast
case "$(uname -m)" in
  x86_64) check fail -O2 -mfpmath=387 ;;  # x87: FLT_EVAL_METHOD == 2
esac
