#include "cli/spectrum_command.h"

#include <cmath>
#include <map>
#include <memory>
#include <numbers>
#include <ostream>
#include <string>
#include <vector>

#include "cli/text.h"
#include "core/choice.h"
#include "spectrum/model.h"
#include "spectrum/moments.h"

namespace oceanref::cli {

namespace {
constexpr double kDegree = std::numbers::pi / 180.0;

// Raw flag values as typed; parsed and validated in run().
struct SpectrumFlags {
  std::string model, wind_speed = "10", fetch = "100000", depth = "inf", spreading, swell = "0",
                     spread_blend = "1", wind_direction = "0", dispersion, gamma, alpha, peak_omega,
                     sigma_low, sigma_high, pm_wind = "u10", tma_attenuation = "exact",
                     suppression = "0.001", gravity = "9.81", k_max, omega, theta, wavevector,
                     swell_model, capillary_wavenumber;
  bool moments = false;
  bool printed = false;
  bool allow_extrapolation = false;
};

// Scene/library setting key → the flag that sets it.
std::string flag_for(const std::string& key) {
  static const std::map<std::string, std::string> flags{
      {"wind_speed", "--wind-speed"},
      {"fetch", "--fetch"},
      {"depth", "--depth"},
      {"gravity", "--gravity"},
      {"wind_direction", "--wind-direction-deg"},
      {"swell", "--swell"},
      {"spread_blend", "--spread-blend"},
      {"gamma", "--gamma"},
      {"alpha", "--alpha"},
      {"peak_frequency", "--peak-omega"},
      {"sigma_low", "--sigma-low"},
      {"sigma_high", "--sigma-high"},
      {"phillips_suppression", "--phillips-suppression"},
      {"capillary_wavenumber", "--capillary-wavenumber"}};
  const auto it = flags.find(key);
  return it == flags.end() ? key : it->second;
}

std::optional<double> optional_number(const std::string& flag, const std::string& text,
                                      const std::string& range) {
  if (text.empty()) return std::nullopt;
  return parse_number(flag, text, false, range);
}

SpectrumSettings settings_from(const SpectrumFlags& f) {
  SpectrumSettings s;
  s.model = parse_choice<UsageError>(kSpectrumModels, "--model", f.model);
  s.wind_speed = parse_number("--wind-speed", f.wind_speed, false, "[0.1, 60] m/s");
  s.fetch = parse_number("--fetch", f.fetch, false, "[1, 1e+07] m");
  s.depth = parse_number("--depth", f.depth, true, "[0.01, inf] m");
  s.gravity = parse_number("--gravity", f.gravity, false, "[0.1, 100] m/s^2");
  const double direction_deg =
      parse_number_in("--wind-direction-deg", f.wind_direction, kDegreesRange);
  s.wind_direction = direction_deg * kDegree;
  if (!f.spreading.empty()) {
    s.spreading = parse_choice<UsageError>(kSpreadingModels, "--spreading", f.spreading);
  }
  if (!f.dispersion.empty()) {
    s.dispersion = parse_choice<UsageError>(kDispersionKinds, "--dispersion", f.dispersion);
  }
  s.swell = parse_number("--swell", f.swell, false, "[0, 1]");
  s.spread_blend = parse_number("--spread-blend", f.spread_blend, false, "[0, 1]");
  s.gamma = optional_number("--gamma", f.gamma, "[1, 20]");
  s.alpha = optional_number("--alpha", f.alpha, "(0, 10]");
  s.peak_frequency = optional_number("--peak-omega", f.peak_omega, "[0.0001, 1e+04] rad/s");
  s.sigma_low = optional_number("--sigma-low", f.sigma_low, "(0, 1]");
  s.sigma_high = optional_number("--sigma-high", f.sigma_high, "(0, 1]");
  s.pm_wind = parse_choice<UsageError>(kPiersonMoskowitzWinds, "--pm-wind", f.pm_wind);
  s.depth_attenuation =
      parse_choice<UsageError>(kDepthAttenuations, "--tma-attenuation", f.tma_attenuation);
  s.phillips_suppression = parse_number("--phillips-suppression", f.suppression, false, "[0, 0.1]");
  s.printed_spreading = f.printed;
  s.allow_extrapolation = f.allow_extrapolation;
  // Either flag is refused where it would change nothing (as a scene reports the key unused).
  if (!f.swell_model.empty()) {
    s.swell_model = parse_choice<UsageError>(kSwellModels, "--swell-model", f.swell_model);
    if (s.swell == 0.0 || s.spread_blend == 0.0) {
      throw UsageError("--swell-model", std::string("has no effect with --") +
                                            (s.swell == 0.0 ? "swell 0" : "spread-blend 0") +
                                            " (it sets how the swell xi widens the cos-2s spread)");
    }
  }
  if (!f.capillary_wavenumber.empty()) {
    s.capillary_wavenumber =
        parse_number("--capillary-wavenumber", f.capillary_wavenumber, false, "[1, 10000] rad/m");
    if (!capillary_wavenumber_used(s)) {
      throw UsageError("--capillary-wavenumber",
                       "has no effect here: k_m enters only the capillary dispersion and the "
                       "unified spectrum and spreading (give --dispersion capillary, --model "
                       "unified or --spreading unified)");
    }
  }
  return s;
}

Spectrum spectrum_from(const SpectrumFlags& f) {
  const SpectrumSettings settings = settings_from(f);
  try {
    return make_spectrum(settings);
  } catch (const SettingError& e) {
    throw UsageError(flag_for(e.key()), e.what());
  }
}

// The most rows one table may have (--omega x --theta-deg): about 60 MB of CSV.
constexpr double kMaxTableRows = 1e6;

void write_omega_table(std::ostream& out, const Spectrum& s, const std::vector<double>& omegas) {
  out << "omega,S\n";
  for (const double w : omegas) {
    out << format_number(w) << ',' << format_number(frequency_spectrum(s, w)) << '\n';
  }
}

void write_directional_table(std::ostream& out, const Spectrum& s,
                             const std::vector<double>& omegas,
                             const std::vector<double>& thetas_deg) {
  out << "omega,theta_deg,S,D\n";
  for (const double w : omegas) {
    const double spectrum = frequency_spectrum(s, w);
    for (const double t : thetas_deg) {
      out << format_number(w) << ',' << format_number(t) << ',' << format_number(spectrum) << ','
          << format_number(spreading_at_frequency(s, w, t * kDegree)) << '\n';
    }
  }
}

void write_wavevector_table(std::ostream& out, const Spectrum& s, const std::string& list) {
  struct Wavevector {
    double kx, kz;
  };
  std::vector<Wavevector> ks;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = list.find(',', start);
    const std::string item = list.substr(start, comma - start);
    const std::size_t colon = item.find(':');
    if (colon == std::string::npos) {
      throw UsageError("--wavevector", "expected kx:kz pairs separated by commas, got '" +
                                           escape_value(item) + "'");
    }
    ks.push_back({parse_number("--wavevector", item.substr(0, colon), false, "in rad/m"),
                  parse_number("--wavevector", item.substr(colon + 1), false, "in rad/m")});
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  out << "kx,kz,Theta\n";
  for (const Wavevector& k : ks) {
    out << format_number(k.kx) << ',' << format_number(k.kz) << ','
        << format_number(wavevector_spectrum(s, k.kx, k.kz)) << '\n';
  }
}

void write_moments(std::ostream& out, const Spectrum& s, const std::string& k_max_text) {
  const double k_max = k_max_text.empty()
                           ? kDefaultMaxWavenumber
                           : parse_number("--k-max", k_max_text, true, "(k_p, 1e+06] rad/m");
  if (!(k_max > s.peak_wavenumber) || (k_max > kMaxMomentWavenumber && k_max != HUGE_VAL)) {
    throw UsageError("--k-max",
                     "must be in (k_p, 1e6] rad/m or inf, with the peak wavenumber k_p = " +
                         format_number(s.peak_wavenumber) + " rad/m, got " +
                         escape_value(k_max_text));
  }
  SpectralMoments m;
  try {
    m = spectral_moments(s, k_max);
  } catch (const std::runtime_error& e) {
    throw UsageError("--k-max", std::string(e.what()) + " (k_max = " + format_number(k_max) + ")");
  }
  out << "m0,Hs,mss_x,mss_z,mss\n"
      << format_number(m.m0) << ',' << format_number(m.significant_wave_height) << ','
      << format_number(m.mss_x) << ',' << format_number(m.mss_z) << ',' << format_number(m.mss)
      << '\n';
}
}  // namespace

std::function<void(std::ostream&)> add_spectrum_command(CLI::App& app) {
  auto flags = std::make_shared<SpectrumFlags>();
  CLI::App* cmd = app.add_subcommand(
      "spectrum",
      "Evaluate a wave spectrum: S(omega), D(omega,theta), Theta(k) or its moments, as CSV with "
      "17 significant digits.");
  cmd->add_option("--model", flags->model,
                  "phillips | pierson-moskowitz | jonswap | tma | donelan | unified")
      ->required();
  cmd->add_option("--wind-speed", flags->wind_speed,
                  "U10 [m/s] in [0.1, 60] (U19.5 with --pm-wind u19.5)")
      ->capture_default_str();
  cmd->add_option("--fetch", flags->fetch, "fetch F [m] in [1, 1e7]")->capture_default_str();
  cmd->add_option("--depth", flags->depth, "water depth h [m] in [0.01, inf]")
      ->capture_default_str();
  cmd->add_option("--spreading", flags->spreading,
                  "cos2 | cos4 | mitsuyasu | hasselmann | mastin | gamper | donelan | "
                  "donelan-banner | unified (default: phillips cos2, pierson-moskowitz and "
                  "jonswap hasselmann, tma donelan-banner, donelan donelan, unified unified)");
  cmd->add_option("--swell", flags->swell,
                  "Horvath swell xi in [0, 1], adds 16 tanh(omega_p/omega) xi^2 to the cos-2s "
                  "spread (cos-2s family only)")
      ->capture_default_str();
  cmd->add_option("--swell-model", flags->swell_model,
                  "lutz (default): the swell adds 16 tanh(omega_p/omega) xi^2 (Lutz eq. 29) | "
                  "alimardanov: 16 tanh(min(omega/omega_p, 20)) xi^2 (Alimardanov Algorithm 2); "
                  "needs --swell > 0");
  cmd->add_option("--spread-blend", flags->spread_blend,
                  "blend b in [0, 1]: (1-b) forward cos^2 + b cos-2s (cos-2s family only)")
      ->capture_default_str();
  cmd->add_option("--wind-direction-deg", flags->wind_direction,
                  "wind direction angle [deg]; wind vector (cos, sin) in (x, z)")
      ->capture_default_str()
      ->check(number_in(kDegreesRange));
  cmd->add_option("--dispersion", flags->dispersion,
                  "deep | finite-depth | capillary (default: tma finite-depth, unified "
                  "capillary, others deep)");
  cmd->add_option("--gamma", flags->gamma, "JONSWAP/TMA peak enhancement gamma in [1, 20] (3.3)");
  cmd->add_option("--alpha", flags->alpha,
                  "equilibrium range alpha (pierson-moskowitz, jonswap, tma) or Phillips "
                  "amplitude A (default 0.00405 = alpha_PM/2), in (0, 10]");
  cmd->add_option("--peak-omega", flags->peak_omega,
                  "override the peak angular frequency omega_p [rad/s] (pierson-moskowitz, "
                  "jonswap, tma), in [0.0001, 10000]");
  cmd->add_option("--sigma-low", flags->sigma_low, "JONSWAP/TMA peak width below omega_p (0.07)");
  cmd->add_option("--sigma-high", flags->sigma_high, "JONSWAP/TMA peak width above omega_p (0.09)");
  cmd->add_option("--pm-wind", flags->pm_wind,
                  "u10 (Gamper eq. 3.37, 3.40) | u19.5 (eq. 3.36, 3.38): which wind "
                  "--wind-speed is for pierson-moskowitz")
      ->capture_default_str();
  cmd->add_option("--tma-attenuation", flags->tma_attenuation,
                  "exact (Kitaigorodskii, Vincevicius eq. 1.9) | thompson-vincent (eq. 1.10)")
      ->capture_default_str();
  cmd->add_option("--phillips-suppression", flags->suppression,
                  "Phillips small-wave suppression l/L in [0, 0.1]")
      ->capture_default_str();
  cmd->add_option("--capillary-wavenumber", flags->capillary_wavenumber,
                  "k_m [rad/m] in [1, 10000] (default 370, Gamper 3.4) of the capillary "
                  "dispersion omega^2 = gk(1 + (k/k_m)^2) and of the unified spectrum and "
                  "spreading; only with --dispersion capillary, --model unified or --spreading "
                  "unified");
  cmd->add_option("--gravity", flags->gravity, "g [m/s^2] in [0.1, 100]")->capture_default_str();
  cmd->add_flag("--printed-spreading", flags->printed,
                "use cos2, cos4 and donelan exactly as printed (integral over theta is pi, "
                "3pi/4, tanh(beta pi)) instead of normalized to 1");
  cmd->add_flag("--allow-extrapolation", flags->allow_extrapolation,
                "use a model outside its fitted range (JONSWAP chi < 1e4; Donelan and Unified "
                "inverse wave age clamped to their ranges; Unified alpha_m clamped to >= 0)");
  auto* omega =
      cmd->add_option("--omega", flags->omega, "w1,w2,... [rad/s] -> CSV omega,S (S in m^2 s)");
  cmd->add_option("--theta-deg", flags->theta,
                  "t1,t2,... [deg] with --omega -> CSV omega,theta_deg,S,D (every pair; the "
                  "directional spectrum is S*D)")
      ->needs(omega);
  auto* wavevector = cmd->add_option("--wavevector", flags->wavevector,
                                     "kx:kz,... [rad/m] -> CSV kx,kz,Theta (Theta in m^4)");
  auto* moments =
      cmd->add_flag("--moments", flags->moments,
                    "CSV m0,Hs,mss_x,mss_z,mss by adaptive quadrature over 0 < k <= --k-max");
  cmd->add_option("--k-max", flags->k_max,
                  "upper wavenumber of --moments [rad/m] or inf (default 363.19 = 2pi/1.73 cm, "
                  "Gamper 4.4)")
      ->needs(moments);
  omega->excludes(wavevector)->excludes(moments);
  wavevector->excludes(moments);

  return [flags, cmd](std::ostream& out) {
    if (flags->omega.empty() && flags->wavevector.empty() && !flags->moments) {
      throw UsageError("spectrum", "give one of --omega, --wavevector or --moments");
    }
    const Spectrum s = spectrum_from(*flags);
    if (!flags->omega.empty()) {
      const std::vector<double> omegas =
          parse_number_list("--omega", flags->omega, ">= 0 rad/s each");
      for (const double w : omegas) {
        if (w < 0.0)
          throw UsageError("--omega",
                           "frequencies must be finite and >= 0 rad/s, got " + format_number(w));
      }
      if (flags->theta.empty()) {
        write_omega_table(out, s, omegas);
      } else {
        const std::vector<double> thetas =
            parse_number_list("--theta-deg", flags->theta, "in degrees, each");
        // The table is assembled in memory before it is written (no partial output).
        const double rows = static_cast<double>(omegas.size()) * static_cast<double>(thetas.size());
        if (rows > kMaxTableRows) {
          throw UsageError(
              "--theta-deg",
              std::to_string(omegas.size()) + " frequencies x " + std::to_string(thetas.size()) +
                  " directions = " + shortest_number(rows) + " rows, over the limit of " +
                  shortest_number(kMaxTableRows) + "; split the table into several calls");
        }
        write_directional_table(out, s, omegas, thetas);
      }
    } else if (!flags->wavevector.empty()) {
      write_wavevector_table(out, s, flags->wavevector);
    } else {
      write_moments(out, s, flags->k_max);
    }
    (void)cmd;
  };
}

}  // namespace oceanref::cli
