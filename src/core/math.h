// Portable elementary functions: the only transcendentals the reference path may call.
//
// Every function here is written in plain IEEE-754 binary64 arithmetic (+, −, ×, ÷, sqrt and
// exact operations such as floor, ldexp and bit manipulation) with a fixed operation order. The
// project compiles with -ffp-contract=off and without fast-math (CMakeLists.txt), so the result
// depends on the argument alone: the same bits on every compiler, optimisation level, CPU
// variant and architecture — unlike the platform's libm, whose last bit differs between glibc's
// FMA/AVX2 variants and between x86-64 and aarch64 (DESIGN.md, determinism contract).
//
// Accuracy: every function is evaluated in double-double arithmetic and rounded once; the
// measured maximum error and the share of correctly rounded results per function, against
// MPFR on 10^7 random arguments plus hard cases, are in reference/ACCURACY.md
// (tools/math_accuracy.sh). The contract is ≤ 1 ulp everywhere on the stated domain.
// Special values follow C99 Annex F (NaN in → NaN out, ±∞ and ±0 as libm returns them);
// errno is never set.
#pragma once

#include <cfloat>

#if defined(OCEANREF_BUILDING)  // the library, its program and its tests (CMakeLists.txt)
#if defined(__FAST_MATH__)
#error "oceanref must not be compiled with -ffast-math / -Ofast (determinism contract)"
#endif
#if FLT_EVAL_METHOD != 0
#error "oceanref needs FLT_EVAL_METHOD == 0 (SSE2, not x87): build with -msse2 -mfpmath=sse"
#endif
#endif

namespace oceanref::math {

// e^x
double exp(double x);
// e^x − 1, accurate for |x| ≪ 1
double expm1(double x);
// natural logarithm; −∞ at 0, NaN below 0
double log(double x);
// ln(1 + x), accurate for |x| ≪ 1
double log1p(double x);
// log₁₀ x
double log10(double x);
// x^y with C99 Annex F special cases (pow(x, 0) = 1, pow(1, y) = 1, negative x with integer y)
double pow(double x, double y);

// Trigonometric functions of an angle in radians, with exact argument reduction for every
// finite x (Payne–Hanek beyond the Cody–Waite range).
double sin(double x);
double cos(double x);
double tan(double x);
struct SinCos {
  double sin, cos;
};
// sin x and cos x together (each identical to sin(x) and cos(x))
SinCos sincos(double x);

// Inverse trigonometric functions [rad].
double atan(double x);
double atan2(double y, double x);  // the angle of (x, y) in [−π, π], C99 Annex F signs of zero
double asin(double x);             // NaN outside [−1, 1]
double acos(double x);             // NaN outside [−1, 1]

// Hyperbolic functions.
double sinh(double x);
double cosh(double x);
double tanh(double x);

// √(x² + y²) without undue overflow or underflow
double hypot(double x, double y);
// ∛x
double cbrt(double x);

// Error functions.
double erf(double x);
double erfc(double x);  // accurate in the far tail (no cancellation for large x)

// ln|Γ(x)| and Γ(x).
double lgamma(double x);
double tgamma(double x);

}  // namespace oceanref::math
