#include "waves/mastin.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "core/math.h"
#include "spectrum/moments.h"
#include "waves/fft.h"
#include "waves/random.h"

namespace oceanref {

MastinFilterModel make_mastin_filter(const Spectrum& spectrum, const MastinSettings& settings) {
  MastinFilterModel f;
  f.filter = settings.filter;
  f.hurst = hurst_exponent(settings.fractal_dimension);
  f.peak_wavenumber = spectrum.peak_wavenumber;
  if (settings.filter != MastinFilter::spectrum) {
    const QuadratureResult m0 = zeroth_moment(spectrum, std::numeric_limits<double>::infinity());
    if (!m0.converged) {
      throw std::runtime_error("the power-law filter's normalisation: m0 did not converge");
    }
    f.variance = m0.value;
  }
  return f;
}

double hurst_exponent(double fractal_dimension) {
  return 3.0 - fractal_dimension;
}

double power_law_filter_power(double k, double peak_wavenumber, double variance, double hurst) {
  const double c = variance * hurst * math::pow(peak_wavenumber, 2.0 * hurst) / std::numbers::pi;
  return c * math::pow(k, -(2.0 * hurst + 2.0));
}

double low_frequency_attenuation(double k, double peak_wavenumber) {
  const double sigma = peak_wavenumber / 3.0;
  const double u = (k - peak_wavenumber) / sigma;
  return math::exp(-u * u);  // (e^{−u²/2})²
}

double mastin_filter_power(const Spectrum& spectrum, const MastinFilterModel& filter, double kx,
                           double kz) {
  if (filter.filter == MastinFilter::spectrum) return wavevector_spectrum(spectrum, kx, kz);
  const double k = math::hypot(kx, kz);
  const double kp = filter.peak_wavenumber;
  if (filter.filter == MastinFilter::attenuated_power_law && k < kp) {
    return power_law_filter_power(kp, kp, filter.variance, filter.hurst) *
           low_frequency_attenuation(k, kp);
  }
  return power_law_filter_power(k, kp, filter.variance, filter.hurst);
}

bool is_dominant_component(const Spectrum& spectrum, double omega) {
  return frequency_spectrum(spectrum, omega) >=
         2.0 / 3.0 * frequency_spectrum(spectrum, spectrum.peak_frequency);
}

double mastin_phase_rate(const Spectrum& spectrum, const MastinSettings& settings, double omega) {
  if (settings.animation == MastinAnimation::dispersion) return omega;
  return is_dominant_component(spectrum, omega) ? settings.dominant_phase_rate
                                                : settings.background_phase_rate;
}

std::vector<double> mastin_white_noise(std::uint64_t seed, const Pattern& p) {
  const int n = p.resolution;
  const double half_width = std::sqrt(3.0);
  std::vector<double> w(grid_cells(n));
  for (int row = 0; row < n; ++row) {
    for (int m = 0; m < n; ++m) {
      const std::uint64_t key = component_key(seed, p.cascade | 0x80000000U, m, row);
      w[grid_offset(m, row, n)] = half_width * (2.0 * uniform_open(random_word(key, 0)) - 1.0);
    }
  }
  return w;
}

PatternSpectrum realize_pattern_mastin(const Spectrum& spectrum, const MastinSettings& settings,
                                       const MastinFilterModel& filter, std::uint64_t seed,
                                       const Pattern& p, int threads) {
  PatternSpectrum s = pattern_grid(spectrum, p);
  const int n = p.resolution;
  const std::vector<double> noise = mastin_white_noise(seed, p);
  std::vector<Complex> w(noise.begin(), noise.end());
  forward_fft_2d(w, n, threads);
  const double dk = wavenumber_spacing(p.size);
  // Θ_f on the grid, 0 outside the band (the same mask as eq. 4.2).
  std::vector<double> theta(grid_cells(n));
  for (int b = 0; b < n; ++b) {
    for (int a = 0; a < n; ++a) {
      const double kx = wave_index(a, n) * dk;
      const double kz = wave_index(b, n) * dk;
      const double k = math::hypot(kx, kz);
      if (k > 0.0 && p.band.contains(k)) {
        theta[grid_offset(a, b, n)] = mastin_filter_power(spectrum, filter, kx, kz);
      }
    }
  }
  for (int b = 0; b < n; ++b) {
    for (int a = 0; a < n; ++a) {
      const std::size_t i = grid_offset(a, b, n);
      s.omega[i] = mastin_phase_rate(spectrum, settings, s.omega[i]);
      const std::size_t ic =
          grid_offset(conjugate_array_index(a, n), conjugate_array_index(b, n), n);
      const double even = 0.5 * (theta[i] + theta[ic]);
      if (even == 0.0) continue;
      // The pair's travelling member: larger Θ_f, or on a tie the lower array offset (a
      // self-partner on a Nyquist corner keeps h0 = H, a standing wave's amplitude).
      const bool travelling = theta[i] > theta[ic] || (theta[i] == theta[ic] && i <= ic);
      if (!travelling) continue;
      const double amplitude_filter = std::sqrt(even * dk * dk) / n;
      s.h0[i] = (i == ic ? 1.0 : 2.0) * amplitude_filter * w[i];
    }
  }
  return s;
}

}  // namespace oceanref
