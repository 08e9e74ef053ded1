#include "shading/lighting_terms.h"

#include <cmath>
#include <numbers>

#include "core/math.h"
#include "core/vec3.h"

namespace oceanref {

namespace {
LightingTerms fast_lighting(const ShadingSettings& sh, const Sky& sky, const FrameLighting& light,
                            const Vec3& view, const SurfaceFrame& frame, SlopeVariance s) {
  LightingTerms t;
  if (sh.sun) {
    t.sun_reflectance = reflected_sun(light.sun_disk, view, frame, s, sh.brdf);
    t.sun = scaled(light.sun_radiance, t.sun_reflectance);
  }
  if (sh.sky) t.sky = reflected_sky(view, frame, s, sky, light.hermite, sh.brdf);
  if (sh.sea) {
    t.mean_fresnel = mean_fresnel(view, frame, s, light.hermite, sh.brdf);
    t.sea = refracted_sea(t.mean_fresnel, sh.sea_colour, light.sky_irradiance);
  }
  return t;
}

LightingTerms reference_lighting(const ShadingSettings& sh, const Sky& sky,
                                 const FrameLighting& light, const Vec3& view,
                                 const SurfaceFrame& frame, SlopeVariance s) {
  LightingTerms t;
  const double tolerance = sh.tolerance;
  if (sh.sun && light.sun_reflectance_floor < HUGE_VAL) {
    const ScalarEstimate e =
        reflected_sun_reference(light.sun_direction, kSunAngularRadius, view, frame, s, sh.brdf,
                                tolerance, light.sun_reflectance_floor);
    t.sun_reflectance = e.value;
    t.sun_reflectance_error = e.error;
    t.sun = scaled(light.sun_radiance, e.value);
    for (std::size_t c = 0; c < 3; ++c) t.sun_error[c] = e.error * std::fabs(light.sun_radiance[c]);
    t.evaluations += e.evaluations;
    t.converged = t.converged && e.converged;
  }
  if (sh.sky) {
    const RgbEstimate e =
        reflected_sky_reference(view, frame, s, sky, sh.brdf, tolerance, light.radiance_floor);
    t.sky = e.value;
    t.sky_error = e.error;
    t.evaluations += e.evaluations;
    t.converged = t.converged && e.converged;
  }
  if (sh.sea) {
    const ScalarEstimate e = mean_fresnel_reference(view, frame, s, sh.brdf, tolerance);
    t.mean_fresnel = e.value;
    t.mean_fresnel_error = e.error;
    t.sea = refracted_sea(e.value, sh.sea_colour, light.sky_irradiance);
    // L_sea is linear in 1 − F̄.
    for (std::size_t c = 0; c < 3; ++c) {
      t.sea_error[c] = e.error * sh.sea_colour[c] * light.sky_irradiance[c] / std::numbers::pi;
    }
    t.evaluations += e.evaluations;
    t.converged = t.converged && e.converged;
  }
  return t;
}

// The fast terms with their errors measured against the reference: |fast − reference| plus the
// reference's own estimate.
LightingTerms fast_lighting_with_error(const ShadingSettings& sh, const Sky& sky,
                                       const FrameLighting& light, const Vec3& view,
                                       const SurfaceFrame& frame, SlopeVariance s) {
  LightingTerms t = fast_lighting(sh, sky, light, view, frame, s);
  const LightingTerms r = reference_lighting(sh, sky, light, view, frame, s);
  for (std::size_t c = 0; c < 3; ++c) {
    t.sun_error[c] = std::fabs(t.sun[c] - r.sun[c]) + r.sun_error[c];
    t.sky_error[c] = std::fabs(t.sky[c] - r.sky[c]) + r.sky_error[c];
    t.sea_error[c] = std::fabs(t.sea[c] - r.sea[c]) + r.sea_error[c];
  }
  t.mean_fresnel_error = std::fabs(t.mean_fresnel - r.mean_fresnel) + r.mean_fresnel_error;
  t.sun_reflectance_error =
      std::fabs(t.sun_reflectance - r.sun_reflectance) + r.sun_reflectance_error;
  t.evaluations = r.evaluations;
  t.converged = r.converged;
  return t;
}

}  // namespace

FrameLighting frame_lighting(const Sky& sky, const ShadingSettings& sh, bool fast_rules) {
  const bool fast = fast_rules || sh.accuracy == LightingAccuracy::fast;
  FrameLighting l{
      sky.sun_direction,
      sun_radiance_rgb(sky),
      sky_irradiance(sky).rgb,
      math::cos(kSunAngularRadius),
      2.0 * std::numbers::pi * (1.0 - math::cos(kSunAngularRadius)),
      fast ? gauss_hermite(sh.sky_order) : QuadratureRule{},
      fast ? sun_disk_nodes(sky.sun_direction, kSunAngularRadius,
                            sh.sun_order > 0 ? gauss_legendre(sh.sun_order) : QuadratureRule{})
           : std::vector<SunDiskNode>{},
      {},
      HUGE_VAL};
  // The absolute tolerance: 10⁻³ of the mean sky radiance E_sky/π (a reflected sky or sea term
  // is rarely darker), times the relative tolerance.
  for (std::size_t c = 0; c < 3; ++c) {
    l.radiance_floor[c] = sh.tolerance * 1e-3 * std::fabs(l.sky_irradiance[c]) / std::numbers::pi;
    if (l.sun_radiance[c] > 0.0) {
      l.sun_reflectance_floor =
          std::fmin(l.sun_reflectance_floor, l.radiance_floor[c] / l.sun_radiance[c]);
    }
  }
  return l;
}

LightingTerms four_term_lighting(const ShadingSettings& sh, const Sky& sky,
                                 const FrameLighting& light, const Vec3& view, const Vec3& normal,
                                 double height) {
  const Vec3 light_colour = scaled(light.sun_radiance, light.sun_solid_angle / std::numbers::pi);
  const Vec3 mirror = mirror_direction(view, normal);
  const Vec3 sky_at_mirror = mirror[1] > 0.0 ? sky_radiance_rgb(sky, mirror) : Vec3{};
  const FourTermRadiance r = four_term_shading(sh.four_term, view, normal, light.sun_direction,
                                               height, light_colour, sky_at_mirror);
  LightingTerms t;
  if (sh.sun) t.sun = r.specular;
  if (sh.sky) t.sky = r.reflection;
  if (sh.sea) {
    for (std::size_t c = 0; c < 3; ++c) t.sea[c] = r.ambient[c] + r.subsurface[c];
  }
  t.mean_fresnel = four_term_fresnel(view, normal);
  return t;
}

LightingTerms lighting_terms(const ShadingSettings& sh, const Sky& sky, const FrameLighting& light,
                             const Vec3& view, const SurfaceFrame& frame, SlopeVariance s,
                             bool estimate_fast_error) {
  if (sh.accuracy == LightingAccuracy::reference) {
    return reference_lighting(sh, sky, light, view, frame, s);
  }
  return estimate_fast_error ? fast_lighting_with_error(sh, sky, light, view, frame, s)
                             : fast_lighting(sh, sky, light, view, frame, s);
}

}  // namespace oceanref
