// LEAN mapping (Olano & Baker 2010) as Lutz, Schoentgen & Gilet 2024 §6 apply it to a tiled and
// blended ocean: the first and second moments of the normals' slopes, filtered over a pixel's
// footprint, give the covariance of a Beckmann lobe. Slopes here are LEAN's ñ = (n_x/n_y,
// n_z/n_y) (y up; Lutz writes n.x/n.z with z up), and a Beckmann lobe is the density of the
// half vector's slope h̃ = (h_x/h_y, h_z/h_y) in the slope plane:
//   P(h̃) = exp(−½ (h̃ − b)ᵀ Σ⁻¹ (h̃ − b)) / (2π √det Σ).
// The renderer's BRDF (shading/brdf.h) is the isotropic case Σ = σ²I; these functions serve the
// comparison of filtered shading methods against the supersampled lobe (conformance/lean_study.h).
#pragma once

#include <array>

namespace oceanref {

// B = (ñ_x, ñ_z) and M = (ñ_x², ñ_z², ñ_x ñ_z) of one normal (Lutz eq. 9–10).
struct LeanMoments {
  std::array<double, 2> b{};
  std::array<double, 3> m{};
};
LeanMoments lean_moments(const std::array<double, 3>& normal);

// A symmetric 2×2 matrix (xx, zz, xz).
struct SlopeCovariance {
  double xx = 0.0, zz = 0.0, xz = 0.0;
};
// σ(b, m) = [[m.x − b.x², m.z − b.x b.z], [·, m.y − b.z²]] (Lutz eq. 12).
SlopeCovariance moment_covariance(const std::array<double, 2>& b, const std::array<double, 3>& m);
// Σ = σ(b, m) + (1/s)·I (Lutz eq. 11): the footprint's spread plus the surface's own roughness
// 1/s (s the specular power; here the base slope variance per axis).
SlopeCovariance lean_covariance(const std::array<double, 2>& b, const std::array<double, 3>& m,
                                double base_variance);
// Lutz eq. 13: Σ = Σ_i w_i²(σ(B_i, M_i) − σ(μ_B, μ_M)) + σ(μ_B, μ_M) + (1/s)·I, the covariance
// of a blend of three tiles with weights w (Σ w² = 1), B_i, M_i the tiles' filtered moments and
// μ_B, μ_M the exemplar's means.
SlopeCovariance blended_lean_covariance(const std::array<LeanMoments, 3>& tiles,
                                        const std::array<double, 3>& weights,
                                        const LeanMoments& mean, double base_variance);

// The moments of a tile turned about the vertical by R(θ) = [[cos θ, −sin θ], [sin θ, cos θ]]
// acting on (x, z) column vectors, as tiling.h turns a tile's vectors: B_θ = R B (Lutz eq. 16)
// and, from M alone, M_θ.x = c²M.x − sin2θ M.z + s²M.y, M_θ.y = s²M.x + sin2θ M.z + c²M.y,
// M_θ.z = ½ sin2θ (M.x − M.y) + cos2θ M.z (Lutz eq. 19–21, whose row vectors turn by −θ: their φ
// is our −θ).
LeanMoments turned_lean_moments(const LeanMoments& moments, double cos_theta, double sin_theta);

// P(h̃) of the Beckmann lobe with mean slope b and covariance Σ (density in the slope plane).
double beckmann_slope_density(const std::array<double, 2>& h, const std::array<double, 2>& b,
                              const SlopeCovariance& sigma);

}  // namespace oceanref
