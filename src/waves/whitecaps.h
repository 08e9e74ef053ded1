// The statistics of the Jacobian under a footprint, from which Dupuy & Bruneton 2012 take the
// whitecap coverage W = P(det J < ε) = ½ erfc((μ − ε)/√(2σ²)) (shading/ocean_lighting.h).
//
// The deformation x0 ↦ x0 + uD has J = I + u∂D. Under a footprint (a sample's cell, a pixel) the
// gradient is the read one plus a residual: u∂D = u∂D̄ + M′, A = I + u∂D̄, with M′ zero-mean and
// Gaussian (a sum of many waves), symmetric (∂D_x/∂z = ∂D_z/∂x for every wave), its covariance
// the moments of the waves it holds (JacobianMoments, spectrum/slope_variance.h, scaled by u²).
// For 2×2 matrices det(A + M′) = det A + tr(adj(A) M′) + det M′ exactly, so
//   μ = E[det J] = det A + E[det M′] = det A,  since E[M′_aa M′_cc] = E[M′_ac²] (both Σ P
//   k_a²k_c²/k²), σ² = Var tr(adj(A) M′) + Var det M′       (their covariance is an odd moment: 0),
// with, in the wind frame (a along, c across; α = A_cc, β = A_aa, γ = A_ac + A_ca):
//   Var tr(adj(A) M′) = α² aaaa + β² cccc + γ² aacc + 2αβ aacc − 2αγ aaac − 2βγ accc,
//   Var det M′        = aaaa cccc + 3 aacc² − 4 aaac accc       (Isserlis' theorem).
// Dupuy & Bruneton filter J and J² per cascade and add the cascades' variances (§3.3); here the
// mean is the read fields' det J and the variance comes from the waves the read fields lack:
// the spectrum beyond the cascades (unresolved_jacobian_moments, always) and, with footprint
// filtering, what the filter removed under the footprint (waves/footprint_filter.h).
#pragma once

#include "spectrum/slope_variance.h"

namespace oceanref {

struct Ocean;
struct SlopeVarianceBudget;

// A = I + u∂D̄ in world axes: A_xz = ∂(x0 + uD)_x/∂z0, A_zx = ∂(x0 + uD)_z/∂x0.
struct Deformation {
  double xx = 1.0, xz = 0.0, zx = 0.0, zz = 1.0;
};

// One wave's moments, of wavevector (k_a, k_c) in the wind frame and weight P (u²|h|²):
// P k_a^a k_c^b/k² for a + b = 4.
JacobianMoments jacobian_moments_of_mode(double k_along, double k_across, double weight);

// σ² = Var det(A + M′) for M′ with the (choppiness-scaled) moments m in the wind frame of
// direction φ (cos φ, sin φ given), by the formula in the header comment.
double jacobian_variance(const Deformation& a, const JacobianMoments& m, double wind_cos,
                         double wind_sin);

// The moments of the waves the renderer does not draw, as the BRDF's σ² counts them: the shape
// of the spectrum above the shaded cut-off (band_jacobian_moments from the budget's cut-off to
// its floor; isotropic — aaaa = cccc = 3aacc — when that band is empty) scaled so that
// aaaa + 2aacc + cccc is the budget's unresolved σ²_upwind + σ²_crosswind, times u² of the
// finest cascade (the unresolved waves are as choppy as the shortest drawn ones).
JacobianMoments unresolved_jacobian_moments(const Ocean& ocean, const SlopeVarianceBudget& budget);

}  // namespace oceanref
