// core/math.h forwarded to the platform's libm. Built only with -DOCEANREF_LIBM_MATH=ON, to
// measure what the portable functions cost (tools/bench_portable_math.sh); such a build breaks
// the determinism contract, says so in `oceanref --version` and must never produce references.
#include <cmath>

#include "core/math.h"

namespace oceanref::math {

double exp(double x) {
  return std::exp(x);
}
double expm1(double x) {
  return std::expm1(x);
}
double log(double x) {
  return std::log(x);
}
double log1p(double x) {
  return std::log1p(x);
}
double log10(double x) {
  return std::log10(x);
}
double pow(double x, double y) {
  return std::pow(x, y);
}
double sin(double x) {
  return std::sin(x);
}
double cos(double x) {
  return std::cos(x);
}
double tan(double x) {
  return std::tan(x);
}
SinCos sincos(double x) {
  return {std::sin(x), std::cos(x)};
}
double atan(double x) {
  return std::atan(x);
}
double atan2(double y, double x) {
  return std::atan2(y, x);
}
double asin(double x) {
  return std::asin(x);
}
double acos(double x) {
  return std::acos(x);
}
double sinh(double x) {
  return std::sinh(x);
}
double cosh(double x) {
  return std::cosh(x);
}
double tanh(double x) {
  return std::tanh(x);
}
double hypot(double x, double y) {
  return std::hypot(x, y);
}
double cbrt(double x) {
  return std::cbrt(x);
}
double erf(double x) {
  return std::erf(x);
}
double erfc(double x) {
  return std::erfc(x);
}
double lgamma(double x) {
  return std::lgamma(x);
}
double tgamma(double x) {
  return std::tgamma(x);
}

}  // namespace oceanref::math
