#include "conformance/float32_backend.h"

#include <fftw3.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <string>

#include "conformance/channel_name.h"
#include "core/fp_environment.h"
#include "core/math.h"
#include "spectrum/frequency_spectra.h"
#include "waves/random.h"

namespace oceanref {

namespace {
constexpr float kPiF = std::numbers::pi_v<float>;

// A GPU's ≈1-ulp float elementary functions, stood in by the portable double ones rounded to
// float (never libm: the same bits on every machine).
float exp_f(float x) {
  return static_cast<float>(math::exp(static_cast<double>(x)));
}
float log_f(float x) {
  return static_cast<float>(math::log(static_cast<double>(x)));
}
float pow_f(float x, float y) {
  return static_cast<float>(math::pow(static_cast<double>(x), static_cast<double>(y)));
}
float cos_f(float x) {
  return static_cast<float>(math::cos(static_cast<double>(x)));
}
float sin_f(float x) {
  return static_cast<float>(math::sin(static_cast<double>(x)));
}
float tanh_f(float x) {
  return static_cast<float>(math::tanh(static_cast<double>(x)));
}
float lgamma_f(float x) {
  return static_cast<float>(math::lgamma(static_cast<double>(x)));
}
float atan2_f(float y, float x) {
  return static_cast<float>(math::atan2(static_cast<double>(y), static_cast<double>(x)));
}
float f(double x) {
  return static_cast<float>(x);
}

ComplexF multiply(ComplexF a, ComplexF b) {
  return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re};
}

// Rounds to 11 significant bits (the precision of a half float), keeping the float range.
float to_half_precision(float x) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &x, sizeof bits);
  bits = (bits + (1u << 12)) & ~((1u << 13) - 1u);
  float out = 0.0f;
  std::memcpy(&out, &bits, sizeof out);
  return out;
}

// The spectrum's constants as a shader would receive them: resolved once on the host by
// make_spectrum (double), rounded to float.
struct SpectrumF {
  SpectrumModel model;
  SpreadingModel spreading;
  DispersionKind dispersion;
  bool has_depth;  // finite depth in the dispersion relation
  float g, depth, capillary_k;
  float wind_direction, wind_speed, peak_frequency;
  float alpha, gamma, sigma_low, sigma_high;
  bool pm_u19_5;
  float tma_depth;  // +inf: no TMA attenuation
  float phillips_amplitude, phillips_largest, phillips_smallest;
  float mitsuyasu_peak_spread, swell, spread_blend;
  bool printed;
};

SpectrumF to_float(const Spectrum& s) {
  SpectrumF o{};
  o.model = s.model;
  o.spreading = s.spreading;
  o.dispersion = s.dispersion.kind;
  o.has_depth = s.dispersion.kind != DispersionKind::deep && std::isfinite(s.dispersion.depth);
  o.g = f(s.gravity);
  o.depth = f(s.dispersion.depth);
  o.capillary_k = f(s.dispersion.capillary_wavenumber);
  o.wind_direction = f(s.wind_direction);
  o.wind_speed = f(s.wind_speed);
  o.peak_frequency = f(s.peak_frequency);
  o.alpha = f(s.alpha);
  o.gamma = f(s.gamma);
  o.sigma_low = f(s.sigma_low);
  o.sigma_high = f(s.sigma_high);
  o.pm_u19_5 = s.pm_wind == PiersonMoskowitzWind::u19_5;
  o.tma_depth = f(s.tma_depth);
  o.phillips_amplitude = f(s.phillips_amplitude);
  o.phillips_largest = f(s.phillips_largest_wave);
  o.phillips_smallest = f(s.phillips_smallest_wave);
  o.mitsuyasu_peak_spread = f(s.mitsuyasu_peak_spread);
  o.swell = f(s.swell);
  o.spread_blend = f(s.spread_blend);
  o.printed = s.printed_spreading;
  return o;
}

// --- dispersion (spectrum/dispersion.h) -----------------------------------------------------
float capillary_factor(const SpectrumF& s, float k) {
  if (s.dispersion != DispersionKind::capillary) return 1.0f;
  const float r = k / s.capillary_k;
  return 1.0f + r * r;
}
float capillary_factor_derivative(const SpectrumF& s, float k) {
  if (s.dispersion != DispersionKind::capillary) return 1.0f;
  const float r = k / s.capillary_k;
  return 1.0f + 3.0f * r * r;
}
// sech²(x) = 4e^{−2x}/(1 + e^{−2x})², x ≥ 0.
float sech2_f(float x) {
  const float e = exp_f(-2.0f * std::fabs(x));
  return 4.0f * e / ((1.0f + e) * (1.0f + e));
}
// ω² = g k (1 + (k/k_m)²) tanh(kh).
float angular_frequency(const SpectrumF& s, float k) {
  if (!(k > 0.0f)) return 0.0f;
  const float depth_factor = s.has_depth ? tanh_f(k * s.depth) : 1.0f;
  return std::sqrt(s.g * k * capillary_factor(s, k) * depth_factor);
}
// dω/dk = g [c'(k) tanh(kh) + c(k) k h sech²(kh)] / (2ω), c the capillary factor.
float group_velocity(const SpectrumF& s, float k, float omega) {
  if (!s.has_depth) return s.g * capillary_factor_derivative(s, k) / (2.0f * omega);
  const float kh = k * s.depth;
  return s.g *
         (capillary_factor_derivative(s, k) * tanh_f(kh) +
          capillary_factor(s, k) * kh * sech2_f(kh)) /
         (2.0f * omega);
}

// --- frequency and wavenumber spectra (spectrum/frequency_spectra.h, wavenumber_spectra.h) --
float pow4(float x) {
  return (x * x) * (x * x);
}
// Gamper eq. 3.37 (3.36 for U19.5).
float pierson_moskowitz(const SpectrumF& s, float omega, float alpha) {
  const float e = s.pm_u19_5 ? -f(kPiersonMoskowitzBeta) * pow4(s.g / (s.wind_speed * omega))
                             : -1.25f * pow4(s.peak_frequency / omega);
  return alpha * s.g * s.g / (pow4(omega) * omega) * exp_f(e);
}
// γ^r, r = exp[−(ω − ω_p)²/(2σ²ω_p²)]  (Gamper eq. 3.51).
float peak_enhancement(const SpectrumF& s, float omega, float sigma) {
  const float x = (omega - s.peak_frequency) / (sigma * s.peak_frequency);
  return pow_f(s.gamma, exp_f(-0.5f * x * x));
}
// Φ of Thompson and Vincent (Vincevičius eq. 1.10, with the ω_h ≥ 2 branch).
float thompson_vincent(const SpectrumF& s, float omega) {
  if (std::isinf(s.tma_depth)) return 1.0f;
  const float wh = omega * std::sqrt(s.tma_depth / s.g);
  if (wh <= 1.0f) return 0.5f * wh * wh;
  if (wh < 2.0f) return 1.0f - 0.5f * (2.0f - wh) * (2.0f - wh);
  return 1.0f;
}
float frequency_spectrum(const SpectrumF& s, float omega) {
  switch (s.model) {
    case SpectrumModel::pierson_moskowitz:
      return pierson_moskowitz(s, omega, s.pm_u19_5 ? f(kPiersonMoskowitzAlpha) : s.alpha);
    case SpectrumModel::jonswap:
    case SpectrumModel::tma: {
      const float sigma = omega <= s.peak_frequency ? s.sigma_low : s.sigma_high;
      const float j = pierson_moskowitz(s, omega, s.alpha) * peak_enhancement(s, omega, sigma);
      return s.model == SpectrumModel::tma ? j * thompson_vincent(s, omega) : j;
    }
    case SpectrumModel::donelan: {
      // αg²ω⁻⁴/ω_p exp[−(ω_p/ω)⁴] γ^r  (Gamper eq. 3.68).
      const float e = -pow4(s.peak_frequency / omega);
      return s.alpha * s.g * s.g / pow4(omega) / s.peak_frequency * exp_f(e) *
             peak_enhancement(s, omega, s.sigma_low);
    }
    default:
      return 0.0f;
  }
}
// Ψ(k) [m³]: Phillips' own, or S(ω(k)) dω/dk  (Gamper eq. 3.58).
float wavenumber_spectrum(const SpectrumF& s, float k, float omega) {
  if (s.model == SpectrumModel::phillips) {
    const float big = k * s.phillips_largest;
    const float small = k * s.phillips_smallest;
    return s.phillips_amplitude * exp_f(-1.0f / (big * big) - small * small) / (k * k * k);
  }
  return frequency_spectrum(s, omega) * group_velocity(s, k, omega);
}

// --- directional spreading (spectrum/spreading.h) ------------------------------------------
// θ − φ wrapped to [−π, π].
float wrap(float t) {
  while (t > kPiF) t -= 2.0f * kPiF;
  while (t < -kPiF) t += 2.0f * kPiF;
  return t;
}
float cos_2s_spread(const SpectrumF& s, float omega) {
  const float r = omega / s.peak_frequency;
  float spread = 0.0f;
  switch (s.spreading) {
    case SpreadingModel::mitsuyasu:
      spread = s.mitsuyasu_peak_spread * (r <= 1.0f ? pow_f(r, 5.0f) : pow_f(r, -2.5f));
      break;
    case SpreadingModel::hasselmann:
      if (r < 1.0f) {
        spread = 6.97f * pow_f(r, 4.06f);
      } else {
        const float mu = -2.33f - 1.45f * (s.wind_speed * s.peak_frequency / s.g - 1.17f);
        spread = 9.77f * pow_f(r, mu);
      }
      break;
    case SpreadingModel::mastin:
      spread = 9.77f * pow_f(r, r < 1.0f ? 4.06f : -2.34f);
      break;
    case SpreadingModel::gamper:
      spread = r < 1.0f ? 6.97f * pow_f(r, 5.0f) : 9.77f * pow_f(r, -2.5f);
      break;
    default:
      break;
  }
  if (s.swell != 0.0f) spread += 16.0f * tanh_f(s.peak_frequency / omega) * s.swell * s.swell;
  return spread;
}
// Q(s)|cos(θ/2)|^{2s} in logarithms  (Gamper eq. 3.57).
float cos_2s_spreading(float t, float spread) {
  const float c = std::fabs(cos_f(0.5f * t));
  constexpr float kLn2 = 0.6931472f;
  constexpr float kLnPi = 1.1447299f;
  const float log_q = (2.0f * spread - 1.0f) * kLn2 - kLnPi + 2.0f * lgamma_f(spread + 1.0f) -
                      lgamma_f(2.0f * spread + 1.0f);
  if (spread == 0.0f) return exp_f(log_q);
  if (c == 0.0f) return 0.0f;
  return exp_f(log_q + 2.0f * spread * log_f(c));
}
// β/(2 tanh βπ) sech²(βθ)  (Vincevičius eq. 1.12).
float sech2_spreading(float t, float beta) {
  const float x = beta * kPiF;
  const float b_over_tanh = x < 1e-4f ? (1.0f + x * x / 3.0f) / kPiF : beta / tanh_f(x);
  return 0.5f * b_over_tanh * sech2_f(beta * t);
}
float donelan_beta(float r) {
  if (r > 0.56f && r < 0.95f) return 2.61f * pow_f(r, 1.3f);
  if (r >= 0.95f && r < 1.6f) return 2.28f * pow_f(r, -1.3f);
  return 1.24f;
}
float donelan_banner_beta(float r) {
  if (r < 0.95f) return 2.61f * pow_f(r, 1.3f);
  if (r < 1.6f) return 2.28f * pow_f(r, -1.3f);
  return pow_f(10.0f, -0.4f + 0.8393f * exp_f(-0.567f * log_f(r * r)));
}
float directional_spreading(const SpectrumF& s, float omega, float theta) {
  const float t = wrap(theta - s.wind_direction);
  const float r = omega / s.peak_frequency;
  switch (s.spreading) {
    case SpreadingModel::cos2: {
      const float c = cos_f(t);
      return c * c / (s.printed ? 1.0f : kPiF);
    }
    case SpreadingModel::cos4: {
      const float c = cos_f(t);
      return pow4(c) / (s.printed ? 1.0f : 0.75f * kPiF);
    }
    case SpreadingModel::donelan: {
      const float beta = donelan_beta(r);
      return s.printed ? 0.5f * beta * sech2_f(beta * t) : sech2_spreading(t, beta);
    }
    case SpreadingModel::donelan_banner:
      return sech2_spreading(t, donelan_banner_beta(r));
    default: {
      const float d = cos_2s_spreading(t, cos_2s_spread(s, omega));
      if (s.spread_blend == 1.0f) return d;
      // (1 − b)(2/π)cos²θ on |θ| ≤ π/2 + b D_cos2s  (Alimardanov Algorithm 2).
      const float c = cos_f(t);
      const float forward = std::fabs(t) > 0.5f * kPiF ? 0.0f : 2.0f / kPiF * c * c;
      return (1.0f - s.spread_blend) * forward + s.spread_blend * d;
    }
  }
}

// --- the random draws (waves/random.h): the integer hash exactly, the rest in float -------
struct NormalPairF {
  float real, imag;
};
NormalPairF standard_normal_pair_f(std::uint64_t key) {
  // uniform = ((word >> 11) + 0.5)·2⁻⁵³ in float: the top bits rounded to 24, so u may round to
  // 1 (then −2 ln u = 0: the draw's radius, tiny anyway, becomes 0).
  const auto uniform = [&](std::uint64_t n) {
    return (static_cast<float>(random_word(key, n) >> 11) + 0.5f) * 0x1.0p-53f;
  };
  const float u1 = uniform(0);
  const float u2 = uniform(1);
  const float radius = std::sqrt(-2.0f * log_f(u1));
  const float angle = 2.0f * kPiF * u2;
  return {radius * cos_f(angle), radius * sin_f(angle)};
}

Float32Pattern make_pattern(const SpectrumF& s, std::uint64_t seed, const Pattern& p,
                            Float32Defect defect) {
  const int n = p.resolution;
  const std::size_t cells = grid_cells(n);
  Float32Pattern out{p,
                     std::vector<float>(cells),
                     std::vector<float>(cells),
                     std::vector<float>(cells),
                     std::vector<ComplexF>(cells),
                     std::vector<float>(cells),
                     std::vector<float>(cells),
                     std::vector<float>(cells),
                     std::vector<float>(cells),
                     std::vector<float>(cells)};
  const float dk = 2.0f * kPiF / f(p.size);
  const float lower = f(p.band.lower);
  const float upper = f(p.band.upper);
  for (int b = 0; b < n; ++b) {
    for (int a = 0; a < n; ++a) {
      const std::size_t i = grid_offset(a, b, n);
      const int alpha = wave_index(a, n);
      const int beta = wave_index(b, n);
      const float kx = static_cast<float>(alpha) * dk;
      const float kz = static_cast<float>(beta) * dk;
      const float k = std::sqrt(kx * kx + kz * kz);
      out.kx[i] = kx;
      out.kz[i] = kz;
      out.k[i] = k;
      if (!(k > 0.0f)) continue;
      out.inverse_k[i] = 1.0f / k;
      const float omega = angular_frequency(s, k);
      out.omega[i] = omega;
      // Θ(k) = Ψ(k) D(ω, θ)/k  (Gamper eq. 3.59–3.61).
      const float psi = wavenumber_spectrum(s, k, omega);
      const float jacobian = defect == Float32Defect::drop_polar_jacobian ? 1.0f : k;
      out.theta[i] =
          psi == 0.0f ? 0.0f : psi * directional_spreading(s, omega, atan2_f(kz, kx)) / jacobian;
      if (!(k >= lower && k < upper)) continue;
      out.in_band[i] = 1.0f;
      out.variance[i] = out.theta[i] * dk * dk;
      if (out.variance[i] == 0.0f) continue;
      // h0 = (ξ_r + iξ_i)/√2 · √(2Θ(k)Δk²) = ξ √(Θ(k)Δk²)  (Gamper eq. 4.2).
      const NormalPairF xi = standard_normal_pair_f(component_key(seed, p.cascade, alpha, beta));
      const float amplitude = std::sqrt(out.variance[i]);
      out.h0[i] = {xi.real * amplitude, xi.imag * amplitude};
    }
  }
  return out;
}

// FFTW's planner is not thread-safe.
std::mutex& planner_mutex() {
  static std::mutex m;
  return m;
}

// The unnormalized inverse 2-D DFT (e^{+i…}) of `values` in FFTW single precision; the real part.
std::vector<float> inverse_dft_real(const std::vector<ComplexF>& values, int n) {
  fftwf_complex* c = fftwf_alloc_complex(grid_cells(n));
  fftwf_plan plan = nullptr;
  {
    const std::lock_guard lock(planner_mutex());
    plan = fftwf_plan_dft_2d(n, n, c, c, FFTW_BACKWARD, FFTW_ESTIMATE);
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    c[i][0] = values[i].re;
    c[i][1] = values[i].im;
  }
  fftwf_execute(plan);
  std::vector<float> out(grid_cells(n));
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = c[i][0];
  {
    const std::lock_guard lock(planner_mutex());
    fftwf_destroy_plan(plan);
  }
  fftwf_free(c);
  return out;
}

// ½(h0(k)e^{−iωt} + (h0(−k)e^{−iωt})*) for one entry.
ComplexF evolve(ComplexF h0, ComplexF h0_partner, float omega, double time, Float32Defect defect) {
  float phase = omega * static_cast<float>(time);
  if (defect == Float32Defect::half_float_phase) phase = to_half_precision(phase);
  const ComplexF forward{cos_f(phase), -sin_f(phase)};
  const ComplexF a = multiply(h0, forward);
  const ComplexF b =
      defect == Float32Defect::drop_conjugate_term ? ComplexF{} : multiply(h0_partner, forward);
  return {0.5f * (a.re + b.re), 0.5f * (a.im - b.im)};
}

std::string part_channel(std::size_t cascade, Field field) {
  return exr_channel_name("c" + std::to_string(cascade) + "." +
                          std::string(kFieldNames[static_cast<std::size_t>(field)]));
}
}  // namespace

void check_float32_support(const WaveSettings& waves) {
  const SpectrumSettings& s = waves.spectrum;
  const std::string supported =
      " (the float32 example backend supports the spectra phillips, pierson-moskowitz, jonswap, "
      "tma with tma_attenuation thompson-vincent, donelan; every spreading but unified; the "
      "gaussian realization)";
  if (waves.realization != Realization::gaussian) {
    throw std::invalid_argument("waves.realization: mastin is not supported" + supported);
  }
  if (s.model == SpectrumModel::unified) {
    throw std::invalid_argument("waves.spectrum.model: unified is not supported" + supported);
  }
  if (s.model == SpectrumModel::tma && s.depth_attenuation == DepthAttenuation::exact &&
      std::isfinite(s.depth)) {
    throw std::invalid_argument(
        "waves.spectrum.tma_attenuation: exact (Kitaigorodskii, the default) is not supported: it "
        "inverts the finite-depth dispersion relation per frequency" +
        supported);
  }
  if (s.spreading.value_or(default_spreading(s.model)) == SpreadingModel::unified) {
    throw std::invalid_argument("waves.spreading.model: unified is not supported" + supported);
  }
  if (s.swell != 0.0 && s.swell_model != SwellModel::lutz) {
    throw std::invalid_argument(
        "waves.spreading.swell_model: only lutz (Lutz eq. 29) is supported with swell" + supported);
  }
}

std::vector<Float32Cascade> float32_cascades(const WaveSettings& waves, Float32Defect defect) {
  check_float32_support(waves);
  const ReferenceFpEnvironment fp;
  // The host side: the spectrum's constants and the cascade layout, once per scene.
  const SpectrumF s = to_float(make_spectrum(waves.spectrum));
  const double k_max = waves.minimum_wavelength > 0.0
                           ? 2.0 * std::numbers::pi / waves.minimum_wavelength
                           : std::numeric_limits<double>::infinity();
  const std::vector<Band> high_bands = cascade_bands(
      waves.sizes, waves.resolution, waves.band_partitioning, k_max, waves.band_edges);
  const std::vector<Band> low_bands = cascade_bands(
      waves.sizes, waves.low_resolution, waves.band_partitioning, k_max, waves.band_edges);
  std::vector<Float32Cascade> cascades;
  for (std::size_t i = 0; i < waves.sizes.size(); ++i) {
    const auto index = static_cast<std::uint32_t>(i);
    Float32Cascade c;
    c.high = make_pattern(s, waves.seed, {index, waves.sizes[i], waves.resolution, high_bands[i]},
                          defect);
    c.low = waves.low_resolution == waves.resolution
                ? c.high
                : make_pattern(s, waves.seed,
                               {index, waves.sizes[i], waves.low_resolution, low_bands[i]}, defect);
    cascades.push_back(std::move(c));
  }
  if (defect == Float32Defect::flip_one_phase && !cascades.empty()) {
    // Cascade 0's strongest wave (largest |h0| on N_h; the first in row-major order on ties),
    // negated on both of its grids.
    const Float32Pattern& high = cascades[0].high;
    std::size_t strongest = 0;
    float largest = -1.0f;
    for (std::size_t i = 0; i < high.h0.size(); ++i) {
      const float m = high.h0[i].re * high.h0[i].re + high.h0[i].im * high.h0[i].im;
      if (m > largest) {
        largest = m;
        strongest = i;
      }
    }
    const int n = high.pattern.resolution;
    const int alpha = wave_index(static_cast<int>(strongest % static_cast<std::size_t>(n)), n);
    const int beta = wave_index(static_cast<int>(strongest / static_cast<std::size_t>(n)), n);
    for (Float32Pattern* p : {&cascades[0].high, &cascades[0].low}) {
      const int m = p->pattern.resolution;
      if (alpha < -m / 2 || alpha >= m / 2 || beta < -m / 2 || beta >= m / 2) continue;
      ComplexF& h = p->h0[grid_offset(array_index(alpha, m), array_index(beta, m), m)];
      h = {-h.re, -h.im};
    }
  }
  return cascades;
}

std::vector<ComplexF> float32_hkt(const Float32Pattern& p, double time, Float32Defect defect) {
  const int n = p.pattern.resolution;
  std::vector<ComplexF> h(grid_cells(n));
  for (int b = 0; b < n; ++b) {
    for (int a = 0; a < n; ++a) {
      const std::size_t i = grid_offset(a, b, n);
      const std::size_t ic =
          grid_offset(conjugate_array_index(a, n), conjugate_array_index(b, n), n);
      h[i] = evolve(p.h0[i], p.h0[ic], p.omega[i], time, defect);
    }
  }
  return h;
}

std::vector<float> float32_field(const Float32Pattern& p, const std::vector<ComplexF>& hkt,
                                 Field field) {
  const int n = p.pattern.resolution;
  std::vector<ComplexF> v(grid_cells(n));
  for (int b = 0; b < n; ++b) {
    for (int a = 0; a < n; ++a) {
      const std::size_t i = grid_offset(a, b, n);
      const bool nyquist_x = is_nyquist(wave_index(a, n), n);
      const bool nyquist_z = is_nyquist(wave_index(b, n), n);
      const float kx = p.kx[i];
      const float kz = p.kz[i];
      const float inv = p.inverse_k[i];
      // M_f(k): docs/BACKENDS.md "fields" (waves/fields.h field_multiplier).
      ComplexF m{};
      switch (field) {
        case Field::height:
          m = {1.0f, 0.0f};
          break;
        case Field::slope_x:
          m = {0.0f, nyquist_x ? 0.0f : kx};
          break;
        case Field::slope_z:
          m = {0.0f, nyquist_z ? 0.0f : kz};
          break;
        case Field::displacement_x:
          m = {0.0f, nyquist_x ? 0.0f : -kx * inv};
          break;
        case Field::displacement_z:
          m = {0.0f, nyquist_z ? 0.0f : -kz * inv};
          break;
        case Field::ddx_dx:
          m = {nyquist_x ? 0.0f : kx * (kx * inv), 0.0f};
          break;
        case Field::ddz_dz:
          m = {nyquist_z ? 0.0f : kz * (kz * inv), 0.0f};
          break;
        case Field::ddx_dz:
          m = {nyquist_x || nyquist_z ? 0.0f : kz * (kx * inv), 0.0f};
          break;
      }
      v[i] = multiply(m, hkt[i]);
    }
  }
  return inverse_dft_real(v, n);
}

std::vector<float> float32_field(const PatternSpectrum& s, double time, Field field,
                                 Float32Defect defect) {
  const int n = s.pattern.resolution;
  const double dk = wavenumber_spacing(s.pattern.size);
  const auto to_f = [](Complex z) { return ComplexF{f(z.re), f(z.im)}; };
  std::vector<ComplexF> v(grid_cells(n));
  for (int b = 0; b < n; ++b) {
    for (int a = 0; a < n; ++a) {
      const std::size_t i = grid_offset(a, b, n);
      const std::size_t ic =
          grid_offset(conjugate_array_index(a, n), conjugate_array_index(b, n), n);
      const ComplexF h = evolve(to_f(s.h0[i]), to_f(s.h0[ic]), f(s.omega[i]), time, defect);
      v[i] = multiply(to_f(field_multiplier(field, wave_index(a, n), wave_index(b, n), dk,
                                            s.inverse_wavenumber[i], n)),
                      h);
    }
  }
  return inverse_dft_real(v, n);
}

std::vector<ExrPart> float32_stage_parts(const WaveSettings& waves, Stage stage, double time,
                                         Float32Defect defect) {
  const std::vector<Float32Cascade> cascades = float32_cascades(waves, defect);
  const ReferenceFpEnvironment fp;
  std::vector<ExrPart> parts;
  const auto new_part = [&](const std::string& name, int size) -> ExrPart& {
    ExrPart part{name, 0, 0, {}};
    part.image.width = part.image.height = size;
    parts.push_back(std::move(part));
    return parts.back();
  };
  for (std::size_t i = 0; i < cascades.size(); ++i) {
    const Float32Cascade& c = cascades[i];
    const std::string name = "c" + std::to_string(i);
    const bool multi = c.low.pattern.resolution != c.high.pattern.resolution;
    if (stage == Stage::fields) {
      const std::vector<ComplexF> high_h = float32_hkt(c.high, time, defect);
      const std::vector<ComplexF> low_h = multi ? float32_hkt(c.low, time, defect) : high_h;
      new_part(name, c.high.pattern.resolution);
      const std::size_t high_index = parts.size() - 1;
      if (multi) new_part(name + ".low", c.low.pattern.resolution);
      for (int q = 0; q < kFieldCount; ++q) {
        const Field field = Field(q);
        const bool low = multi && is_low_resolution_field(field);
        ExrPart& target = parts[low ? parts.size() - 1 : high_index];
        target.image.channels.push_back(
            {part_channel(i, field), 1,
             float32_field(low ? c.low : c.high, low ? low_h : high_h, field)});
      }
      continue;
    }
    for (const Float32Pattern* p : multi ? std::vector{&c.high, &c.low} : std::vector{&c.high}) {
      const std::string part_name = name + (p == &c.low ? ".low" : "");
      ExrImage& image = new_part(part_name, p->pattern.resolution).image;
      const auto add = [&](const std::string& channel, std::vector<float> values) {
        image.channels.push_back(
            {exr_channel_name(part_name + "." + channel), 1, std::move(values)});
      };
      const auto add_complex = [&](const std::string& channel, const std::vector<ComplexF>& z) {
        std::vector<float> re(z.size()), im(z.size());
        for (std::size_t k = 0; k < z.size(); ++k) {
          re[k] = z[k].re;
          im[k] = z[k].im;
        }
        add(channel + ".re", std::move(re));
        add(channel + ".im", std::move(im));
      };
      switch (stage) {
        case Stage::spectrum:
          add("theta", p->theta);
          add("variance", p->variance);
          add("in_band", p->in_band);
          break;
        case Stage::h0:
          add_complex("h0", p->h0);
          break;
        case Stage::omega:
          add("omega", p->omega);
          add("kx", p->kx);
          add("kz", p->kz);
          add("k", p->k);
          break;
        case Stage::hkt:
          add_complex("hkt", float32_hkt(*p, time, defect));
          break;
        case Stage::fields:
          break;
      }
    }
  }
  if (defect == Float32Defect::half_float_output) {
    for (ExrPart& part : parts) {
      for (ExrChannel& channel : part.image.channels) {
        for (float& v : channel.values) v = to_half_precision(v);
      }
    }
  }
  return parts;
}

}  // namespace oceanref
