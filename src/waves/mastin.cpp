#include "waves/mastin.h"

#include <cmath>

#include "core/math.h"
#include "waves/fft.h"
#include "waves/random.h"

namespace oceanref {

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

PatternSpectrum realize_pattern_mastin(const Spectrum& spectrum, std::uint64_t seed,
                                       const Pattern& p, int threads) {
  PatternSpectrum s = pattern_grid(spectrum, p);
  const int n = p.resolution;
  const std::vector<double> noise = mastin_white_noise(seed, p);
  std::vector<Complex> w(noise.begin(), noise.end());
  forward_fft_2d(w, n, threads);
  const double dk = wavenumber_spacing(p.size);
  // Θ on the grid, 0 outside the band (the same mask as eq. 4.2).
  std::vector<double> theta(grid_cells(n));
  for (int b = 0; b < n; ++b) {
    for (int a = 0; a < n; ++a) {
      const double kx = wave_index(a, n) * dk;
      const double kz = wave_index(b, n) * dk;
      const double k = math::hypot(kx, kz);
      if (k > 0.0 && p.band.contains(k)) {
        theta[grid_offset(a, b, n)] = wavevector_spectrum(spectrum, kx, kz);
      }
    }
  }
  for (int b = 0; b < n; ++b) {
    for (int a = 0; a < n; ++a) {
      const std::size_t i = grid_offset(a, b, n);
      const std::size_t ic =
          grid_offset(conjugate_array_index(a, n), conjugate_array_index(b, n), n);
      const double even = 0.5 * (theta[i] + theta[ic]);
      if (even == 0.0) continue;
      // The pair's travelling member: larger Θ, or on a tie the lower array offset (a
      // self-partner on a Nyquist corner keeps h0 = H, a standing wave's amplitude).
      const bool travelling = theta[i] > theta[ic] || (theta[i] == theta[ic] && i <= ic);
      if (!travelling) continue;
      const double filter = std::sqrt(even * dk * dk) / n;
      s.h0[i] = (i == ic ? 1.0 : 2.0) * filter * w[i];
    }
  }
  return s;
}

}  // namespace oceanref
