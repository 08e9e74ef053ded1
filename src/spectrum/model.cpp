#include "spectrum/model.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <utility>

#include "core/format.h"
#include "core/math.h"
#include "spectrum/frequency_spectra.h"
#include "spectrum/spreading.h"

namespace oceanref {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = std::numbers::pi;
// JONSWAP is fitted for χ < 10⁴ (Gamper §3.4, after eq. 3.52).
constexpr double kJonswapMaxFetch = 1.0e4;

// A computed quantity in a message (six significant digits); given values and ranges are echoed
// exactly (shortest_number).
std::string number(double v) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

// Rejects values outside [lo, hi] (NaN included) with the key, the range and the value.
void require_range(const char* key, double value, double lo, double hi, const char* unit) {
  if (value >= lo && value <= hi) return;
  throw SettingError(key, std::string("must be in [") + shortest_number(lo) + ", " +
                              shortest_number(hi) + "]" + unit + ", got " + shortest_number(value));
}
void require_positive(const char* key, double value, double hi, const char* unit) {
  if (value > 0.0 && value <= hi) return;
  throw SettingError(key, std::string("must be in (0, ") + shortest_number(hi) + "]" + unit +
                              ", got " + shortest_number(value));
}

std::string extrapolation_hint() {
  return "; pass --allow-extrapolation (scene: waves.spectrum.allow_extrapolation) to use it "
         "anyway";
}

// The gravity-capillary phase speed c(k) in deep water that the Unified model is defined with
// (Elfouhaily et al. 1997; Gamper §3.4), independent of the propagation dispersion chosen.
double unified_phase_speed(const Spectrum& s, double k) {
  const Dispersion capillary{DispersionKind::capillary, s.gravity, kInf,
                             s.unified.capillary_wavenumber};
  return phase_speed(capillary, k);
}

void resolve_frequency_model(const SpectrumSettings& in, Spectrum& s) {
  const double g = in.gravity;
  const double u = in.wind_speed;
  const bool fetch_needed = !(in.alpha && in.peak_frequency);
  switch (in.model) {
    case SpectrumModel::pierson_moskowitz:
      if (in.pm_wind == PiersonMoskowitzWind::u19_5) {
        s.peak_frequency = pierson_moskowitz_peak_frequency_u19_5(u, g);
      } else {
        s.peak_frequency = pierson_moskowitz_peak_frequency_u10(u, g);
      }
      s.alpha = kPiersonMoskowitzAlpha;
      s.gamma = 1.0;
      // The literal eq. 3.36 is used only when nothing overrides its constants.
      s.pm_wind = (in.alpha || in.peak_frequency) ? PiersonMoskowitzWind::u10 : in.pm_wind;
      break;
    case SpectrumModel::jonswap:
    case SpectrumModel::tma: {
      const double chi = dimensionless_fetch(in.fetch, u, g);
      if (fetch_needed && chi >= kJonswapMaxFetch && !in.allow_extrapolation) {
        throw SettingError("fetch",
                           "JONSWAP is fitted for dimensionless fetch gF/U10² < 1e4 "
                           "(Gamper eq. 3.52), i.e. fetch < " +
                               number(kJonswapMaxFetch * u * u / g) + " m at U10 = " + number(u) +
                               " m/s; got " + number(in.fetch) + " m" + extrapolation_hint());
      }
      s.alpha = jonswap_alpha(chi);
      s.peak_frequency =
          peak_frequency_from_dimensionless(jonswap_dimensionless_peak_frequency(chi), u, g);
      s.gamma = 3.3;
      s.tma_depth = in.model == SpectrumModel::tma ? in.depth : kInf;
      s.depth_attenuation = in.depth_attenuation;
      break;
    }
    case SpectrumModel::donelan: {
      // θ_p = θ_w, so U_c = U10 (Gamper eq. 3.62).
      const double chi = dimensionless_fetch(in.fetch, u, g);
      double omega_c = donelan_inverse_wave_age(chi);
      if (!(omega_c > kDonelanMinInverseWaveAge && omega_c < kDonelanMaxInverseWaveAge)) {
        if (!in.allow_extrapolation) {
          throw SettingError(
              "fetch",
              "Donelan's inverse wave age Ω_c = 11.6 (gF/U10²)^-0.23 = " + number(omega_c) +
                  " (fetch " + number(in.fetch) + " m, U10 " + number(u) +
                  " m/s) is outside its fitted range (0.83, 5) (Gamper eq. 3.67)" +
                  extrapolation_hint() + " with Ω_c clamped to the range");
        }
        omega_c =
            std::fmin(std::fmax(omega_c, kDonelanMinInverseWaveAge), kDonelanMaxInverseWaveAge);
      }
      s.inverse_wave_age = omega_c;
      s.peak_frequency = donelan_peak_frequency(omega_c, u, g);
      s.alpha = donelan_alpha(omega_c);
      s.gamma = donelan_gamma(omega_c);
      s.sigma_low = s.sigma_high = donelan_sigma(omega_c);
      break;
    }
    default:
      break;
  }
  if (in.alpha) s.alpha = *in.alpha;
  if (in.peak_frequency) s.peak_frequency = *in.peak_frequency;
  if (in.gamma) s.gamma = *in.gamma;
  if (in.sigma_low) s.sigma_low = *in.sigma_low;
  if (in.sigma_high) s.sigma_high = *in.sigma_high;
}

void resolve_unified_model(const SpectrumSettings& in, Spectrum& s) {
  const double g = in.gravity;
  const double u = in.wind_speed;
  double omega_c = unified_inverse_wave_age(dimensionless_fetch(in.fetch, u, g));
  if (!(omega_c < kUnifiedMaxInverseWaveAge)) {
    if (!in.allow_extrapolation) {
      throw SettingError("fetch", "the Unified inverse wave age Ω_c = " + number(omega_c) +
                                      " (fetch " + number(in.fetch) + " m, U10 " + number(u) +
                                      " m/s) is outside its range [0.84, 5) (Gamper eq. 3.70)" +
                                      extrapolation_hint() + " with Ω_c clamped to 5");
    }
    omega_c = kUnifiedMaxInverseWaveAge;
  }
  UnifiedParameters& p = s.unified;
  p.inverse_wave_age = omega_c;
  p.peak_wavenumber = unified_peak_wavenumber(omega_c, u, g);
  p.peak_phase_speed = u / omega_c;
  p.gamma = unified_gamma(omega_c);
  p.sigma = unified_sigma(omega_c);
  p.long_wave_alpha = unified_long_wave_alpha(omega_c);
  p.friction_velocity = friction_velocity(u, roughness_length(u, p.peak_phase_speed, g));
  p.short_wave_alpha = unified_short_wave_alpha(p.friction_velocity, p.min_phase_speed);
  if (p.short_wave_alpha < 0.0) {
    if (!in.allow_extrapolation) {
      throw SettingError("wind_speed",
                         "the Unified short-wave parameter α_m = 0.01[1 + ln(u*/c_m)] is " +
                             number(p.short_wave_alpha) + " < 0 at U10 = " + number(u) +
                             " m/s (friction velocity u* = " + number(p.friction_velocity) +
                             " m/s < c_m/e); the model needs U10 of about 2.7 m/s or more" +
                             extrapolation_hint() + " with α_m clamped to 0");
    }
    p.short_wave_alpha = 0.0;
  }
  s.inverse_wave_age = omega_c;
  s.peak_wavenumber = p.peak_wavenumber;
  s.peak_frequency = angular_frequency(s.dispersion, p.peak_wavenumber);
}

void validate(const SpectrumSettings& in) {
  require_range("wind_speed", in.wind_speed, 0.1, 60.0, " m/s");
  require_range("fetch", in.fetch, 1.0, 1.0e7, " m");
  require_range("depth", in.depth, 0.01, kInf, " m");
  require_range("gravity", in.gravity, 0.1, 100.0, " m/s²");
  require_range("wind_direction", in.wind_direction, -4.0 * kPi, 4.0 * kPi, " rad");
  require_range("swell", in.swell, 0.0, 1.0, "");
  require_range("spread_blend", in.spread_blend, 0.0, 1.0, "");
  require_range("phillips_suppression", in.phillips_suppression, 0.0, 0.1, "");
  require_range("capillary_wavenumber", in.capillary_wavenumber, 1.0, 1.0e4, " rad/m");
  if (in.gamma) require_range("gamma", *in.gamma, 1.0, 20.0, "");
  if (in.alpha) require_positive("alpha", *in.alpha, 10.0, "");
  // Below 1e-4 rad/s (a 17-hour period, far beyond any wind sea or swell) the spectrum's mass
  // lies at wavenumbers under 1e-9 rad/m and its moments no longer converge in double precision.
  if (in.peak_frequency) {
    require_range("peak_frequency", *in.peak_frequency, 1.0e-4, 1.0e4, " rad/s");
  }
  if (in.sigma_low) require_positive("sigma_low", *in.sigma_low, 1.0, "");
  if (in.sigma_high) require_positive("sigma_high", *in.sigma_high, 1.0, "");
  const bool frequency_law = in.model == SpectrumModel::pierson_moskowitz ||
                             in.model == SpectrumModel::jonswap || in.model == SpectrumModel::tma;
  const bool jonswap_law = in.model == SpectrumModel::jonswap || in.model == SpectrumModel::tma;
  if ((in.gamma || in.sigma_low || in.sigma_high) && !jonswap_law) {
    throw SettingError(in.gamma ? "gamma" : (in.sigma_low ? "sigma_low" : "sigma_high"),
                       "applies to the jonswap and tma models only");
  }
  if (in.peak_frequency && !frequency_law) {
    throw SettingError("peak_frequency",
                       "applies to the pierson-moskowitz, jonswap and tma models only");
  }
  if (in.alpha && !(frequency_law || in.model == SpectrumModel::phillips)) {
    throw SettingError("alpha",
                       "applies to the pierson-moskowitz, jonswap, tma and phillips models only");
  }
}
}  // namespace

bool is_cos_2s_family(SpreadingModel m) {
  return m == SpreadingModel::mitsuyasu || m == SpreadingModel::hasselmann ||
         m == SpreadingModel::mastin || m == SpreadingModel::gamper;
}

SpreadingModel default_spreading(SpectrumModel m) {
  switch (m) {
    case SpectrumModel::phillips:
      return SpreadingModel::cos2;
    case SpectrumModel::pierson_moskowitz:
      return SpreadingModel::hasselmann;
    case SpectrumModel::jonswap:
      return SpreadingModel::hasselmann;
    case SpectrumModel::tma:
      return SpreadingModel::donelan_banner;
    case SpectrumModel::donelan:
      return SpreadingModel::donelan;
    case SpectrumModel::unified:
      return SpreadingModel::unified;
  }
  return SpreadingModel::hasselmann;
}

DispersionKind default_dispersion(SpectrumModel m) {
  if (m == SpectrumModel::tma) return DispersionKind::finite_depth;
  if (m == SpectrumModel::unified) return DispersionKind::capillary;
  return DispersionKind::deep;
}

// k_m is read by capillary_factor (dispersion.cpp), unified_phase_speed (the Unified spectrum's
// and spreading's c(k)), unified_short_wave_side_effect (F_m) and c_m = unified_min_phase_speed.
bool capillary_wavenumber_used(const SpectrumSettings& s) {
  return s.dispersion.value_or(default_dispersion(s.model)) == DispersionKind::capillary ||
         s.model == SpectrumModel::unified ||
         s.spreading.value_or(default_spreading(s.model)) == SpreadingModel::unified;
}

Spectrum make_spectrum(const SpectrumSettings& in) {
  validate(in);
  Spectrum s{};
  s.model = in.model;
  s.spreading = in.spreading.value_or(default_spreading(in.model));
  s.dispersion = Dispersion{in.dispersion.value_or(default_dispersion(in.model)), in.gravity,
                            in.depth, in.capillary_wavenumber};
  s.wind_speed = in.wind_speed;
  s.wind_direction = in.wind_direction;
  s.gravity = in.gravity;
  s.swell = in.swell;
  s.spread_blend = in.spread_blend;
  s.printed_spreading = in.printed_spreading;
  s.swell_model = in.swell_model;
  s.unified.capillary_wavenumber = in.capillary_wavenumber;
  s.unified.min_phase_speed = unified_min_phase_speed(in.capillary_wavenumber);
  if (!is_cos_2s_family(s.spreading)) {
    if (in.swell != 0.0) {
      throw SettingError("swell",
                         "applies to the cos-2s spreading family only (mitsuyasu, "
                         "hasselmann, mastin, gamper), not " +
                             std::string(to_string(s.spreading)));
    }
    if (in.spread_blend != 1.0) {
      throw SettingError("spread_blend",
                         "applies to the cos-2s spreading family only "
                         "(mitsuyasu, hasselmann, mastin, gamper), not " +
                             std::string(to_string(s.spreading)));
    }
  }

  switch (in.model) {
    case SpectrumModel::unified:
      resolve_unified_model(in, s);
      break;
    case SpectrumModel::phillips:
      s.phillips_largest_wave = phillips_largest_wave(in.wind_speed, in.gravity);
      s.phillips_smallest_wave = in.phillips_suppression * s.phillips_largest_wave;
      // Default A = α_PM/2: the k⁻³ tail of Ψ then equals the Pierson–Moskowitz one.
      s.phillips_amplitude = in.alpha.value_or(0.5 * kPiersonMoskowitzAlpha);
      s.peak_wavenumber = phillips_peak_wavenumber(s.phillips_largest_wave);
      s.peak_frequency = angular_frequency(s.dispersion, s.peak_wavenumber);
      break;
    default:
      resolve_frequency_model(in, s);
      s.peak_wavenumber = wavenumber_from_frequency(s.dispersion, s.peak_frequency);
      break;
  }
  if (in.model != SpectrumModel::donelan && in.model != SpectrumModel::unified) {
    s.inverse_wave_age = in.wind_speed * s.peak_frequency / in.gravity;
  }
  // The Unified spreading needs c_p and u*; for other models take them at this model's peak.
  if (in.model != SpectrumModel::unified) {
    s.unified.peak_phase_speed = phase_speed(s.dispersion, s.peak_wavenumber);
    s.unified.friction_velocity = friction_velocity(
        in.wind_speed, roughness_length(in.wind_speed, s.unified.peak_phase_speed, in.gravity));
  }
  s.mitsuyasu_peak_spread = mitsuyasu_peak_spread(s.peak_frequency, in.wind_speed, in.gravity);
  return s;
}

// S(ω): the model's own frequency spectrum, or for wavenumber models S(ω) = Ψ(k(ω)) dk/dω
// (the change of variables of Gamper eq. 3.58 run backwards).
double frequency_spectrum(const Spectrum& s, double omega) {
  if (!(omega > 0.0) || std::isinf(omega)) return 0.0;
  switch (s.model) {
    case SpectrumModel::pierson_moskowitz:
      if (s.pm_wind == PiersonMoskowitzWind::u19_5) {
        return pierson_moskowitz_u19_5(omega, s.wind_speed, s.gravity);
      }
      return pierson_moskowitz(omega, s.alpha, s.peak_frequency, s.gravity);
    case SpectrumModel::jonswap:
      return jonswap(omega, s.alpha, s.peak_frequency, s.gamma, s.sigma_low, s.sigma_high,
                     s.gravity);
    case SpectrumModel::tma: {
      // S_TMA = S_JONSWAP · Φ(ω, h)  (Vincevičius eq. 1.11).
      const double j =
          jonswap(omega, s.alpha, s.peak_frequency, s.gamma, s.sigma_low, s.sigma_high, s.gravity);
      if (j == 0.0) return 0.0;
      return j * (s.depth_attenuation == DepthAttenuation::exact
                      ? kitaigorodskii_depth_attenuation(omega, s.tma_depth, s.gravity)
                      : thompson_vincent_depth_attenuation(omega, s.tma_depth, s.gravity));
    }
    case SpectrumModel::donelan:
      return donelan(omega, s.alpha, s.peak_frequency, s.gamma, s.sigma_low, s.gravity);
    case SpectrumModel::unified:
    case SpectrumModel::phillips: {
      const double k = wavenumber_from_frequency(s.dispersion, omega);
      const double psi = wavenumber_spectrum(s, k);
      return psi == 0.0 ? 0.0 : psi / group_velocity(s.dispersion, k);
    }
  }
  return 0.0;
}

// Ψ(k): the model's own wavenumber spectrum, or Ψ(k) = S(ω(k)) dω/dk for frequency models
// (Gamper eq. 3.58, generalized from ω = √(gk) to the chosen dispersion relation).
double wavenumber_spectrum(const Spectrum& s, double k) {
  if (!(k > 0.0) || std::isinf(k)) return 0.0;
  switch (s.model) {
    case SpectrumModel::unified:
      return unified(k, unified_phase_speed(s, k), s.unified);
    case SpectrumModel::phillips:
      return phillips(k, s.phillips_amplitude, s.phillips_largest_wave, s.phillips_smallest_wave);
    default: {
      const double spectrum = frequency_spectrum(s, angular_frequency(s.dispersion, k));
      return spectrum == 0.0 ? 0.0 : spectrum * group_velocity(s.dispersion, k);
    }
  }
}

double cos_2s_spread(const Spectrum& s, double omega) {
  double spread = 0.0;
  switch (s.spreading) {
    case SpreadingModel::mitsuyasu:
      spread = mitsuyasu_spread(omega, s.peak_frequency, s.mitsuyasu_peak_spread);
      break;
    case SpreadingModel::hasselmann:
      spread = hasselmann_spread(omega, s.peak_frequency, s.wind_speed, s.gravity);
      break;
    case SpreadingModel::mastin:
      spread = mastin_spread(omega, s.peak_frequency);
      break;
    case SpreadingModel::gamper:
      spread = gamper_spread(omega, s.peak_frequency);
      break;
    default:
      return 0.0;
  }
  if (s.swell_model == SwellModel::alimardanov) {
    return spread + alimardanov_swell_spread(omega, s.peak_frequency, s.swell);
  }
  return spread + horvath_swell_spread(omega, s.peak_frequency, s.swell);
}

SpreadingAt spreading_at(const Spectrum& s, double omega, double k) {
  SpreadingAt d;
  d.spectrum = &s;
  const double ratio = omega / s.peak_frequency;
  switch (s.spreading) {
    case SpreadingModel::cos2:
    case SpreadingModel::cos4:
      break;
    case SpreadingModel::donelan:
      d.parameter = donelan_beta(ratio);
      break;
    case SpreadingModel::donelan_banner:
      d.parameter = donelan_banner_beta(ratio);
      break;
    case SpreadingModel::unified:
      d.parameter = unified_upwind_ratio(unified_phase_speed(s, k), s.unified.peak_phase_speed,
                                         s.unified.min_phase_speed, s.unified.friction_velocity);
      break;
    default:
      d.parameter = cos_2s_spread(s, omega);
      d.log_normalization = cos_2s_log_normalization(d.parameter);
  }
  return d;
}

// D(ω, k, θ) for the wave direction θ (absolute, radians), from spreading_at(s, ω, k).
double directional_spreading(const SpreadingAt& d, double theta) {
  const Spectrum& s = *d.spectrum;
  const double t = wrap_angle(theta - s.wind_direction);
  switch (s.spreading) {
    case SpreadingModel::cos2:
      return cosine_power_spreading(t, 2.0) / (s.printed_spreading ? 1.0 : kPi);
    case SpreadingModel::cos4:
      return cosine_power_spreading(t, 4.0) / (s.printed_spreading ? 1.0 : 0.75 * kPi);
    case SpreadingModel::donelan:
      return s.printed_spreading ? donelan_spreading(t, d.parameter)
                                 : sech2_spreading(t, d.parameter);
    case SpreadingModel::donelan_banner:
      return sech2_spreading(t, d.parameter);
    case SpreadingModel::unified:
      return unified_spreading(t, d.parameter);
    default: {
      const double value = cos_2s_spreading(t, d.parameter, d.log_normalization);
      return s.spread_blend == 1.0 ? value : spread_blend(t, value, s.spread_blend);
    }
  }
}

// D(ω, k, θ) for the wave direction θ (absolute, radians); ω and k belong together.
double directional_spreading(const Spectrum& s, double omega, double k, double theta) {
  return directional_spreading(spreading_at(s, omega, k), theta);
}

double spreading_at_frequency(const Spectrum& s, double omega, double theta) {
  return directional_spreading(s, omega, wavenumber_from_frequency(s.dispersion, omega), theta);
}

double spreading_at_wavenumber(const Spectrum& s, double k, double theta) {
  return directional_spreading(s, angular_frequency(s.dispersion, k), k, theta);
}

// Θ(k) = Ψ(k) D(ω(k), θ) / k, θ = atan2(k_z, k_x)  (Gamper eq. 3.59–3.61, with Ψ = Θ_k of
// eq. 3.58 for the chosen dispersion relation).
double wavevector_spectrum(const Spectrum& s, double kx, double kz) {
  const double k = math::hypot(kx, kz);
  if (!(k > 0.0) || std::isinf(k)) return 0.0;
  const double psi = wavenumber_spectrum(s, k);
  if (psi == 0.0) return 0.0;
  return psi * spreading_at_wavenumber(s, k, math::atan2(kz, kx)) / k;
}

double spreading_integral(const Spectrum& s, double omega) {
  if (!s.printed_spreading) return 1.0;
  switch (s.spreading) {
    case SpreadingModel::cos2:
      return cosine_power_integral(2.0);
    case SpreadingModel::cos4:
      return cosine_power_integral(4.0);
    case SpreadingModel::donelan:
      return math::tanh(donelan_beta(omega / s.peak_frequency) * kPi);
    default:
      return 1.0;
  }
}

std::string_view to_string(SpectrumModel m) {
  return choice_name(kSpectrumModels, m);
}
std::string_view to_string(SpreadingModel m) {
  return choice_name(kSpreadingModels, m);
}
std::string_view to_string(DispersionKind d) {
  return choice_name(kDispersionKinds, d);
}
std::string_view to_string(SwellModel m) {
  return choice_name(kSwellModels, m);
}

}  // namespace oceanref
