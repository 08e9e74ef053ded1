#include "cli/sky_command.h"

#include <cmath>
#include <memory>
#include <numbers>
#include <ostream>
#include <string>

#include "cli/text.h"
#include "core/math.h"
#include "io/exr.h"
#include "io/output_file.h"
#include "sky/preetham.h"

namespace oceanref::cli {

namespace {
constexpr double kDegree = std::numbers::pi / 180.0;
constexpr NumberRange kZenithRange{0.0, 180.0, " degrees"};
constexpr NumberRange kTurbidityRange{kMinTurbidity, kMaxTurbidity};

struct SkyFlags {
  std::string zenith, azimuth = "0", turbidity = "2.5", dir, output;
  bool sun = false;
  bool irradiance = false;
  bool printed = false;
  int size = 0;
};

void write_directions(std::ostream& out, const Sky& sky, const std::string& list) {
  out << "x,y,z,Y,chroma_x,chroma_y,R,G,B\n";
  std::size_t start = 0;
  while (true) {
    const std::size_t end = list.find(';', start);
    const Vec3 d = parse_unit_vector("--dir", list.substr(start, end - start));
    const Chromaticity c = sky_chromaticity(sky, d);
    const Vec3 rgb = sky_radiance_rgb(sky, d);
    out << format_number(d[0]) << ',' << format_number(d[1]) << ',' << format_number(d[2]) << ','
        << format_number(c.Y) << ',' << format_number(c.x) << ',' << format_number(c.y) << ','
        << format_number(rgb[0]) << ',' << format_number(rgb[1]) << ',' << format_number(rgb[2])
        << '\n';
    if (end == std::string::npos) break;
    start = end + 1;
  }
}

// The upper hemisphere in an equidistant polar projection: pixel centre (u, v) ∈ [−1, 1]²,
// r = √(u² + v²) ≤ 1 ↦ zenith angle θ = r·π/2, azimuth φ = atan2(v, u) (u along +X, v along +Z);
// outside the disk 0. The sun disk (angular radius 0.2667°) is added where a pixel centre falls
// inside it.
void write_hemisphere(const std::string& path, const Sky& sky, int n, TransmittanceForm form) {
  ExrImage image;
  image.width = n;
  image.height = n;
  std::vector<float> r(static_cast<std::size_t>(n) * static_cast<std::size_t>(n));
  std::vector<float> g(r.size()), b(r.size()), y(r.size());
  const Vec3 sun = sun_radiance_rgb(sky, form);
  const double sun_luminance = sun_radiance_xyz(sky, form)[1];
  const double cos_sun_radius = math::cos(kSunAngularRadius);
  for (int row = 0; row < n; ++row) {
    for (int column = 0; column < n; ++column) {
      const double u = (2.0 * column + 1.0) / n - 1.0;
      const double v = (2.0 * row + 1.0) / n - 1.0;
      const double radius = std::sqrt(u * u + v * v);
      if (radius > 1.0) continue;
      const Vec3 d = direction_from_angles(0.5 * std::numbers::pi * radius, math::atan2(v, u));
      Vec3 rgb = sky_radiance_rgb(sky, d);
      double luminance = sky_chromaticity(sky, d).Y;
      const Vec3& s = sky.sun_direction;
      if (d[0] * s[0] + d[1] * s[1] + d[2] * s[2] >= cos_sun_radius) {
        for (std::size_t c = 0; c < 3; ++c) rgb[c] += sun[c];
        luminance += sun_luminance;
      }
      const std::size_t i = static_cast<std::size_t>(row) * static_cast<std::size_t>(n) +
                            static_cast<std::size_t>(column);
      r[i] = static_cast<float>(rgb[0]);
      g[i] = static_cast<float>(rgb[1]);
      b[i] = static_cast<float>(rgb[2]);
      y[i] = static_cast<float>(luminance);
    }
  }
  image.channels = {{"R", 1, r}, {"G", 1, g}, {"B", 1, b}, {"Y", 1, y}};
  image.attributes["oceanref.units"] = "linear sRGB (D65) radiance in cd/m^2; Y luminance cd/m^2";
  image.attributes["oceanref.projection"] =
      "equidistant polar: pixel centre (u, v) in [-1, 1]^2, zenith angle = |(u, v)| * 90 deg, "
      "azimuth = atan2(v, u) from +X towards +Z; outside the unit disk 0";
  image.attributes["oceanref.sky"] = "Preetham 1999, turbidity " + format_number(sky.turbidity) +
                                     ", sun zenith " + format_number(sky.sun_zenith / kDegree) +
                                     " deg";
  write_exr(path, image);
}
}  // namespace

std::function<void(std::ostream&)> add_sky_command(CLI::App& app) {
  auto flags = std::make_shared<SkyFlags>();
  CLI::App* cmd = app.add_subcommand(
      "sky",
      "The Preetham 1999 sky and sun: radiance in given directions (--dir), the sun disk "
      "(--sun), the horizontal sky irradiance (--irradiance) or the hemisphere as EXR (--size, "
      "-o). Radiance in cd/m^2 per linear sRGB (D65) channel.");
  cmd->add_option("--sun-zenith-deg", flags->zenith,
                  "sun zenith angle [deg]; above 90 the sun has set (sun radiance 0, sky at its "
                  "90-degree limit)")
      ->required()
      ->check(number_in(kZenithRange));
  cmd->add_option("--sun-azimuth-deg", flags->azimuth, "sun azimuth [deg], from +X towards +Z")
      ->capture_default_str()
      ->check(number_in(kDegreesRange));
  cmd->add_option("--turbidity", flags->turbidity, "turbidity T")
      ->capture_default_str()
      ->check(number_in(kTurbidityRange));
  auto* dir = cmd->add_option("--dir", flags->dir,
                              "x,y,z[;x,y,z...] (+Y up) -> CSV x,y,z,Y,chroma_x,chroma_y,R,G,B "
                              "(sky only; below the horizon, y <= 0, its horizon limit)");
  auto* sun = cmd->add_flag("--sun", flags->sun,
                            "CSV Y,chroma_x,chroma_y,R,G,B,angular_radius_rad of the sun disk");
  auto* irradiance = cmd->add_flag(
      "--irradiance", flags->irradiance,
      "CSV E_Y,E_X,E_Z,R,G,B,relative_error: horizontal irradiance of the sky dome (lx for E_Y), "
      "sun excluded, by adaptive quadrature");
  auto* size = cmd->add_option("--size", flags->size, "hemisphere image size N (with -o)")
                   ->check(integer_in(1, 8192));
  auto* output = cmd->add_option("-o,--output", flags->output, "sky.exr (with --size)");
  cmd->add_flag("--printed-transmittance", flags->printed,
                "Rayleigh and aerosol transmittance as printed in Preetham's appendix "
                "(exponent -4.08 m instead of factor m)");
  size->needs(output);
  output->needs(size);
  dir->excludes(sun)->excludes(irradiance)->excludes(size);
  sun->excludes(irradiance)->excludes(size);
  irradiance->excludes(size);
  return [flags](std::ostream& out) {
    check_output_paths({{"--output", flags->output}}, {});
    const double zenith = parse_number_in("--sun-zenith-deg", flags->zenith, kZenithRange);
    const double azimuth = parse_number_in("--sun-azimuth-deg", flags->azimuth, kDegreesRange);
    const double turbidity = parse_number_in("--turbidity", flags->turbidity, kTurbidityRange);
    const Sky sky = make_sky(turbidity, zenith * kDegree, azimuth * kDegree);
    const TransmittanceForm form =
        flags->printed ? TransmittanceForm::printed : TransmittanceForm::physical;
    if (!flags->dir.empty()) {
      write_directions(out, sky, flags->dir);
    } else if (flags->sun) {
      const Vec3 xyz = sun_radiance_xyz(sky, form);
      const Vec3 rgb = xyz_to_linear_srgb(xyz);
      const double sum = xyz[0] + xyz[1] + xyz[2];
      out << "Y,chroma_x,chroma_y,R,G,B,angular_radius_rad\n"
          << format_number(xyz[1]) << ',' << format_number(sum > 0.0 ? xyz[0] / sum : 0.0) << ','
          << format_number(sum > 0.0 ? xyz[1] / sum : 0.0) << ',' << format_number(rgb[0]) << ','
          << format_number(rgb[1]) << ',' << format_number(rgb[2]) << ','
          << format_number(kSunAngularRadius) << '\n';
    } else if (flags->irradiance) {
      const SkyIrradiance e = sky_irradiance(sky);
      out << "E_Y,E_X,E_Z,R,G,B,relative_error\n"
          << format_number(e.xyz[1]) << ',' << format_number(e.xyz[0]) << ','
          << format_number(e.xyz[2]) << ',' << format_number(e.rgb[0]) << ','
          << format_number(e.rgb[1]) << ',' << format_number(e.rgb[2]) << ','
          << format_number(e.relative_error) << '\n';
    } else if (flags->size != 0 || !flags->output.empty()) {
      write_hemisphere(flags->output, sky, flags->size, form);
    } else {
      throw UsageError("sky", "give one of --dir, --sun, --irradiance or --size N -o sky.exr");
    }
  };
}

}  // namespace oceanref::cli
