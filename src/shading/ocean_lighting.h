// The lighting terms of the ocean surface (Bruneton 2010 §4; Gamper §4.5): reflected sun,
// reflected sky, refracted sea light and whitecaps (Dupuy & Bruneton 2012), each separately.
// Radiance in cd/m² per linear sRGB (D65) channel.
#pragma once

#include "shading/ocean_brdf.h"
#include "sky/preetham.h"

namespace oceanref {

// The sky that facets of slope ζ reflect into V, per unit of p(ζ)dζ: the integrand of the next
// function, F(V·m) ⟨V·ñ⟩₊ L_sky(L(m)) / (V·N (1 + Λ_V + Λ_L)), 0 where V·ñ ≤ 0 or L·N ≤ 0.
Vec3 reflected_sky_per_slope(double zeta_x, double zeta_y, const Vec3& view, const ViewTerms& v,
                             const SurfaceFrame& frame, SlopeVariance s, const Sky& sky,
                             const BrdfOptions& options);
// The sky reflected into V: ∫ f(L, V) L_sky(L) cos θ_L dω_L, written over facet slopes as
// ∫ F(V·m) G(L, V) L_sky(L(m)) ⟨V·ñ⟩₊/(V·N) p(ζ) dζ with L(m) the mirror of V about m and
// G = 1/(1 + Λ_V + Λ_L) (Bruneton 2010 eq. 8 integrated over the sky), by Gauss–Hermite
// quadrature of the given order per axis. Directions below the horizon see no sky.
Vec3 reflected_sky(const Vec3& view, const SurfaceFrame& frame, SlopeVariance s, const Sky& sky,
                   int order, const BrdfOptions& options = {});
// The same with the Gauss–Hermite rule given.
Vec3 reflected_sky(const Vec3& view, const SurfaceFrame& frame, SlopeVariance s, const Sky& sky,
                   const QuadratureRule& hermite, const BrdfOptions& options = {});
// The demo's shortcut, a prefiltered sky texture read once: F̄ times the mean of L_sky over the
// mirror directions of V about facets distributed by p(ζ) (no Fresnel, masking or visibility
// weighting — what a filtered environment lookup holds), Gauss–Hermite of the given order.
Vec3 reflected_sky_filtered(const Vec3& view, const SurfaceFrame& frame, SlopeVariance s,
                            const Sky& sky, int order, const BrdfOptions& options = {});
// The crudest shortcut: F̄·L_sky at the mirror direction of V about N (no filtering).
Vec3 reflected_sky_mirror(const Vec3& view, const SurfaceFrame& frame, SlopeVariance s,
                          const Sky& sky, int order, const BrdfOptions& options = {});

// L_sea = (1 − F̄)·sea colour·E_sky/π  (Bruneton 2010 §4.3).
Vec3 refracted_sea(double mean_fresnel, const Vec3& sea_colour, const Vec3& sky_irradiance);

// Whitecap coverage W = P(det J < ε) for det J normal with the footprint's mean μ and variance σ²:
// W = ½ erfc((μ − ε)/√(2σ²))  (Dupuy & Bruneton 2012, §3.3); W = [μ < ε] when σ² = 0.
double whitecap_coverage(double jacobian_mean, double jacobian_variance, double threshold);
// Foam radiance: a Lambertian white of albedo a lit by the sun and the sky,
// a·(E_sun + E_sky)/π, mixed as (1 − W)·L_ocean + W·L_foam.
Vec3 foam_radiance(double albedo, const Vec3& sun_irradiance, const Vec3& sky_irradiance);
// An object's Lambertian surface of reflectance ρ (per channel) with unit normal n facing the
// viewer, unshadowed: ρ/π·(E_sun max(0, n·s) + E_sky (1 + n_y)/2) — the sun's irradiance at
// normal incidence E_sun = L_sun Ω_sun, and the sky as a uniform upper hemisphere of the given
// horizontal irradiance E_sky (view factor (1 + n_y)/2). A model chosen for objects, not from
// the seeds: both renderers use it, so they agree on objects.
Vec3 diffuse_object_radiance(const Vec3& albedo, const Vec3& normal, const Vec3& sun_direction,
                             const Vec3& sun_normal_irradiance, const Vec3& sky_irradiance);
Vec3 mix_whitecaps(const Vec3& ocean, const Vec3& foam, double coverage);

}  // namespace oceanref
