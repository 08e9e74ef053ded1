// The lighting of one sample of the sea: the reflected sun, the reflected sky and the refracted
// sea light with their estimated errors, by the reference integrals (reference_lighting.h) or
// the fixed-order rules (ocean_lighting.h) as the scene's shading settings say. Shared by the
// renderer and `oceanref brdf`, so both compute the same numbers from the same settings.
#pragma once

#include <array>
#include <vector>

#include "core/choice.h"
#include "shading/four_term.h"
#include "shading/ocean_lighting.h"
#include "shading/reference_lighting.h"
#include "waves/ocean.h"
#include "waves/surface.h"

namespace oceanref {

// How the lighting integrals (reflected sun, reflected sky, F̄) are computed (DESIGN.md,
// "Accuracy contract").
enum class LightingAccuracy {
  reference,  // converged to `tolerance`, with error estimates (shading/reference_lighting.h)
  fast,       // fixed-order rules of `sky_order` and `sun_order` (shading/ocean_lighting.h)
};
inline constexpr std::array<Choice<LightingAccuracy>, 2> kLightingAccuracies{{
    {LightingAccuracy::reference, "reference"},
    {LightingAccuracy::fast, "fast"},
}};

// The shading model of the sea (`shading.model`): Bruneton 2010's ocean BRDF under the Preetham
// sky (the reference), or Vincevičius 2024's four-term model (shading/four_term.h), an
// alternative a real-time renderer may use, in closed form (no integrals, no error).
enum class ShadingModel { bruneton, four_term };
inline constexpr std::array<Choice<ShadingModel>, 2> kShadingModels{{
    {ShadingModel::bruneton, "bruneton"},
    {ShadingModel::four_term, "four_term"},
}};

struct ShadingSettings {
  ShadingModel model = ShadingModel::bruneton;
  FourTermParameters four_term;  // model four_term
  bool sun = true;
  bool sky = true;
  bool sea = true;
  bool whitecaps = false;
  BrdfOptions brdf;
  LightingAccuracy accuracy = LightingAccuracy::reference;
  // Reference: each term's error ≤ max(tolerance·|term|, tolerance·10⁻³·E_sky/π) per channel.
  double tolerance = 1e-6;
  int sky_order = 4;  // fast: Gauss–Hermite order per axis of the reflected sky and F̄
  int sun_order = 2;  // fast: Gauss–Legendre order over the sun disk (0: point sun)
  Vec3 sea_colour{10.0 / 255.0 * 0.1, 40.0 / 255.0 * 0.1, 120.0 / 255.0 * 0.1};
  double foam_albedo = 0.8;
  double whitecap_threshold = 0.0;  // foam where det J < threshold
  Interpolation interpolation = Interpolation::bicubic;
  // The shading normal: of the rasterized surface (N_l bands) or from the N_h slopes
  // (waves/surface.h).
  ShadingNormals normals = ShadingNormals::surface;
};

// Everything the shading of a frame shares: computed once, not per sample.
struct FrameLighting {
  Vec3 sun_direction;
  Vec3 sun_radiance;                  // L_sun, cd/m² per channel
  Vec3 sky_irradiance;                // E_sky on a horizontal plane
  double cos_sun_radius;              // the sun disk's edge
  double sun_solid_angle;             // Ω_sun
  QuadratureRule hermite;             // fast: Gauss–Hermite rule of the sky and F̄ (sky_order)
  std::vector<SunDiskNode> sun_disk;  // fast: the nodes of the sun-disk rule (sun_order)
  Vec3 radiance_floor;                // reference: the absolute tolerance per channel
  double sun_reflectance_floor;       // reference: the same for the sun's reflectance
};
// The fast rules' nodes are built for shading.accuracy fast, and for reference accuracy too when
// `fast_rules` (the renderer's two-level estimate shades every sample by them and corrects each
// pixel by the reference: RenderJob::lighting_correction).
FrameLighting frame_lighting(const Sky& sky, const ShadingSettings& shading,
                             bool fast_rules = false);

// The lighting terms of one sample and their estimated absolute errors.
struct LightingTerms {
  Vec3 sun{}, sky{}, sea{};
  double sun_reflectance = 0.0;  // ∫_disk f cos θ_L dω: sun = sun_reflectance·L_sun
  double mean_fresnel = 0.0;
  double sun_reflectance_error = 0.0;
  Vec3 sun_error{}, sky_error{}, sea_error{};
  double mean_fresnel_error = 0.0;
  long evaluations = 0;  // integrand evaluations of the reference integrals
  bool converged = true;
};
// Vincevičius's four terms (eq. 2.11–2.15) as LightingTerms: `sun` the specular L_s, `sky` the
// reflection L_r (the Preetham sky at the mirror direction of V about N, 0 below the horizon),
// `sea` the ambient and subsurface light L_a + L_ss, each 0 when its shading toggle is off; F the
// model's Fresnel (as mean_fresnel); errors 0 (closed forms). C_l = L_sun Ω_sun/π (the radiance
// of a white Lambertian surface facing the sun); H = `height` [m] above the mean sea level.
LightingTerms four_term_lighting(const ShadingSettings& sh, const Sky& sky,
                                 const FrameLighting& light, const Vec3& view, const Vec3& normal,
                                 double height);

// The terms for the view V at a surface frame with unresolved slope variance s. With reference
// accuracy the errors are the integrators' estimates; with fast accuracy they are
// |fast − reference| + the reference's estimate when `estimate_fast_error` (which costs the
// reference integrals), else 0.
LightingTerms lighting_terms(const ShadingSettings& shading, const Sky& sky,
                             const FrameLighting& light, const Vec3& view,
                             const SurfaceFrame& frame, SlopeVariance s, bool estimate_fast_error);

}  // namespace oceanref
