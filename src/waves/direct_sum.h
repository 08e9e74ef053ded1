// The ground truth: every raw field of a cascade at any point and time as the explicit sum over
// all its wave components, η(x, t) = Σ_k h(k, t) e^{ik·x}  (Gamper eq. 4.4), with the spectral
// derivatives taken analytically.
//
// A component on a Nyquist line (α or β = −N/2) is its own conjugate partner: it stands for
// the real standing wave cos(k_x x), whose derivative −k_x sin(k_x x) vanishes at the grid nodes
// — the continuous meaning of the Nyquist rule of Gamper eq. 4.12 and 4.18. Everywhere else
// e^{ik·x}. The sum is then the band-limited field whose samples the FFT grid holds, so the two
// agree at grid nodes to rounding, and the sum is exact between nodes.
#pragma once

#include <array>

#include "waves/fields.h"

namespace oceanref {

// h(k, t) of a cascade's two grids at one time: what the summation sums. A frame evaluates it
// once and then sums at as many points as it needs.
struct EvolvedCascade {
  std::vector<Complex> low;
  std::vector<Complex> high;
  double time = 0.0;  // t [s] (a Gerstner wave set, waves/gerstner.h, is summed at it)
};
EvolvedCascade evolve_cascade(const PatternSpectrum& low, const PatternSpectrum& high, double time);

// The raw fields (the order of kFieldNames) of one cascade at (x, z) [m].
std::array<double, kFieldCount> direct_sum(const PatternSpectrum& low, const PatternSpectrum& high,
                                           const EvolvedCascade& h, double x, double z);
// Every raw field of ONE pattern (η and D as well as the slopes and ∂D, all from its band) and
// ∂D_z/∂x at (x, z): the exact derivatives of the field the sum represents.
CascadeSurface direct_sum_surface(const PatternSpectrum& s, const std::vector<Complex>& h, double x,
                                  double z);

// The exact band-limited fields of one pattern (the sums above) on the lattice of points
// (m, n)·spacing, 0 ≤ m, n < points, row-major [n·points + m]; only the requested fields (and
// ∂D_z/∂x when `ddz_dx`) are filled. Separable: Σ_β e_β(z) Σ_α e_α(x) M h, each output summed
// alone in a fixed order (any thread count gives the same bits).
struct LatticeFields {
  int points = 0;
  double spacing = 0.0;
  std::array<std::vector<double>, kFieldCount> values;
  std::vector<double> ddz_dx;
};
LatticeFields direct_sum_on_lattice(const PatternSpectrum& s, const std::vector<Complex>& h,
                                    int points, double spacing, const std::vector<Field>& fields,
                                    bool ddz_dx, int threads);

// The same at time t [s] for a single point.
std::array<double, kFieldCount> direct_sum(const PatternSpectrum& low, const PatternSpectrum& high,
                                           double x, double z, double time);

}  // namespace oceanref
