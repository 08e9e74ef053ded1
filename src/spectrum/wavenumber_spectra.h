// Omnidirectional wavenumber spectra Ψ(k) [m³] (∫Ψ dk = m0) native to the wavenumber domain:
// Elfouhaily et al. 1997 "Unified" and Tessendorf's Phillips, with their parameter laws.
// k in rad/m, speeds in m/s, U10 in m/s, g in m/s².
#pragma once

namespace oceanref {

// --- Unified / Elfouhaily 1997 (Gamper §3.4, eq. 3.69–3.72) ------------------------------
inline constexpr double kUnifiedMinInverseWaveAge = 0.84;  // Ω_c range (Gamper §3.4)
inline constexpr double kUnifiedMaxInverseWaveAge = 5.0;
inline constexpr double kUnifiedMinPhaseSpeed = 0.23;         // c_m [m/s] at k_m = 370 rad/m
inline constexpr double kUnifiedCapillaryWavenumber = 370.0;  // k_m [rad/m] of c_m
inline constexpr double kVonKarman = 0.41;                    // κ

double unified_inverse_wave_age(double chi);
double unified_peak_wavenumber(double inverse_wave_age, double wind_speed, double g);
double unified_gamma(double inverse_wave_age);
double unified_sigma(double inverse_wave_age);
double unified_long_wave_alpha(double inverse_wave_age);
double pierson_moskowitz_shape(double k, double k_p);
double unified_peak_enhancement(double k, double k_p, double gamma, double sigma);
double unified_long_wave_side_effect(double k, double k_p, double inverse_wave_age,
                                     double shape_times_enhancement);
double unified_short_wave_side_effect(double k, double k_m, double shape_times_enhancement);
double roughness_length(double wind_speed, double peak_phase_speed, double g);
double friction_velocity(double wind_speed, double roughness);
double unified_short_wave_alpha(double friction_velocity, double c_m);
double unified_min_phase_speed(double capillary_wavenumber);
double unified_curvature_term(double alpha, double reference_speed, double phase_speed,
                              double side_effect);
double unified_upwind_ratio(double phase_speed, double peak_phase_speed, double c_m,
                            double friction_velocity);

// Everything Ψ(k) needs besides k and c(k), resolved once from U10 and fetch.
struct UnifiedParameters {
  double inverse_wave_age;                         // Ω_c
  double peak_wavenumber;                          // k_p [rad/m]
  double peak_phase_speed;                         // c_p = U10/Ω_c [m/s]
  double gamma;                                    // γ
  double sigma;                                    // σ
  double long_wave_alpha;                          // α_p
  double short_wave_alpha;                         // α_m (may be clamped to ≥ 0, see model.cpp)
  double friction_velocity;                        // u* [m/s]
  double capillary_wavenumber;                     // k_m [rad/m]
  double min_phase_speed = kUnifiedMinPhaseSpeed;  // c_m [m/s] at k_m: unified_min_phase_speed
};
double unified(double k, double phase_speed, const UnifiedParameters& p);

// --- Phillips (Tessendorf; Gamper eq. 3.73–3.74) ------------------------------------------
double phillips_largest_wave(double wind_speed, double g);
double phillips(double k, double amplitude, double largest_wave, double smallest_wave);
double phillips_peak_wavenumber(double largest_wave);

}  // namespace oceanref
