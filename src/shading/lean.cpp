#include "shading/lean.h"

#include <cmath>
#include <numbers>

#include "core/math.h"

namespace oceanref {

// Lutz eq. 9–10.
LeanMoments lean_moments(const std::array<double, 3>& n) {
  const double x = n[0] / n[1], z = n[2] / n[1];
  return {{x, z}, {x * x, z * z, x * z}};
}

// Lutz eq. 12.
SlopeCovariance moment_covariance(const std::array<double, 2>& b, const std::array<double, 3>& m) {
  return {m[0] - b[0] * b[0], m[1] - b[1] * b[1], m[2] - b[0] * b[1]};
}

// Lutz eq. 11.
SlopeCovariance lean_covariance(const std::array<double, 2>& b, const std::array<double, 3>& m,
                                double base_variance) {
  SlopeCovariance s = moment_covariance(b, m);
  s.xx += base_variance;
  s.zz += base_variance;
  return s;
}

// Lutz eq. 13.
SlopeCovariance blended_lean_covariance(const std::array<LeanMoments, 3>& tiles,
                                        const std::array<double, 3>& weights,
                                        const LeanMoments& mean, double base_variance) {
  const SlopeCovariance global = moment_covariance(mean.b, mean.m);
  SlopeCovariance s = global;
  for (std::size_t i = 0; i < 3; ++i) {
    const SlopeCovariance t = moment_covariance(tiles[i].b, tiles[i].m);
    const double w2 = weights[i] * weights[i];
    s.xx += w2 * (t.xx - global.xx);
    s.zz += w2 * (t.zz - global.zz);
    s.xz += w2 * (t.xz - global.xz);
  }
  s.xx += base_variance;
  s.zz += base_variance;
  return s;
}

// Lutz eq. 16 and 19–21 (with φ = −θ).
LeanMoments turned_lean_moments(const LeanMoments& t, double c, double s) {
  const double sin2 = 2.0 * s * c, cos2 = c * c - s * s;
  LeanMoments r;
  r.b = {c * t.b[0] - s * t.b[1], s * t.b[0] + c * t.b[1]};
  r.m = {c * c * t.m[0] - sin2 * t.m[2] + s * s * t.m[1],
         s * s * t.m[0] + sin2 * t.m[2] + c * c * t.m[1],
         0.5 * sin2 * (t.m[0] - t.m[1]) + cos2 * t.m[2]};
  return r;
}

// Olano & Baker 2010 eq. 3 (the anisotropic Beckmann lobe in the slope plane).
double beckmann_slope_density(const std::array<double, 2>& h, const std::array<double, 2>& b,
                              const SlopeCovariance& sigma) {
  const double det = sigma.xx * sigma.zz - sigma.xz * sigma.xz;
  const double dx = h[0] - b[0], dz = h[1] - b[1];
  // (h − b)ᵀ Σ⁻¹ (h − b) with Σ⁻¹ = [[zz, −xz], [−xz, xx]]/det.
  const double q = (sigma.zz * dx * dx - 2.0 * sigma.xz * dx * dz + sigma.xx * dz * dz) / det;
  return math::exp(-0.5 * q) / (2.0 * std::numbers::pi * std::sqrt(det));
}

}  // namespace oceanref
