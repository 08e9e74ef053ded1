#include "sky/preetham.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/fp_environment.h"
#include "core/math.h"
#include "core/quadrature.h"
#include "core/vec3.h"
#include "sky/spectral_tables.h"

namespace oceanref {

namespace {
constexpr double kPi = std::numbers::pi;

// γ, the angle between two unit vectors, accurate also for tiny angles.
double angle_between(const Vec3& a, const Vec3& b) {
  const Vec3 d{a[0] - b[0], a[1] - b[1], a[2] - b[2]};
  const Vec3 s{a[0] + b[0], a[1] + b[1], a[2] + b[2]};
  return 2.0 * math::atan2(length(d), length(s));
}

double zenith_chromaticity(double t, double theta, const double (&m)[3][4]) {
  const double th[4] = {theta * theta * theta, theta * theta, theta, 1.0};
  const double tt[3] = {t * t, t, 1.0};
  double sum = 0.0;
  for (int i = 0; i < 3; ++i) {
    double row = 0.0;
    for (int j = 0; j < 4; ++j) row += m[i][j] * th[j];
    sum += tt[i] * row;
  }
  return sum;
}
}  // namespace

PerezCoefficients perez_luminance_coefficients(double t) {
  return {0.1787 * t - 1.4630, -0.3554 * t + 0.4275, -0.0227 * t + 5.3251, 0.1206 * t - 2.5771,
          -0.0670 * t + 0.3703};
}

PerezCoefficients perez_x_coefficients(double t) {
  return {-0.0193 * t - 0.2592, -0.0665 * t + 0.0008, -0.0004 * t + 0.2125, -0.0641 * t - 0.8989,
          -0.0033 * t + 0.0452};
}

PerezCoefficients perez_y_coefficients(double t) {
  return {-0.0167 * t - 0.2608, -0.0950 * t + 0.0092, -0.0079 * t + 0.2102, -0.0441 * t - 1.6537,
          -0.0109 * t + 0.0529};
}

double perez(const PerezAngles& p, const PerezCoefficients& k) {
  const double horizon = p.cos_theta > 0.0 ? math::exp(k.b / p.cos_theta) : 0.0;  // B < 0
  return (1.0 + k.a * horizon) *
         (1.0 + k.c * math::exp(k.d * p.gamma) + k.e * p.cos_gamma * p.cos_gamma);
}

double perez(double theta, double gamma, const PerezCoefficients& k) {
  return perez({math::cos(theta), gamma, math::cos(gamma)}, k);
}

double zenith_luminance(double t, double theta_s) {
  const double chi = (4.0 / 9.0 - t / 120.0) * (kPi - 2.0 * theta_s);
  return 1000.0 * ((4.0453 * t - 4.9710) * math::tan(chi) - 0.2155 * t + 2.4192);
}

double zenith_chromaticity_x(double t, double theta_s) {
  static constexpr double m[3][4] = {{0.00166, -0.00375, 0.00209, 0.0},
                                     {-0.02903, 0.06377, -0.03202, 0.00394},
                                     {0.11693, -0.21196, 0.06052, 0.25886}};
  return zenith_chromaticity(t, theta_s, m);
}

double zenith_chromaticity_y(double t, double theta_s) {
  static constexpr double m[3][4] = {{0.00275, -0.00610, 0.00317, 0.0},
                                     {-0.04214, 0.08970, -0.04153, 0.00516},
                                     {0.15346, -0.26756, 0.06670, 0.26688}};
  return zenith_chromaticity(t, theta_s, m);
}

Vec3 direction_from_angles(double zenith, double azimuth) {
  return {math::sin(zenith) * math::cos(azimuth), math::cos(zenith),
          math::sin(zenith) * math::sin(azimuth)};
}

Sky make_sky(double turbidity, double sun_zenith, double sun_azimuth) {
  const ReferenceFpEnvironment fp;
  if (!(turbidity >= kMinTurbidity && turbidity <= kMaxTurbidity)) {
    throw std::invalid_argument("turbidity must be in [2, 10] (Preetham's fitted range), got " +
                                std::to_string(turbidity));
  }
  if (!(sun_zenith >= 0.0 && sun_zenith <= kPi)) {
    throw std::invalid_argument("sun zenith angle must be in [0, pi] rad ([0, 180] degrees), got " +
                                std::to_string(sun_zenith));
  }
  if (!std::isfinite(sun_azimuth)) {
    throw std::invalid_argument("sun azimuth must be finite, got " + std::to_string(sun_azimuth));
  }
  Sky s{};
  s.turbidity = turbidity;
  s.sun_direction = direction_from_angles(sun_zenith, sun_azimuth);
  s.sun_zenith = sun_zenith;
  s.model_sun_zenith = std::fmin(sun_zenith, 0.5 * kPi);
  s.luminance = perez_luminance_coefficients(turbidity);
  s.x = perez_x_coefficients(turbidity);
  s.y = perez_y_coefficients(turbidity);
  s.zenith_luminance = zenith_luminance(turbidity, s.model_sun_zenith);
  s.zenith_x = zenith_chromaticity_x(turbidity, s.model_sun_zenith);
  s.zenith_y = zenith_chromaticity_y(turbidity, s.model_sun_zenith);
  // γ is measured to the sun held at the horizon when it has set.
  s.model_sun_direction = direction_from_angles(
      s.model_sun_zenith, math::atan2(s.sun_direction[2], s.sun_direction[0]));
  s.perez_at_zenith_luminance = perez(0.0, s.model_sun_zenith, s.luminance);
  s.perez_at_zenith_x = perez(0.0, s.model_sun_zenith, s.x);
  s.perez_at_zenith_y = perez(0.0, s.model_sun_zenith, s.y);
  return s;
}

Chromaticity sky_chromaticity(const Sky& sky, const Vec3& direction) {
  // For the unit direction d and sun s: cos θ = d_y and cos γ = d·s, with γ from the accurate
  // half-angle form (one transcendental for the three coefficient sets). Below the horizon
  // (d_y ≤ 0) cos θ is held at 0, where the gradation factor 1 + A e^{B/cos θ} reaches its limit
  // 1 with every derivative 0 (B < 0): the sky is continued smoothly by its horizon (README,
  // "Sky below the horizon").
  const PerezAngles angles{std::clamp(direction[1], 0.0, 1.0),
                           angle_between(direction, sky.model_sun_direction),
                           std::clamp(dot(direction, sky.model_sun_direction), -1.0, 1.0)};
  return {sky.zenith_x * perez(angles, sky.x) / sky.perez_at_zenith_x,
          sky.zenith_y * perez(angles, sky.y) / sky.perez_at_zenith_y,
          sky.zenith_luminance * perez(angles, sky.luminance) / sky.perez_at_zenith_luminance};
}

Vec3 sky_radiance_xyz(const Sky& sky, const Vec3& direction) {
  const Chromaticity c = sky_chromaticity(sky, direction);
  return xyY_to_XYZ(c.x, c.y, c.Y);
}

Vec3 sky_radiance_rgb(const Sky& sky, const Vec3& direction) {
  return xyz_to_linear_srgb(sky_radiance_xyz(sky, direction));
}

double relative_optical_mass(double sun_zenith) {
  const double degrees = sun_zenith * 180.0 / kPi;
  return 1.0 / (math::cos(sun_zenith) + 0.15 * math::pow(93.885 - degrees, -1.253));
}

double angstrom_beta(double turbidity) {
  return 0.04608 * turbidity - 0.04586;
}

double rayleigh_transmittance(double wavelength, double mass, TransmittanceForm form) {
  const double micrometres = wavelength / 1000.0;
  if (form == TransmittanceForm::printed) {
    return math::exp(-0.008735 * math::pow(micrometres, -4.08 * mass));
  }
  return math::exp(-mass * 0.008735 * math::pow(micrometres, -4.08));
}

double aerosol_transmittance(double wavelength, double mass, double beta, TransmittanceForm form) {
  constexpr double alpha = 1.3;  // Ångström exponent (Preetham A.5)
  const double micrometres = wavelength / 1000.0;
  if (form == TransmittanceForm::printed) {
    return math::exp(-beta * math::pow(micrometres, -alpha * mass));
  }
  return math::exp(-mass * beta * math::pow(micrometres, -alpha));
}

double ozone_transmittance(double wavelength, double mass) {
  constexpr double ozone_thickness = 0.35;  // l [cm NTP]
  return math::exp(-interpolate(kOzoneAbsorption, wavelength) * ozone_thickness * mass);
}

double mixed_gas_transmittance(double wavelength, double mass) {
  const double k = interpolate(kMixedGasAbsorption, wavelength) * mass;
  return math::exp(-1.41 * k / math::pow(1.0 + 118.93 * k, 0.45));
}

double water_vapour_transmittance(double wavelength, double mass) {
  constexpr double precipitable_water = 2.0;  // w [cm]
  const double k = interpolate(kWaterVapourAbsorption, wavelength) * precipitable_water * mass;
  return math::exp(-0.2385 * k / math::pow(1.0 + 20.07 * k, 0.45));
}

namespace {
double extraterrestrial_radiance(double wavelength) {
  if (wavelength < 380.0 || wavelength > 750.0) return 0.0;
  const double u = (wavelength - 380.0) / 10.0;
  const auto i = static_cast<std::size_t>(std::fmin(std::floor(u), 36.0));
  const double t = u - static_cast<double>(i);
  const double a = kExtraterrestrialSolarRadiance[i];
  const double b = kExtraterrestrialSolarRadiance[i + 1];
  return kSolarRadianceUnit * (a + t * (b - a));
}
}  // namespace

double sun_spectral_radiance(double wavelength, double sun_zenith, double turbidity,
                             TransmittanceForm form) {
  if (!(sun_zenith < 0.5 * kPi)) return 0.0;
  const double m = relative_optical_mass(sun_zenith);
  return extraterrestrial_radiance(wavelength) * rayleigh_transmittance(wavelength, m, form) *
         aerosol_transmittance(wavelength, m, angstrom_beta(turbidity), form) *
         ozone_transmittance(wavelength, m) * mixed_gas_transmittance(wavelength, m) *
         water_vapour_transmittance(wavelength, m);
}

Vec3 sun_radiance_xyz(const Sky& sky, TransmittanceForm form) {
  Vec3 xyz{0.0, 0.0, 0.0};
  for (std::size_t i = 0; i < kCie1931Observer.size(); ++i) {
    const ColorMatchingSample& c = kCie1931Observer[i];
    const double weight = (i == 0 || i + 1 == kCie1931Observer.size()) ? 2.5 : 5.0;  // trapezoid
    const double l = sun_spectral_radiance(c.wavelength, sky.sun_zenith, sky.turbidity, form);
    xyz[0] += weight * l * c.x;
    xyz[1] += weight * l * c.y;
    xyz[2] += weight * l * c.z;
  }
  for (double& v : xyz) v *= kLuminousEfficacy;
  return xyz;
}

Vec3 sun_radiance_rgb(const Sky& sky, TransmittanceForm form) {
  return xyz_to_linear_srgb(sun_radiance_xyz(sky, form));
}

SkyIrradiance sky_irradiance(const Sky& sky, double relative_tolerance) {
  const double sun_azimuth = math::atan2(sky.sun_direction[2], sky.sun_direction[0]);
  const QuadratureTolerance inner_tolerance{relative_tolerance * 0.1, 0.0, 4000};
  const QuadratureTolerance outer_tolerance{relative_tolerance, 0.0, 4000};
  // θ breakpoints: the sun's zenith angle (circumsolar peak), ascending.
  std::vector<double> thetas{0.0, 0.25 * kPi, 0.5 * kPi};
  const double sun_theta = sky.model_sun_zenith;
  if (sun_theta > 1e-3 && sun_theta < 0.5 * kPi - 1e-3 &&
      std::fabs(sun_theta - 0.25 * kPi) > 1e-3) {
    thetas.push_back(sun_theta);
    std::sort(thetas.begin(), thetas.end());
  }
  SkyIrradiance out{};
  for (std::size_t component = 0; component < 3; ++component) {
    // E = ∫₀^{π/2} cos θ sin θ ∫_{−π}^{π} L(θ, φ) dφ dθ, φ measured from the sun's azimuth.
    const QuadratureResult r = integrate(
        [&](double theta) {
          const double ring =
              integrate(
                  [&](double phi) {
                    return sky_radiance_xyz(
                        sky, direction_from_angles(theta, phi + sun_azimuth))[component];
                  },
                  {-kPi, -0.5 * kPi, -0.05, 0.0, 0.05, 0.5 * kPi, kPi}, inner_tolerance)
                  .value;
          return math::cos(theta) * math::sin(theta) * ring;
        },
        thetas, outer_tolerance);
    out.xyz[component] = r.value;
    out.relative_error = std::fmax(out.relative_error, r.error / std::fabs(r.value));
  }
  out.rgb = xyz_to_linear_srgb(out.xyz);
  return out;
}

}  // namespace oceanref
