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

#include <array>
#include <vector>

#include "core/math.h"
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

// The geometry behind the integrals' coordinates and breakpoints, one function per piece, so
// that each is tested against what it stands for (tests/test_reference_lighting.cpp).
namespace reference_geometry {
// The reflected sky's coordinates: ζ = (s_x t_x, s_y t_y), s = √(2σ²), and t = u n̂ + w n̂⊥ with
// n̂ from the centre t₀ of the horizon's ellipse towards the origin; the ellipse is
// u = u₀ + U sin θ, w = centre(θ) ± half-chord(θ), θ ∈ [−π/2, π/2]. Requires V·N > 0.
struct SkyFrame {
  double sx, sy;        // √(2σ_x²), √(2σ_y²)
  double nx, ny;        // n̂ in t
  double u0, extent;    // u₀ = −|t₀|, U
  double b, c, radius;  // the ellipse's form (b, c of [[a, b], [b, c]]) and R = 1/v_n
};
SkyFrame sky_frame(const Vec3& view, const SurfaceFrame& frame, SlopeVariance s);
// ζ at (u, w).
std::array<double, 2> sky_frame_slope(const SkyFrame& k, double u, double w);
// The horizon ellipse's chord at θ (angle = sin θ, cos θ): its centre and half-length in w.
std::array<double, 2> sky_frame_chord(const SkyFrame& k, const math::SinCos& angle);
// The part of the chord (centre ± half-chord) inside the slope plane's [−T, T], T =
// kSlopeTruncation: `whole_line` when it covers all of [−T, T] (the Gaussian in w is then
// integrated over the whole line: beyond ±T it is below e^−36); else [lo, hi], empty when
// hi ≤ lo.
struct ChordRange {
  bool whole_line;
  double lo, hi;
};
ChordRange chord_in_slope_plane(double centre, double half_chord);
// (u, w) of the facet that mirrors V into the sun (the circumsolar peak, a breakpoint of both
// rules); (0, 0) when the sun or that facet is below the surface's plane.
std::array<double, 2> circumsolar_facet(const SkyFrame& k, const Vec3& view,
                                        const SurfaceFrame& frame, const Vec3& sun);
// The θ in (θ_lo, θ_hi) where an end of the chord crosses w ∈ {0, ±2, ±kSlopeTruncation}.
std::vector<double> chord_scale_crossings(const SkyFrame& k, double theta_lo, double theta_hi);
// The sun disk as the unit disk (x, y) (reflected_sun_reference, axes from sun_disk_axes): the
// direction of a point, with dω/(dx dy); and the surface's horizon L·N = 0, to first order in
// ρ the line x (u·N) + y (w·N) = sun_disk_horizon.
Vec3 sun_disk_direction(const Vec3& sun, double sun_radius, const std::array<Vec3, 2>& axes,
                        double x, double y, double& solid_angle_density);
double sun_disk_horizon(const Vec3& sun, double sun_radius, const SurfaceFrame& frame);
// The breakpoints of reflected_sun_reference's rules over the disk, x = sin θ, y = η cos θ
// (outer rule over θ ∈ [−π/2, π/2], inner over η ∈ [−1, 1]): around the lobe's peak (x0, y0) at
// distances lobe·4^j in x and in η (a lobe narrower than the disk is never straddled unseen by a
// Kronrod rule), and on the surface's horizon L·N = 0 of a setting sun, where the BRDF falls to 0
// with a kink. To first order in ρ_s that is the line x (u·N) + y (w·N) = horizon
// (sun_disk_horizon; curved by O(ρ_s²), 2e-5 of the disk): a breakpoint of the inner rule at each
// θ when the line runs along x (|w·N| ≥ |u·N|), of the outer rule when it runs along y.
struct SunDiskBreaks {
  std::vector<double> theta;  // ascending, in [−π/2, π/2], the horizon's included
  std::vector<double> eta;    // ascending, in [−1, 1], the horizon's not (sun_disk_eta_breaks)
  double horizon, un, wn;     // the line; u·N, w·N
  bool horizon_across_x;      // |w·N| ≥ |u·N|
};
SunDiskBreaks sun_disk_breaks(double x0, double y0, double lobe, double horizon, double un,
                              double wn);
// The inner rule's breakpoints at θ (angle = sin θ, cos θ): eta, with the horizon's η where the
// line crosses the chord at θ inside (−1, 1).
std::vector<double> sun_disk_eta_breaks(const SunDiskBreaks& b, const math::SinCos& angle);
}  // namespace reference_geometry

}  // namespace oceanref
