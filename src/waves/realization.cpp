#include "waves/realization.h"

#include <cmath>
#include <numbers>

#include "waves/random.h"

namespace oceanref {

int wave_index(int a, int n) {
  return a < n / 2 ? a : a - n;
}
int array_index(int alpha, int n) {
  return alpha < 0 ? alpha + n : alpha;
}
int conjugate_array_index(int a, int n) {
  return (n - a) % n;
}
bool is_nyquist(int alpha, int n) {
  return alpha == -n / 2;
}

double wavenumber_spacing(double size) {
  return 2.0 * std::numbers::pi / size;
}

Complex initial_amplitude(const Spectrum& spectrum, std::uint64_t seed, const Pattern& p, int alpha,
                          int beta) {
  const double dk = wavenumber_spacing(p.size);
  const double kx = alpha * dk;
  const double kz = beta * dk;
  const double k = std::hypot(kx, kz);
  if (!(k > 0.0) || !p.band.contains(k)) return 0.0;
  const double theta = wavevector_spectrum(spectrum, kx, kz);
  if (theta == 0.0) return 0.0;
  const NormalPair xi = standard_normal_pair(component_key(seed, p.cascade, alpha, beta));
  const double scale = std::sqrt(2.0 * theta * dk * dk) / std::numbers::sqrt2;
  return {xi.real * scale, xi.imag * scale};
}

PatternSpectrum realize_pattern(const Spectrum& spectrum, std::uint64_t seed, const Pattern& p) {
  const int n = p.resolution;
  const double dk = wavenumber_spacing(p.size);
  PatternSpectrum s{p, std::vector<Complex>(grid_cells(n)), std::vector<double>(grid_cells(n))};
  for (int b = 0; b < n; ++b) {
    for (int a = 0; a < n; ++a) {
      const int alpha = wave_index(a, n);
      const int beta = wave_index(b, n);
      const std::size_t i = grid_offset(a, b, n);
      s.h0[i] = initial_amplitude(spectrum, seed, p, alpha, beta);
      s.omega[i] = angular_frequency(spectrum.dispersion, std::hypot(alpha * dk, beta * dk));
    }
  }
  return s;
}

std::vector<Complex> spectrum_at_time(const PatternSpectrum& s, double time) {
  const int n = s.pattern.resolution;
  std::vector<Complex> h(s.h0.size());
  for (int b = 0; b < n; ++b) {
    const int bc = conjugate_array_index(b, n);
    for (int a = 0; a < n; ++a) {
      const std::size_t i = grid_offset(a, b, n);
      const std::size_t ic = grid_offset(conjugate_array_index(a, n), bc, n);
      const double phase = s.omega[i] * time;
      const Complex forward(std::cos(phase), -std::sin(phase));  // e^{−iωt}
      h[i] = 0.5 * (s.h0[i] * forward + std::conj(s.h0[ic] * forward));
    }
  }
  return h;
}

}  // namespace oceanref
