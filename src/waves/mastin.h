// Mastin, Watterberg and Mareda 1987, "Fourier Synthesis of Ocean Scenes": an alternative
// realization of h0. A seeded white-noise image is Fourier transformed and filtered by the
// square root of the directional spectrum; the waves are animated by shifting each component's
// phase by ω(k)t (Mastin eq. 9–10, the "deep water model", here with the chosen dispersion).
//
// Made exact and reproducible here:
//   * noise: w(m, n) uniform in (−√3, √3) (unit variance), from word 0 of the key
//     component_key(seed, cascade | 2³¹, m, n) (the cascade's high bit keeps it apart from the
//     Gaussian draws), mapped as uniform_open;
//   * filter: W(k)·√(½(Θ(k) + Θ(−k))Δk²)/N — the centrosymmetric mean of Θ, because the
//     transform of a real image is Hermitian and a real filter must be even to keep it so;
//     E|H(k)|² = ½(Θ(k) + Θ(−k))Δk², so the height variance is ΣΘ(k)Δk² as for eq. 4.2;
//   * animation: each conjugate pair (k, −k) is one wave travelling along the member with the
//     larger Θ (downwind; ties by array order): h0(k) = 2H(k) on that member, 0 on the other,
//     so that eq. 4.7 gives h(k, t) = H(k)e^{−iωt} and h(−k, t) = H(k)* e^{iωt}.
// Unlike eq. 4.2 the noise image depends on N, so resolutions are not subsets of each other.
#pragma once

#include "waves/realization.h"

namespace oceanref {

// The white-noise image of a pattern, w(m, n) ∈ (−√3, √3), row-major.
std::vector<double> mastin_white_noise(std::uint64_t seed, const Pattern& p);

// h0 of a pattern by Mastin's filtering (see above), with ω and 1/|k| as realize_pattern.
PatternSpectrum realize_pattern_mastin(const Spectrum& spectrum, std::uint64_t seed,
                                       const Pattern& p, int threads);

}  // namespace oceanref
