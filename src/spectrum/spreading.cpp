#include "spectrum/spreading.h"

#include <cmath>
#include <numbers>

#include "core/math.h"

namespace oceanref {

namespace {
constexpr double kPi = std::numbers::pi;
constexpr double kLn2 = 0.6931471805599453;
constexpr double kLnPi = 1.1447298858494002;
// sech²(x) = 4e^{−2|x|}/(1 + e^{−2|x|})², no overflow.
double sech2(double x) {
  const double e = math::exp(-2.0 * std::fabs(x));
  return 4.0 * e / ((1.0 + e) * (1.0 + e));
}
}  // namespace

// θ wrapped to [−π, π] (exact: std::remainder is exact).
double wrap_angle(double theta) {
  return std::remainder(theta, 2.0 * kPi);
}

// ln Q(s) = (2s−1) ln 2 − ln π + 2 ln Γ(s+1) − ln Γ(2s+1): Q in logarithms (lgamma) so large s
// cannot overflow (Gamper eq. 3.57; Alimardanov eq. 2.20; Mastin eq. 6 with N_p = 1/Q).
double cos_2s_log_normalization(double s) {
  return (2.0 * s - 1.0) * kLn2 - kLnPi + 2.0 * math::lgamma(s + 1.0) - math::lgamma(2.0 * s + 1.0);
}

// Q(s) = 2^{2s−1}/π · Γ²(s+1)/Γ(2s+1)  (Gamper eq. 3.57).
double cos_2s_normalization(double s) {
  return math::exp(cos_2s_log_normalization(s));
}

// |cos(θ/2)| for any θ: cos(θ/2) towards the wind; behind it (|θ| > π/2, θ wrapped to
// [−π, π]) sin((π − |θ|)/2) with π − |θ| exact (Sterbenz), π meaning fl(π). So the angle atan2
// gives a wavevector exactly opposite the wind, fl(π), has |cos(θ/2)| = 0 as the true angle π
// has; cos(fl(π)/2) = 6.1e-17 left D = Q·(6.1e-17)^{2s} there (≈ 5e-5·Q for s = 0.13) on the
// upwind axis of every grid whose wind blows along an axis.
double half_angle_cosine(double theta) {
  const double t = wrap_angle(theta);
  if (std::fabs(t) <= 0.5 * kPi) return std::fabs(math::cos(0.5 * t));
  return math::sin(0.5 * (kPi - std::fabs(t)));
}

// D = Q(s) |cos(θ/2)|^{2s}, evaluated as exp(ln Q + 2s ln|cos(θ/2)|)  (Gamper eq. 3.57;
// Alimardanov eq. 2.19; Lutz eq. 27–28; Mastin eq. 4), ln Q = cos_2s_log_normalization(s)
// computed once for many θ.
double cos_2s_spreading(double theta, double s, double log_normalization) {
  if (s == 0.0) return math::exp(log_normalization);
  const double c = half_angle_cosine(theta);
  if (c == 0.0) return 0.0;
  return math::exp(log_normalization + 2.0 * s * math::log(c));
}

double cos_2s_spreading(double theta, double s) {
  return cos_2s_spreading(theta, s, cos_2s_log_normalization(s));
}

// s_p = 11.5 (ω_p U/g)^−2.5  (Alimardanov eq. 2.22).
double mitsuyasu_peak_spread(double omega_p, double wind_speed, double g) {
  return 11.5 * math::pow(omega_p * wind_speed / g, -2.5);
}

// s = s_p (ω/ω_p)⁵ for ω ≤ ω_p, s_p (ω/ω_p)^−2.5 above  (Alimardanov eq. 2.21).
double mitsuyasu_spread(double omega, double omega_p, double peak_spread) {
  const double r = omega / omega_p;
  return r <= 1.0 ? peak_spread * math::pow(r, 5.0) : peak_spread * math::pow(r, -2.5);
}

// s = 6.97 (ω/ω_p)^4.06 for ω < ω_p, 9.77 (ω/ω_p)^μ for ω ≥ ω_p with
// μ = −2.33 − 1.45 (U ω_p/g − 1.17)  (Hasselmann et al. 1980; Alimardanov §2.7.2).
double hasselmann_spread(double omega, double omega_p, double wind_speed, double g) {
  const double r = omega / omega_p;
  if (r < 1.0) return 6.97 * math::pow(r, 4.06);
  const double mu = -2.33 - 1.45 * (wind_speed * omega_p / g - 1.17);
  return 9.77 * math::pow(r, mu);
}

// p = 9.77 (f/f_m)^μ, μ = 4.06 for f < f_m, −2.34 for f > f_m  (Mastin eq. 5); f/f_m = ω/ω_p.
double mastin_spread(double omega, double omega_p) {
  const double r = omega / omega_p;
  return 9.77 * math::pow(r, r < 1.0 ? 4.06 : -2.34);
}

// s = 6.97 (ω/ω_p)⁵ for ω < ω_p, 9.77 (ω/ω_p)^−2.5 for ω ≥ ω_p  (Gamper eq. 3.57 as printed).
double gamper_spread(double omega, double omega_p) {
  const double r = omega / omega_p;
  return r < 1.0 ? 6.97 * math::pow(r, 5.0) : 9.77 * math::pow(r, -2.5);
}

// Δs = 16 tanh(ω_p/ω) ξ²  (Lutz eq. 29, after Horvath 2015), added to any cos-2s spread.
double horvath_swell_spread(double omega, double omega_p, double swell) {
  if (swell == 0.0) return 0.0;
  const double t = omega > 0.0 ? math::tanh(omega_p / omega) : 1.0;
  return 16.0 * t * swell * swell;
}

// Δs = 16 tanh(min(ω/ω_p, 20)) ξ²  (Alimardanov Algorithm 2, line 1): the ratio the other way
// round from Lutz eq. 29, so swell narrows the high-frequency side; 0 at ω = 0.
double alimardanov_swell_spread(double omega, double omega_p, double swell) {
  if (swell == 0.0) return 0.0;
  const double t = math::tanh(std::fmin(omega / omega_p, 20.0));
  return 16.0 * t * swell * swell;
}

// (2/π) cos²θ on the forward half-plane |θ| ≤ π/2, 0 behind: the cos² partner of the spread
// blend (Alimardanov Algorithm 2), restricted so that ∫D dθ = 1 (see FORMULAS.md).
double forward_cos2_spreading(double theta) {
  const double t = wrap_angle(theta);
  if (std::fabs(t) > 0.5 * kPi) return 0.0;
  const double c = math::cos(t);
  return 2.0 / kPi * c * c;
}

// D = (1 − b) D_cos² + b D_cos2s  (Alimardanov Algorithm 2, "spreadBlend" b ∈ [0, 1]).
double spread_blend(double theta, double cos_2s, double blend) {
  return (1.0 - blend) * forward_cos2_spreading(theta) + blend * cos_2s;
}

// D = |k̂·ŵ|^p = |cos θ|^p, as printed (Gamper eq. 3.73, §3.4): ∫D dθ ≠ 1.
double cosine_power_spreading(double theta, double power) {
  return math::pow(std::fabs(math::cos(theta)), power);
}

// ∫_{−π}^{π} |cos θ|^p dθ = 2√π Γ((p+1)/2) / Γ(p/2 + 1): π for p = 2, 3π/4 for p = 4
// (Gamper §3.4).
double cosine_power_integral(double power) {
  return 2.0 * std::sqrt(kPi) *
         math::exp(math::lgamma(0.5 * (power + 1.0)) - math::lgamma(0.5 * power + 1.0));
}

// β = 2.61 r^1.3 for 0.56 < r < 0.95, 2.28 r^−1.3 for 0.95 ≤ r < 1.6, 1.24 otherwise,
// r = ω/ω_p  (Gamper eq. 3.65).
double donelan_beta(double omega_ratio) {
  const double r = omega_ratio;
  if (r > 0.56 && r < 0.95) return 2.61 * math::pow(r, 1.3);
  if (r >= 0.95 && r < 1.6) return 2.28 * math::pow(r, -1.3);
  return 1.24;
}

// D = ½ β sech²(βθ), as printed (Gamper eq. 3.64): ∫_{−π}^{π} D dθ = tanh(βπ) < 1.
double donelan_spreading(double theta, double beta) {
  return 0.5 * beta * sech2(beta * wrap_angle(theta));
}

// β_s = 2.61 r^1.3 for r < 0.95, 2.28 r^−1.3 for 0.95 ≤ r < 1.6, 10^ε for r ≥ 1.6 with
// ε = −0.4 + 0.8393 exp[−0.567 ln(r²)]  (Vincevičius eq. 1.12; the first branch extended below
// r = 0.56 as Vincevičius does, and ln(r²) read as in Banner 1990, which makes β continuous).
double donelan_banner_beta(double omega_ratio) {
  const double r = omega_ratio;
  if (r < 0.95) return 2.61 * math::pow(r, 1.3);
  if (r < 1.6) return 2.28 * math::pow(r, -1.3);
  const double epsilon = -0.4 + 0.8393 * math::exp(-0.567 * math::log(r * r));
  return math::pow(10.0, epsilon);
}

// D = β/(2 tanh(βπ)) sech²(βθ), ∫_{−π}^{π} D dθ = 1 exactly  (Vincevičius eq. 1.12).
// β → 0 gives the uniform 1/(2π).
double sech2_spreading(double theta, double beta) {
  const double x = beta * kPi;
  // β/tanh(βπ) → 1/π as β → 0 (series 1/π · (1 + x²/3) below x = 1e-4, exact in double).
  const double b_over_tanh = x < 1e-4 ? (1.0 + x * x / 3.0) / kPi : beta / math::tanh(x);
  return 0.5 * b_over_tanh * sech2(beta * wrap_angle(theta));
}

// D = [1 + Δ(k) cos 2θ] / (2π)  (Gamper eq. 3.72, Elfouhaily et al. 1997 eq. 49; Gamper's
// eq. 3.69 misprints the factor as 1 + Δ + cos 2θ).
double unified_spreading(double theta, double upwind_ratio) {
  return (1.0 + upwind_ratio * math::cos(2.0 * theta)) / (2.0 * kPi);
}

}  // namespace oceanref
