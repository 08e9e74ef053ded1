#include "waves/realization.h"

#include <cmath>
#include <numbers>

#include "core/check.h"
#include "core/math.h"
#include "core/memory.h"
#include "core/parallel.h"
#include "waves/fft.h"
#include "waves/random.h"

namespace oceanref {

double wavenumber_spacing(double size) {
  return 2.0 * std::numbers::pi / size;
}

double cell_variance(const Spectrum& spectrum, const Pattern& p, int alpha, int beta) {
  const double dk = wavenumber_spacing(p.size);
  const double kx = alpha * dk;
  const double kz = beta * dk;
  const double k = math::hypot(kx, kz);
  if (!(k > 0.0) || !p.band.contains(k)) return 0.0;
  return wavevector_spectrum(spectrum, kx, kz) * dk * dk;
}

Complex initial_amplitude(const Spectrum& spectrum, std::uint64_t seed, const Pattern& p, int alpha,
                          int beta) {
  // 2·(ΘΔk·Δk) is the 2ΘΔkΔk of before, bit for bit: doubling is exact.
  const double variance = cell_variance(spectrum, p, alpha, beta);
  if (variance == 0.0) return 0.0;
  const NormalPair xi = standard_normal_pair(component_key(seed, p.cascade, alpha, beta));
  const double scale = std::sqrt(2.0 * variance) / std::numbers::sqrt2;
  return {xi.real * scale, xi.imag * scale};
}

PatternSpectrum pattern_grid(const Spectrum& spectrum, const Pattern& p) {
  const int n = p.resolution;
  OCEANREF_EXPECTS(n >= 2 && (n & (n - 1)) == 0,
                   "a pattern's N is a power of two >= 2, got " + std::to_string(n));
  OCEANREF_EXPECTS(p.size > 0.0, "a pattern's size L is positive, got " + std::to_string(p.size));
  const double dk = wavenumber_spacing(p.size);
  PatternSpectrum s{p, allocate_buffer<Complex>(grid_cells(n), "a wave grid's h0"),
                    allocate_buffer<double>(grid_cells(n), "a wave grid's 1/k"),
                    allocate_buffer<double>(grid_cells(n), "a wave grid's omega")};
  for (int b = 0; b < n; ++b) {
    for (int a = 0; a < n; ++a) {
      const std::size_t i = grid_offset(a, b, n);
      const double k = math::hypot(wave_index(a, n) * dk, wave_index(b, n) * dk);
      s.inverse_wavenumber[i] = k > 0.0 ? 1.0 / k : 0.0;
      s.omega[i] = angular_frequency(spectrum.dispersion, k);
    }
  }
  return s;
}

PatternSpectrum realize_pattern(const Spectrum& spectrum, std::uint64_t seed, const Pattern& p) {
  PatternSpectrum s = pattern_grid(spectrum, p);
  const int n = p.resolution;
  for (int b = 0; b < n; ++b) {
    for (int a = 0; a < n; ++a) {
      s.h0[grid_offset(a, b, n)] =
          initial_amplitude(spectrum, seed, p, wave_index(a, n), wave_index(b, n));
    }
  }
  return s;
}

std::vector<Complex> spectrum_at_time(const PatternSpectrum& s, double time, int threads) {
  std::vector<Complex> h;
  evolve_spectrum(s, time, threads, h);
  return h;
}

void evolve_spectrum(const PatternSpectrum& s, double time, int threads, std::vector<Complex>& h) {
  const int n = s.pattern.resolution;
  OCEANREF_EXPECTS(s.h0.size() == grid_cells(n) && s.omega.size() == grid_cells(n),
                   "h0 and omega hold N x N entries for N = " + std::to_string(n));
  h.resize(s.h0.size());
  parallel_for(n, threads, [&](int b) {
    const int bc = conjugate_array_index(b, n);
    for (int a = 0; a < n; ++a) {
      const std::size_t i = grid_offset(a, b, n);
      const std::size_t ic = grid_offset(conjugate_array_index(a, n), bc, n);
      const double phase = s.omega[i] * time;
      const Complex forward = conj(unit_phasor(phase));  // e^{−iωt}
      // ½[h0(k)e^{−iωt} + (h0(−k)e^{−iωt})*]  (core/complex.h: products written out)
      h[i] = 0.5 * (s.h0[i] * forward + conj(s.h0[ic] * forward));
    }
  });
}

}  // namespace oceanref
