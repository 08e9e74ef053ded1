// The variance of the sea surface's slopes along and across the wind: what the spectrum's
// moments give for a band of waves (Gamper A.1 in the wind frame, spectrum/moments.h), what a
// renderer leaves unresolved, and the roughness of the ocean BRDF (Bruneton 2010 eq. 4, whose
// σ_x², σ_y² are taken along the frame's T_x (upwind) and T_y (crosswind), shading/ocean_brdf.h).
#pragma once

namespace oceanref {

struct SlopeVariance {
  double upwind = 0.0;     // σ_x², along the wind
  double crosswind = 0.0;  // σ_y², across it
};
inline SlopeVariance scaled(const SlopeVariance& v, double factor) {
  return {factor * v.upwind, factor * v.crosswind};
}
inline SlopeVariance operator+(const SlopeVariance& a, const SlopeVariance& b) {
  return {a.upwind + b.upwind, a.crosswind + b.crosswind};
}

// The second moments of the displacement gradient ∂D of a band of waves (the residual M′ whose
// Jacobian statistics give the whitecap coverage, waves/whitecaps.h), in the wind frame (a along
// the wind, c across it): a wave of wavevector k (along k_a, across k_c) and power P adds
// P k_a⁴/k² to E[(∂D_a/∂a)²] = aaaa, P k_c⁴/k² to E[(∂D_c/∂c)²] = cccc, P k_a²k_c²/k² to
// E[(∂D_a/∂c)²] = E[(∂D_a/∂a)(∂D_c/∂c)] = aacc, P k_a³k_c/k² to aaac and P k_a k_c³/k² to
// accc [1]. aaaa + aacc and aacc + cccc are the band's slope variances along and across.
struct JacobianMoments {
  double aaaa = 0.0, aaac = 0.0, aacc = 0.0, accc = 0.0, cccc = 0.0;
};
inline JacobianMoments scaled(const JacobianMoments& m, double factor) {
  return {factor * m.aaaa, factor * m.aaac, factor * m.aacc, factor * m.accc, factor * m.cccc};
}
inline JacobianMoments operator+(const JacobianMoments& a, const JacobianMoments& b) {
  return {a.aaaa + b.aaaa, a.aaac + b.aaac, a.aacc + b.aacc, a.accc + b.accc, a.cccc + b.cccc};
}

}  // namespace oceanref
