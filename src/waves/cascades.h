// Cascades (Gamper §4.4): several periodic patterns of different size L_i, each an N×N grid of
// wavevectors k = (α, β)·Δk_i, Δk_i = 2π/L_i, α, β ∈ [−N/2, N/2). With band partitioning the
// wavevector plane is split into rings so that every wavevector is sampled by one cascade only:
// cascade i takes r_{i−1} ≤ |k| < r_i with r_i = πN/L_i, the largest radius its grid covers
// in every direction (its Nyquist wavenumber). The larger tile (denser sampling) takes
// precedence, and the hand-over is at the smaller range's maximum wavenumber (Fig. 4.10).
// The strict upper bound also excludes every Nyquist line (α or β = −N/2) from the bands.
#pragma once

#include <limits>
#include <vector>

namespace oceanref {

// The two golden-ratio shrink factors of Gamper eq. 4.27: f = φ⁻¹ or f = 1 − φ⁻¹.
enum class GoldenFactor { large, small };
double golden_factor(GoldenFactor f);
// L_i = f^i L for i = 0 … count−1  (Gamper eq. 4.27).
std::vector<double> golden_ratio_sizes(double largest, int count, GoldenFactor f);

// λ_min = 1.73 cm: no wave shorter than this in spectra without capillary physics (Gamper §4.4).
inline constexpr double kMinimumWavelength = 0.0173;

// The wavenumber ring [lower, upper) a cascade samples on a grid of one resolution.
struct Band {
  double lower = 0.0;
  double upper = std::numeric_limits<double>::infinity();
  bool contains(double k) const { return k >= lower && k < upper; }
};

// r = πN/L: the Nyquist wavenumber of an N-point pattern of size L.
double nyquist_wavenumber(double size, int resolution);

// The band of each cascade (sizes strictly decreasing when partitioned). Without partitioning
// every cascade samples its whole grid. Every band is capped at k_max (the λ_min floor, or ∞).
// `edges` (count − 1 increasing wavenumbers, partitioned only) replaces the hand-over at each
// Nyquist wavenumber by chosen ones, as Dupuy & Bruneton 2012's sub-spectra (Lutz eq. 3): cascade
// i takes [e_{i−1}, e_i), the last [e_{count−2}, its Nyquist wavenumber); each e_i must not
// exceed cascade i's Nyquist wavenumber (checked by the scene parser).
std::vector<Band> cascade_bands(const std::vector<double>& sizes, int resolution, bool partitioned,
                                double k_max, const std::vector<double>& edges = {});

}  // namespace oceanref
