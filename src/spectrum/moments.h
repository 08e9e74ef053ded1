// Spectral moments of the continuous spectrum by adaptive quadrature (Gamper appendix A.1):
//   m0 = ∫Ψ dk [m²], Hs = 4√m0 [m],
//   mss_x = ∬ k_x² Θ dk, mss_z = ∬ k_z² Θ dk, mss = mss_x + mss_z = ∫ k² Ψ dk  (eq. A.1–A.2).
#pragma once

#include "core/quadrature.h"
#include "spectrum/model.h"
#include "spectrum/slope_variance.h"

namespace oceanref {

// λ_min = 1.73 cm floor for spectra without capillary physics (Gamper §4.4): k = 2π/λ_min.
inline constexpr double kDefaultMaxWavenumber = 2.0 * 3.141592653589793 / 0.0173;
// The largest finite k_max spectral_moments accepts [rad/m] (a wavelength of 6.3 µm, far beyond
// every model's capillary range; beyond ~1e150 the integrands' powers of k overflowed and the
// result fell back silently); k_max = inf is accepted too (integrated on a mapped interval).
inline constexpr double kMaxMomentWavenumber = 1e6;

struct SpectralMoments {
  double m0 = 0.0;
  double significant_wave_height = 0.0;
  double mss_x = 0.0;
  double mss_z = 0.0;
  double mss = 0.0;
  double m0_error = 0.0;  // quadrature error estimates (absolute)
  double mss_x_error = 0.0;
  double mss_z_error = 0.0;
};

// Breakpoints for integrals over k ∈ (0, k_max], increasing: 0, k_p·2^j for j = −6 … 12 (k_p/64
// to 4096 k_p) below k_max, the Unified spectrum's k_m when below k_max, then k_max (or +∞).
std::vector<double> wavenumber_breakpoints(const Spectrum& s, double k_max);

// m0 = ∫Ψ dk over k ∈ (0, k_max] (k_max may be +∞). Throws std::runtime_error if the
// quadrature does not converge.
QuadratureResult zeroth_moment(const Spectrum& s, double k_max,
                               const QuadratureTolerance& tolerance = {});

// Integrates over k ∈ (0, k_max] (k_max may be +∞). Throws std::runtime_error naming the moment
// when a quadrature does not converge (e.g. mss of a k⁻³ tail with k_max = ∞ diverges).
SpectralMoments spectral_moments(const Spectrum& s, double k_max,
                                 const QuadratureTolerance& tolerance = {});

// The slope variances of the waves with k_lo ≤ |k| ≤ k_hi along and across the wind:
// ∫ k² Ψ(k) ∫ cos²(θ − φ) D dθ dk and the same with sin² (Gamper A.1 in the wind frame) — the
// roughness a renderer leaves to the BRDF (Bruneton 2010 §4). k_hi may be +∞ when it converges.
SlopeVariance band_slope_variance(const Spectrum& s, double k_lo, double k_hi,
                                  const QuadratureTolerance& tolerance = {});

// The displacement-gradient moments (spectrum/slope_variance.h) of the waves with
// k_lo ≤ |k| ≤ k_hi: ∫ k² Ψ(k) ∫ c^a s^b D dθ dk with c = cos(θ − φ), s = sin(θ − φ), a + b = 4
// (a wave's P k_a^a k_c^b/k² in the continuous form). Unscaled by choppiness.
JacobianMoments band_jacobian_moments(const Spectrum& s, double k_lo, double k_hi,
                                      const QuadratureTolerance& tolerance = {});

// ∫_{−π}^{π} g(θ) D(k, θ) dθ with θ the absolute direction, split at the wind direction.
QuadratureResult integrate_over_direction(const Spectrum& s, double k,
                                          const std::function<double(double)>& weight,
                                          const QuadratureTolerance& tolerance = {});

}  // namespace oceanref
