#include "waves/slope_budget.h"

#include <cmath>
#include <numbers>

#include "core/check.h"
#include "core/fp_environment.h"
#include "core/math.h"
#include "core/parallel.h"
#include "waves/ocean.h"

namespace oceanref {

SlopeVariance resolved_slope_variance(const PatternSpectrum& s, const std::vector<Complex>& h,
                                      double wind_direction, Interpolation mode,
                                      SlopeReading reading) {
  const int n = s.pattern.resolution;
  OCEANREF_EXPECTS(h.size() == grid_cells(n),
                   "h(k, t) holds N x N entries for N = " + std::to_string(n) + ", got " +
                       std::to_string(h.size()));
  const double spacing = s.pattern.size / n;  // Δ
  const double dk = wavenumber_spacing(s.pattern.size);
  // Per-axis factors of every wave index (the same along x and z), in physical units.
  std::vector<AxisTransfer> axis(static_cast<std::size_t>(n));
  for (int a = 0; a < n; ++a) {
    AxisTransfer t = axis_transfer(wave_index(a, n), n, mode);
    t.derivative /= spacing * spacing;
    t.cross /= spacing;
    axis[static_cast<std::size_t>(a)] = t;
  }
  const math::SinCos wind = math::sincos(wind_direction);
  double upwind = 0.0;
  double crosswind = 0.0;
  for (int b = 0; b < n; ++b) {
    const AxisTransfer& tz = axis[static_cast<std::size_t>(b)];
    for (int a = 0; a < n; ++a) {
      const Complex c = h[grid_offset(a, b, n)];
      const double power = c.re * c.re + c.im * c.im;  // |h(k, t)|²
      if (power == 0.0) continue;
      const AxisTransfer& tx = axis[static_cast<std::size_t>(a)];
      double m_xx, m_zz, m_xz;
      if (reading == SlopeReading::derivative_of_height) {
        m_xx = tx.derivative * tz.value;
        m_zz = tx.value * tz.derivative;
        m_xz = tx.cross * tz.cross;
      } else {
        const double d_x = derivative_factor(wave_index(a, n), dk, n).im;
        const double d_z = derivative_factor(wave_index(b, n), dk, n).im;
        const double v = tx.value * tz.value;
        m_xx = d_x * d_x * v;
        m_zz = d_z * d_z * v;
        m_xz = d_x * d_z * v;
      }
      // ŵᵀMŵ along (cos φ, sin φ) and across, (−sin φ, cos φ).
      upwind += power * (wind.cos * wind.cos * m_xx + 2.0 * wind.cos * wind.sin * m_xz +
                         wind.sin * wind.sin * m_zz);
      crosswind += power * (wind.sin * wind.sin * m_xx - 2.0 * wind.cos * wind.sin * m_xz +
                            wind.cos * wind.cos * m_zz);
    }
  }
  return {upwind, crosswind};
}

double slope_floor_wavenumber(double minimum_wavelength) {
  return minimum_wavelength > 0.0 ? 2.0 * std::numbers::pi / minimum_wavelength
                                  : kDefaultMaxWavenumber * 10.0;
}

namespace {
// σ² is held at kMinimumSlopeVariance per axis (`clamped` then set).
void clamp_unresolved(SlopeVarianceBudget& b) {
  for (double* v : {&b.unresolved.upwind, &b.unresolved.crosswind}) {
    if (*v < kMinimumSlopeVariance) {
      *v = kMinimumSlopeVariance;
      b.clamped = true;
    }
  }
}
}  // namespace

SlopeVarianceBudget slope_variance_budget(const Ocean& ocean, double minimum_wavelength,
                                          double time, Interpolation mode, ShadingNormals normals,
                                          int threads) {
  SlopeVarianceBudget b;
  b.floor_wavenumber = slope_floor_wavenumber(minimum_wavelength);
  const double phi = ocean.spectrum.wind_direction;
  if (ocean.gerstner) {
    // The set draws [k_min, k_max]: what it carries is its own mean square slope, read exactly
    // (direct summation); unresolved is the spectrum above k_max plus the draw's deficit in its
    // band. The waves longer than 2π/k_min are neither drawn nor roughness (not in σ²).
    const GerstnerWaves& g = *ocean.gerstner;
    b.cutoff_wavenumber = std::fmin(g.max_wavenumber, b.floor_wavenumber);
    b.moment = band_slope_variance(ocean.spectrum, 0.0, b.floor_wavenumber);
    b.above_cutoff = band_slope_variance(ocean.spectrum, b.cutoff_wavenumber, b.floor_wavenumber);
    b.discrete = b.resolved = gerstner_slope_variance(g, phi);
    const SlopeVariance band =
        band_slope_variance(ocean.spectrum, g.min_wavenumber, b.cutoff_wavenumber);
    b.sampling = {band.upwind - b.discrete.upwind, band.crosswind - b.discrete.crosswind};
    b.unresolved = {b.above_cutoff.upwind + b.sampling.upwind,
                    b.above_cutoff.crosswind + b.sampling.crosswind};
    clamp_unresolved(b);
    return b;
  }
  const auto pattern_of = [&](const CascadeSpectra& c) -> const PatternSpectrum& {
    return normals == ShadingNormals::surface ? c.low : c.high;
  };
  for (const CascadeSpectra& c : ocean.cascades) {
    const PatternSpectrum& p = pattern_of(c);
    b.cutoff_wavenumber = std::fmax(
        b.cutoff_wavenumber,
        std::fmin(p.pattern.band.upper, nyquist_wavenumber(p.pattern.size, p.pattern.resolution)));
  }
  b.cutoff_wavenumber = std::fmin(b.cutoff_wavenumber, b.floor_wavenumber);
  // Independent tasks, each into its own slot, summed below in cascade order: per cascade the
  // resolved and discrete variances; then the spectrum's moment and the part above the cut-off.
  const std::size_t cascades = ocean.cascades.size();
  std::vector<SlopeVariance> resolved(cascades), discrete(cascades);
  parallel_for(static_cast<int>(cascades) + 2, threads, [&](int task) {
    const auto i = static_cast<std::size_t>(task);
    if (i == cascades) {
      b.moment = band_slope_variance(ocean.spectrum, 0.0, b.floor_wavenumber);
      return;
    }
    if (i == cascades + 1) {
      b.above_cutoff = band_slope_variance(ocean.spectrum, b.cutoff_wavenumber, b.floor_wavenumber);
      return;
    }
    const PatternSpectrum& p = pattern_of(ocean.cascades[i]);
    const std::vector<Complex> h = spectrum_at_time(p, time);
    // Direct summation differentiates the summed height in either mode; the grids are read as
    // the interpolated height (surface) or the interpolated spectral slopes (high resolution).
    const SlopeReading reading = normals == ShadingNormals::surface || mode == Interpolation::direct
                                     ? SlopeReading::derivative_of_height
                                     : SlopeReading::interpolated_slopes;
    resolved[i] = resolved_slope_variance(p, h, phi, mode, reading);
    discrete[i] = resolved_slope_variance(p, h, phi, Interpolation::direct,
                                          SlopeReading::derivative_of_height);
  });
  for (std::size_t i = 0; i < cascades; ++i) {
    b.resolved.upwind += resolved[i].upwind;
    b.resolved.crosswind += resolved[i].crosswind;
    b.discrete.upwind += discrete[i].upwind;
    b.discrete.crosswind += discrete[i].crosswind;
  }
  const auto difference = [](const SlopeVariance& x, const SlopeVariance& y) {
    return SlopeVariance{x.upwind - y.upwind, x.crosswind - y.crosswind};
  };
  b.interpolation_loss = difference(b.discrete, b.resolved);
  b.sampling = difference(difference(b.moment, b.above_cutoff), b.discrete);
  b.unresolved = difference(b.moment, b.resolved);
  clamp_unresolved(b);
  return b;
}

}  // namespace oceanref
