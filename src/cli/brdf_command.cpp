#include "cli/brdf_command.h"

#include <cmath>
#include <memory>
#include <numbers>
#include <ostream>
#include <string>

#include "cli/text.h"
#include "core/choice.h"
#include "core/math.h"
#include "shading/lighting_terms.h"

namespace oceanref::cli {

namespace {
constexpr NumberRange kTurbidityRange{kMinTurbidity, kMaxTurbidity};

struct BrdfFlags {
  std::string view, sun, normal = "0,1,0", sigma2, wind = "0", turbidity = "2.5",
                         sea = "0.0039216,0.0156863,0.0470588", fresnel = "exact", erfc = "exact",
                         accuracy = "reference";
  ShadingSettings defaults;  // the renderer's: the same settings give the same numbers
  double tolerance = defaults.tolerance;
  int order = defaults.sky_order;
  int sun_order = defaults.sun_order;
};

void row(std::ostream& out, const std::string& name, double v) {
  out << name << ',' << format_number(v) << '\n';
}
void rows(std::ostream& out, const std::string& name, const Vec3& v) {
  row(out, name + ".R", v[0]);
  row(out, name + ".G", v[1]);
  row(out, name + ".B", v[2]);
}
// A term and its estimated error: NAME.R, NAME.G, NAME.B, NAME.R_error, ….
void rows(std::ostream& out, const std::string& name, const Vec3& v, const Vec3& error) {
  rows(out, name, v);
  row(out, name + ".R_error", error[0]);
  row(out, name + ".G_error", error[1]);
  row(out, name + ".B_error", error[2]);
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
      ->capture_default_str()
      ->check(number_in(kDegreesRange));
  cmd->add_option("--turbidity", f->turbidity, "turbidity")
      ->capture_default_str()
      ->check(number_in(kTurbidityRange));
  cmd->add_option("--sea-colour", f->sea,
                  "r,g,b sea colour (the demo's 10/255, 40/255, 120/255 x 0.1)")
      ->capture_default_str();
  cmd->add_option("--accuracy", f->accuracy,
                  "reference (each integral converged to --tolerance, with its error estimate) | "
                  "fast (fixed orders --order, --sun-order; errors are |fast - reference| + the "
                  "reference's estimate); as the scene key shading.accuracy")
      ->capture_default_str();
  cmd->add_option("--tolerance", f->tolerance,
                  "reference: relative tolerance of each integral, in [1e-10, 1e-2]")
      ->check(number_in(kMinLightingTolerance, kMaxLightingTolerance))
      ->capture_default_str();
  cmd->add_option("--order", f->order,
                  "fast: Gauss-Hermite order per axis for the sky and mean Fresnel, 1-1024")
      ->check(integer_in(1, kMaxQuadratureOrder))
      ->capture_default_str();
  cmd->add_option("--sun-order", f->sun_order,
                  "fast: Gauss-Legendre order over the sun disk (0: point sun), 0-256")
      ->check(integer_in(0, 256))
      ->capture_default_str();
  cmd->add_option("--fresnel", f->fresnel, "exact | schlick")->capture_default_str();
  cmd->add_option("--erfc", f->erfc, "exact | rational")->capture_default_str();
  return [f, cmd](std::ostream& out) {
    const Vec3 view = parse_unit_vector("--view", f->view);
    const Vec3 sun = parse_unit_vector("--sun", f->sun);
    const Vec3 normal = parse_unit_vector("--normal", f->normal);
    const std::vector<double> s2 = parse_number_list("--sigma2", f->sigma2, "[1e-06, 1] each");
    if (s2.size() != 2 || s2[0] < 1e-6 || s2[0] > 1.0 || s2[1] < 1e-6 || s2[1] > 1.0) {
      throw UsageError("--sigma2", "expected sx,sy with each in [1e-6, 1], got '" +
                                       escape_value(f->sigma2) + "'");
    }
    const double wind = parse_number_in("--wind-deg", f->wind, kDegreesRange);
    const double turbidity = parse_number_in("--turbidity", f->turbidity, kTurbidityRange);
    const std::vector<double> sea = parse_number_list("--sea-colour", f->sea, "[0, 1] each");
    if (sea.size() != 3 || sea[0] < 0 || sea[1] < 0 || sea[2] < 0 || sea[0] > 1 || sea[1] > 1 ||
        sea[2] > 1) {
      throw UsageError("--sea-colour",
                       "expected r,g,b each in [0, 1], got '" + escape_value(f->sea) + "'");
    }
    BrdfOptions options;
    options.fresnel = parse_choice<UsageError>(kShadingFresnelForms, "--fresnel", f->fresnel);
    options.erfc = parse_choice<UsageError>(kErfcForms, "--erfc", f->erfc);
    ShadingSettings shading;
    shading.brdf = options;
    shading.sea_colour = {sea[0], sea[1], sea[2]};
    shading.accuracy = parse_choice<UsageError>(kLightingAccuracies, "--accuracy", f->accuracy);
    const bool fast = shading.accuracy == LightingAccuracy::fast;
    if (fast && cmd->count("--tolerance") > 0) {
      throw UsageError("--tolerance", "applies to --accuracy reference only");
    }
    for (const char* flag : {"--order", "--sun-order"}) {
      if (!fast && cmd->count(flag) > 0) {
        throw UsageError(flag,
                         "applies to --accuracy fast only (reference converges to "
                         "--tolerance)");
      }
    }
    shading.tolerance = f->tolerance;
    shading.sky_order = f->order;
    shading.sun_order = f->sun_order;
    const double sun_zenith = math::acos(std::fmin(std::fmax(sun[1], -1.0), 1.0));
    const Sky sky = make_sky(turbidity, sun_zenith, math::atan2(sun[2], sun[0]));
    const SurfaceFrame frame = wind_frame(normal, wind * std::numbers::pi / 180.0);
    const SlopeVariance s{s2[0], s2[1]};
    const BrdfTerms t = ocean_brdf(sun, view, frame, s, options);
    const FrameLighting light = frame_lighting(sky, shading);
    const LightingTerms terms = lighting_terms(shading, sky, light, view, frame, s, true);
    // The shortcuts of real-time shaders, with this mode's F̄ and a Gauss–Hermite rule (the fast
    // order, or 64 for reference) for the filtered sky.
    const int shortcut_order = fast ? f->order : 64;
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
    row(out, "F_mean", terms.mean_fresnel);
    row(out, "F_mean_error", terms.mean_fresnel_error);
    row(out, "F_mean_fit", mean_fresnel_fit(view, frame, s));
    row(out, "sun_reflectance", terms.sun_reflectance);
    row(out, "sun_reflectance_error", terms.sun_reflectance_error);
    rows(out, "L_sun_incident", light.sun_radiance);
    rows(out, "L_sun", terms.sun, terms.sun_error);
    rows(out, "L_sky", terms.sky, terms.sky_error);
    rows(out, "L_sky_filtered",
         reflected_sky_filtered(view, frame, s, sky, shortcut_order, options));
    rows(out, "L_sky_mirror", reflected_sky_mirror(view, frame, s, sky, shortcut_order, options));
    rows(out, "E_sky", light.sky_irradiance);
    rows(out, "L_sea", terms.sea, terms.sea_error);
    row(out, "evaluations", static_cast<double>(terms.evaluations));
    row(out, "converged", terms.converged ? 1.0 : 0.0);
  };
}

}  // namespace oceanref::cli
