// Spectra: S(ω), Ψ(k), D(ω, θ), Θ(k) and the moments of the continuous spectrum
// (spectrum/model.h, spectrum/moments.h), with the keyword names of scene files.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string>

#include "common.h"
#include "core/choice.h"
#include "spectrum/model.h"
#include "spectrum/moments.h"

namespace oceanref::python {

namespace {
constexpr double kDegree = std::numbers::pi / 180.0;

// "pierson_moskowitz" and "pierson-moskowitz" both name the model.
std::string hyphenated(std::string name) {
  std::replace(name.begin(), name.end(), '_', '-');
  return name;
}

double number(const std::string& key, const py::handle& value) {
  try {
    return value.cast<double>();
  } catch (const py::cast_error&) {
    throw ArgumentError(key, "expected a number, got " + std::string(py::str(value)));
  }
}

const char* const kKeywords =
    "wind_speed, fetch, depth, gravity, wind_direction_deg, spreading, dispersion, swell, "
    "swell_model, "
    "spread_blend, gamma, alpha, peak_frequency, sigma_low, sigma_high, pm_wind, "
    "tma_attenuation, phillips_suppression, capillary_wavenumber, printed_spreading, "
    "allow_extrapolation";

SpectrumSettings settings_from(const std::string& model_name, const py::kwargs& kw) {
  SpectrumSettings s;
  s.model = parse_choice<ArgumentError>(kSpectrumModels, "model", hyphenated(model_name));
  for (const auto& item : kw) {  // no structured binding: clang 15 cannot capture one
    const std::string key = py::str(item.first);
    const py::handle value = item.second;
    if (value.is_none()) continue;  // the model's own value
    const auto text = [&]() { return std::string(py::str(value)); };
    if (key == "wind_speed") {
      s.wind_speed = number(key, value);
    } else if (key == "fetch") {
      s.fetch = number(key, value);
    } else if (key == "depth") {
      s.depth = number(key, value);
    } else if (key == "gravity") {
      s.gravity = number(key, value);
    } else if (key == "wind_direction_deg") {
      const double deg = number(key, value);
      if (!(std::fabs(deg) <= 720.0)) {
        throw ArgumentError(key, "must be in [-720, 720] degrees, got " + text());
      }
      s.wind_direction = deg * kDegree;
    } else if (key == "spreading") {
      s.spreading = parse_choice<ArgumentError>(kSpreadingModels, key, hyphenated(text()));
    } else if (key == "dispersion") {
      s.dispersion = parse_choice<ArgumentError>(kDispersionKinds, key, hyphenated(text()));
    } else if (key == "swell") {
      s.swell = number(key, value);
    } else if (key == "swell_model") {
      s.swell_model = parse_choice<ArgumentError>(kSwellModels, key, text());
    } else if (key == "spread_blend") {
      s.spread_blend = number(key, value);
    } else if (key == "gamma") {
      s.gamma = number(key, value);
    } else if (key == "alpha") {
      s.alpha = number(key, value);
    } else if (key == "peak_frequency") {
      s.peak_frequency = number(key, value);
    } else if (key == "sigma_low") {
      s.sigma_low = number(key, value);
    } else if (key == "sigma_high") {
      s.sigma_high = number(key, value);
    } else if (key == "pm_wind") {
      s.pm_wind = parse_choice<ArgumentError>(kPiersonMoskowitzWinds, key, text());
    } else if (key == "tma_attenuation") {
      s.depth_attenuation =
          parse_choice<ArgumentError>(kDepthAttenuations, key, hyphenated(text()));
    } else if (key == "phillips_suppression") {
      s.phillips_suppression = number(key, value);
    } else if (key == "capillary_wavenumber") {
      s.capillary_wavenumber = number(key, value);
    } else if (key == "printed_spreading") {
      s.printed_spreading = value.cast<bool>();
    } else if (key == "allow_extrapolation") {
      s.allow_extrapolation = value.cast<bool>();
    } else {
      throw ArgumentError(key, std::string("unknown keyword (accepted: ") + kKeywords + ")");
    }
  }
  return s;
}

// A validated spectrum (SettingError → ValueError "key: range", as `oceanref spectrum`).
struct PySpectrum {
  Spectrum spectrum;
};

std::string key_name(const std::string& key) {
  return key == "wind_direction" ? "wind_direction_deg" : key;
}

PySpectrum make(const std::string& model, const py::kwargs& kw) {
  const SpectrumSettings settings = settings_from(model, kw);
  try {
    return {make_spectrum(settings)};
  } catch (const SettingError& e) {
    throw ArgumentError(key_name(e.key()), e.what());
  }
}

template <typename F>
py::array_t<double> map1(const DoubleArray& x, F f) {
  py::array_t<double> out(std::vector<py::ssize_t>(x.shape(), x.shape() + x.ndim()));
  const double* in = x.data();
  double* o = out.mutable_data();
  for (py::ssize_t i = 0; i < x.size(); ++i) o[i] = f(in[i]);
  return out;
}

template <typename F>
py::array_t<double> map2(const DoubleArray& a, const DoubleArray& b, F f) {
  if (a.ndim() != b.ndim() || !std::equal(a.shape(), a.shape() + a.ndim(), b.shape())) {
    throw ArgumentError("arrays", "the two arguments must have the same shape (broadcast first)");
  }
  py::array_t<double> out(std::vector<py::ssize_t>(a.shape(), a.shape() + a.ndim()));
  const double* x = a.data();
  const double* y = b.data();
  double* o = out.mutable_data();
  for (py::ssize_t i = 0; i < a.size(); ++i) o[i] = f(x[i], y[i]);
  return out;
}
}  // namespace

void bind_spectrum(py::module_& m) {
  py::class_<PySpectrum>(m, "Spectrum",
                         "A validated wave spectrum: a model, its spreading and dispersion with "
                         "every derived parameter resolved (spectrum/model.h).")
      .def(py::init(&make), py::arg("model"))
      .def(
          "frequency",
          [](const PySpectrum& s, const DoubleArray& omega) {
            return map1(omega, [&](double w) { return frequency_spectrum(s.spectrum, w); });
          },
          py::arg("omega"), "S(omega) [m^2 s] at angular frequencies omega [rad/s].")
      .def(
          "wavenumber",
          [](const PySpectrum& s, const DoubleArray& k) {
            return map1(k, [&](double x) { return wavenumber_spectrum(s.spectrum, x); });
          },
          py::arg("k"), "Psi(k) [m^3] at wavenumbers k [rad/m].")
      .def(
          "spreading",
          [](const PySpectrum& s, const DoubleArray& omega, const DoubleArray& theta_deg) {
            return map2(omega, theta_deg, [&](double w, double t) {
              return spreading_at_frequency(s.spectrum, w, t * kDegree);
            });
          },
          py::arg("omega"), py::arg("theta_deg"),
          "D(omega, theta) [1/rad]; theta [deg] is the absolute wave direction (0 = +x).")
      .def(
          "wavevector",
          [](const PySpectrum& s, const DoubleArray& kx, const DoubleArray& kz) {
            return map2(kx, kz,
                        [&](double x, double z) { return wavevector_spectrum(s.spectrum, x, z); });
          },
          py::arg("kx"), py::arg("kz"), "Theta(kx, kz) [m^4] at wavevectors [rad/m].")
      .def(
          "moments",
          [](const PySpectrum& s, std::optional<double> k_max_arg) {
            const double k_max = k_max_arg.value_or(kDefaultMaxWavenumber);
            if (!(k_max > s.spectrum.peak_wavenumber)) {
              throw ArgumentError("k_max", "must exceed the peak wavenumber k_p = " +
                                               format_number(s.spectrum.peak_wavenumber) +
                                               " rad/m, got " + format_number(k_max));
            }
            SpectralMoments r;
            try {
              r = spectral_moments(s.spectrum, k_max);
            } catch (const std::runtime_error& e) {
              throw ArgumentError(
                  "k_max", std::string(e.what()) + " (k_max = " + format_number(k_max) + ")");
            }
            py::dict d;
            d["m0"] = r.m0;
            d["Hs"] = r.significant_wave_height;
            d["mss_x"] = r.mss_x;
            d["mss_z"] = r.mss_z;
            d["mss"] = r.mss;
            d["m0_error"] = r.m0_error;
            d["mss_x_error"] = r.mss_x_error;
            d["mss_z_error"] = r.mss_z_error;
            d["k_max"] = k_max;
            return d;
          },
          py::arg("k_max") = py::none(),
          "Moments of the continuous spectrum up to k_max [rad/m] by adaptive quadrature.")
      .def_property_readonly("model",
                             [](const PySpectrum& s) { return to_string(s.spectrum.model); })
      .def_property_readonly("spreading_model",
                             [](const PySpectrum& s) { return to_string(s.spectrum.spreading); })
      .def_property_readonly(
          "dispersion", [](const PySpectrum& s) { return to_string(s.spectrum.dispersion.kind); })
      .def_property_readonly("peak_frequency",
                             [](const PySpectrum& s) { return s.spectrum.peak_frequency; })
      .def_property_readonly("peak_wavenumber",
                             [](const PySpectrum& s) { return s.spectrum.peak_wavenumber; })
      .def_property_readonly("alpha", [](const PySpectrum& s) { return s.spectrum.alpha; })
      .def_property_readonly("gamma", [](const PySpectrum& s) { return s.spectrum.gamma; })
      .def_property_readonly("gravity", [](const PySpectrum& s) { return s.spectrum.gravity; });
  m.attr("DEFAULT_K_MAX") = kDefaultMaxWavenumber;
}

}  // namespace oceanref::python
