#include "shading/ocean_lighting.h"

#include <cmath>
#include <numbers>

#include "core/check.h"
#include "core/math.h"
#include "core/quadrature.h"
#include "core/vec3.h"

namespace oceanref {

namespace {
// The unit normal of the facet of slope ζ: m = (N − ζ_x T_x − ζ_y T_y)/|…|, |…| = √(1 + |ζ|²).
Vec3 facet_normal(const SurfaceFrame& f, double zx, double zy, double length) {
  Vec3 m{};
  for (std::size_t k = 0; k < 3; ++k) {
    m[k] = (f.normal[k] - zx * f.tangent_x[k] - zy * f.tangent_y[k]) / length;
  }
  return m;
}
}  // namespace

Vec3 reflected_sky(const Vec3& view, const SurfaceFrame& f, SlopeVariance s, const Sky& sky,
                   int order, const BrdfOptions& options) {
  return reflected_sky(view, f, s, sky, gauss_hermite(order), options);
}

Vec3 reflected_sky_per_slope(double zx, double zy, const Vec3& view, const ViewTerms& v,
                             const SurfaceFrame& f, SlopeVariance s, const Sky& sky,
                             const BrdfOptions& options) {
  // Facet normal m ∝ ñ = N − ζ_x T_x − ζ_y T_y; V·ñ its area projected towards V.
  const double projected = v.cos_theta - zx * dot(view, f.tangent_x) - zy * dot(view, f.tangent_y);
  if (!(projected > 0.0)) return {0.0, 0.0, 0.0};
  const double length = std::sqrt(1.0 + zx * zx + zy * zy);
  const double cos_vm = projected / length;
  const Vec3 m = facet_normal(f, zx, zy, length);
  Vec3 light{};  // the mirror of V about m
  for (std::size_t k = 0; k < 3; ++k) light[k] = 2.0 * cos_vm * m[k] - view[k];
  const double ln = dot(light, f.normal);
  if (!(ln > 0.0)) return {0.0, 0.0, 0.0};
  const double lambda_light =
      smith_lambda(ln, directional_slope_variance(light, f, s), options.erfc);
  // 1/(zV(1 + Λ_V + Λ_L)) written so that it stays finite at grazing view.
  const double weight = projected / (v.smith.visible_area + v.cos_theta * lambda_light) *
                        fresnel_reflectance(cos_vm, options.fresnel);
  Vec3 radiance = sky_radiance_rgb(sky, light);
  for (double& c : radiance) c *= weight;
  return radiance;
}

Vec3 reflected_sky(const Vec3& view, const SurfaceFrame& f, SlopeVariance s, const Sky& sky,
                   const QuadratureRule& g, const BrdfOptions& options) {
  Vec3 sum{0.0, 0.0, 0.0};
  const ViewTerms v = view_terms(view, f, s, options.erfc);
  if (!(v.cos_theta > 0.0)) return sum;
  // p(ζ)dζ = e^{−|t|²}/π dt with ζ = √(2σ²)·t: the Gauss–Hermite weights over π.
  for_each_hermite_slope(g, s, [&](double zx, double zy, double w) {
    const Vec3 l = reflected_sky_per_slope(zx, zy, view, v, f, s, sky, options);
    const double weight = w / std::numbers::pi;
    for (std::size_t k = 0; k < 3; ++k) sum[k] += weight * l[k];
  });
  return sum;
}

Vec3 reflected_sky_mirror(const Vec3& view, const SurfaceFrame& f, SlopeVariance s, const Sky& sky,
                          int order, const BrdfOptions& options) {
  const double vn = dot(view, f.normal);
  if (!(vn > 0.0)) return {0.0, 0.0, 0.0};
  Vec3 mirror{};
  for (std::size_t k = 0; k < 3; ++k) mirror[k] = 2.0 * vn * f.normal[k] - view[k];
  const double fresnel = mean_fresnel(view, f, s, order, options);
  Vec3 l = sky_radiance_rgb(sky, mirror);
  for (double& c : l) c *= fresnel;
  return l;
}

Vec3 reflected_sky_filtered(const Vec3& view, const SurfaceFrame& f, SlopeVariance s,
                            const Sky& sky, int order, const BrdfOptions& options) {
  Vec3 sum{0.0, 0.0, 0.0};
  if (!(dot(view, f.normal) > 0.0)) return sum;
  const QuadratureRule g = gauss_hermite(order);
  for_each_hermite_slope(g, s, [&](double zx, double zy, double w) {
    const Vec3 m = facet_normal(f, zx, zy, std::sqrt(1.0 + zx * zx + zy * zy));
    const double vm = dot(view, m);
    Vec3 light{};
    for (std::size_t k = 0; k < 3; ++k) light[k] = 2.0 * vm * m[k] - view[k];
    const Vec3 radiance = sky_radiance_rgb(sky, light);  // its horizon limit below
    const double weight = w / std::numbers::pi;
    for (std::size_t k = 0; k < 3; ++k) sum[k] += weight * radiance[k];
  });
  const double fresnel = mean_fresnel(view, f, s, order, options);
  for (double& c : sum) c *= fresnel;
  return sum;
}

Vec3 refracted_sea(double mean_fresnel_value, const Vec3& sea_colour, const Vec3& e_sky) {
  OCEANREF_EXPECTS(
      mean_fresnel_value >= 0.0 && mean_fresnel_value <= 1.0,
      "a mean Fresnel reflectance in [0, 1], got " + std::to_string(mean_fresnel_value));
  Vec3 l{};
  for (std::size_t k = 0; k < 3; ++k) {
    l[k] = (1.0 - mean_fresnel_value) * sea_colour[k] * e_sky[k] / std::numbers::pi;
  }
  return l;
}

double whitecap_coverage(double mean, double variance, double threshold) {
  OCEANREF_EXPECTS(variance >= 0.0, "a variance >= 0, got " + std::to_string(variance));
  if (!(variance > 0.0)) return mean < threshold ? 1.0 : 0.0;
  return 0.5 * math::erfc((mean - threshold) / std::sqrt(2.0 * variance));
}

Vec3 foam_radiance(double albedo, const Vec3& e_sun, const Vec3& e_sky) {
  Vec3 l{};
  for (std::size_t k = 0; k < 3; ++k) l[k] = albedo * (e_sun[k] + e_sky[k]) / std::numbers::pi;
  return l;
}

Vec3 diffuse_object_radiance(const Vec3& albedo, const Vec3& normal, const Vec3& sun_direction,
                             const Vec3& sun_normal_irradiance, const Vec3& sky_irradiance) {
  const double cos_sun = std::fmax(0.0, dot(normal, sun_direction));
  const double sky_view = 0.5 * (1.0 + normal[1]);
  Vec3 l{};
  for (std::size_t k = 0; k < 3; ++k) {
    l[k] = albedo[k] * (sun_normal_irradiance[k] * cos_sun + sky_irradiance[k] * sky_view) /
           std::numbers::pi;
  }
  return l;
}

Vec3 mix_whitecaps(const Vec3& ocean, const Vec3& foam, double coverage) {
  Vec3 l{};
  for (std::size_t k = 0; k < 3; ++k) l[k] = (1.0 - coverage) * ocean[k] + coverage * foam[k];
  return l;
}

}  // namespace oceanref
