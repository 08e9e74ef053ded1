// The lighting integrals of the ocean BRDF converged to a tolerance, each with an error estimate
// (DESIGN.md, "Accuracy contract"): the reference that the fixed-order rules of
// ocean_lighting.h ("fast") are measured against.
//
// Method. Over facet slopes ζ = (√(2σ_x²) t_x, √(2σ_y²) t_y) the slope density is
// p(ζ)dζ = e^{−|t|²}/π dt. The integrands are smooth except where
//   - facets turn away from the viewer (V·ñ = 0): a straight line in t;
//   - the mirrored direction crosses the horizon (L·N = 0): in ζ the circle |ζ + v_t/v_n| =
//     1/v_n (v_t the tangential part of V, v_n = V·N), an axis-aligned ellipse in t. It lies
//     inside the visible half-plane, so it alone bounds the reflected sky;
//   - the sun disk's edge (uniform radiance inside, none outside).
// Each integral is written in coordinates in which these boundaries are coordinate lines (the
// half-plane as u < d in a rotated frame; the ellipse as t_x = e_x + r_x sin θ, t_y between the
// chord's ends; the sun disk as x = sin θ, y = η cos θ on the unit disk), so that each piece is
// smooth, and integrated by iterated adaptive Gauss–Kronrod (adaptive_cubature.h) with
// breakpoints at the Gaussian's scale and at the integrand's peaks (the sun's mirror point in
// the sky, the specular direction in the sun disk). The slope plane is truncated to |t_x|,
// |t_y| ≤ 6: the neglected Gaussian mass is 2·erfc(6) ≈ 4·10⁻¹⁷ of the total, below any
// accepted tolerance.
#pragma once

#include "shading/ocean_brdf.h"
#include "sky/preetham.h"

namespace oceanref {

inline constexpr double kSlopeTruncation = 6.0;  // |t| bound of the slope plane (see above)
// Each function below requires σ_x², σ_y² > 0 (std::invalid_argument otherwise; the renderer's
// slope budget floors σ² at 1e-10).
// The accepted range of relative tolerances (scene key shading.tolerance, brdf --tolerance).
inline constexpr double kMinLightingTolerance = 1e-10;
inline constexpr double kMaxLightingTolerance = 1e-2;

struct ScalarEstimate {
  double value = 0.0;
  double error = 0.0;  // estimated absolute error
  long evaluations = 0;
  bool converged = true;
};
struct RgbEstimate {
  Vec3 value{};
  Vec3 error{};  // per channel
  long evaluations = 0;
  bool converged = true;
};

// F̄ = 1 − ∫(1 − F(V·m)) ⟨V·ñ⟩₊ p dζ / ∫⟨V·ñ⟩₊ p dζ (the transmitted share is integrated, so its
// relative accuracy holds even where F̄ → 1), to the given relative tolerance of 1 − F̄.
ScalarEstimate mean_fresnel_reference(const Vec3& view, const SurfaceFrame& frame, SlopeVariance s,
                                      const BrdfOptions& options, double relative_tolerance);
// ∫ f(L, V) L_sky(L) cos θ_L dω_L (the integral reflected_sky approximates), per channel to
// max(absolute[c], relative·|value[c]|).
RgbEstimate reflected_sky_reference(const Vec3& view, const SurfaceFrame& frame, SlopeVariance s,
                                    const Sky& sky, const BrdfOptions& options, double relative,
                                    const Vec3& absolute);
// ∫_disk f(L, V) cos θ_L dω_L over the sun disk of angular radius ρ (the reflectance that,
// times L_sun, is the reflected sun), to max(absolute, relative·|value|). When
// reflected_sun_bound is within `absolute` the disk is not integrated: the value is 0 and the
// bound its error (far from the glitter, most of the sea).
ScalarEstimate reflected_sun_reference(const Vec3& sun, double sun_radius, const Vec3& view,
                                       const SurfaceFrame& frame, SlopeVariance s,
                                       const BrdfOptions& options, double relative,
                                       double absolute);
// An upper bound of that integral without integrating: with F ≤ 1 and Λ ≥ 0 in Bruneton's eq. 8,
// f cos θ_L ≤ p(ζ)/(4 (h·N)⁴ (V·N)); over the disk the unnormalized half vector H = L + V moves
// by |L − S| ≤ ρ from H_S = S + V, so the facet slope ζ = H_t/H_n moves by at most
// Δ = ρ√(1 + |ζ_S|²)/(H_S·N − ρ), the Mahalanobis distance √q of ζ is at least √q_S − Δ/σ_min,
// and h·N ≥ (H_S·N − ρ)/(|H_S| + ρ). Times πρ² ≥ the disk's solid angle 2π(1 − cos ρ). +∞ when
// H_S·N ≤ ρ (no bound of this form); 0 when V is below the surface.
double reflected_sun_bound(const Vec3& sun, double sun_radius, const Vec3& view,
                           const SurfaceFrame& frame, SlopeVariance s);

}  // namespace oceanref
