// Sky and BRDF probes (sky/preetham.h, shading/ocean_brdf.h) and the reference lighting
// integrals with their error estimates (shading/reference_lighting.h). Angles in degrees at the
// interface, directions +Y up, radiance in cd/m^2 per linear sRGB channel.
#include <cmath>
#include <numbers>
#include <string>

#include "common.h"
#include "core/choice.h"
#include "core/math.h"
#include "shading/reference_lighting.h"
#include "sky/preetham.h"

namespace oceanref::python {

namespace {
constexpr double kDegree = std::numbers::pi / 180.0;

// As `oceanref sky`: zenith in [0, 180], azimuth in [-720, 720], turbidity in [2, 10].
Sky sky_from(double zenith_deg, double azimuth_deg, double turbidity) {
  if (!(zenith_deg >= 0.0 && zenith_deg <= 180.0)) {
    throw ArgumentError("sun_zenith_deg", "must be in [0, 180], got " + format_number(zenith_deg));
  }
  if (!(std::fabs(azimuth_deg) <= 720.0)) {
    throw ArgumentError("sun_azimuth_deg",
                        "must be in [-720, 720], got " + format_number(azimuth_deg));
  }
  if (!(turbidity >= kMinTurbidity && turbidity <= kMaxTurbidity)) {
    throw ArgumentError("turbidity", "must be in [2, 10], got " + format_number(turbidity));
  }
  return make_sky(turbidity, zenith_deg * kDegree, azimuth_deg * kDegree);
}

py::array_t<double> vec3(const Vec3& v) {
  return to_array({v[0], v[1], v[2]}, {3});
}

// As `oceanref brdf --sigma2`: two slope variances, each in [1e-6, 1].
SlopeVariance slope_variance(const py::handle& value) {
  const DoubleArray a = DoubleArray::ensure(value);
  if (!a || a.size() != 2 || !(a.data()[0] >= 1e-6 && a.data()[0] <= 1.0) ||
      !(a.data()[1] >= 1e-6 && a.data()[1] <= 1.0)) {
    throw ArgumentError(
        "sigma2", "expected (sx, sy) with each in [1e-6, 1], got " + std::string(py::str(value)));
  }
  return {a.data()[0], a.data()[1]};
}

BrdfOptions options_from(const std::string& fresnel, const std::string& erfc) {
  BrdfOptions o;
  o.fresnel = parse_choice<ArgumentError>(kFresnelForms, "fresnel", fresnel);
  o.erfc = parse_choice<ArgumentError>(kErfcForms, "erfc", erfc);
  return o;
}

SurfaceFrame frame_from(const py::handle& normal, double wind_deg) {
  if (!(std::fabs(wind_deg) <= 720.0)) {
    throw ArgumentError("wind_deg", "must be in [-720, 720], got " + format_number(wind_deg));
  }
  return wind_frame(unit_vector("normal", normal), wind_deg * kDegree);
}

double tolerance_from(double t) {
  if (!(t >= kMinLightingTolerance && t <= kMaxLightingTolerance)) {
    throw ArgumentError("tolerance", "must be in [1e-10, 1e-2], got " + format_number(t));
  }
  return t;
}

py::dict scalar_estimate(const ScalarEstimate& e) {
  py::dict d;
  d["value"] = e.value;
  d["error"] = e.error;
  d["evaluations"] = e.evaluations;
  d["converged"] = e.converged;
  return d;
}
}  // namespace

void bind_lighting(py::module_& m) {
  m.def(
      "_sky",
      [](const DoubleArray& directions, double zenith, double azimuth, double turbidity) {
        const Sky sky = sky_from(zenith, azimuth, turbidity);
        if (directions.ndim() != 2 || directions.shape(1) != 3) {
          throw ArgumentError("direction", "expected x,y,z or an array of shape (n, 3)");
        }
        const py::ssize_t n = directions.shape(0);
        std::vector<double> rgb(static_cast<std::size_t>(3 * n));
        std::vector<double> xyY(rgb.size());
        for (py::ssize_t i = 0; i < n; ++i) {
          const py::array_t<double> row =
              to_array({directions.at(i, 0), directions.at(i, 1), directions.at(i, 2)}, {3});
          const Vec3 d = unit_vector("direction", row);
          const Vec3 c = sky_radiance_rgb(sky, d);
          const Chromaticity chroma = sky_chromaticity(sky, d);
          const std::size_t k = static_cast<std::size_t>(3 * i);
          for (std::size_t j = 0; j < 3; ++j) rgb[k + j] = c[j];
          xyY[k] = chroma.x;
          xyY[k + 1] = chroma.y;
          xyY[k + 2] = chroma.Y;
        }
        return py::make_tuple(to_array(rgb, {n, 3}), to_array(xyY, {n, 3}));
      },
      py::arg("directions"), py::arg("sun_zenith_deg"), py::arg("sun_azimuth_deg"),
      py::arg("turbidity"));
  m.def(
      "_sun",
      [](double zenith, double azimuth, double turbidity) {
        const Sky sky = sky_from(zenith, azimuth, turbidity);
        py::dict d;
        d["rgb"] = vec3(sun_radiance_rgb(sky));
        d["xyz"] = vec3(sun_radiance_xyz(sky));
        d["direction"] = vec3(sky.sun_direction);
        d["angular_radius_rad"] = kSunAngularRadius;
        return d;
      },
      py::arg("sun_zenith_deg"), py::arg("sun_azimuth_deg"), py::arg("turbidity"));
  m.def(
      "_sky_irradiance",
      [](double zenith, double azimuth, double turbidity) {
        const Sky sky = sky_from(zenith, azimuth, turbidity);
        const SkyIrradiance e = sky_irradiance(sky);
        py::dict d;
        d["rgb"] = vec3(e.rgb);
        d["xyz"] = vec3(e.xyz);
        d["relative_error"] = e.relative_error;
        return d;
      },
      py::arg("sun_zenith_deg"), py::arg("sun_azimuth_deg"), py::arg("turbidity"));
  m.def(
      "_brdf",
      [](const py::object& view, const py::object& light, const py::object& sigma2,
         const py::object& normal, double wind_deg, const std::string& fresnel,
         const std::string& erfc) {
        const BrdfTerms t = ocean_brdf(unit_vector("light", light), unit_vector("view", view),
                                       frame_from(normal, wind_deg), slope_variance(sigma2),
                                       options_from(fresnel, erfc));
        py::dict d;
        d["zeta_x"] = t.zeta_x;
        d["zeta_y"] = t.zeta_y;
        d["p"] = t.p;
        d["sigma2_view"] = t.sigma2_view;
        d["sigma2_light"] = t.sigma2_light;
        d["lambda_view"] = t.lambda_view;
        d["lambda_light"] = t.lambda_light;
        d["fresnel"] = t.fresnel;
        d["brdf_cos"] = t.brdf_cos;
        return d;
      },
      py::arg("view"), py::arg("light"), py::arg("sigma2"), py::arg("normal"), py::arg("wind_deg"),
      py::arg("fresnel"), py::arg("erfc"));
  m.def(
      "_mean_fresnel_reference",
      [](const py::object& view, const py::object& sigma2, const py::object& normal,
         double wind_deg, double tolerance, const std::string& fresnel, const std::string& erfc) {
        const auto v = unit_vector("view", view);
        const auto frame = frame_from(normal, wind_deg);
        const auto s = slope_variance(sigma2);
        const auto o = options_from(fresnel, erfc);
        const double t = tolerance_from(tolerance);
        ScalarEstimate e;
        {
          py::gil_scoped_release release;
          e = mean_fresnel_reference(v, frame, s, o, t);
        }
        return scalar_estimate(e);
      },
      py::arg("view"), py::arg("sigma2"), py::arg("normal"), py::arg("wind_deg"),
      py::arg("tolerance"), py::arg("fresnel"), py::arg("erfc"));
  m.def(
      "_reflected_sky_reference",
      [](const py::object& view, const py::object& sigma2, double zenith, double azimuth,
         double turbidity, const py::object& normal, double wind_deg, double tolerance,
         double absolute, const std::string& fresnel, const std::string& erfc) {
        const Sky sky = sky_from(zenith, azimuth, turbidity);
        const auto v = unit_vector("view", view);
        const auto frame = frame_from(normal, wind_deg);
        const auto s = slope_variance(sigma2);
        const auto o = options_from(fresnel, erfc);
        const double t = tolerance_from(tolerance);
        if (!(absolute >= 0.0 && absolute <= 1e30)) {
          throw ArgumentError("absolute",
                              "must be in [0, 1e30] cd/m^2, got " + format_number(absolute));
        }
        RgbEstimate e;
        {
          py::gil_scoped_release release;
          e = reflected_sky_reference(v, frame, s, sky, o, t, Vec3{absolute, absolute, absolute});
        }
        py::dict d;
        d["value"] = vec3(e.value);
        d["error"] = vec3(e.error);
        d["evaluations"] = e.evaluations;
        d["converged"] = e.converged;
        return d;
      },
      py::arg("view"), py::arg("sigma2"), py::arg("sun_zenith_deg"), py::arg("sun_azimuth_deg"),
      py::arg("turbidity"), py::arg("normal"), py::arg("wind_deg"), py::arg("tolerance"),
      py::arg("absolute"), py::arg("fresnel"), py::arg("erfc"));
  m.def(
      "_reflected_sun_reference",
      [](const py::object& view, const py::object& sun, const py::object& sigma2, double sun_radius,
         const py::object& normal, double wind_deg, double tolerance, double absolute,
         const std::string& fresnel, const std::string& erfc) {
        const auto v = unit_vector("view", view);
        const auto l = unit_vector("sun", sun);
        const auto frame = frame_from(normal, wind_deg);
        const auto s = slope_variance(sigma2);
        const auto o = options_from(fresnel, erfc);
        const double t = tolerance_from(tolerance);
        if (!(sun_radius > 0.0 && sun_radius <= 0.1)) {
          throw ArgumentError("sun_radius",
                              "must be in (0, 0.1] rad, got " + format_number(sun_radius));
        }
        if (!(absolute >= 0.0 && absolute <= 1e30)) {
          throw ArgumentError("absolute", "must be in [0, 1e30], got " + format_number(absolute));
        }
        ScalarEstimate e;
        {
          py::gil_scoped_release release;
          e = reflected_sun_reference(l, sun_radius, v, frame, s, o, t, absolute);
        }
        return scalar_estimate(e);
      },
      py::arg("view"), py::arg("sun"), py::arg("sigma2"), py::arg("sun_radius"), py::arg("normal"),
      py::arg("wind_deg"), py::arg("tolerance"), py::arg("absolute"), py::arg("fresnel"),
      py::arg("erfc"));
  m.attr("SUN_ANGULAR_RADIUS") = kSunAngularRadius;
}

}  // namespace oceanref::python
