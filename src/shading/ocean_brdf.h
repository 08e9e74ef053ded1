// The ocean BRDF of Bruneton, Neyret, Holzschuch 2010 ("Real-time Realistic Ocean Lighting using
// Seamless Transitions from Geometry to BRDF"), exact: an anisotropic Gaussian distribution of
// facet slopes, Smith's masking with the exact erfc, the exact unpolarized Fresnel reflectance of
// water, and the sun and sky integrated rather than looked up. The approximations real-time
// shaders make (Schlick Fresnel, the rational erfc, the mean-Fresnel fit, the sky lookup in the
// mirror direction) are options, and their errors are measured (reference/ACCURACY.md).
//
// Frame: the mean surface normal N, the wind-aligned tangent T_x (upwind) and T_y = N × T_x
// (crosswind), an orthonormal basis (wind_frame). Slopes: a facet where the surface rises by
// ζ = (ζ_x, ζ_y) per unit length along (T_x, T_y) has the normal ñ = N − ζ_x T_x − ζ_y T_y (the
// sums over slopes: for_each_hermite_slope, ocean_lighting.h, reference_lighting.h). ocean_brdf
// reports the slope of the facet whose normal is the half vector h with the demo's sign,
// ζ = (h·T_x, h·T_y)/(h·N), the opposite; p(ζ) is even, so both give the same density.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

#include "core/choice.h"
#include "core/quadrature.h"
#include "core/vec3.h"
#include "spectrum/slope_variance.h"

namespace oceanref {

struct SurfaceFrame {
  Vec3 normal;     // N, unit
  Vec3 tangent_x;  // T_x, unit, ⟂ N (upwind)
  Vec3 tangent_y;  // T_y = N × T_x, unit (crosswind)
};
// The frame of a normal N with T_x the projection of the wind direction (cos A, 0, sin A) on
// the plane ⟂ N (+Y up, wind angle A from +X towards +Z). Where that projection's squared length
// is below 1e-20 (the wind within 1e-10 rad of ±N, where it has no direction on the plane), T_x is
// the projection of +Z instead.
SurfaceFrame wind_frame(const Vec3& normal, double wind_angle);

// p(ζ) = exp(−½(ζ_x²/σ_x² + ζ_y²/σ_y²)) / (2π σ_x σ_y)  (Bruneton 2010 eq. 4).
double slope_density(double zeta_x, double zeta_y, SlopeVariance s);
// σ² seen along a direction d: σ_x² cos²φ + σ_y² sin²φ, φ the azimuth of d in the frame
// (exact: cos²φ = (d·T_x)²/((d·T_x)² + (d·T_y)²)). The demo computes φ = atan2(…) and then
// 1/(1 + φ²) as if φ were tan φ — a misprint recorded in FORMULAS.md.
double directional_slope_variance(const Vec3& d, const SurfaceFrame& f, SlopeVariance s);

enum class ErfcForm { exact, rational };  // math::erfc, or 2e^{−x²}/(2.319x + √(4 + 1.52x²))
inline constexpr std::array<Choice<ErfcForm>, 2> kErfcForms{{
    {ErfcForm::exact, "exact"},
    {ErfcForm::rational, "rational"},
}};
// erfc(x) for x ≥ 0 by the rational approximation of the demo (Bruneton's ocean.glsl).
double rational_erfc(double x);
// Smith's Λ for Gaussian slopes: Λ = (e^{−ν²} − ν√π erfc ν)/(2ν√π), ν = cos θ/√(2σ²(1 − cos²θ))
// (Bruneton 2010 eq. 7, after Smith 1967). Λ → ∞ as cos θ → 0; Λ = 0 at cos θ = 1.
double smith_lambda(double cos_theta, double sigma2, ErfcForm form = ErfcForm::exact);
// cos θ · (1 + Λ(cos θ)): finite as cos θ → 0, where it tends to √(σ²/(2π)).
double visible_projected_area(double cos_theta, double sigma2, ErfcForm form = ErfcForm::exact);
// Both of the above for one direction from a single erfc and exponential (0 < cos θ).
struct SmithTerms {
  double lambda;        // Λ
  double visible_area;  // cos θ·(1 + Λ)
};
SmithTerms smith_terms(double cos_theta, double sigma2, ErfcForm form = ErfcForm::exact);

// Exact dielectric, 0.02 + 0.98(1 − cos)^5 (Schlick with the demo's constants), or 1 (a perfect
// mirror facet: for energy checks).
enum class FresnelForm { exact, schlick, unity };
inline constexpr std::array<Choice<FresnelForm>, 3> kFresnelForms{{
    {FresnelForm::exact, "exact"},
    {FresnelForm::schlick, "schlick"},
    {FresnelForm::unity, "unity"},
}};
// The forms a scene (shading.fresnel) and `oceanref brdf` offer: unity is for energy checks.
inline constexpr std::span<const Choice<FresnelForm>, 2> kShadingFresnelForms =
    std::span(kFresnelForms).first<2>();
inline constexpr double kWaterRefractiveIndex = 1.333;
// Unpolarized Fresnel reflectance of an air–water interface (n = 1.333) for cos θ_i ∈ [0, 1]:
// ½(r_s² + r_p²) with r_s = (cos i − n cos t)/(cos i + n cos t), r_p = (n cos i − cos t)/(n cos i
// + cos t), sin t = sin i / n (Born & Wolf §1.5).
double fresnel_reflectance(double cos_incidence, FresnelForm form = FresnelForm::exact);

struct BrdfOptions {
  FresnelForm fresnel = FresnelForm::exact;
  ErfcForm erfc = ErfcForm::exact;
};

// All intermediates of the BRDF for one pair of directions (for probing and `oceanref brdf`).
struct BrdfTerms {
  double zeta_x, zeta_y;  // slope of the facet reflecting L into V
  double p;               // slope density p(ζ)
  double sigma2_view, sigma2_light;
  double lambda_view, lambda_light;  // Λ_V, Λ_L
  double fresnel;                    // F(V·h)
  double brdf_cos;  // f(L, V)·cos θ_L = F p /(4 (h·N)⁴ (V·N)(1 + Λ_V + Λ_L))
};
// Bruneton 2010 eq. 8–9 (the demo's reflectedSunRadiance without its clamps): 0 when L or V is
// below the mean surface.
BrdfTerms ocean_brdf(const Vec3& light, const Vec3& view, const SurfaceFrame& frame,
                     SlopeVariance s, const BrdfOptions& options = {});
// The view's part of the BRDF, the same for every light direction (computed once per sample).
struct ViewTerms {
  double cos_theta = 0.0;  // V·N
  double sigma2 = 0.0;     // σ² along V
  SmithTerms smith{};      // Λ_V and cos θ_V (1 + Λ_V); zero when V·N ≤ 0
};
ViewTerms view_terms(const Vec3& view, const SurfaceFrame& frame, SlopeVariance s,
                     ErfcForm form = ErfcForm::exact);
// ocean_brdf with the view terms given: the same bits as the form above.
BrdfTerms ocean_brdf(const Vec3& light, const Vec3& view, const ViewTerms& view_part,
                     const SurfaceFrame& frame, SlopeVariance s, const BrdfOptions& options = {});

// The sun reflected into V, integrated over the sun disk (angular radius ρ, uniform radiance
// L_sun): ∫_disk f cos θ_L dω · L_sun, by Gauss–Legendre quadrature in the disk's polar
// coordinates (order × 4·order points). With order 0 the sun is a point: f cos θ_L Ω_sun L_sun.
double reflected_sun(const Vec3& sun, double sun_radius, const Vec3& view,
                     const SurfaceFrame& frame, SlopeVariance s, int order,
                     const BrdfOptions& options = {});
// The same with the Gauss–Legendre rule given (empty: point sun), so a renderer builds it once.
double reflected_sun(const Vec3& sun, double sun_radius, const Vec3& view,
                     const SurfaceFrame& frame, SlopeVariance s, const QuadratureRule& disk,
                     const BrdfOptions& options = {});
// Two unit vectors completing the sun direction S to an orthonormal basis (u, w = S × u): the
// axes of the sun disk's tangent plane.
std::array<Vec3, 2> sun_disk_axes(const Vec3& sun);
// A node of the sun-disk rule: a direction L inside the disk and its weight [sr].
struct SunDiskNode {
  Vec3 direction;
  double weight;
};
// The nodes of the rule above (order × 4·order; empty rule: the sun's centre with weight
// Ω_sun = 2π(1 − cos ρ)); they depend on the sun only, so a renderer computes them per frame.
std::vector<SunDiskNode> sun_disk_nodes(const Vec3& sun, double sun_radius,
                                        const QuadratureRule& disk);
// Σ weight · f(L, V) cos θ_L over the nodes.
double reflected_sun(const std::vector<SunDiskNode>& nodes, const Vec3& view,
                     const SurfaceFrame& frame, SlopeVariance s, const BrdfOptions& options = {});

// The Gauss–Hermite product rule over facet slopes: calls facet(ζ_x, ζ_y, w) for every pair
// (t_i, t_j) of the rule's nodes, i the outer loop, with ζ = (√(2σ_x²)·t_i, √(2σ_y²)·t_j) and
// w = w_i·w_j. Since p(ζ)dζ = e^{−|t|²}/π dt, Σ w·f(ζ)/π ≈ ∫ f(ζ) p(ζ) dζ. The slope sums of
// mean_fresnel, reflected_sky and reflected_sky_filtered, in this one order.
template <class Facet>
void for_each_hermite_slope(const QuadratureRule& hermite, const SlopeVariance& s,
                            const Facet& facet) {
  const std::size_t n = hermite.nodes.size();
  for (std::size_t i = 0; i < n; ++i) {
    const double zeta_x = std::sqrt(2.0 * s.upwind) * hermite.nodes[i];
    for (std::size_t j = 0; j < n; ++j) {
      const double zeta_y = std::sqrt(2.0 * s.crosswind) * hermite.nodes[j];
      facet(zeta_x, zeta_y, hermite.weights[i] * hermite.weights[j]);
    }
  }
}

// Mean Fresnel over the visible slopes: F̄ = ∫ F(V·m) ⟨V·ñ⟩₊ p dζ / (cos θ_V (1 + Λ_V)), ñ the
// unnormalized facet normal, by Gauss–Hermite quadrature of the given order per axis.
double mean_fresnel(const Vec3& view, const SurfaceFrame& frame, SlopeVariance s, int order,
                    const BrdfOptions& options = {});
// The same with the Gauss–Hermite rule given.
double mean_fresnel(const Vec3& view, const SurfaceFrame& frame, SlopeVariance s,
                    const QuadratureRule& hermite, const BrdfOptions& options = {});
// The demo's fit, as the demo uses it: F̄ ≈ 0.02 + 0.98·(1 − cos θ_V)^{5 exp(−2.69 σ_V)} /
// (1 + 22.7 σ_V^1.5), σ_V² the slope variance along V (Bruneton's ocean demo, meanFresnel).
double mean_fresnel_fit(const Vec3& view, const SurfaceFrame& frame, SlopeVariance s);

}  // namespace oceanref
