#!/usr/bin/env bash
# Checks a built oceanref against the determinism contract at the machine-code level:
#   1. the program and the libraries import no transcendental from libm (they must call the
#      portable functions of src/core/math.h; exact operations such as sqrt, floor or fmod are
#      allowed, they are correctly rounded everywhere);
#   2. no fused multiply-add instruction appears in the libraries or the program (a compiler may
#      emit them for -march=x86-64-v3/native, or on aarch64, if contraction were allowed).
#
#   tools/check_binary.sh BUILD_DIR [OBJDUMP]      (OBJDUMP: e.g. aarch64-linux-gnu-objdump)
set -euo pipefail

build_dir=${1:?usage: tools/check_binary.sh BUILD_DIR [OBJDUMP]}
objdump_tool=${2:-objdump}
nm_tool=${objdump_tool%objdump}nm
program="$build_dir/src/oceanref"
# The libraries: one per folder of src/ (src/CMakeLists.txt).
libraries=()
for layer in core spectrum waves sky shading raster scene io conformance; do
  libraries+=("$build_dir/src/liboceanref_$layer.a")
done
for f in "$program" "${libraries[@]}"; do
  [ -f "$f" ] || { echo "check_binary: $f not found (build first)" >&2; exit 2; }
done

# Every libm transcendental, with the float/long double/_Float128 variants and glibc's
# internal __*_finite aliases.
transcendental='^(__)?(exp|exp2|exp10|expm1|log|log2|log10|log1p|logb|pow|pow10|sin|cos|tan|sincos|asin|acos|atan|atan2|sinh|cosh|tanh|asinh|acosh|atanh|hypot|cbrt|erf|erfc|lgamma|lgamma_r|gamma|tgamma|j0|j1|jn|y0|y1|yn|cexp|clog|cpow|csin|ccos|ctan|cabs|carg)(f|l|f128|f64|f32x|f64x)?(_finite)?(@.*)?$'
failures=0
imports=$("$nm_tool" -D --undefined-only "$program" | awk '{print $NF}' | grep -E "$transcendental" || true)
if [ -n "$imports" ]; then
  echo "FAIL: $program imports libm transcendentals: $(echo $imports)" >&2
  failures=$((failures + 1))
fi
for library in "${libraries[@]}"; do
  undefined=$("$nm_tool" --undefined-only "$library" 2>/dev/null | awk '{print $NF}' | sort -u |
    grep -E "$transcendental" || true)
  if [ -n "$undefined" ]; then
    echo "FAIL: $library calls libm transcendentals: $(echo $undefined)" >&2
    failures=$((failures + 1))
  fi
done

# Fused multiply-add mnemonics: x86 FMA3/FMA4 (vfmadd…, vfmsub…, vfnmadd…, vfnmsub…,
# vfmaddsub…, vfmsubadd…), aarch64 scalar and vector (fmadd, fmsub, fnmadd, fnmsub, fmla, fmls).
fma='\s(vf(n)?m(add|sub)[a-z0-9]*|vfmaddsub[a-z0-9]*|vfmsubadd[a-z0-9]*|fn?m(add|sub)|fml[as])\s'
for f in "${libraries[@]}" "$program"; do
  count=$("$objdump_tool" -d --no-show-raw-insn "$f" 2>/dev/null | grep -cE "$fma" || true)
  if [ "$count" -ne 0 ]; then
    echo "FAIL: $f contains $count fused multiply-add instructions, e.g.:" >&2
    "$objdump_tool" -d --no-show-raw-insn "$f" | grep -E "$fma" | head -5 >&2
    failures=$((failures + 1))
  fi
done
[ "$failures" -eq 0 ] && echo "check_binary: $build_dir: no libm transcendental imported, no FMA instruction"
[ "$failures" -eq 0 ]
