#include "spectrum/wavenumber_spectra.h"

#include <cmath>

#include "core/math.h"

namespace oceanref {

// Ω_c = 0.84 · tanh[(χ/χ0)^0.4]^−0.75, χ0 = 2.2·10⁴  (Gamper eq. 3.70).
double unified_inverse_wave_age(double chi) {
  return 0.84 * math::pow(math::tanh(math::pow(chi / 2.2e4, 0.4)), -0.75);
}

// k_p = g Ω_c² / U10²  (Gamper §3.4, Unified).
double unified_peak_wavenumber(double inverse_wave_age, double wind_speed, double g) {
  const double r = inverse_wave_age / wind_speed;
  return g * r * r;
}

// γ = 1.7 for Ω_c < 1, 1.7 + 6 log10 Ω_c for 1 ≤ Ω_c  (Gamper §3.4, J_p).
double unified_gamma(double inverse_wave_age) {
  return inverse_wave_age < 1.0 ? 1.7 : 1.7 + 6.0 * math::log10(inverse_wave_age);
}

// σ = 0.08 (1 + 4/Ω_c³)  (Gamper §3.4, J_p).
double unified_sigma(double inverse_wave_age) {
  return 0.08 * (1.0 + 4.0 / (inverse_wave_age * inverse_wave_age * inverse_wave_age));
}

// α_p = 0.006 √Ω_c  (Gamper §3.4, B_l).
double unified_long_wave_alpha(double inverse_wave_age) {
  return 0.006 * std::sqrt(inverse_wave_age);
}

// L_PM = exp[−5/4 (k_p/k)²]  (Gamper §3.4, Unified).
double pierson_moskowitz_shape(double k, double k_p) {
  if (!(k > 0.0)) return 0.0;
  const double r = k_p / k;
  const double e = -1.25 * r * r;
  return e < -745.0 ? 0.0 : math::exp(e);
}

// J_p = γ^Γ, Γ = exp[−(√(k/k_p) − 1)² / (2σ²)]  (Gamper §3.4, Unified).
double unified_peak_enhancement(double k, double k_p, double gamma, double sigma) {
  const double x = (std::sqrt(k / k_p) - 1.0) / sigma;
  const double e = -0.5 * x * x;
  const double big_gamma = (std::isinf(x) || e < -745.0) ? 0.0 : math::exp(e);
  return math::pow(gamma, big_gamma);
}

// F_p = L_PM J_p exp[−Ω_c/√10 (√(k/k_p) − 1)]  (Gamper §3.4, B_l).
double unified_long_wave_side_effect(double k, double k_p, double inverse_wave_age,
                                     double shape_times_enhancement) {
  if (shape_times_enhancement == 0.0) return 0.0;
  const double e = -inverse_wave_age / std::sqrt(10.0) * (std::sqrt(k / k_p) - 1.0);
  return shape_times_enhancement * (e < -745.0 ? 0.0 : math::exp(e));
}

// F_m = L_PM J_p exp[−¼ (k/k_m − 1)²]  (Gamper §3.4, B_h).
double unified_short_wave_side_effect(double k, double k_m, double shape_times_enhancement) {
  if (shape_times_enhancement == 0.0) return 0.0;
  const double x = k / k_m - 1.0;
  const double e = -0.25 * x * x;
  return shape_times_enhancement * (e < -745.0 ? 0.0 : math::exp(e));
}

// z0 = 3.7·10⁻⁵ (U10²/g) (U10/c_p)^0.9  (Gamper §3.4, after Donelan et al. 1993).
double roughness_length(double wind_speed, double peak_phase_speed, double g) {
  return 3.7e-5 * wind_speed * wind_speed / g * math::pow(wind_speed / peak_phase_speed, 0.9);
}

// u* = κ U10 / ln(10/z0)  (Gamper §3.4, law of the wall, κ = 0.41).
double friction_velocity(double wind_speed, double roughness) {
  return kVonKarman * wind_speed / math::log(10.0 / roughness);
}

// α_m = 10⁻²[1 + ln(u*/c_m)] for u* < c_m, 10⁻²[1 + 3 ln(u*/c_m)] otherwise (Gamper §3.4).
double unified_short_wave_alpha(double friction_velocity, double c_m) {
  const double l = math::log(friction_velocity / c_m);
  return 1e-2 * (friction_velocity < c_m ? 1.0 + l : 1.0 + 3.0 * l);
}

// c_m = 0.23 √(370/k_m) m/s: Gamper §3.4's c_m = 0.23 m/s is the minimum phase speed, at k = k_m,
// of ω² = gk(1 + (k/k_m)²), c_min = √(2g/k_m) ∝ k_m^−½; exactly 0.23 at k_m = 370 (FORMULAS).
double unified_min_phase_speed(double capillary_wavenumber) {
  return kUnifiedMinPhaseSpeed * std::sqrt(kUnifiedCapillaryWavenumber / capillary_wavenumber);
}

// B = ½ α (c_ref/c) F: B_l with (α_p, c_p, F_p), B_h with (α_m, c_m, F_m) (Gamper §3.4).
double unified_curvature_term(double alpha, double reference_speed, double phase_speed,
                              double side_effect) {
  if (side_effect == 0.0) return 0.0;
  return 0.5 * alpha * reference_speed / phase_speed * side_effect;
}

// Δ(k) = tanh[a0 + a_p (c/c_p)^2.5 + a_m (c_m/c)^2.5], a0 = ln2/4, a_p = 4,
// a_m = 0.13 u*/c_m  (Gamper eq. 3.72).
double unified_upwind_ratio(double phase_speed, double peak_phase_speed, double c_m,
                            double friction_velocity) {
  constexpr double a0 = 0.6931471805599453 / 4.0;
  constexpr double ap = 4.0;
  const double am = 0.13 * friction_velocity / c_m;
  return math::tanh(a0 + ap * math::pow(phase_speed / peak_phase_speed, 2.5) +
                    am * math::pow(c_m / phase_speed, 2.5));
}

// Ψ(k) = k⁻³ (B_l + B_h)  (Gamper eq. 3.71), c = ω/k from the gravity-capillary relation.
double unified(double k, double phase_speed, const UnifiedParameters& p) {
  if (!(k > 0.0) || std::isinf(k)) return 0.0;
  const double shape = pierson_moskowitz_shape(k, p.peak_wavenumber);
  if (shape == 0.0) return 0.0;
  const double lj = shape * unified_peak_enhancement(k, p.peak_wavenumber, p.gamma, p.sigma);
  const double b_l = unified_curvature_term(
      p.long_wave_alpha, p.peak_phase_speed, phase_speed,
      unified_long_wave_side_effect(k, p.peak_wavenumber, p.inverse_wave_age, lj));
  const double b_h =
      unified_curvature_term(p.short_wave_alpha, p.min_phase_speed, phase_speed,
                             unified_short_wave_side_effect(k, p.capillary_wavenumber, lj));
  return (b_l + b_h) / (k * k * k);
}

// L = U²/g, the largest wave from a continuous wind of speed U (Tessendorf; Gamper §3.4).
double phillips_largest_wave(double wind_speed, double g) {
  return wind_speed * wind_speed / g;
}

// Ψ(k) = k · A exp[−(kL)⁻² − (kl)²] / k⁴: the radial factor of Gamper eq. 3.73/3.74 times the
// polar Jacobian k, so that Θ(k) = Ψ(k) D(θ) / k reproduces eq. 3.73 exactly.
double phillips(double k, double amplitude, double largest_wave, double smallest_wave) {
  if (!(k > 0.0) || std::isinf(k)) return 0.0;
  const double kl_big = k * largest_wave;
  const double kl_small = k * smallest_wave;
  const double e = -1.0 / (kl_big * kl_big) - kl_small * kl_small;
  if (e < -745.0) return 0.0;
  return amplitude * math::exp(e) / (k * k * k);
}

// k_p = √(2/3)/L: maximum of k⁻³ exp[−(kL)⁻²] (derivative of eq. 3.74 × k, with l = 0).
double phillips_peak_wavenumber(double largest_wave) {
  return 0.816496580927726 / largest_wave;
}

}  // namespace oceanref
