// Gerstner (trochoidal) waves: a wave model beside the FFT ocean, evaluated as an explicit sum
// (Vincevičius 2024 §1.2.1: one wave moves every surface point on a circle; an ocean is a sum
// of them; its limits are the cost of the sum, tiling and loops). The seed gives no equation;
// this is the standard form (Fournier & Reeves 1986; Tessendorf 2001 "Simulating Ocean Water"
// §3.1) written in the convention of waves/fields.h.
//
// Model. Wave i has amplitude A_i, wavenumber k_i, direction θ_i (wave vector
// k_i = k_i(cos θ_i, sin θ_i) in (x, z)), phase φ_i and angular frequency ω_i; its phase at a
// rest point x0 = (x, z) is ψ_i = k_i·x0 − ω_i t + φ_i. The raw fields (the order of
// kFieldNames) are the sums over i of
//   η = A cos ψ,  ∂η/∂x = −k_x A sin ψ,  ∂η/∂z = −k_z A sin ψ,
//   D = k̂ A sin ψ,  ∂D_x/∂x = (k_x²/k) A cos ψ,  ∂D_z/∂z = (k_z²/k) A cos ψ,
//   ∂D_x/∂z = ∂D_z/∂x = (k_x k_z/k) A cos ψ,
// and the surface point is (x0 + u·D, η) with the choppiness u ≤ 0 (add_cascade scales D and
// ∂D by u). Tessendorf's Gerstner wave x = x0 − k̂ A sin ψ, y = A cos ψ is u = −1; other u are
// the "steepness" variants (0 ≤ −u·k·A ≤ 1).
//
// Equivalence with the FFT ocean: a Gerstner wave with choppiness u IS one component of the
// choppy FFT ocean of that cascade choppiness — the entry h0(k) = A e^{iφ} (h0(−k) = 0) of a
// PatternSpectrum evolves to h(±k, t) = ½A e^{±i(φ − ωt)} (Gamper eq. 4.7), whose fields
// (fields.h: multipliers 1, ik, −ik/k, k_a k_b/k) are exactly the lines above
// (tests/test_gerstner.cpp compares with direct_sum and synthesize_cascade).
//
// Limits.
//   * Cost: O(N) per point and field set (one sincos per wave), where the FFT gives N² waves
//     at O(log N) per point; Vincevičius reports real-time use degrading beyond ~65 waves.
//   * Tiling: none — the sum is evaluated anywhere; it is periodic only if every wave vector is
//     a lattice wave (k_i = 2π(α_i, β_i)/L for one L), then with period L.
//   * Loops: x0 ↦ x0 + u D has J = I + u∇D with ∇D = Σ k_i A_i cos ψ_i k̂_i k̂_iᵀ (symmetric).
//     Its trace norm is ≤ Σ k_i A_i, so every eigenvalue μ of u∇D has |μ| ≤ |u|Σ k_i A_i = b and
//     det J = (1 + μ1)(1 + μ2) ≥ 1 − |μ1| − |μ2| ≥ 1 − b: no loops anywhere at any time when
//     b < 1 (sufficient, tight for one wave, where det J = 1 + u k A cos ψ). Beyond it the
//     surface folds (det J < 0) where 1 + u k A cos ψ < 0 for one wave.
//   * Precision: ψ is formed in double from x, z and t as given (no exact reduction as for
//     lattice waves): absolute phase error ~1e-16·|k·x0 − ωt|.
//
// Determinism: sums in wave index order, elementary functions from core/math.h only; a drawn
// set is a pure function of (spectrum, draw settings, seed) through waves/random.h.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "spectrum/model.h"
#include "spectrum/slope_variance.h"
#include "waves/fields.h"

namespace oceanref {

struct GerstnerWave {
  double amplitude = 0.0;          // A [m]
  double wavenumber = 0.0;         // k [rad/m]
  double direction = 0.0;          // θ [rad]: wave vector k(cos θ, sin θ) in (x, z)
  double phase = 0.0;              // φ [rad]
  double angular_frequency = 0.0;  // ω [rad/s]
};

struct GerstnerWaves {
  std::vector<GerstnerWave> waves;
  double choppiness = 0.0;  // u ≤ 0
  // The band a drawn set samples, [k_min, k_max] [rad/m] (draw_gerstner_waves; 0 otherwise).
  double min_wavenumber = 0.0, max_wavenumber = 0.0;
};

// The most waves a set may have.
inline constexpr int kMaxGerstnerWaves = 1024;
// The cascade index that keys a drawn set's random numbers (no FFT cascade uses it).
inline constexpr std::uint32_t kGerstnerCascade = 0xFFFF'FFFFu;

// How a wave set is drawn from a spectrum: [k_min, k_max] split into count/direction_bins bins
// equal in log k, the directions [φ_wind − π, φ_wind + π) into direction_bins equal bins, one
// wave per (k bin, direction bin) cell.
struct GerstnerDraw {
  int count = 64;                // waves, 1–1024, a multiple of direction_bins
  int direction_bins = 8;        // 1–count
  double choppiness = -1.0;      // u ≤ 0
  double min_wavenumber = 0.1;   // k_min [rad/m], > 0
  double max_wavenumber = 10.0;  // k_max [rad/m], k_min < k_max ≤ 1e6
};

// Throws SettingError (a std::invalid_argument) naming the field and its valid range.
void validate(const GerstnerDraw& draw);
// Throws SettingError unless u ≤ 0 and every wave has finite A ≥ 0, k ≥ 0, θ, φ, ω.
void validate(const GerstnerWaves& waves);

// ψ = k·x0 − ωt + φ  (Tessendorf 2001 §3.1, with the phase φ of Gamper eq. 4.2's h0).
double gerstner_phase(const GerstnerWave& w, double cos_theta, double sin_theta, double x, double z,
                      double time);

// The raw fields (kFieldNames order; D and ∂D not scaled by u) of the sum at (x, z) and time t:
// Σ_i in index order of the per-wave lines in the header comment.
std::array<double, kFieldCount> gerstner_raw_fields(const GerstnerWaves& waves, double x, double z,
                                                    double time);

// The combined fields of the sum at a rest point: add_cascade with the set's choppiness, then
// finish_surface_combination (exact J, det J, slopes J⁻ᵀ∇η, normal, foam indicator).
PointFields gerstner_point(const GerstnerWaves& waves, double x, double z, double time);

// A wave set from the spectrum (stratified sampling, one wave per cell):
//   cell (i, j) = [k_i, k_{i+1}] × [θ_j, θ_{j+1}], k_i = k_min (k_max/k_min)^{i/n_k},
//   θ_j = φ_wind − π + 2πj/n_θ;
//   variance V_ij = ∫∫cell Θ k dk dθ = ∫ Ψ(k) ∫ D(k, θ) dθ dk by nested adaptive Gauss–Kronrod
//   (core/quadrature.h; relative 1e-10, absolute 1e-12·m_band/count with m_band = ∫Ψ dk over
//   [k_min, k_max]; std::runtime_error if a cell does not converge);
//   A = √(2V) (½A² = V: the cell's variance, Gamper eq. 4.2 in the mean),
//   k = k_i (k_{i+1}/k_i)^{ξ0}, θ = θ_j + ξ1 Δθ, φ = 2π ξ2, ω = ω(k) of the spectrum's
//   dispersion relation, with ξn = uniform_open(random_word(component_key(seed,
//   kGerstnerCascade, i, j), n)). Waves in order i·n_θ + j; a cell without variance keeps a
//   wave of amplitude 0. So ½ΣA² is the spectrum's variance over k_min ≤ |k| ≤ k_max (with a
//   normalized spreading: ∫Ψ dk), the same for every seed.
GerstnerWaves draw_gerstner_waves(const Spectrum& spectrum, const GerstnerDraw& draw,
                                  std::uint64_t seed);

// The mean square slope of the sum over positions along and across the wind direction φ:
// Σ ½A_i²k_i² cos²(θ_i − φ) and Σ ½A_i²k_i² sin²(θ_i − φ) (Gamper A.1 on the set; the waves'
// cross terms average out when no two share a wave vector).
SlopeVariance gerstner_slope_variance(const GerstnerWaves& waves, double wind_direction);
// b = |u| Σ k_i A_i: det J ≥ 1 − b everywhere at all times, so b < 1 means no loops.
double gerstner_steepness_bound(const GerstnerWaves& waves);

// det J sampled on the lattice (x_min + m·h, z_min + n·h), h = extent/points, 0 ≤ m, n < points
// (the far edges excluded, so a square of whole periods is sampled evenly).
struct GerstnerLoops {
  double min_jacobian = 0.0;     // the smallest det J on the lattice
  double folded_fraction = 0.0;  // the share of lattice points with det J < 0
  double min_x = 0.0;            // the rest point of the smallest det J (the first in row-major
  double min_z = 0.0;            // order, rows along x, when tied)
};
// Throws std::invalid_argument unless points is 1–4096, extent > 0 and the numbers are finite.
GerstnerLoops gerstner_loops(const GerstnerWaves& waves, double time, double x_min, double z_min,
                             double extent, int points);

}  // namespace oceanref
