#include "shading/four_term.h"

#include <cmath>
#include <cstddef>
#include <string>

#include "core/errors.h"
#include "core/format.h"
#include "core/math.h"

namespace oceanref {

namespace {

// x², x³, x⁴, x⁵ by multiplication in a fixed order (exact powers need no transcendental).
double four_term_square(double x) {
  return x * x;
}
double four_term_cube(double x) {
  return four_term_square(x) * x;
}
double four_term_fourth(double x) {
  return four_term_square(four_term_square(x));
}
double four_term_fifth(double x) {
  return four_term_fourth(x) * x;
}

// max(x, floor) that lets NaN through (std::fmax would return the floor for a NaN x).
double four_term_at_least(double x, double floor) {
  return x < floor ? floor : x;
}

// (s·a) ⊙ b, channel by channel: a scalar weight times the product of two colours.
Vec3 four_term_weighted_product(double s, const Vec3& a, const Vec3& b) {
  return {(s * a[0]) * b[0], (s * a[1]) * b[1], (s * a[2]) * b[2]};
}

[[noreturn]] void four_term_reject(const std::string& key, const std::string& symbol,
                                   const std::string& range, double value,
                                   const std::string& where = "") {
  throw SettingError(key, "four-term shading " + key + " (" + symbol + ") must be " + range +
                              ", got " + shortest_number(value) + where);
}

void four_term_require_intensity(const char* key, const char* symbol, double value) {
  if (!(value >= 0.0 && std::isfinite(value))) {
    four_term_reject(key, symbol, "in [0, inf)", value);
  }
}

void four_term_require_colour(const char* key, const char* symbol, const Vec3& colour) {
  static constexpr const char* kChannels[3] = {"red", "green", "blue"};
  for (std::size_t c = 0; c < 3; ++c) {
    if (!(colour[c] >= 0.0 && colour[c] <= 1.0)) {
      four_term_reject(key, symbol, "in [0, 1] in each channel", colour[c],
                       std::string(" in the ") + kChannels[c] + " channel");
    }
  }
}

}  // namespace

void validate(const FourTermParameters& p) {
  four_term_require_intensity("ambient_intensity", "k_a", p.ambient_intensity);
  four_term_require_colour("ambient_colour", "C_a", p.ambient_colour);
  four_term_require_intensity("air_bubble_density", "ρ_a", p.air_bubble_density);
  four_term_require_colour("air_bubble_colour", "C_b", p.air_bubble_colour);
  four_term_require_intensity("subsurface_height_intensity", "k_ss1",
                              p.subsurface_height_intensity);
  four_term_require_intensity("subsurface_view_intensity", "k_ss2", p.subsurface_view_intensity);
  four_term_require_colour("water_scattering_colour", "C_ws", p.water_scattering_colour);
  four_term_require_colour("specular_colour", "C_s", p.specular_colour);
  if (!(p.shininess >= 1.0 && p.shininess <= 10000.0)) {
    four_term_reject("shininess", "n", "in [1, 10000]", p.shininess);
  }
  four_term_require_intensity("reflection_intensity", "k_r", p.reflection_intensity);
}

// Vincevičius eq. 2.14 (the bracket [a, b]).
double four_term_clamped_cosine(const Vec3& a, const Vec3& b) {
  return four_term_at_least(dot(a, b), 0.0);
}

// Vincevičius eq. 2.13.
double four_term_fresnel(const Vec3& view, const Vec3& normal) {
  return four_term_fifth(1.0 - four_term_at_least(dot(view, normal), 0.15));
}

// Vincevičius eq. 2.15: reflect(−D_v, N) = −D_v − 2(N·(−D_v))N = 2(D_v·N)N − D_v.
Vec3 mirror_direction(const Vec3& view, const Vec3& normal) {
  return combine(2.0 * dot(view, normal), normal, -1.0, view);
}

// Vincevičius eq. 2.12 (N read as ⟨N_y⟩₊).
Vec3 four_term_ambient(const FourTermParameters& p, const Vec3& normal, const Vec3& light_colour) {
  const double up = four_term_at_least(normal[1], 0.0);
  const Vec3 sky_lit =
      four_term_weighted_product(p.ambient_intensity * up, p.ambient_colour, light_colour);
  const Vec3 bubbles =
      four_term_weighted_product(p.air_bubble_density, p.air_bubble_colour, light_colour);
  return {sky_lit[0] + bubbles[0], sky_lit[1] + bubbles[1], sky_lit[2] + bubbles[2]};
}

// Vincevičius eq. 2.14 (L_ss1).
double wave_peak_scattering(double subsurface_height_intensity, double height, const Vec3& view,
                            const Vec3& normal, const Vec3& sun) {
  const double towards_sun = four_term_clamped_cosine(sun, scaled(view, -1.0));
  const double behind_facet = 0.5 - 0.5 * dot(sun, normal);
  return ((subsurface_height_intensity * four_term_at_least(height, 0.0)) *
          four_term_fourth(towards_sun)) *
         four_term_cube(behind_facet);
}

// Vincevičius eq. 2.14 (L_ss2).
double view_scattering(double subsurface_view_intensity, const Vec3& view, const Vec3& normal) {
  return subsurface_view_intensity * four_term_square(four_term_clamped_cosine(view, normal));
}

// Vincevičius eq. 2.14 (L_ss).
Vec3 four_term_subsurface(const FourTermParameters& p, const Vec3& view, const Vec3& normal,
                          const Vec3& sun, double height, double fresnel,
                          const Vec3& light_colour) {
  const double scattering =
      wave_peak_scattering(p.subsurface_height_intensity, height, view, normal, sun) +
      view_scattering(p.subsurface_view_intensity, view, normal);
  return four_term_weighted_product((1.0 - fresnel) * scattering, p.water_scattering_colour,
                                    light_colour);
}

// Phong eq. 1.17 (Vincevičius §1.2.9), 0 for a sun below the facet's horizon.
double phong_specular_lobe(const Vec3& view, const Vec3& normal, const Vec3& sun,
                           double shininess) {
  if (dot(sun, normal) <= 0.0) return 0.0;
  const Vec3 reflected_sun = mirror_direction(sun, normal);
  return math::pow(four_term_clamped_cosine(view, reflected_sun), shininess);
}

// Vincevičius §2.4 "Specular Reflection" with eq. 1.17.
Vec3 four_term_specular(const FourTermParameters& p, const Vec3& view, const Vec3& normal,
                        const Vec3& sun, double fresnel, const Vec3& light_colour) {
  const double lobe = phong_specular_lobe(view, normal, sun, p.shininess);
  return four_term_weighted_product(fresnel * lobe, p.specular_colour, light_colour);
}

// Vincevičius eq. 2.15.
Vec3 four_term_reflection(const Vec3& sky_radiance_at_mirror, double fresnel,
                          double reflection_intensity) {
  return scaled(sky_radiance_at_mirror, fresnel * reflection_intensity);
}

// Vincevičius eq. 2.11–2.15.
FourTermRadiance four_term_shading(const FourTermParameters& p, const Vec3& view,
                                   const Vec3& normal, const Vec3& sun_direction, double height,
                                   const Vec3& light_colour, const Vec3& sky_at_mirror) {
  const double fresnel = four_term_fresnel(view, normal);
  FourTermRadiance r;
  r.ambient = four_term_ambient(p, normal, light_colour);
  r.subsurface =
      four_term_subsurface(p, view, normal, sun_direction, height, fresnel, light_colour);
  r.specular = four_term_specular(p, view, normal, sun_direction, fresnel, light_colour);
  r.reflection = four_term_reflection(sky_at_mirror, fresnel, p.reflection_intensity);
  return r;
}

// Vincevičius eq. 2.11.
Vec3 four_term_total(const FourTermRadiance& r) {
  Vec3 sum{};
  for (std::size_t c = 0; c < 3; ++c) {
    sum[c] = ((r.ambient[c] + r.subsurface[c]) + r.specular[c]) + r.reflection[c];
  }
  return sum;
}

}  // namespace oceanref
