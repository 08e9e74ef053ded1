// Where the spectrum's slope variance goes in a rendered frame (issue 12, point 5).
//
// The spectrum's mean square slope along the wind and across it up to the floor k_f
// (Gamper eq. A.1 in the wind frame, spectrum/moments.h) is split into
//   resolved   — the mean square, over uniformly random positions, of the slope field the
//                renderer shades (∇η of what it draws, before the choppy remapping J⁻ᵀ), computed
//                exactly from the frame's discrete spectrum h(k, t) and the interpolation's
//                variance transfer (interpolation.h; cross terms between grid modes and between
//                cascades vanish in that mean when no wavevector is sampled twice, which band
//                partitioning guarantees);
//   unresolved — everything else, the BRDF's σ² (Bruneton 2010 §4):
//       above_cutoff        the spectrum beyond the largest wavenumber the shaded bands sample,
//       interpolation_loss  what reading the grids between nodes removes from those bands,
//       sampling            the continuous spectrum below the cut-off minus the realization's
//                           discrete sum Σ|h|²(k·ŵ)² (the random draw and the Riemann sum; either
//                           sign).
// So resolved + unresolved = moment per axis, exactly up to rounding and the quadrature
// tolerance, unless the realization carries more slope than the whole spectrum (then σ² is held
// at kMinimumSlopeVariance and `clamped` is set).
//
// Choppy displacement is not in this account: the shaded slope J⁻ᵀ∇η is a nonlinear remapping
// of ∇η whose mean square is not a spectral moment (it diverges where det J → 0), so the
// identity is stated for the linear slope field ∇η that carries the spectrum's variance; with
// u = 0 the two coincide.
#pragma once

#include "spectrum/moments.h"
#include "waves/interpolation.h"
#include "waves/surface.h"

namespace oceanref {

struct Ocean;
struct PatternSpectrum;

// The smallest σ² the budget hands to the BRDF (per axis).
inline constexpr double kMinimumSlopeVariance = 1e-10;

// How the shaded slope field reads a pattern: as the derivative of the interpolated height
// (the surface's own gradient; also what direct summation gives) or as the interpolated
// spectral slope fields (Gamper eq. 4.13–4.14 on the grid, then read between nodes).
enum class SlopeReading { derivative_of_height, interpolated_slopes };

// Mean square over uniformly random positions of one pattern's shaded slope field along the
// wind (cos φ, sin φ) and across it, from its h(k, t) (Gamper eq. A.1 on the discrete spectrum
// as the renderer reads it):
// Σ_k |h|² ŵᵀM(k)ŵ with M_xx = W_xV_z, M_zz = V_xW_z, M_xz = c_xc_z (derivative of the
// height) or M = d dᵀ V_xV_z with d = d(k, 1) of eq. 4.12 (interpolated slopes); V, W, c the
// per-axis factors of interpolation.h in physical units (W/Δ², c/Δ).
SlopeVariance resolved_slope_variance(const PatternSpectrum& s, const std::vector<Complex>& h,
                                      double wind_direction, Interpolation mode,
                                      SlopeReading reading);

struct SlopeVarianceBudget {
  double cutoff_wavenumber = 0.0;  // largest |k| the shaded bands sample [rad/m]
  double floor_wavenumber = 0.0;   // k_f = 2π/λ_min (or 10·2π/1.73 cm without a floor)
  SlopeVariance moment;            // the spectrum, 0 < |k| ≤ k_f (A.1, wind frame)
  SlopeVariance discrete;          // Σ|h|²(k·ŵ)² of the shaded bands, read exactly
  SlopeVariance resolved;          // the shaded slope field as rendered
  SlopeVariance above_cutoff;
  SlopeVariance interpolation_loss;
  SlopeVariance sampling;
  SlopeVariance unresolved;  // the BRDF's σ²
  bool clamped = false;
};

// k_f for a λ_min floor [m] (0: no floor).
double slope_floor_wavenumber(double minimum_wavelength);

// The budget of a frame at time t with the renderer's interpolation and normals: the N_l
// patterns for `surface`, the N_h patterns for `high_resolution`. The cascades and the two
// moment integrals run on up to `threads` threads (the same bits for any count).
SlopeVarianceBudget slope_variance_budget(const Ocean& ocean, double minimum_wavelength,
                                          double time, Interpolation mode, ShadingNormals normals,
                                          int threads = 1);

}  // namespace oceanref
