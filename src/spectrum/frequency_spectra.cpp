#include "spectrum/frequency_spectra.h"

#include <cmath>
#include <numbers>

#include "core/math.h"
#include "spectrum/dispersion.h"

namespace oceanref {

namespace {
// exp(x) with x ≤ −745 returning exactly 0, so that prefactor·exp(x) is 0, not 0·∞ = NaN,
// when a prefactor like ω⁻⁵ overflows as ω → 0 (exp underflows to 0 below −745 anyway).
double exp_or_zero(double x) {
  return x < -745.0 ? 0.0 : math::exp(x);
}
double pow4(double x) {
  return (x * x) * (x * x);
}
double pow5(double x) {
  return pow4(x) * x;
}
}  // namespace

// Θ(ω) = αg²/ω⁵ · exp[−β (g/(U19.5 ω))⁴]  (Gamper eq. 3.36, β = 0.74).
double pierson_moskowitz_u19_5(double omega, double u19_5, double g) {
  if (!(omega > 0.0)) return 0.0;
  const double e = -kPiersonMoskowitzBeta * pow4(g / (u19_5 * omega));
  if (e < -745.0) return 0.0;
  return kPiersonMoskowitzAlpha * g * g / pow5(omega) * math::exp(e);
}

// ω_p = (4β/5)^{1/4} · g/U19.5 ≈ 0.877 g/U19.5  (Gamper eq. 3.38).
double pierson_moskowitz_peak_frequency_u19_5(double u19_5, double g) {
  return std::sqrt(std::sqrt(0.8 * kPiersonMoskowitzBeta)) * g / u19_5;
}

// ω_p ≈ 0.855 g/U10  (Gamper eq. 3.40).
double pierson_moskowitz_peak_frequency_u10(double u10, double g) {
  return 0.855 * g / u10;
}

// Θ(ω) = αg²/ω⁵ · exp[−5/4 (ω_p/ω)⁴]  (Gamper eq. 3.37).
double pierson_moskowitz(double omega, double alpha, double omega_p, double g) {
  if (!(omega > 0.0)) return 0.0;
  const double e = -1.25 * pow4(omega_p / omega);
  if (e < -745.0) return 0.0;
  return alpha * g * g / pow5(omega) * math::exp(e);
}

// χ = gF/U10²  (Gamper eq. 3.43).
double dimensionless_fetch(double fetch, double wind_speed, double g) {
  return g * fetch / (wind_speed * wind_speed);
}

// ν = 3.5 χ^−0.33  (Gamper eq. 3.52).
double jonswap_dimensionless_peak_frequency(double chi) {
  return 3.5 * math::pow(chi, -0.33);
}

// ω_p = 2π g ν / U10  (Gamper eq. 3.53).
double peak_frequency_from_dimensionless(double nu, double wind_speed, double g) {
  return 2.0 * std::numbers::pi * g * nu / wind_speed;
}

// α = 0.076 χ^−0.22  (Gamper eq. 3.54).
double jonswap_alpha(double chi) {
  return 0.076 * math::pow(chi, -0.22);
}

// σ = 0.07 for ω ≤ ω_p, 0.09 above (Gamper eq. 3.51; values overridable).
double jonswap_peak_width(double omega, double omega_p, double sigma_low, double sigma_high) {
  return omega <= omega_p ? sigma_low : sigma_high;
}

// r = exp[−(ω − ω_p)² / (2σ²ω_p²)]  (Gamper eq. 3.51).
double peak_enhancement_exponent(double omega, double omega_p, double sigma) {
  const double x = (omega - omega_p) / (sigma * omega_p);
  return std::isinf(x) ? 0.0 : exp_or_zero(-0.5 * x * x);
}

// Θ(ω) = αg²/ω⁵ · exp[−5/4 (ω_p/ω)⁴] · γ^r  (Gamper eq. 3.51).
double jonswap(double omega, double alpha, double omega_p, double gamma, double sigma_low,
               double sigma_high, double g) {
  const double r = peak_enhancement_exponent(
      omega, omega_p, jonswap_peak_width(omega, omega_p, sigma_low, sigma_high));
  return pierson_moskowitz(omega, alpha, omega_p, g) * math::pow(gamma, r);
}

// ω_h = ω √(h/g)  (Vincevičius eq. 1.9).
double depth_frequency(double omega, double depth, double g) {
  return omega * std::sqrt(depth / g);
}

// Φ = [k_h⁻³ ∂k_h/∂ω] / [k_∞⁻³ ∂k_∞/∂ω], k_h from ω² = gk tanh(kh)  (Vincevičius eq. 1.9).
// With k_∞ = ω²/g the denominator is 2g²/ω⁵. Φ → 1 as h → ∞ and Φ ≈ ω_h²/2 as ω_h → 0.
double kitaigorodskii_depth_attenuation(double omega, double depth, double g) {
  if (std::isinf(depth)) return 1.0;
  if (!(omega > 0.0)) return 0.0;
  const Dispersion finite{DispersionKind::finite_depth, g, depth, 370.0};
  const double k = wavenumber_from_frequency(finite, omega);
  const double kh = k * depth;
  if (kh > 40.0) return 1.0;  // tanh(kh) = 1 and sech²(kh) < 1e-34: Φ = 1 to double precision
  const double k_over_kdeep = k * g / (omega * omega);  // k_h / k_∞ ≥ 1
  const double dk_over_dkdeep = g / (2.0 * omega * group_velocity(finite, k));
  // (k_h/k_∞)⁻³ · (dk_h/dω)/(dk_∞/dω)
  return dk_over_dkdeep / (k_over_kdeep * k_over_kdeep * k_over_kdeep);
}

// Φ ≈ ω_h²/2 for ω_h ≤ 1, 1 − (2 − ω_h)²/2 for 1 < ω_h < 2, 1 for ω_h ≥ 2
// (Vincevičius eq. 1.10; the printed form omits the ω_h ≥ 2 branch, where it would decrease).
double thompson_vincent_depth_attenuation(double omega, double depth, double g) {
  if (std::isinf(depth)) return 1.0;
  const double wh = depth_frequency(omega, depth, g);
  if (wh <= 1.0) return 0.5 * wh * wh;
  if (wh < 2.0) return 1.0 - 0.5 * (2.0 - wh) * (2.0 - wh);
  return 1.0;
}

// Ω_c = 11.6 χ^−0.23, unclamped  (Gamper eq. 3.67).
double donelan_inverse_wave_age(double chi) {
  return 11.6 * math::pow(chi, -0.23);
}

// ω_p = Ω_c g / U_c  (Gamper eq. 3.66).
double donelan_peak_frequency(double inverse_wave_age, double wind_speed, double g) {
  return inverse_wave_age * g / wind_speed;
}

// γ = 1.7 for Ω_c < 1, 1.7 + 6 log10 Ω_c for 1 ≤ Ω_c  (Gamper eq. 3.68).
double donelan_gamma(double inverse_wave_age) {
  return inverse_wave_age < 1.0 ? 1.7 : 1.7 + 6.0 * math::log10(inverse_wave_age);
}

// σ = 0.08 (1 + 4/Ω_c³)  (Gamper eq. 3.68).
double donelan_sigma(double inverse_wave_age) {
  return 0.08 * (1.0 + 4.0 / (inverse_wave_age * inverse_wave_age * inverse_wave_age));
}

// α = 0.006 Ω_c^0.55  (Gamper eq. 3.68).
double donelan_alpha(double inverse_wave_age) {
  return 0.006 * math::pow(inverse_wave_age, 0.55);
}

// Θ(ω) = αg²ω⁻⁵ (ω/ω_p) exp[−(ω_p/ω)⁴] γ^r  (Gamper eq. 3.68).
double donelan(double omega, double alpha, double omega_p, double gamma, double sigma, double g) {
  if (!(omega > 0.0)) return 0.0;
  const double e = -pow4(omega_p / omega);
  if (e < -745.0) return 0.0;
  const double r = peak_enhancement_exponent(omega, omega_p, sigma);
  return alpha * g * g / pow4(omega) / omega_p * math::exp(e) * math::pow(gamma, r);
}

}  // namespace oceanref
