// Perlin gradient noise (Perlin 2002, "Improving noise": the quintic fade) on the unit lattice,
// with its exact gradient: the aperiodic noise of Lutz, Schoentgen & Gilet 2024's baseline that
// mixes a periodic ocean with low-frequency noise (Lutz eq. 2, after NVIDIA 2011 and Rydahl 2009).
//
// At lattice vertex (i, j) a unit gradient g = (cos φ, sin φ), φ = 2π·uniform_open(word 0 of the
// key mix(mix(mix(key) ^ uint64(i)) ^ uint64(j))) (waves/random.h); at a point of the cell
// (i, j) + (u, v), n = Σ_corners W_x W_z g·d with d the point minus the corner, W = 1 − s or s per
// axis and s(t) = 6t⁵ − 15t⁴ + 10t³. n is C², 0 at the vertices; with the gradients' directions
// uniform, its mean is 0 and its mean square over the plane is
//   E[n²] = ½ Σ_corners ∫∫ W_x² W_z² |d|² = 4AB,  A = ∫(1 − s)²t² dt = 535/18018,
//   B = ∫(1 − s)² dt = 181/462,  so E[n²] = 96835/2081079 ≈ 0.04653.
#pragma once

#include <array>
#include <cstdint>

#include "waves/fields.h"

namespace oceanref {

// E[n²] = 96835/2081079 (derived above; tests/test_noise_blend.cpp samples it).
inline constexpr double kGradientNoiseMeanSquare = 96835.0 / 2081079.0;

// |n| ≤ √2 (Σ W = 1, |g·d| ≤ |d| ≤ √2) and |∇n| ≤ √2·Σ_corners(|W′_x|W_z + W_x|W′_z|) + |Σ W g|
// ≤ √2·(2·15/8 + 2·15/8) + 1 (the fade's slope is at most 15/8): bounds for the ray tracer.
inline constexpr double kGradientNoiseValueBound = 1.4142135623730951;
inline constexpr double kGradientNoiseSlopeBound = 7.5 * 1.4142135623730951 + 1.0;

struct NoiseSample {
  double value = 0.0;
  double d_dx = 0.0, d_dz = 0.0;  // per lattice unit
};
// n and ∇n at (x, z) in lattice units, for the gradients keyed by `key`.
NoiseSample gradient_noise(std::uint64_t key, double x, double z);

// The noise of Lutz eq. 2 for an ocean: D_P = (A_x n_x, A_η n_η, A_z n_z)(x/λ), three independent
// noises (keys mix(mix(mix(seed) ^ 0x6e6f) ^ c), c = 0 for D_x, 1 for η, 2 for D_z), each
// scaled so that its mean square is the exemplar's: A_c = √(m_c/E[n²]) with m_c the time mean of
// the exemplar's spatial mean square, ½Σ_i u_i²Σ_k |g_c h0,i(k)|² (u = 1 for η).
struct NoiseBlend {
  double weight = 0.0;  // w_P
  double cell = 1.0;    // λ [m]: the lattice's spacing
  std::array<double, 3> amplitude{};
  std::array<std::uint64_t, 3> keys{};
};
NoiseBlend make_noise_blend(std::uint64_t seed, double weight, double cell,
                            const std::array<double, 3>& mean_squares);

// The noise's raw fields at (x, z) as a cascade's sum holds them (η, ∇η, D, ∂D; ddz_dx).
PointFields noise_fields(const NoiseBlend& blend, double x, double z);
// Lutz eq. 2 on raw sums: (1 − w_P)·exemplar + w_P·noise, field by field.
void mix_noise(PointFields& exemplar, const PointFields& noise, double weight);

}  // namespace oceanref
