// Directional spreading functions D(θ) [1/rad] and their spread parameters. θ is the angle
// between the wave direction and the wind (peak) direction, any real value (wrapped to
// (−π, π] where the formula needs it). Each normalized form satisfies ∫_{−π}^{π} D dθ = 1.
#pragma once

namespace oceanref {

double wrap_angle(double theta);

// --- The cosine-2s family: D = Q(s) |cos(θ/2)|^{2s} ---------------------------------------
// |cos(θ/2)|, exactly 0 at θ = ±fl(π) (the angle atan2 gives a wavevector opposite the wind).
double half_angle_cosine(double theta);
double cos_2s_log_normalization(double s);
double cos_2s_normalization(double s);
double cos_2s_spreading(double theta, double s);
// The same D with ln Q(s) = cos_2s_log_normalization(s) given (computed once for many θ).
double cos_2s_spreading(double theta, double s, double log_normalization);
double mitsuyasu_peak_spread(double omega_p, double wind_speed, double g);
double mitsuyasu_spread(double omega, double omega_p, double peak_spread);
double hasselmann_spread(double omega, double omega_p, double wind_speed, double g);
double mastin_spread(double omega, double omega_p);
double gamper_spread(double omega, double omega_p);
double horvath_swell_spread(double omega, double omega_p, double swell);
double alimardanov_swell_spread(double omega, double omega_p, double swell);
double forward_cos2_spreading(double theta);
double spread_blend(double theta, double cos_2s, double blend);

// --- Phillips |k̂·ŵ|^p ---------------------------------------------------------------------
double cosine_power_spreading(double theta, double power);
double cosine_power_integral(double power);

// --- sech² family ---------------------------------------------------------------------------
double donelan_beta(double omega_ratio);
double donelan_spreading(double theta, double beta);
double donelan_banner_beta(double omega_ratio);
double sech2_spreading(double theta, double beta);

// --- Unified / Elfouhaily ------------------------------------------------------------------
double unified_spreading(double theta, double upwind_ratio);

}  // namespace oceanref
