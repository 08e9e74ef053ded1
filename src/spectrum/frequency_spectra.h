// One-dimensional frequency spectra S(ω) [m²·s] and their parameter laws.
// ω in rad/s, U in m/s, fetch F in m, depth h in m, g in m/s². Every function is one equation
// of a seed (cited beside its definition); all are finite for ω ∈ [0, ∞] (0 at ω = 0).
#pragma once

namespace oceanref {

// --- Pierson–Moskowitz (Gamper §3.4) -----------------------------------------------------
inline constexpr double kPiersonMoskowitzAlpha = 8.1e-3;  // α (Gamper eq. 3.36)
inline constexpr double kPiersonMoskowitzBeta = 0.74;     // β (eq. 3.36; printed "74×10⁻¹")
inline constexpr double kU19_5PerU10 = 1.026;  // U19.5 ≈ 1.026·U10 (eq. 3.39, inverted in print)

double pierson_moskowitz_u19_5(double omega, double u19_5, double g);
double pierson_moskowitz_peak_frequency_u19_5(double u19_5, double g);
double pierson_moskowitz_peak_frequency_u10(double u10, double g);
double pierson_moskowitz(double omega, double alpha, double omega_p, double g);

// --- Fetch-limited growth and JONSWAP (Gamper §3.4) --------------------------------------
double dimensionless_fetch(double fetch, double wind_speed, double g);
double jonswap_dimensionless_peak_frequency(double chi);
double peak_frequency_from_dimensionless(double nu, double wind_speed, double g);
double jonswap_alpha(double chi);
double jonswap_peak_width(double omega, double omega_p, double sigma_low, double sigma_high);
double peak_enhancement_exponent(double omega, double omega_p, double sigma);
double jonswap(double omega, double alpha, double omega_p, double gamma, double sigma_low,
               double sigma_high, double g);

// --- TMA depth attenuation (Vincevičius §1.2.7) ------------------------------------------
double depth_frequency(double omega, double depth, double g);
double kitaigorodskii_depth_attenuation(double omega, double depth, double g);
double thompson_vincent_depth_attenuation(double omega, double depth, double g);

// --- Donelan 1985 (Gamper §3.4) ----------------------------------------------------------
inline constexpr double kDonelanMinInverseWaveAge = 0.83;  // Ω_c range (Gamper eq. 3.67)
inline constexpr double kDonelanMaxInverseWaveAge = 5.0;
double donelan_inverse_wave_age(double chi);
double donelan_peak_frequency(double inverse_wave_age, double wind_speed, double g);
double donelan_gamma(double inverse_wave_age);
double donelan_sigma(double inverse_wave_age);
double donelan_alpha(double inverse_wave_age);
double donelan(double omega, double alpha, double omega_p, double gamma, double sigma, double g);

}  // namespace oceanref
