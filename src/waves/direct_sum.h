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

// The raw fields (the order of kFieldNames) of one cascade at (x, z) [m] and time t [s].
std::array<double, kFieldCount> direct_sum(const PatternSpectrum& low, const PatternSpectrum& high,
                                           double x, double z, double time);

}  // namespace oceanref
