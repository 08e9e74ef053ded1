// A wave spectrum as the renderer uses it: a model, a spreading function and a dispersion
// relation with every derived parameter resolved once, and the forms derived from it:
//   S(ω) [m²·s]  one-dimensional frequency spectrum        (∫S dω = m0)
//   Ψ(k) [m³]    one-dimensional wavenumber spectrum        (∫Ψ dk = m0)
//   D    [1/rad] directional spreading                      (∫D dθ = 1 when normalized)
//   Θ(k) [m⁴]    two-dimensional wavevector spectrum        (∬Θ dk_x dk_z = m0)
#pragma once

#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "core/choice.h"
#include "core/errors.h"
#include "spectrum/dispersion.h"
#include "spectrum/wavenumber_spectra.h"

namespace oceanref {

enum class SpectrumModel { phillips, pierson_moskowitz, jonswap, tma, donelan, unified };
enum class SpreadingModel {
  cos2,
  cos4,
  mitsuyasu,
  hasselmann,
  mastin,
  gamper,
  donelan,
  donelan_banner,
  unified
};
enum class PiersonMoskowitzWind { u10, u19_5 };           // which wind the speed means
enum class DepthAttenuation { exact, thompson_vincent };  // TMA Φ: eq. 1.9 or eq. 1.10
// How the swell ξ widens the cos-2s spread s (FORMULAS.md item 9): Δs = 16 tanh(ω_p/ω) ξ²
// (Lutz eq. 29) or 16 tanh(min(ω/ω_p, 20)) ξ² (Alimardanov Algorithm 2), added to s either way.
enum class SwellModel { lutz, alimardanov };

// The names of the choices, as scene files, the command line and the Python module spell them.
inline constexpr std::array<Choice<SpectrumModel>, 6> kSpectrumModels{{
    {SpectrumModel::phillips, "phillips"},
    {SpectrumModel::pierson_moskowitz, "pierson-moskowitz"},
    {SpectrumModel::jonswap, "jonswap"},
    {SpectrumModel::tma, "tma"},
    {SpectrumModel::donelan, "donelan"},
    {SpectrumModel::unified, "unified"},
}};
inline constexpr std::array<Choice<SpreadingModel>, 9> kSpreadingModels{{
    {SpreadingModel::cos2, "cos2"},
    {SpreadingModel::cos4, "cos4"},
    {SpreadingModel::mitsuyasu, "mitsuyasu"},
    {SpreadingModel::hasselmann, "hasselmann"},
    {SpreadingModel::mastin, "mastin"},
    {SpreadingModel::gamper, "gamper"},
    {SpreadingModel::donelan, "donelan"},
    {SpreadingModel::donelan_banner, "donelan-banner"},
    {SpreadingModel::unified, "unified"},
}};
inline constexpr std::array<Choice<PiersonMoskowitzWind>, 2> kPiersonMoskowitzWinds{{
    {PiersonMoskowitzWind::u10, "u10"},
    {PiersonMoskowitzWind::u19_5, "u19.5"},
}};
inline constexpr std::array<Choice<DepthAttenuation>, 2> kDepthAttenuations{{
    {DepthAttenuation::exact, "exact"},
    {DepthAttenuation::thompson_vincent, "thompson-vincent"},
}};
inline constexpr std::array<Choice<SwellModel>, 2> kSwellModels{{
    {SwellModel::lutz, "lutz"},
    {SwellModel::alimardanov, "alimardanov"},
}};

// What a user chooses. Unset optionals take the model's own value.
struct SpectrumSettings {
  SpectrumModel model = SpectrumModel::jonswap;
  double wind_speed = 10.0;  // U10 [m/s] (U19.5 for pierson-moskowitz with u19_5)
  double fetch = 1.0e5;      // F [m]
  double depth = std::numeric_limits<double>::infinity();  // h [m]
  double gravity = 9.81;                                   // g [m/s²]
  double wind_direction = 0.0;  // φ [rad]: wind vector (cos φ, sin φ) in (x, z)
  std::optional<SpreadingModel> spreading;
  std::optional<DispersionKind> dispersion;
  double swell = 0.0;                         // ξ (Lutz eq. 29), cos-2s family only
  SwellModel swell_model = SwellModel::lutz;  // the form of Δs(ξ), used when ξ ≠ 0
  double spread_blend = 1.0;                  // b (Alimardanov Algorithm 2), cos-2s family only
  bool printed_spreading = false;  // cos2/cos4/donelan as printed (∫D ≠ 1) instead of normalized
  std::optional<double> gamma;     // peak enhancement γ (JONSWAP/TMA)
  std::optional<double> alpha;     // equilibrium range α (PM/JONSWAP/TMA) or A (Phillips)
  std::optional<double> peak_frequency;  // ω_p [rad/s] (PM/JONSWAP/TMA)
  std::optional<double> sigma_low;       // σ for ω ≤ ω_p (JONSWAP/TMA)
  std::optional<double> sigma_high;      // σ for ω > ω_p (JONSWAP/TMA)
  PiersonMoskowitzWind pm_wind = PiersonMoskowitzWind::u10;
  DepthAttenuation depth_attenuation = DepthAttenuation::exact;
  double phillips_suppression = 1e-3;  // l/L (Gamper §3.4)
  // k_m [rad/m] of the capillary dispersion and of the Unified spectrum and spreading (Gamper
  // §3.4: 370); see capillary_wavenumber_used.
  double capillary_wavenumber = 370.0;
  bool allow_extrapolation = false;
};

// A validated spectrum with every derived parameter resolved (plain data, cheap to copy).
struct Spectrum {
  SpectrumModel model;
  SpreadingModel spreading;
  Dispersion dispersion;
  double wind_speed;      // U [m/s] as given
  double wind_direction;  // φ [rad]
  double gravity;
  double peak_frequency;   // ω_p [rad/s]
  double peak_wavenumber;  // k_p [rad/m]
  // Frequency-spectrum parameters (PM, JONSWAP, TMA, Donelan).
  double alpha = 0.0;
  double gamma = 1.0;
  double sigma_low = 0.07;
  double sigma_high = 0.09;
  double inverse_wave_age = 0.0;  // Ω_c (Donelan, Unified); U ω_p/g otherwise
  PiersonMoskowitzWind pm_wind = PiersonMoskowitzWind::u10;
  // TMA.
  double tma_depth = std::numeric_limits<double>::infinity();
  DepthAttenuation depth_attenuation = DepthAttenuation::exact;
  // Unified (also used by the unified spreading with any model).
  UnifiedParameters unified{};
  // Phillips.
  double phillips_amplitude = 0.0;
  double phillips_largest_wave = 0.0;
  double phillips_smallest_wave = 0.0;
  // Spreading.
  double mitsuyasu_peak_spread = 0.0;
  double swell = 0.0;
  SwellModel swell_model = SwellModel::lutz;
  double spread_blend = 1.0;
  bool printed_spreading = false;
};

Spectrum make_spectrum(const SpectrumSettings& settings);

double frequency_spectrum(const Spectrum& s, double omega);
double wavenumber_spectrum(const Spectrum& s, double k);
double directional_spreading(const Spectrum& s, double omega, double k, double theta);
// D(ω, k, θ) for many θ at one (ω, k): what does not depend on θ (the cos-2s spread s(ω) and
// ln Q(s), the sech² β(ω/ω_p), the Unified upwind ratio) computed once. The spreading's value
// at θ is directional_spreading(s, ω, k, θ)'s, bit for bit.
struct SpreadingAt {
  const Spectrum* spectrum = nullptr;
  double parameter = 0.0;          // s, β or the upwind ratio, by the spreading model
  double log_normalization = 0.0;  // ln Q(s) of the cos-2s family
};
SpreadingAt spreading_at(const Spectrum& s, double omega, double k);
double directional_spreading(const SpreadingAt& d, double theta);
double spreading_at_frequency(const Spectrum& s, double omega, double theta);
double spreading_at_wavenumber(const Spectrum& s, double k, double theta);
double wavevector_spectrum(const Spectrum& s, double kx, double kz);
// ∫_{−π}^{π} D dθ of the chosen spreading in closed form where one exists (1 when
// normalized; π, 3π/4, tanh(βπ) for the printed cos2, cos4 and donelan forms).
double spreading_integral(const Spectrum& s, double omega);
// The cos-2s spread s(ω) (with swell) for the cos-2s family; 0 for the others.
double cos_2s_spread(const Spectrum& s, double omega);
bool is_cos_2s_family(SpreadingModel m);

SpreadingModel default_spreading(SpectrumModel m);
DispersionKind default_dispersion(SpectrumModel m);
// Whether these settings read capillary_wavenumber k_m: the capillary dispersion (Alimardanov
// eq. 2.9), the Unified spectrum and the Unified spreading (their c(k), F_m and c_m, Gamper §3.4).
bool capillary_wavenumber_used(const SpectrumSettings& s);

// The names of kSpectrumModels, kSpreadingModels, kDispersionKinds, kSwellModels.
std::string_view to_string(SpectrumModel m);
std::string_view to_string(SpreadingModel m);
std::string_view to_string(DispersionKind d);
std::string_view to_string(SwellModel m);

}  // namespace oceanref
