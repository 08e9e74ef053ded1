// Complex numbers for the wave synthesis, with every operation written out.
//
// Not std::complex: its operators may be compiled into fused multiply-adds (gcc 12 emits
// vfmaddsub for std::complex products at -march=x86-64-v3 even with -ffp-contract=off) and
// std::abs calls the platform's hypot, both of which break bit-reproducibility (DESIGN.md,
// determinism contract). Layout {re, im}, the same as KissFFT's kiss_fft_cpx.
#pragma once

#include "core/math.h"

namespace oceanref {

struct Complex {
  double re = 0.0;
  double im = 0.0;
  constexpr Complex() = default;
  constexpr Complex(double real, double imaginary = 0.0) : re(real), im(imaginary) {}
  friend constexpr bool operator==(Complex, Complex) = default;
};

constexpr Complex operator+(Complex a, Complex b) {
  return {a.re + b.re, a.im + b.im};
}
constexpr Complex operator-(Complex a, Complex b) {
  return {a.re - b.re, a.im - b.im};
}
constexpr Complex operator-(Complex a) {
  return {-a.re, -a.im};
}
// (a + ib)(c + id) = (ac − bd) + i(ad + bc), each product rounded before the sum.
constexpr Complex operator*(Complex a, Complex b) {
  return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re};
}
constexpr Complex operator*(double s, Complex a) {
  return {s * a.re, s * a.im};
}
constexpr Complex& operator+=(Complex& a, Complex b) {
  a = a + b;
  return a;
}
constexpr Complex conj(Complex a) {
  return {a.re, -a.im};
}
// i·a
constexpr Complex times_i(Complex a) {
  return {-a.im, a.re};
}
// |a| by the portable hypot
inline double abs(Complex a) {
  return math::hypot(a.re, a.im);
}
// e^{iθ} = cos θ + i sin θ
inline Complex unit_phasor(double theta) {
  const math::SinCos s = math::sincos(theta);
  return {s.cos, s.sin};
}

}  // namespace oceanref
