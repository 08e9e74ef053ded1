// Gerstner (trochoidal) waves (waves/gerstner.h): closed form, derivatives, equality with one
// component of the FFT ocean, the variance of a set drawn from a spectrum, determinism, loops and
// the trochoid shape.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <numeric>
#include <string>
#include <tuple>
#include <vector>

#include "conformance/render_output.h"
#include "core/errors.h"
#include "core/math.h"
#include "core/quadrature.h"
#include "scene/scene.h"
#include "spectrum/moments.h"
#include "waves/direct_sum.h"
#include "waves/fields.h"
#include "waves/gerstner.h"
#include "waves/ocean.h"
#include "waves/random.h"

using namespace oceanref;

namespace {
constexpr double kGerstnerPi = std::numbers::pi;

double gerstner_field(const std::array<double, kFieldCount>& f, Field which) {
  return f[static_cast<std::size_t>(which)];
}

Spectrum gerstner_spectrum(SpectrumModel model, double wind_direction = 0.3) {
  SpectrumSettings in;
  in.model = model;
  in.wind_direction = wind_direction;
  in.fetch = 5.0e4;
  return make_spectrum(in);
}

// The fields of one wave written out independently with libm (the lines of gerstner.h's header
// and fields.h's one-wave example: η = A cos ψ, D = k̂ A sin ψ and their derivatives).
std::array<double, kFieldCount> gerstner_closed_form(const GerstnerWave& w, double x, double z,
                                                     double t) {
  const double c = std::cos(w.direction);
  const double s = std::sin(w.direction);
  const double psi = w.wavenumber * (c * x + s * z) - w.angular_frequency * t + w.phase;
  const double a = w.amplitude;
  const double k = w.wavenumber;
  return {a * std::cos(psi),
          -k * c * a * std::sin(psi),
          -k * s * a * std::sin(psi),
          c * a * std::sin(psi),
          s * a * std::sin(psi),
          k * c * c * a * std::cos(psi),
          k * s * s * a * std::cos(psi),
          k * c * s * a * std::cos(psi)};
}

GerstnerWaves gerstner_three_waves() {
  return {{{0.5, 0.8, 0.6, 1.1, 2.9}, {0.2, 1.3, -2.0, 4.0, 3.5}, {0.05, 3.7, 2.5, -0.3, 6.0}},
          -0.7};
}

// The key of a thrown SettingError and its message ("" when nothing is thrown).
std::string gerstner_rejection(const GerstnerDraw& d) {
  try {
    validate(d);
  } catch (const SettingError& e) {
    return e.key() + ": " + e.what();
  }
  return "";
}

// A wave with wave vector 2π(a, b)/L: periodic on the L-square lattice.
GerstnerWave gerstner_lattice_wave(int a, int b, double size, double amplitude, double phase) {
  GerstnerWave w;
  w.amplitude = amplitude;
  w.wavenumber = 2.0 * kGerstnerPi * std::hypot(a, b) / size;
  w.direction = std::atan2(static_cast<double>(b), static_cast<double>(a));
  w.phase = phase;
  w.angular_frequency = 1.3;
  return w;
}

// The curvature of the circle through three points (4·area / product of the sides).
double gerstner_circle_curvature(double x0, double y0, double x1, double y1, double x2, double y2) {
  const double cross = (x1 - x0) * (y2 - y0) - (y1 - y0) * (x2 - x0);
  const double a = std::hypot(x1 - x0, y1 - y0);
  const double b = std::hypot(x2 - x1, y2 - y1);
  const double c = std::hypot(x2 - x0, y2 - y0);
  return 2.0 * std::fabs(cross) / (a * b * c);
}
}  // namespace

TEST_CASE("gerstner: one wave's fields are the closed form, sums add in index order") {
  const GerstnerWaves set = gerstner_three_waves();
  double worst = 0.0;
  for (const double x : {0.0, 1.7, -13.1, 55.5}) {
    for (const double z : {0.0, -2.4, 31.0}) {
      for (const double t : {0.0, 0.9, 12.5}) {
        std::array<double, kFieldCount> sum{};
        for (const GerstnerWave& w : set.waves) {
          const GerstnerWaves one{{w}, set.choppiness};
          const auto got = gerstner_raw_fields(one, x, z, t);
          const auto want = gerstner_closed_form(w, x, z, t);
          for (std::size_t f = 0; f < got.size(); ++f) {
            worst = std::max(worst, std::fabs(got[f] - want[f]));
            sum[f] += got[f];
          }
        }
        // The set is the sum of its waves, in index order: the same bits.
        const auto all = gerstner_raw_fields(set, x, z, t);
        for (std::size_t f = 0; f < all.size(); ++f) CHECK(all[f] == sum[f]);
      }
    }
  }
  // |ψ| ≤ ~200 rad: the two phase computations differ by a few ulp of ψ (~1e-13 rad).
  MESSAGE("max |gerstner - closed form| = " << worst);
  CHECK(worst < 1e-12);
}

TEST_CASE("gerstner: slopes and displacement derivatives match central differences") {
  const GerstnerWaves set = gerstner_three_waves();
  const double h = 1e-4;  // error ≤ h²/6·Σk³A ≈ 2e-9 plus rounding ~1e-12
  double worst = 0.0;
  for (const double x : {0.3, -7.7}) {
    for (const double z : {1.1, 20.0}) {
      const double t = 2.2;
      const auto f = gerstner_raw_fields(set, x, z, t);
      const auto xp = gerstner_raw_fields(set, x + h, z, t);
      const auto xm = gerstner_raw_fields(set, x - h, z, t);
      const auto zp = gerstner_raw_fields(set, x, z + h, t);
      const auto zm = gerstner_raw_fields(set, x, z - h, t);
      auto d = [&](const std::array<double, kFieldCount>& p,
                   const std::array<double, kFieldCount>& m, Field which) {
        return (gerstner_field(p, which) - gerstner_field(m, which)) / (2.0 * h);
      };
      const double errors[] = {d(xp, xm, Field::height) - gerstner_field(f, Field::slope_x),
                               d(zp, zm, Field::height) - gerstner_field(f, Field::slope_z),
                               d(xp, xm, Field::displacement_x) - gerstner_field(f, Field::ddx_dx),
                               d(zp, zm, Field::displacement_z) - gerstner_field(f, Field::ddz_dz),
                               d(zp, zm, Field::displacement_x) - gerstner_field(f, Field::ddx_dz),
                               // ∂D_z/∂x = ∂D_x/∂z (fields.h): the raw ddx_dz stands for both.
                               d(xp, xm, Field::displacement_z) - gerstner_field(f, Field::ddx_dz)};
      for (const double e : errors) worst = std::max(worst, std::fabs(e));
    }
  }
  MESSAGE("max |finite difference - analytic| = " << worst);
  CHECK(worst < 1e-8);
}

TEST_CASE("gerstner: a wave with choppiness u is one component of the choppy FFT ocean") {
  // h0(k) = A e^{iφ} at (α, β) = (3, −2), h0(−k) = 0: h(±k, t) = ½A e^{±i(φ − ωt)} (Gamper
  // eq. 4.7), so direct_sum and the FFT must give the Gerstner wave (A, |k|, atan2(β, α), φ, ω).
  const Spectrum s = gerstner_spectrum(SpectrumModel::jonswap);
  const double size = 50.0;
  const int n = 16;
  const int alpha = 3, beta = -2;
  const double amplitude = 0.5, phase = 0.8;
  PatternSpectrum p = pattern_grid(s, Pattern{0, size, n, Band{}});
  const std::size_t i = grid_offset(array_index(alpha, n), array_index(beta, n), n);
  p.h0[i] = Complex(amplitude * std::cos(phase), amplitude * std::sin(phase));
  GerstnerWave w;
  w.amplitude = amplitude;
  w.wavenumber = std::hypot(alpha, beta) * 2.0 * kGerstnerPi / size;
  w.direction = std::atan2(static_cast<double>(beta), static_cast<double>(alpha));
  w.phase = phase;
  w.angular_frequency = p.omega[i];
  CHECK(w.angular_frequency == angular_frequency(s.dispersion, w.wavenumber));
  const double u = -0.9;
  const GerstnerWaves g{{w}, u};

  double worst_direct = 0.0, worst_fft = 0.0, worst_jacobian = 0.0;
  for (const double t : {0.0, 1.7, 13.2}) {
    // Anywhere (off the grid and outside the tile too): the explicit sum.
    for (const double x : {0.0, 1.234, 37.5, -80.2}) {
      for (const double z : {0.0, 4.321, -12.0, 99.9}) {
        const auto direct = direct_sum(p, p, x, z, t);
        const auto gerstner = gerstner_raw_fields(g, x, z, t);
        for (std::size_t f = 0; f < direct.size(); ++f) {
          worst_direct = std::max(worst_direct, std::fabs(direct[f] - gerstner[f]));
        }
        // The same combined with choppiness u: the Jacobian of the choppy ocean.
        PointFields ocean;
        add_cascade(ocean, direct, u);
        finish_combination(ocean);
        worst_jacobian = std::max(worst_jacobian,
                                  std::fabs(ocean.jacobian - gerstner_point(g, x, z, t).jacobian));
      }
    }
    // At the grid nodes: the FFT synthesis.
    const CascadeFields fft = synthesize_cascade(p, p, t, 1);
    for (int b = 0; b < n; ++b) {
      for (int a = 0; a < n; ++a) {
        const double x = a * size / n, z = b * size / n;
        const auto gerstner = gerstner_raw_fields(g, x, z, t);
        for (std::size_t f = 0; f < gerstner.size(); ++f) {
          const double v = fft.values[f][grid_offset(a, b, n)];
          worst_fft = std::max(worst_fft, std::fabs(v - gerstner[f]));
        }
      }
    }
  }
  MESSAGE("max |direct_sum - gerstner| = " << worst_direct
                                           << ", max |FFT - gerstner| = " << worst_fft
                                           << ", max |det J difference| = " << worst_jacobian);
  CHECK(worst_direct < 1e-13);
  CHECK(worst_fft < 1e-13);
  CHECK(worst_jacobian < 1e-13);
}

TEST_CASE("gerstner: a drawn set carries the spectrum's variance over its band") {
  for (const SpectrumModel model :
       {SpectrumModel::jonswap, SpectrumModel::pierson_moskowitz, SpectrumModel::donelan,
        SpectrumModel::unified, SpectrumModel::phillips}) {
    CAPTURE(to_string(model));
    const Spectrum s = gerstner_spectrum(model);
    GerstnerDraw d;
    d.count = 96;
    d.direction_bins = 12;
    d.min_wavenumber = 0.3 * s.peak_wavenumber;
    d.max_wavenumber = 30.0 * s.peak_wavenumber;
    const GerstnerWaves g = draw_gerstner_waves(s, d, 7);
    REQUIRE(g.waves.size() == 96);
    CHECK(g.choppiness == d.choppiness);

    // Independently: m0(k_max) − m0(k_min) by spectrum/moments.h (a 1-D integral of Ψ, against
    // the drawn 2-D cells of Ψ·D, each to a relative 1e-10).
    const double want =
        zeroth_moment(s, d.max_wavenumber).value - zeroth_moment(s, d.min_wavenumber).value;
    double variance = 0.0;
    for (const GerstnerWave& w : g.waves) variance += 0.5 * w.amplitude * w.amplitude;
    MESSAGE(to_string(model) << ": ½ΣA² = " << variance << ", ∫Ψ dk = " << want
                             << ", relative difference " << std::fabs(variance / want - 1.0));
    CHECK(std::fabs(variance / want - 1.0) < 1e-8);

    // Each wave inside its cell, and each wavenumber row carrying ∫Ψ dk over its bin
    // (∫D dθ = 1 over the direction bins).
    const int n_k = d.count / d.direction_bins;
    for (int i = 0; i < n_k; ++i) {
      const double ratio = d.max_wavenumber / d.min_wavenumber;
      const double k0 = i == 0 ? d.min_wavenumber
                               : d.min_wavenumber * math::exp(i / double(n_k) * math::log(ratio));
      const double k1 =
          i + 1 == n_k ? d.max_wavenumber
                       : d.min_wavenumber * math::exp((i + 1) / double(n_k) * math::log(ratio));
      const QuadratureResult row =
          integrate([&](double k) { return wavenumber_spectrum(s, k); }, {k0, k1});
      double row_variance = 0.0;
      for (int j = 0; j < d.direction_bins; ++j) {
        const GerstnerWave& w = g.waves[static_cast<std::size_t>(i * d.direction_bins + j)];
        const double theta0 =
            s.wind_direction - kGerstnerPi + 2.0 * kGerstnerPi * j / d.direction_bins;
        const double theta1 =
            s.wind_direction - kGerstnerPi + 2.0 * kGerstnerPi * (j + 1) / d.direction_bins;
        CHECK(w.wavenumber >= k0);
        CHECK(w.wavenumber <= k1);
        CHECK(w.direction >= theta0);
        CHECK(w.direction <= theta1);
        CHECK(w.phase > 0.0);
        CHECK(w.phase < 2.0 * kGerstnerPi);
        CHECK(w.angular_frequency == angular_frequency(s.dispersion, w.wavenumber));
        row_variance += 0.5 * w.amplitude * w.amplitude;
      }
      CHECK(std::fabs(row_variance / row.value - 1.0) < 1e-8);
    }
  }
}

TEST_CASE("gerstner: under the Unified spreading each cell carries Ψ (1 + Δ(k) cos 2θ)/2π") {
  // The cos-2θ spreading of Elfouhaily et al. (Gamper eq. 3.72) integrates in θ in closed form:
  // ∫_{θ0}^{θ1} (1 + Δ cos 2t)/2π dt = (θ1 − θ0 + Δ/2 (sin 2t1 − sin 2t0))/2π, t = θ − φ_wind.
  // Δ(k) = tanh(ln2/4 + 4 (c/c_p)^2.5 + 0.13 u*/c_m (c_m/c)^2.5) with the gravity-capillary
  // c(k) = √(g/k (1 + (k/k_m)²)), written here with libm. The draw integrates Ψ·D over each cell
  // in 2-D; here the θ integral is exact and only the k integral is numeric.
  SpectrumSettings in;
  in.model = SpectrumModel::jonswap;
  in.spreading = SpreadingModel::unified;
  in.wind_direction = 0.3;
  in.fetch = 5.0e4;
  const Spectrum s = make_spectrum(in);
  REQUIRE(s.spreading == SpreadingModel::unified);
  const UnifiedParameters& u = s.unified;
  auto upwind_ratio = [&](double k) {
    const double c = std::sqrt(s.gravity / k *
                               (1.0 + (k / u.capillary_wavenumber) * (k / u.capillary_wavenumber)));
    return std::tanh(std::log(2.0) / 4.0 + 4.0 * std::pow(c / u.peak_phase_speed, 2.5) +
                     0.13 * u.friction_velocity / u.min_phase_speed *
                         std::pow(u.min_phase_speed / c, 2.5));
  };
  GerstnerDraw d;
  d.count = 48;
  d.direction_bins = 12;
  d.min_wavenumber = 0.3 * s.peak_wavenumber;
  d.max_wavenumber = 300.0 * s.peak_wavenumber;  // up to k_m's neighbourhood, where Δ turns
  const GerstnerWaves g = draw_gerstner_waves(s, d, 3);
  const int n_k = d.count / d.direction_bins;
  double min_ratio = 1.0, max_ratio = 0.0;
  for (int i = 0; i < n_k; ++i) {
    const double ratio = d.max_wavenumber / d.min_wavenumber;
    const double k0 = i == 0 ? d.min_wavenumber
                             : d.min_wavenumber * math::exp(i / double(n_k) * math::log(ratio));
    const double k1 = i + 1 == n_k
                          ? d.max_wavenumber
                          : d.min_wavenumber * math::exp((i + 1) / double(n_k) * math::log(ratio));
    min_ratio = std::min(min_ratio, upwind_ratio(k0));
    max_ratio = std::max(max_ratio, upwind_ratio(k0));
    for (int j = 0; j < d.direction_bins; ++j) {
      CAPTURE(i);
      CAPTURE(j);
      const double t0 = -kGerstnerPi + 2.0 * kGerstnerPi * j / d.direction_bins;
      const double t1 = -kGerstnerPi + 2.0 * kGerstnerPi * (j + 1) / d.direction_bins;
      const QuadratureResult want = integrate(
          [&](double k) {
            return wavenumber_spectrum(s, k) *
                   (t1 - t0 + 0.5 * upwind_ratio(k) * (std::sin(2.0 * t1) - std::sin(2.0 * t0))) /
                   (2.0 * kGerstnerPi);
          },
          {k0, k1}, QuadratureTolerance{1e-12, 0.0, 4000});
      REQUIRE(want.converged);
      const GerstnerWave& w = g.waves[static_cast<std::size_t>(i * d.direction_bins + j)];
      // Both sides converged to ≤ 1e-10 relative; libm's tanh/pow against the library's differ
      // by ulps.
      CHECK(std::fabs(0.5 * w.amplitude * w.amplitude / want.value - 1.0) < 1e-8);
    }
  }
  // The band spans Δ's range, so a Δ read at the wrong k would move the cells' split in θ.
  MESSAGE("Δ(k) over the band's bin edges: " << min_ratio << " … " << max_ratio);
  CHECK(min_ratio < 0.3);
  CHECK(max_ratio > 0.9);
}

TEST_CASE("gerstner: a drawn set depends only on the spectrum, the draw settings and the seed") {
  const Spectrum s = gerstner_spectrum(SpectrumModel::jonswap);
  GerstnerDraw d;
  d.count = 24;
  d.direction_bins = 6;
  d.choppiness = -0.5;
  d.min_wavenumber = 0.05;
  d.max_wavenumber = 2.0;
  const GerstnerWaves a = draw_gerstner_waves(s, d, 42);
  const GerstnerWaves other = draw_gerstner_waves(s, d, 43);
  const GerstnerWaves b = draw_gerstner_waves(s, d, 42);
  REQUIRE(a.waves.size() == b.waves.size());
  int phases_differ = 0;
  for (std::size_t i = 0; i < a.waves.size(); ++i) {
    // Bit for bit, with another draw in between (no hidden state).
    CHECK(a.waves[i].amplitude == b.waves[i].amplitude);
    CHECK(a.waves[i].wavenumber == b.waves[i].wavenumber);
    CHECK(a.waves[i].direction == b.waves[i].direction);
    CHECK(a.waves[i].phase == b.waves[i].phase);
    CHECK(a.waves[i].angular_frequency == b.waves[i].angular_frequency);
    // Another seed: the cells' variances stay, the jitter and the phases change.
    CHECK(other.waves[i].amplitude == a.waves[i].amplitude);
    if (other.waves[i].phase != a.waves[i].phase) ++phases_differ;
  }
  CHECK(phases_differ == static_cast<int>(a.waves.size()));

  // The documented mapping, cell (i, j) = (2, 4): ξn = uniform_open(random_word(component_key(
  // seed, 0xFFFFFFFF, i, j), n)); k = k_i (k_{i+1}/k_i)^{ξ0}, θ = θ_j + ξ1 Δθ, φ = 2π ξ2.
  const int i = 2, j = 4, n_k = 4;
  const std::uint64_t key = component_key(42, 0xFFFF'FFFFu, i, j);
  const double ratio = d.max_wavenumber / d.min_wavenumber;
  const double k0 = d.min_wavenumber * math::exp(i / double(n_k) * math::log(ratio));
  const double k1 = d.min_wavenumber * math::exp((i + 1) / double(n_k) * math::log(ratio));
  const double theta0 = s.wind_direction - kGerstnerPi + 2.0 * kGerstnerPi * j / 6.0;
  const double theta1 = s.wind_direction - kGerstnerPi + 2.0 * kGerstnerPi * (j + 1) / 6.0;
  const GerstnerWave& w = a.waves[static_cast<std::size_t>(i * 6 + j)];
  CHECK(w.wavenumber == k0 * math::exp(uniform_open(random_word(key, 0)) * math::log(k1 / k0)));
  CHECK(w.direction == theta0 + uniform_open(random_word(key, 1)) * (theta1 - theta0));
  CHECK(w.phase == 2.0 * kGerstnerPi * uniform_open(random_word(key, 2)));
}

TEST_CASE("gerstner: draw settings and wave sets are validated with the field and its range") {
  const GerstnerDraw good;
  CHECK(gerstner_rejection(good).empty());
  auto with = [&](auto change) {
    GerstnerDraw d = good;
    change(d);
    return gerstner_rejection(d);
  };
  const std::string count = with([](GerstnerDraw& d) { d.count = 0; });
  CHECK(count.find("count") == 0);
  CHECK(count.find("[1, 1024]") != std::string::npos);
  CHECK(with([](GerstnerDraw& d) { d.count = 1025; }).find("count") == 0);
  CHECK(with([](GerstnerDraw& d) { d.direction_bins = 7; }).find("direction_bins") == 0);
  CHECK(with([](GerstnerDraw& d) { d.direction_bins = 0; }).find("direction_bins") == 0);
  // The ends of the ranges are valid: one wave per direction bin, one bin, 1024 waves.
  CHECK(with([](GerstnerDraw& d) { d.direction_bins = d.count; }).empty());
  CHECK(with([](GerstnerDraw& d) { d.direction_bins = 1; }).empty());
  CHECK(with([](GerstnerDraw& d) { d.direction_bins = 2 * d.count; }).find("direction_bins") == 0);
  CHECK(with([](GerstnerDraw& d) {
          d.count = 1024;
          d.direction_bins = 1024;
        }).empty());
  CHECK(with([](GerstnerDraw& d) { d.choppiness = 0.1; }).find("choppiness") == 0);
  CHECK(with([](GerstnerDraw& d) {
          d.choppiness = std::numeric_limits<double>::quiet_NaN();
        }).find("choppiness") == 0);
  CHECK(with([](GerstnerDraw& d) { d.min_wavenumber = 0.0; }).find("min_wavenumber") == 0);
  const std::string k_max = with([](GerstnerDraw& d) { d.max_wavenumber = d.min_wavenumber; });
  CHECK(k_max.find("max_wavenumber") == 0);
  CHECK(k_max.find("(min_wavenumber = 0.1, 1e6]") != std::string::npos);
  CHECK(with([](GerstnerDraw& d) {
          d.max_wavenumber = std::numeric_limits<double>::infinity();
        }).find("max_wavenumber") == 0);
  const Spectrum s = gerstner_spectrum(SpectrumModel::jonswap);
  GerstnerDraw bad;
  bad.count = 0;
  CHECK_THROWS_AS(draw_gerstner_waves(s, bad, 1), std::invalid_argument);

  GerstnerWaves g = gerstner_three_waves();
  CHECK_NOTHROW(validate(g));
  g.choppiness = 0.5;
  CHECK_THROWS_AS(validate(g), SettingError);
  // Each field of a wave outside its range is refused under its own key; 0 amplitude and
  // wavenumber are valid (a still wave).
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const auto refused_key = [](const GerstnerWaves& waves) -> std::string {
    try {
      validate(waves);
    } catch (const SettingError& e) {
      return e.key();
    }
    return "";
  };
  const auto with_wave = [&](auto change) {
    GerstnerWaves w = gerstner_three_waves();
    change(w.waves[1]);
    return refused_key(w);
  };
  CHECK(with_wave([](GerstnerWave& w) { w.amplitude = -1.0; }) == "amplitude");
  CHECK(with_wave([&](GerstnerWave& w) { w.amplitude = inf; }) == "amplitude");
  CHECK(with_wave([](GerstnerWave& w) { w.amplitude = 0.0; }).empty());
  CHECK(with_wave([](GerstnerWave& w) { w.wavenumber = -0.5; }) == "wavenumber");
  CHECK(with_wave([&](GerstnerWave& w) { w.wavenumber = nan; }) == "wavenumber");
  CHECK(with_wave([](GerstnerWave& w) { w.wavenumber = 0.0; }).empty());
  CHECK(with_wave([&](GerstnerWave& w) { w.direction = inf; }) == "direction");
  CHECK(with_wave([&](GerstnerWave& w) { w.phase = nan; }) == "phase");
  CHECK(with_wave([&](GerstnerWave& w) { w.angular_frequency = -inf; }) == "angular_frequency");
  CHECK(with_wave([](GerstnerWave& w) { w.angular_frequency = -3.0; }).empty());
  g = gerstner_three_waves();
  CHECK_THROWS_AS(gerstner_loops(g, 0.0, 0.0, 0.0, 10.0, 0), std::invalid_argument);
  CHECK_THROWS_AS(gerstner_loops(g, 0.0, 0.0, 0.0, 0.0, 8), std::invalid_argument);
  CHECK_THROWS_AS(gerstner_loops(g, std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0, 1.0, 8),
                  std::invalid_argument);
}

TEST_CASE("gerstner: one wave with |u|kA = 0.9 never folds; its min det J is 1 - 0.9") {
  // det J = 1 + u k A cos ψ (∇D = kA cos ψ k̂k̂ᵀ, rank one): min 1 − |u|kA at the crests.
  const double size = 40.0;
  const int points = 128;
  const GerstnerWave w = gerstner_lattice_wave(2, 1, size, 0.6, 0.0);
  const GerstnerWaves g{{w}, -0.9 / (w.wavenumber * w.amplitude)};
  CHECK(std::fabs(gerstner_steepness_bound(g) - 0.9) < 1e-15);
  for (const double t : {0.0, 0.37, 5.1, 100.0}) {
    const GerstnerLoops loops = gerstner_loops(g, t, 0.0, 0.0, size, points);
    CHECK(loops.folded_fraction == 0.0);
    CHECK(loops.min_jacobian >= 0.1 - 1e-14);
  }
  // At t = 0 the lattice holds crests (ψ = 2π(2m + n)/128 ≡ 0): the minimum is 1 − 0.9 there.
  const GerstnerLoops loops = gerstner_loops(g, 0.0, -size / 2, -size / 2, size, points);
  MESSAGE("min det J = " << loops.min_jacobian << " at (" << loops.min_x << ", " << loops.min_z
                         << ")");
  CHECK(std::fabs(loops.min_jacobian - 0.1) < 1e-14);
  const double psi =
      w.wavenumber * (std::cos(w.direction) * loops.min_x + std::sin(w.direction) * loops.min_z);
  CHECK(std::cos(psi) > 1.0 - 1e-12);
  // The lattice is (x_min + m·h, z_min + n·h), h = extent/points: the minimum sits on it.
  const double h = size / points;
  const double m = (loops.min_x + size / 2) / h, n = (loops.min_z + size / 2) / h;
  CHECK(std::fabs(m - std::nearbyint(m)) < 1e-9);
  CHECK(std::fabs(n - std::nearbyint(n)) < 1e-9);
  const GerstnerLoops corner = gerstner_loops(g, 0.0, 3.0, -4.0, 10.0, 1);
  CHECK(corner.min_x == 3.0);
  CHECK(corner.min_z == -4.0);
  CHECK(std::fabs(gerstner_point(g, 0.0, 0.0, 0.0).jacobian - 0.1) < 1e-14);
  CHECK(gerstner_point(g, 0.0, 0.0, 0.0).foam == 0.0);
}

TEST_CASE("gerstner: one wave with |u|kA = 1.2 folds on acos(1/1.2)/pi of its period") {
  // det J < 0 ⇔ cos ψ > 1/1.2 (u < 0): an arc of 2 acos(1/1.2) of every 2π. On the lattice
  // (m, n)·L/P the phase of the wave 2π(a, b)/L is 2π(am + bn)/P + φ − ωt, and (m, n) ↦
  // am + bn mod P hits each multiple of g = gcd(a, b, P) equally often: the lattice sees P/g
  // evenly spaced phases, and an arc holds its length/spacing ± 1 of them, so the folded
  // fraction is within g/P of the analytic one.
  const double size = 60.0;
  const int points = 200;
  const double want = std::acos(1.0 / 1.2) / kGerstnerPi;
  struct LatticeCase {
    int a, b;
    double time;
  };
  for (const LatticeCase c : {LatticeCase{3, 1, 0.0}, LatticeCase{4, 0, 0.0},
                              LatticeCase{3, 1, 2.3}, LatticeCase{0, 5, 7.7}}) {
    const GerstnerWave w = gerstner_lattice_wave(c.a, c.b, size, 0.4, 0.37);
    const GerstnerWaves g{{w}, -1.2 / (w.wavenumber * w.amplitude)};
    const GerstnerLoops loops = gerstner_loops(g, c.time, 0.0, 0.0, size, points);
    const int gcd = std::gcd(std::gcd(c.a, c.b), points);
    const double tolerance = static_cast<double>(gcd) / points;
    MESSAGE("(a, b) = (" << c.a << ", " << c.b << "): folded " << loops.folded_fraction
                         << ", analytic " << want << ", tolerance " << tolerance);
    CHECK(std::fabs(loops.folded_fraction - want) <= tolerance);
    // The minimum 1 − 1.2 at a crest, the lattice within half a phase step of it.
    CHECK(loops.min_jacobian >= -0.2 - 1e-14);
    CHECK(loops.min_jacobian <= -0.2 + 1.2 * (1.0 - std::cos(kGerstnerPi * gcd / points)));
  }
}

TEST_CASE("gerstner: det J >= 1 - |u| sum k A, tight for aligned crests") {
  // Two collinear waves with their crests together at the origin: det J = 1 − b there.
  const GerstnerWaves aligned{{{0.6, 0.5, 0.4, 0.0, 1.0}, {0.2, 1.3, 0.4, 0.0, 2.0}},
                              -0.9 / (0.5 * 0.6 + 1.3 * 0.2)};
  CHECK(std::fabs(gerstner_steepness_bound(aligned) - 0.9) < 1e-15);
  CHECK(std::fabs(gerstner_point(aligned, 0.0, 0.0, 0.0).jacobian - 0.1) < 1e-14);

  // A drawn set (many directions) scaled to b = 0.95: never below 0.05.
  const Spectrum s = gerstner_spectrum(SpectrumModel::jonswap);
  GerstnerDraw d;
  d.count = 64;
  d.direction_bins = 8;
  d.min_wavenumber = 0.5 * s.peak_wavenumber;
  d.max_wavenumber = 20.0 * s.peak_wavenumber;
  GerstnerWaves g = draw_gerstner_waves(s, d, 3);
  g.choppiness = -1.0;
  g.choppiness = -0.95 / gerstner_steepness_bound(g);
  double lowest = 1.0;
  for (const double t : {0.0, 3.0, 17.0}) {
    const GerstnerLoops loops = gerstner_loops(g, t, -50.0, -50.0, 100.0, 64);
    CHECK(loops.folded_fraction == 0.0);
    lowest = std::min(lowest, loops.min_jacobian);
  }
  MESSAGE("drawn set with b = 0.95: lowest det J on the lattices = " << lowest);
  CHECK(lowest >= 0.05 - 1e-12);
  CHECK(lowest < 1.0);

  // The lattice's statistics against det J of gerstner_point at each of its points (at a time
  // and rest points that differ from each other).
  const double t = 3.0, x_min = -31.0, z_min = 7.0, extent = 40.0;
  const int points = 24;
  const GerstnerLoops loops = gerstner_loops(g, t, x_min, z_min, extent, points);
  double min_det = std::numeric_limits<double>::infinity(), min_x = 0.0, min_z = 0.0;
  int folded = 0;
  for (int n = 0; n < points; ++n) {
    for (int m = 0; m < points; ++m) {
      const double x = x_min + m * (extent / points), z = z_min + n * (extent / points);
      const double det = gerstner_point(g, x, z, t).jacobian;
      folded += det < 0.0 ? 1 : 0;
      if (det < min_det) std::tie(min_det, min_x, min_z) = std::tuple{det, x, z};
    }
  }
  CHECK(loops.folded_fraction == doctest::Approx(folded / double(points * points)).epsilon(1e-15));
  CHECK(loops.min_jacobian == doctest::Approx(min_det).epsilon(1e-13));
  CHECK(loops.min_x == min_x);
  CHECK(loops.min_z == min_z);
}

TEST_CASE("gerstner: the displaced profile of one wave is a trochoid") {
  // X(x0) = x0 + uA sin(kx0), Y = A cos(kx0) with c = −ukA: the trochoid traced at radius c/k
  // of a circle of radius 1/k. Near the crest dX/dx0 = 1 − c, near the trough 1 + c; curvatures
  // κ = |X'Y'' − Y'X''|/|X'|³ = Ak²/(1 ∓ c)² (crest sharper than trough).
  const double k = 0.5, a = 1.2, c = 0.8;
  const GerstnerWaves g{{{a, k, 0.0, 0.0, 0.0}}, -c / (k * a)};
  auto point = [&](double x0) {
    const auto f = gerstner_raw_fields(g, x0, 0.0, 0.0);
    return std::array<double, 2>{x0 + g.choppiness * gerstner_field(f, Field::displacement_x),
                                 gerstner_field(f, Field::height)};
  };
  const double delta = 1e-3 / k;
  const double trough = kGerstnerPi / k;
  // (X(x0 + δ) − X(x0 − δ))/2δ = 1 ∓ c sin(kδ)/(kδ): within c(kδ)²/6 of 1 ∓ c.
  const double crest_ratio = (point(delta)[0] - point(-delta)[0]) / (2.0 * delta);
  const double trough_ratio = (point(trough + delta)[0] - point(trough - delta)[0]) / (2.0 * delta);
  const double sinc = std::sin(k * delta) / (k * delta);
  CHECK(std::fabs(crest_ratio - (1.0 - c * sinc)) < 1e-11);
  CHECK(std::fabs(trough_ratio - (1.0 + c * sinc)) < 1e-11);
  const double ratio_tolerance = c * 1e-6 / 6.0 + 1e-12;
  CHECK(std::fabs(crest_ratio - (1.0 - c)) < ratio_tolerance);
  CHECK(std::fabs(trough_ratio - (1.0 + c)) < ratio_tolerance);
  // Curvature from the circle through three displaced points: O((kδ)²) relative error.
  const auto p0 = point(-delta), p1 = point(0.0), p2 = point(delta);
  const auto q0 = point(trough - delta), q1 = point(trough), q2 = point(trough + delta);
  const double crest = gerstner_circle_curvature(p0[0], p0[1], p1[0], p1[1], p2[0], p2[1]);
  const double bottom = gerstner_circle_curvature(q0[0], q0[1], q1[0], q1[1], q2[0], q2[1]);
  const double crest_want = a * k * k / ((1.0 - c) * (1.0 - c));
  const double trough_want = a * k * k / ((1.0 + c) * (1.0 + c));
  MESSAGE("crest curvature " << crest << " (trochoid " << crest_want << "), trough " << bottom
                             << " (" << trough_want << ")");
  CHECK(std::fabs(crest / crest_want - 1.0) < 1e-5);
  CHECK(std::fabs(bottom / trough_want - 1.0) < 1e-5);
  // The period stays 2π/k: X(x0 + λ) = X(x0) + λ.
  const double lambda = 2.0 * kGerstnerPi / k;
  CHECK(std::fabs(point(1.0 + lambda)[0] - (point(1.0)[0] + lambda)) < 1e-12);
  // c = 1 (u = −1/(kA), Tessendorf's form): a cusp, det J = 0 at the crest.
  const GerstnerWaves cusp{{{a, k, 0.0, 0.0, 0.0}}, -1.0 / (k * a)};
  CHECK(std::fabs(gerstner_point(cusp, 0.0, 0.0, 0.0).jacobian) < 1e-15);
}

TEST_CASE("gerstner loop check: a 256² lattice over twice the longest wave, below the camera") {
  // What `render` reports for a Gerstner ocean (gerstner_loop_check): the bound b = |u|Σ k_i A_i,
  // and where b ≥ 1, det J on a 256² lattice over the square of side 2·(2π/k_min) centred
  // below the camera at the scene's time. The golden Gerstner scene has b ≈ 1.16.
  const Scene scene =
      load_scene(std::string(OCEANREF_SOURCE_DIR) + "/reference/scenes/golden/gerstner_waves.json");
  const Ocean ocean = realize_ocean(scene.waves, 1);
  REQUIRE(ocean.gerstner.has_value());
  const GerstnerWaves& g = *ocean.gerstner;
  const GerstnerLoopCheck c = gerstner_loop_check(scene, ocean);
  CHECK(c.steepness_bound == gerstner_steepness_bound(g));
  REQUIRE(c.steepness_bound >= 1.0);
  CHECK(c.sampled);
  const double side = 4.0 * std::numbers::pi / g.min_wavenumber;
  CHECK(c.extent == doctest::Approx(side).epsilon(1e-14));
  const GerstnerLoops expected = gerstner_loops(g, scene.time, scene.camera.position.x - 0.5 * side,
                                                scene.camera.position.z - 0.5 * side, side, 256);
  CHECK(c.loops.min_jacobian == expected.min_jacobian);
  CHECK(c.loops.folded_fraction == expected.folded_fraction);
  CHECK(c.loops.min_x == expected.min_x);
  CHECK(c.loops.min_z == expected.min_z);
  // The minimum lies inside the square below the camera.
  CHECK(std::fabs(c.loops.min_x - scene.camera.position.x) <= 0.5 * side);
  CHECK(std::fabs(c.loops.min_z - scene.camera.position.z) <= 0.5 * side);
  // Gentler waves (b = 0.5): nothing to sample, det J ≥ 1 − b everywhere.
  GerstnerWaves softer = g;
  softer.choppiness *= 0.5 / c.steepness_bound;
  Ocean gentle = ocean;
  gentle.gerstner = softer;
  const GerstnerLoopCheck none = gerstner_loop_check(scene, gentle);
  CHECK(none.steepness_bound == doctest::Approx(0.5).epsilon(1e-12));
  CHECK_FALSE(none.sampled);
  CHECK(none.extent == 0.0);
}
