// Mastin, Watterberg and Mareda 1987, "Fourier Synthesis of Ocean Scenes": an alternative
// realization of h0. A seeded white-noise image is Fourier transformed and its magnitude filtered
// (the phase kept); the waves are animated by shifting each component's phase (Mastin,
// "Ocean scene animation").
//
// Made exact and reproducible here:
//   * noise: w(m, n) uniform in (−√3, √3) (unit variance), from word 0 of the key
//     component_key(seed, cascade | 2³¹, m, n) (the cascade's high bit keeps it apart from the
//     Gaussian draws), mapped as uniform_open;
//   * filter: W(k)·√(½(Θ_f(k) + Θ_f(−k))Δk²)/N, where Θ_f is the filter's power (below) — the
//     centrosymmetric mean, because the transform of a real image is Hermitian and a real filter
//     must be even to keep it so (a real, non-negative factor keeps the phase, as Mastin's
//     magnitude filtering does); E|H(k)|² = ½(Θ_f(k) + Θ_f(−k))Δk², so the height variance is
//     ΣΘ_f(k)Δk² as for eq. 4.2;
//   * the three filters: the scene's spectrum Θ (Mastin eq. 3–6 with the mastin spreading; any
//     model here), and Voss's power-law ("1/f") filter with and without Mastin's Gaussian
//     attenuation of the low frequencies (their Figs. 2–3), whose constants the paper leaves
//     open and which are fixed below;
//   * animation: each conjugate pair (k, −k) is one wave travelling along the member with the
//     larger Θ_f (downwind; ties by array order): h0(k) = 2H(k) on that member, 0 on the other,
//     so that eq. 4.7 gives h(k, t) = H(k)e^{−iω't} and h(−k, t) = H(k)* e^{iω't}; the phase
//     rate ω' is the dispersion relation's ω(k) (Mastin eq. 10, "the deep water model", here
//     with the scene's dispersion) or, for the ad hoc technique of *Hot Air*, one constant rate
//     for the dominant components and another for the rest.
// Unlike eq. 4.2 the noise image depends on N, so resolutions are not subsets of each other.
#pragma once

#include <array>

#include "core/choice.h"
#include "waves/realization.h"

namespace oceanref {

// The filter applied to the noise's magnitude.
enum class MastinFilter { spectrum, power_law, attenuated_power_law };
inline constexpr std::array<Choice<MastinFilter>, 3> kMastinFilters{{
    {MastinFilter::spectrum, "spectrum"},
    {MastinFilter::power_law, "power_law"},
    {MastinFilter::attenuated_power_law, "attenuated_power_law"},
}};

// How time moves the phase.
enum class MastinAnimation { dispersion, constant_shift };
inline constexpr std::array<Choice<MastinAnimation>, 2> kMastinAnimations{{
    {MastinAnimation::dispersion, "dispersion"},
    {MastinAnimation::constant_shift, "constant_shift"},
}};

struct MastinSettings {
  MastinFilter filter = MastinFilter::spectrum;
  // D of the power-law filters: 2.1 in Mastin's Figs. 1–3. In (2, 3).
  double fractal_dimension = 2.1;
  MastinAnimation animation = MastinAnimation::dispersion;
  // The ad hoc rates [rad/s]: Hot Air's 0.05 and 0.003 rad per frame at 30 frames/s.
  double dominant_phase_rate = 1.5;
  double background_phase_rate = 0.09;
};

// The filter resolved for a spectrum: what Θ_f needs besides the spectrum itself.
struct MastinFilterModel {
  MastinFilter filter = MastinFilter::spectrum;
  double hurst = 0.9;            // H = 3 − D
  double peak_wavenumber = 0.0;  // k_p of the scene's spectrum [rad/m]
  double variance = 0.0;         // m0 of the scene's spectrum [m²] (power-law normalisation)
};

// Resolves k_p and m0 (by adaptive quadrature over k ∈ (0, ∞), spectrum/moments.h) for the
// power-law filters; throws std::runtime_error if m0 does not converge.
MastinFilterModel make_mastin_filter(const Spectrum& spectrum, const MastinSettings& settings);

// H = 3 − D: the Hurst exponent of a fractional-Brownian surface of fractal dimension D
// (Saupe 1988, "Algorithms for random fractals", ch. 2 of Peitgen & Saupe, "The Science of Fractal
// Images": spectral synthesis of fBm surfaces, amplitude ∝ |k|^{−(H+1)}).
double hurst_exponent(double fractal_dimension);

// The spectral-synthesis power law, Θ_1/f(k) = C·k^{−(2H+2)} [m⁴] (amplitude filter
// k^{−(H+1)}, the "1/f filter" of Mastin Fig. 2), with C = m0·H·k_p^{2H}/π so that its variance
// over k ≥ k_p, ∫_{k_p}^∞ Θ 2πk dk, equals the scene spectrum's m0: the two filters compared at
// equal energy (Mastin normalises his filters to unit gain; ours keep physical units).
double power_law_filter_power(double k, double peak_wavenumber, double variance, double hurst);

// Mastin Fig. 3: the low frequencies attenuated by a Gaussian "forced to fit at the peak
// frequency": below k_p the filter is the Gaussian amplitude response Θ_1/f(k_p)^½·e^{−u²/2},
// u = (k − k_p)/σ, which meets the power law at k_p (so the filter peaks there, at the
// roughness's "fineness"); from k_p up it is the power law. The paper gives no width; ours is
// σ = k_p/3 (amplitude 1.1% of the peak's at k = 0). This is the Gaussian's power factor e^{−u²}.
double low_frequency_attenuation(double k, double peak_wavenumber);

// Θ_f(k) of the filter at wavevector (kx, kz) [m⁴]: the spectrum's Θ, or the (attenuated)
// power law, isotropic.
double mastin_filter_power(const Spectrum& spectrum, const MastinFilterModel& filter, double kx,
                           double kz);

// Whether a wave of angular frequency ω is one of Mastin's dominant components: "bounded by
// two-thirds of the energy of the peak frequency", read as S(ω) ≥ ⅔·S(ω_p) for the scene's
// frequency spectrum.
bool is_dominant_component(const Spectrum& spectrum, double omega);

// The phase rate ω' [rad/s] of a component of angular frequency ω (see above).
double mastin_phase_rate(const Spectrum& spectrum, const MastinSettings& settings, double omega);

// The white-noise image of a pattern, w(m, n) ∈ (−√3, √3), row-major.
std::vector<double> mastin_white_noise(std::uint64_t seed, const Pattern& p);

// h0 of a pattern by Mastin's filtering (see above), 1/|k| as realize_pattern, and ω replaced by
// the phase rate of settings.animation.
PatternSpectrum realize_pattern_mastin(const Spectrum& spectrum, const MastinSettings& settings,
                                       const MastinFilterModel& filter, std::uint64_t seed,
                                       const Pattern& p, int threads);

}  // namespace oceanref
