#include "cli/brdf_command.h"

#include <cmath>
#include <memory>
#include <numbers>
#include <ostream>
#include <string>

#include "cli/text.h"
#include "core/math.h"
#include "shading/ocean_lighting.h"

namespace oceanref::cli {

namespace {
struct BrdfFlags {
  std::string view, sun, normal = "0,1,0", sigma2, wind = "0", turbidity = "2.5",
                         sea = "0.0039216,0.0156863,0.0470588", fresnel = "exact", erfc = "exact";
  int order = 32;
  int sun_order = 8;
};

void row(std::ostream& out, const std::string& name, double v) {
  out << name << ',' << format_number(v) << '\n';
}
void rows(std::ostream& out, const std::string& name, const Vec3& v) {
  row(out, name + ".R", v[0]);
  row(out, name + ".G", v[1]);
  row(out, name + ".B", v[2]);
}
}  // namespace

std::function<void(std::ostream&)> add_brdf_command(CLI::App& app) {
  auto f = std::make_shared<BrdfFlags>();
  CLI::App* cmd = app.add_subcommand(
      "brdf",
      "Every term of the Bruneton 2010 ocean BRDF and lighting for one view, sun and normal: "
      "p, Lambda_V, Lambda_L, F, mean Fresnel (exact and fit), reflected sun, sky and sea light "
      "(CSV quantity,value; radiance in cd/m^2 per linear sRGB channel).");
  cmd->add_option("--view", f->view, "x,y,z towards the viewer (+Y up)")->required();
  cmd->add_option("--sun", f->sun, "x,y,z towards the sun (its zenith angle sets the sky)")
      ->required();
  cmd->add_option("--normal", f->normal, "x,y,z mean surface normal")->capture_default_str();
  cmd->add_option("--sigma2", f->sigma2, "sx,sy slope variances upwind and crosswind, in [1e-6, 1]")
      ->required();
  cmd->add_option("--wind-deg", f->wind, "wind direction angle [deg] (upwind tangent)")
      ->capture_default_str();
  cmd->add_option("--turbidity", f->turbidity, "turbidity in [2, 10]")->capture_default_str();
  cmd->add_option("--sea-colour", f->sea,
                  "r,g,b sea colour (the demo's 10/255, 40/255, 120/255 x 0.1)")
      ->capture_default_str();
  cmd->add_option("--order", f->order, "Gauss-Hermite order per axis for the sky and mean Fresnel")
      ->check(CLI::Range(1, 512))
      ->capture_default_str();
  cmd->add_option("--sun-order", f->sun_order,
                  "Gauss-Legendre order over the sun disk (0: point sun)")
      ->check(CLI::Range(0, 256))
      ->capture_default_str();
  cmd->add_option("--fresnel", f->fresnel, "exact | schlick")->capture_default_str();
  cmd->add_option("--erfc", f->erfc, "exact | rational")->capture_default_str();
  return [f](std::ostream& out) {
    const Vec3 view = parse_unit_vector("--view", f->view);
    const Vec3 sun = parse_unit_vector("--sun", f->sun);
    const Vec3 normal = parse_unit_vector("--normal", f->normal);
    const std::vector<double> s2 = parse_number_list("--sigma2", f->sigma2);
    if (s2.size() != 2 || s2[0] < 1e-6 || s2[0] > 1.0 || s2[1] < 1e-6 || s2[1] > 1.0) {
      throw UsageError("--sigma2",
                       "expected sx,sy with each in [1e-6, 1], got '" + f->sigma2 + "'");
    }
    const double wind = parse_number("--wind-deg", f->wind);
    if (std::fabs(wind) > 720.0) throw UsageError("--wind-deg", "must be in [-720, 720]");
    const double turbidity = parse_number("--turbidity", f->turbidity);
    if (turbidity < kMinTurbidity || turbidity > kMaxTurbidity) {
      throw UsageError("--turbidity", "must be in [2, 10], got " + f->turbidity);
    }
    const std::vector<double> sea = parse_number_list("--sea-colour", f->sea);
    if (sea.size() != 3 || sea[0] < 0 || sea[1] < 0 || sea[2] < 0 || sea[0] > 1 || sea[1] > 1 ||
        sea[2] > 1) {
      throw UsageError("--sea-colour", "expected r,g,b each in [0, 1]");
    }
    BrdfOptions options;
    if (f->fresnel == "schlick") {
      options.fresnel = FresnelForm::schlick;
    } else if (f->fresnel != "exact") {
      throw UsageError("--fresnel", "expected exact or schlick, got '" + f->fresnel + "'");
    }
    if (f->erfc == "rational") {
      options.erfc = ErfcForm::rational;
    } else if (f->erfc != "exact") {
      throw UsageError("--erfc", "expected exact or rational, got '" + f->erfc + "'");
    }
    const double sun_zenith = math::acos(std::fmin(std::fmax(sun[1], -1.0), 1.0));
    const Sky sky = make_sky(turbidity, sun_zenith, math::atan2(sun[2], sun[0]));
    const SurfaceFrame frame = wind_frame(normal, wind * std::numbers::pi / 180.0);
    const SlopeVariance s{s2[0], s2[1]};
    const BrdfTerms t = ocean_brdf(sun, view, frame, s, options);
    const double fresnel_mean = mean_fresnel(view, frame, s, f->order, options);
    const double reflected =
        reflected_sun(sun, kSunAngularRadius, view, frame, s, f->sun_order, options);
    const Vec3 l_sun = sun_radiance_rgb(sky);
    const SkyIrradiance e_sky = sky_irradiance(sky);
    out << "quantity,value\n";
    row(out, "zeta_x", t.zeta_x);
    row(out, "zeta_y", t.zeta_y);
    row(out, "p", t.p);
    row(out, "sigma2_view", t.sigma2_view);
    row(out, "sigma2_sun", t.sigma2_light);
    row(out, "Lambda_V", t.lambda_view);
    row(out, "Lambda_L", t.lambda_light);
    row(out, "F", t.fresnel);
    row(out, "brdf_cos", t.brdf_cos);
    row(out, "F_mean", fresnel_mean);
    row(out, "F_mean_fit", mean_fresnel_fit(view, frame, s));
    row(out, "sun_reflectance", reflected);
    rows(out, "L_sun_incident", l_sun);
    rows(out, "L_sun", {reflected * l_sun[0], reflected * l_sun[1], reflected * l_sun[2]});
    rows(out, "L_sky", reflected_sky(view, frame, s, sky, f->order, options));
    rows(out, "L_sky_filtered", reflected_sky_filtered(view, frame, s, sky, f->order, options));
    rows(out, "L_sky_mirror", reflected_sky_mirror(view, frame, s, sky, f->order, options));
    rows(out, "E_sky", e_sky.rgb);
    rows(out, "L_sea", refracted_sea(fresnel_mean, {sea[0], sea[1], sea[2]}, e_sky.rgb));
  };
}

}  // namespace oceanref::cli
