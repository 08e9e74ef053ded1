// The four-term water shading model of Vincevičius 2024 (§2.4 "Ocean Shading", eq. 2.11–2.15,
// with Phong's specular lobe of §1.2.9, eq. 1.17): an ambient term, a subsurface-scattering
// term, a Fresnel-weighted Phong highlight of the sun and the Fresnel-weighted reflected sky,
//
//   L = L_a + L_ss + L_s + L_r                                                      (eq. 2.11)
//
// The seed builds it from the GDC talk "Wakes, Explosions and Lighting: Interactive Water
// Simulation in Atlas" (Mihelich & Tcheklokov, 2019), whose slides we could not read; we
// compared with two public implementations of the same four-term model and with
// GarrettGunnell/Water (Acerola), a public implementation of the Atlas scattering terms.
//
// Conventions: +Y up; `view` D_v is the unit vector from the surface point towards the camera;
// `sun` D_s is the unit vector from the surface point towards the sun; `normal` N is the unit
// shading normal. Colours and radiances are per linear-sRGB channel; a product of two colours
// (C_a C_l, …) is channel by channel. Every function is plain arithmetic in a fixed order
// (integer powers by multiplication, others by oceanref::math::pow), and a NaN argument gives a
// NaN result (the clamps are written so that NaN passes through, not max/fmax, which drop it).
//
// Light colour C_l: the caller passes the radiance of a white Lambertian surface facing the sun,
// L_sun·Ω_sun/π per channel (= E_sun⊥/π). With it, every k·C weight of the model is a
// dimensionless reflectance-like factor: a term equal to C_l looks as bright as white paper in
// full sun. C_sky is a radiance: the caller evaluates its sky model in mirror_direction().
//
// Readings of the seed (misprints and gaps; to be copied into src/FORMULAS.md):
//
//  1. Ambient, eq. 2.12 "L_a = k_a N C_a C_l + ρ_a C_b C_l" multiplies by the vector N where a
//     scalar is needed. We use the normal's up component, clamped: ⟨N_y⟩₊ = max(N·Ŷ, 0).
//     Why: the seed defines the ambient light as "a constant illumination that does not depend
//     on the direction of the light source", so the factor can depend on N alone, and N·Ŷ (the
//     cosine between the facet and the zenith, the classic hemispherical-ambient weight) is the
//     only direction-free scalar of N in a +Y-up scene; a public implementation of this same
//     four-term model computes dot(N, (0, 1, 0)) there. The clamp keeps folded-over facets of a
//     choppy surface (N_y < 0) from giving negative radiance. Rejected alternative: in Atlas's
//     own scattering sum (as GarrettGunnell/Water implements it) the corresponding term is
//     k₃⟨D_s·N⟩₊ C_ss L_sun, a Lambert term of the sun; the seed lists it as ambient, light-
//     direction-free, so we do not follow Atlas there. FORMULAS.md should record both.
//  2. The bracket [a, b] of eq. 2.14 is the clamped cosine ⟨a·b⟩₊ = max(a·b, 0) (Atlas's
//     angle-bracket notation; implementations write max(dot(a, b), 0)). The unbracketed factor
//     (0.5 − 0.5 D_s·N)³ lies in [0, 1] for unit vectors and is kept as printed.
//  3. Fresnel, eq. 2.13 F = (1 − max(D_v·N, 0.15))⁵ is kept as printed: Schlick's form with
//     F₀ = 0 and the cosine floored at 0.15, so F ∈ [0, 0.85⁵ = 0.4437]. It is not water's
//     Fresnel reflectance (0.02 at normal incidence, → 1 at grazing); it is the model's weight.
//  4. Specular: the seed says only that L_s is Phong's eq. 1.17 with "the Fresnel effect
//     incorporated", and lists a specular colour C_s that no printed equation uses. We read
//     L_s = F C_s C_l ⟨D_v·R⟩₊^shininess, R = reflect(−D_s, N) = 2(D_s·N)N − D_s, with F the
//     eq. 2.13 weight of the view (the same F as L_r, a multiplicative factor, as the public
//     implementations do). At the mirror configuration R = D_v, so D_v·N = D_s·N there. No Phong
//     normalisation ((n + 2)/2π): eq. 1.17 has none, so the peak is F C_s C_l. Added: L_s = 0
//     when D_s·N ≤ 0 (the sun below the facet's horizon), which eq. 1.17 alone does not exclude
//     (a facet facing away from the sun could otherwise show a highlight).
//  5. Reflection, eq. 2.15: D_i (camera to fragment) = −D_v, and reflect is GLSL's
//     reflect(I, N) = I − 2(N·I)N, so the mirror direction is M = 2(D_v·N)N − D_v, a unit vector
//     for unit inputs (not renormalised). On steep facets M can point below the horizon; the
//     caller's sky model decides what is seen there.
//  6. Subsurface, eq. 2.14: H ("Ocean Height") is the surface point's elevation above the mean
//     sea level in metres, so k_ss1 is per metre. Atlas divides its two scattering terms by
//     1 + Λ(D_s) (Smith's masking of the sun); the seed drops it and so do we. (1 − F) weights
//     L_ss only, as printed (Atlas weights its whole scattering sum, including the terms that
//     became L_a).
//
// Defaults (look-development values, not measurements; the seed gives none):
//  - C_ws = C_a = (0.016, 0.0736, 0.16), k_ss1 = 1 /m, k_ss2 = 1, ρ_a = 1, C_b = (0, 0.02, 0.016),
//    k_a = 0.5: the scattering colour, bubble colour and density and the three scattering
//    strengths of GarrettGunnell/Water's Atlas terms (as its public GLSL ports set them); Atlas
//    uses one scattering colour for both, so C_a defaults to C_ws.
//  - shininess = 50: both public implementations of the four-term model use 50.
//  - C_s = (1, 1, 1): chosen, so the highlight has the sun's colour (one implementation has no
//    C_s at all, i.e. white).
//  - k_r = 1: chosen, so L_r is the sky reflected with the model's own Fresnel weight, unscaled
//    (the implementations use 0.41 to 1 as a look setting).
#pragma once

#include "core/vec3.h"

namespace oceanref {

// The parameters of Vincevičius Table 2.2 (symbols in parentheses). Valid ranges: validate().
struct FourTermParameters {
  double ambient_intensity = 0.5;                     // k_a ≥ 0
  Vec3 ambient_colour{0.016, 0.0736, 0.16};           // C_a, each channel in [0, 1]
  double air_bubble_density = 1.0;                    // ρ_a ≥ 0
  Vec3 air_bubble_colour{0.0, 0.02, 0.016};           // C_b, each channel in [0, 1]
  double subsurface_height_intensity = 1.0;           // k_ss1 ≥ 0, per metre of height
  double subsurface_view_intensity = 1.0;             // k_ss2 ≥ 0
  Vec3 water_scattering_colour{0.016, 0.0736, 0.16};  // C_ws, each channel in [0, 1]
  Vec3 specular_colour{1.0, 1.0, 1.0};                // C_s, each channel in [0, 1]
  double shininess = 50.0;                            // Phong exponent in [1, 10000]
  double reflection_intensity = 1.0;                  // k_r ≥ 0
};

// Throws SettingError (a std::invalid_argument) whose key is the field's name and whose message
// states the field, its symbol, its valid range and the value given: intensities and the bubble
// density finite and ≥ 0, colours with each channel in [0, 1], shininess in [1, 10000].
void validate(const FourTermParameters& parameters);

// The four terms of eq. 2.11 at one surface point, each a radiance per channel, so that the
// renderer can write each as an image layer.
struct FourTermRadiance {
  Vec3 ambient{};     // L_a
  Vec3 subsurface{};  // L_ss
  Vec3 specular{};    // L_s
  Vec3 reflection{};  // L_r
};

// ⟨a·b⟩₊ = max(a·b, 0), the bracket [a, b] of Vincevičius eq. 2.14 (reading 2).
double four_term_clamped_cosine(const Vec3& a, const Vec3& b);

// F = (1 − max(D_v·N, 0.15))⁵, Vincevičius eq. 2.13 (reading 3).
double four_term_fresnel(const Vec3& view, const Vec3& normal);

// reflect(D_i, N) with D_i = −D_v: 2(D_v·N)N − D_v, Vincevičius eq. 2.15 (reading 5). Also
// Phong's reflected sun direction R = mirror_direction(D_s, N) (eq. 1.17).
Vec3 mirror_direction(const Vec3& view, const Vec3& normal);

// L_a = k_a ⟨N_y⟩₊ C_a C_l + ρ_a C_b C_l, Vincevičius eq. 2.12 (reading 1).
Vec3 four_term_ambient(const FourTermParameters& parameters, const Vec3& normal,
                       const Vec3& light_colour);

// L_ss1 = k_ss1 max(0, H) ⟨D_s·(−D_v)⟩₊⁴ (0.5 − 0.5 D_s·N)³, Vincevičius eq. 2.14; H in metres
// above the mean sea level, k_ss1 per metre (reading 6).
double wave_peak_scattering(double subsurface_height_intensity, double height, const Vec3& view,
                            const Vec3& normal, const Vec3& sun);

// L_ss2 = k_ss2 ⟨D_v·N⟩₊², Vincevičius eq. 2.14.
double view_scattering(double subsurface_view_intensity, const Vec3& view, const Vec3& normal);

// L_ss = (1 − F)(L_ss1 + L_ss2) C_ws C_l, Vincevičius eq. 2.14, with F = four_term_fresnel.
Vec3 four_term_subsurface(const FourTermParameters& parameters, const Vec3& view,
                          const Vec3& normal, const Vec3& sun, double height, double fresnel,
                          const Vec3& light_colour);

// ⟨D_v·R⟩₊^shininess with R = reflect(−D_s, N), Phong eq. 1.17 (Vincevičius §1.2.9); 0 when
// D_s·N ≤ 0, the sun below the facet's horizon (reading 4).
double phong_specular_lobe(const Vec3& view, const Vec3& normal, const Vec3& sun, double shininess);

// L_s = F C_s C_l ⟨D_v·R⟩₊^shininess, Vincevičius §2.4 "Specular Reflection" with eq. 1.17
// (reading 4); F = four_term_fresnel.
Vec3 four_term_specular(const FourTermParameters& parameters, const Vec3& view, const Vec3& normal,
                        const Vec3& sun, double fresnel, const Vec3& light_colour);

// L_r = F k_r C_sky, Vincevičius eq. 2.15; C_sky is the sky radiance in mirror_direction(D_v, N).
Vec3 four_term_reflection(const Vec3& sky_radiance_at_mirror, double fresnel,
                          double reflection_intensity);

// The four terms at one surface point: view D_v, normal N, sun D_s (unit vectors), height H
// [m above the mean sea level], light colour C_l (the radiance of a white Lambertian surface
// facing the sun) and the sky radiance the caller evaluated in mirror_direction(view, normal).
// Vincevičius eq. 2.11–2.15. The parameters are not validated here (validate() once, up front).
FourTermRadiance four_term_shading(const FourTermParameters& parameters, const Vec3& view,
                                   const Vec3& normal, const Vec3& sun_direction, double height,
                                   const Vec3& light_colour, const Vec3& sky_at_mirror);

// L = L_a + L_ss + L_s + L_r, Vincevičius eq. 2.11 (summed in that order, channel by channel).
Vec3 four_term_total(const FourTermRadiance& radiance);

}  // namespace oceanref
