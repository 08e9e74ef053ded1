// One random realization of a spectrum on a cascade's wavevector grid (Gamper §4.1–4.2).
//
// Index conventions (tested in tests/test_waves.cpp and tests/test_stages.cpp; docs/BACKENDS.md):
//   * a field sample (m, n), 0 ≤ m, n < N, sits at x = m·L/N, z = n·L/N; arrays are row-major
//     in z: value[n·N + m];
//   * a spectrum entry at array index (a, b) holds the wavevector k = (α, β)·2π/L with
//     α = a for a < N/2 and α = a − N otherwise (likewise β), so α, β ∈ [−N/2, N/2);
//   * the complex-conjugate partner of (a, b) is ((N − a) mod N, (N − b) mod N)  (Gamper eq. 4.9),
//     the wavevector −k, except on a Nyquist line (α or β = −N/2), where −N/2 is its own
//     partner: there the partner stands for the same wave.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/complex.h"
#include "spectrum/model.h"
#include "waves/cascades.h"

namespace oceanref {

// One cascade sampled on one grid resolution.
struct Pattern {
  std::uint32_t cascade = 0;  // the index that keys the random draws
  double size = 0.0;          // L [m]
  int resolution = 0;         // N, a power of two
  Band band;                  // the wavenumbers this pattern samples
};

// Offset of array entry (a, b) (or field sample (m, n)) in a row-major N×N array; N² entries.
inline std::size_t grid_offset(int a, int b, int n) {
  return static_cast<std::size_t>(b) * static_cast<std::size_t>(n) + static_cast<std::size_t>(a);
}
inline std::size_t grid_cells(int n) {
  return grid_offset(0, n, n);
}

// a → α
inline int wave_index(int a, int n) {
  return a < n / 2 ? a : a - n;
}
// α → a
inline int array_index(int alpha, int n) {
  return alpha < 0 ? alpha + n : alpha;
}
// The partner a of the conjugate wave (Gamper eq. 4.9).
inline int conjugate_array_index(int a, int n) {
  return (n - a) % n;
}
// α = −N/2: the Nyquist line.
inline bool is_nyquist(int alpha, int n) {
  return alpha == -n / 2;
}

// Δk = 2π/L [rad/m]
double wavenumber_spacing(double size);

// Θ(k)Δk_xΔk_z, the variance of the wave with integer wavevector (α, β): 0 at k = 0 and outside
// the pattern's band (the entries where no h0 is drawn).
double cell_variance(const Spectrum& spectrum, const Pattern& p, int alpha, int beta);

// h0(k) = (ξ_r + iξ_i)/√2 · √(2Θ(k)Δk_xΔk_z)  (Gamper eq. 4.2), with (ξ_r, ξ_i) keyed by
// (seed, cascade, α, β); 0 outside the pattern's band and at k = 0.
Complex initial_amplitude(const Spectrum& spectrum, std::uint64_t seed, const Pattern& p, int alpha,
                          int beta);

// A pattern's frozen random spectrum h0 and the angular frequency ω(|k|) of every entry.
struct PatternSpectrum {
  Pattern pattern;
  std::vector<Complex> h0;                 // [b·N + a]
  std::vector<double> inverse_wavenumber;  // 1/|k| [m/rad], 0 at k = 0
  std::vector<double> omega;  // ω(|k|) [rad/s] from the spectrum's dispersion relation
};

// The grid of a pattern with h0 = 0 (1/|k| and ω filled in).
PatternSpectrum pattern_grid(const Spectrum& spectrum, const Pattern& p);
// The grid with h0 drawn from the spectrum (eq. 4.2).
PatternSpectrum realize_pattern(const Spectrum& spectrum, std::uint64_t seed, const Pattern& p);

// h(k, t) = ½h0(k)e^{−iωt} + ½h0(−k)* e^{iωt}  (Gamper eq. 4.7): Hermitian, h(−k) = h(k)*.
// Rows are split among `threads`; every entry is computed alone, so the result is the same.
void evolve_spectrum(const PatternSpectrum& s, double time, int threads, std::vector<Complex>& h);
std::vector<Complex> spectrum_at_time(const PatternSpectrum& s, double time, int threads = 1);

}  // namespace oceanref
