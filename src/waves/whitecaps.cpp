#include "waves/whitecaps.h"

#include "spectrum/moments.h"
#include "waves/ocean.h"
#include "waves/slope_budget.h"

namespace oceanref {

JacobianMoments jacobian_moments_of_mode(double k_along, double k_across, double weight) {
  const double a = k_along, c = k_across;
  const double w = weight / (a * a + c * c);
  return {w * a * a * a * a, w * a * a * a * c, w * a * a * c * c, w * a * c * c * c,
          w * c * c * c * c};
}

// Var det(A + M′) (Dupuy & Bruneton 2012 §3.3's σ², derived in the header comment).
double jacobian_variance(const Deformation& a, const JacobianMoments& m, double wind_cos,
                         double wind_sin) {
  // A in the wind frame: R A Rᵀ with R = [[c, s], [−s, c]] (world (x, z) → (along, across)).
  const double c = wind_cos, s = wind_sin;
  const double xa = c * a.xx + s * a.zx, za = c * a.xz + s * a.zz;    // (R A) row a
  const double xc = -s * a.xx + c * a.zx, zc = -s * a.xz + c * a.zz;  // (R A) row c
  const double aa = xa * c + za * s, ac = -xa * s + za * c;
  const double ca = xc * c + zc * s, cc = -xc * s + zc * c;
  const double alpha = cc, beta = aa, gamma = ac + ca;
  const double linear = alpha * alpha * m.aaaa + beta * beta * m.cccc + gamma * gamma * m.aacc +
                        2.0 * alpha * beta * m.aacc - 2.0 * alpha * gamma * m.aaac -
                        2.0 * beta * gamma * m.accc;
  const double quadratic = m.aaaa * m.cccc + 3.0 * m.aacc * m.aacc - 4.0 * m.aaac * m.accc;
  return linear + quadratic;
}

JacobianMoments unresolved_jacobian_moments(const Ocean& ocean, const SlopeVarianceBudget& budget) {
  const double target = budget.unresolved.upwind + budget.unresolved.crosswind;
  const JacobianMoments above =
      band_jacobian_moments(ocean.spectrum, budget.cutoff_wavenumber, budget.floor_wavenumber);
  const double total = above.aaaa + 2.0 * above.aacc + above.cccc;
  // An isotropic band: E[cos⁴] = E[sin⁴] = 3/8, E[cos² sin²] = 1/8 of its slope variance.
  const JacobianMoments shape =
      total > 0.0 ? scaled(above, 1.0 / total) : JacobianMoments{0.375, 0.0, 0.125, 0.0, 0.375};
  // The choppiness of the smallest cascade (of the Gerstner set).
  double u = ocean.gerstner ? ocean.gerstner->choppiness : 0.0, finest = 0.0;
  for (const CascadeSpectra& c : ocean.cascades) {
    if (finest == 0.0 || c.high.pattern.size < finest) {
      finest = c.high.pattern.size;
      u = c.choppiness;
    }
  }
  return scaled(shape, target * u * u);
}

}  // namespace oceanref
