// Double-double arithmetic for the portable elementary functions (core/math.h): a value is the
// unevaluated sum hi + lo of two doubles with |lo| ≤ ½ ulp(hi). Only +, −, × and ÷ of doubles are
// used — no fused multiply-add (the project builds with -ffp-contract=off), so every result is
// the same on every IEEE-754 machine.
//
// References: Dekker 1971 (two_product with Veltkamp splitting), Knuth TAOCP vol. 2 §4.2.2
// (two_sum), Joldes, Muller & Popescu 2017 (error bounds of the double-word algorithms).
#pragma once

#include <bit>
#include <cstdint>

namespace oceanref::math::dd {

struct DD {
  double hi = 0.0, lo = 0.0;
};

// s + e = a + b exactly (Knuth's TwoSum, no condition on the magnitudes).
inline DD two_sum(double a, double b) {
  const double s = a + b;
  const double bb = s - a;
  const double e = (a - (s - bb)) + (b - bb);
  return {s, e};
}

// s + e = a + b exactly, provided |a| ≥ |b| or a = 0 (Dekker's FastTwoSum).
inline DD fast_two_sum(double a, double b) {
  const double s = a + b;
  const double e = b - (s - a);
  return {s, e};
}

// Veltkamp's split: a = hi + lo with hi holding the upper 26 bits, exactly (|a| < 2^996).
inline DD split(double a) {
  constexpr double kSplitter = 134217729.0;  // 2^27 + 1
  const double t = kSplitter * a;
  const double hi = t - (t - a);
  return {hi, a - hi};
}

// p + e = a·b exactly (Dekker's TwoProduct), barring overflow and underflow.
inline DD two_product(double a, double b) {
  const double p = a * b;
  const DD x = split(a);
  const DD y = split(b);
  const double e = ((x.hi * y.hi - p) + x.hi * y.lo + x.lo * y.hi) + x.lo * y.lo;
  return {p, e};
}

// (hi + lo) renormalised so that |lo| ≤ ½ ulp(hi).
inline DD normalize(DD a) {
  return fast_two_sum(a.hi, a.lo);
}

inline DD add(DD a, DD b) {  // Joldes et al. Algorithm 6 (AccurateDWPlusDW), rel. error ≤ 3u²
  const DD s = two_sum(a.hi, b.hi);
  const DD t = two_sum(a.lo, b.lo);
  DD v = fast_two_sum(s.hi, s.lo + t.hi);
  return fast_two_sum(v.hi, t.lo + v.lo);
}

inline DD add(DD a, double b) {  // Joldes et al. Algorithm 4 (DWPlusFP), rel. error ≤ 2u²
  const DD s = two_sum(a.hi, b);
  return fast_two_sum(s.hi, a.lo + s.lo);
}

inline DD neg(DD a) {
  return {-a.hi, -a.lo};
}

inline DD mul(DD a, double b) {  // Joldes et al. Algorithm 9 (DWTimesFP3), rel. error ≤ 2u²
  const DD c = two_product(a.hi, b);
  return fast_two_sum(c.hi, a.lo * b + c.lo);
}

inline DD mul(DD a, DD b) {  // Joldes et al. Algorithm 12 (DWTimesDW2 without FMA), ≤ 5u²
  const DD c = two_product(a.hi, b.hi);
  const double t = a.hi * b.lo + a.lo * b.hi;
  return fast_two_sum(c.hi, c.lo + t);
}

inline DD div(DD a, DD b) {  // Joldes et al. Algorithm 17 (DWDivDW2), rel. error ≤ 15u²
  const double q = a.hi / b.hi;
  const DD r = add(a, neg(mul(b, q)));
  const double q2 = r.hi / b.hi;
  return fast_two_sum(q, q2);
}

inline double to_double(DD a) {
  return a.hi + a.lo;
}

// The IEEE-754 bit pattern of a double and back (exact).
inline std::uint64_t bits(double x) {
  return std::bit_cast<std::uint64_t>(x);
}
inline double from_bits(std::uint64_t b) {
  return std::bit_cast<double>(b);
}

}  // namespace oceanref::math::dd
