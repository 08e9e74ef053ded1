// Mastin, Watterberg and Mareda 1987 as a scene realization (waves.realization = "mastin",
// issue 17): the setting reaches realize_ocean, and the filtered white noise has the statistics of
// the filter (src/waves/mastin.h).
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "core/quadrature.h"
#include "waves/mastin.h"
#include "waves/ocean.h"

using namespace oceanref;

namespace {
double norm(Complex a) {
  return a.re * a.re + a.im * a.im;
}

WaveSettings two_cascades(Realization r) {
  WaveSettings w;
  w.seed = 5;
  w.realization = r;
  w.spectrum.model = SpectrumModel::jonswap;
  w.spectrum.wind_direction = 0.4;
  w.sizes = {120.0, 30.0};
  w.resolution = 16;
  w.low_resolution = 8;
  w.choppiness = {-1.0, -1.0};
  return w;
}
}  // namespace

TEST_CASE("realize_ocean: waves.realization mastin draws Mastin's h0, gaussian eq. 4.2") {
  const Ocean mastin = realize_ocean(two_cascades(Realization::mastin), 2);
  const Ocean gaussian = realize_ocean(two_cascades(Realization::gaussian), 2);
  REQUIRE(mastin.cascades.size() == 2);
  const double k_max = 2.0 * std::numbers::pi / kMinimumWavelength;
  const std::vector<Band> high = cascade_bands({120.0, 30.0}, 16, true, k_max);
  const std::vector<Band> low = cascade_bands({120.0, 30.0}, 8, true, k_max);
  for (std::uint32_t i = 0; i < 2; ++i) {
    CAPTURE(i);
    const Pattern ph{i, i == 0 ? 120.0 : 30.0, 16, high[i]};
    const Pattern pl{i, i == 0 ? 120.0 : 30.0, 8, low[i]};
    // Bit for bit the realization of waves/mastin.h on both grids (multi-resolution), and
    // likewise eq. 4.2 for the Gaussian one.
    CHECK(mastin.cascades[i].high.h0 ==
          realize_pattern_mastin(mastin.spectrum, {}, {}, 5, ph, 1).h0);
    CHECK(mastin.cascades[i].low.h0 ==
          realize_pattern_mastin(mastin.spectrum, {}, {}, 5, pl, 1).h0);
    CHECK(gaussian.cascades[i].high.h0 == realize_pattern(gaussian.spectrum, 5, ph).h0);
    CHECK(gaussian.cascades[i].low.h0 == realize_pattern(gaussian.spectrum, 5, pl).h0);
  }
  // The fields differ everywhere that matters: compare the height grids of each cascade.
  const std::vector<CascadeFields> fm = synthesize_ocean(mastin, 2.0, 2);
  const std::vector<CascadeFields> fg = synthesize_ocean(gaussian, 2.0, 2);
  for (std::size_t i = 0; i < 2; ++i) {
    const auto& hm = fm[i].values[static_cast<std::size_t>(Field::height)];
    const auto& hg = fg[i].values[static_cast<std::size_t>(Field::height)];
    REQUIRE(hm.size() == hg.size());
    std::size_t same = 0;
    for (std::size_t c = 0; c < hm.size(); ++c)
      if (hm[c] == hg[c]) ++same;
    CHECK(same == 0);
  }
  // Same thread count or not, the same realization (the cascades are the parallel loop).
  CHECK(realize_ocean(two_cascades(Realization::mastin), 1).cascades[1].high.h0 ==
        mastin.cascades[1].high.h0);
}

TEST_CASE("Mastin 1987: mean |h0|^2 of each wave pair follows the filter, downwind member only") {
  // For each of the three filters (the spectrum, and the power laws of Mastin Figs. 2-3).
  // E|W(k)|² = N² for unit-variance white noise (unnormalized transform), H = W·√(½(Θ(k) +
  // Θ(−k))Δk²)/N and h0 = 2H on the pair's downwind member, 0 on the other: so per pair
  // E(|h0(k)|² + |h0(−k)|²) = 2(Θ(k) + Θ(−k))Δk², and E|h0|² = ΘΔk² on a self-partner (Nyquist
  // corner, h0 = H). Every grid entry is in the band (no partitioning), k = 0 excluded.
  SpectrumSettings settings;
  settings.model = SpectrumModel::jonswap;
  settings.wind_direction = 0.7;
  const Spectrum s = make_spectrum(settings);
  const MastinFilter filters[] = {MastinFilter::spectrum, MastinFilter::power_law,
                                  MastinFilter::attenuated_power_law};
  for (const MastinFilter kind : filters) {
    CAPTURE(static_cast<int>(kind));
    MastinSettings ms;
    ms.filter = kind;
    const MastinFilterModel filter = make_mastin_filter(s, ms);
    const int n = 16;
    const Pattern p{0, 150.0, n, Band{}};
    const double dk = wavenumber_spacing(p.size);
    // Θ_f(k)Δk² of entry (α, β); 0 at k = 0 (every other entry is in the band).
    const auto cell_variance = [&](const Spectrum& sp, const Pattern&, int alpha, int beta) {
      if (alpha == 0 && beta == 0) return 0.0;
      return mastin_filter_power(sp, filter, alpha * dk, beta * dk) * dk * dk;
    };
    const int seeds = 400;
    std::vector<double> sum(grid_cells(n)), sum_sq(grid_cells(n));
    for (int seed = 0; seed < seeds; ++seed) {
      const PatternSpectrum r =
          realize_pattern_mastin(s, ms, filter, static_cast<std::uint64_t>(seed), p, 1);
      for (int b = 0; b < n; ++b) {
        for (int a = 0; a < n; ++a) {
          const std::size_t i = grid_offset(a, b, n);
          const std::size_t ic =
              grid_offset(conjugate_array_index(a, n), conjugate_array_index(b, n), n);
          if (i > ic) continue;  // each pair once
          const double cv = cell_variance(s, p, wave_index(a, n), wave_index(b, n));
          const double cvc = cell_variance(s, p, wave_index(conjugate_array_index(a, n), n),
                                           wave_index(conjugate_array_index(b, n), n));
          // Only the member with the larger Θ carries the wave.
          if (cv > cvc) CHECK(r.h0[ic] == Complex{});
          if (cvc > cv) CHECK(r.h0[i] == Complex{});
          const double e = norm(r.h0[i]) + (i == ic ? 0.0 : norm(r.h0[ic]));
          sum[i] += e;
          sum_sq[i] += e * e;
        }
      }
    }
    // Each pair's sample mean within 5 standard errors of the filter (|W|² is close to
    // exponential, so the relative standard error is about 1/√400 = 5%); and the pooled ratio
    // within 4 standard errors of 1.
    int pairs = 0;
    double ratio_sum = 0.0, ratio_var = 0.0;
    for (int b = 0; b < n; ++b) {
      for (int a = 0; a < n; ++a) {
        const std::size_t i = grid_offset(a, b, n);
        const int ac = conjugate_array_index(a, n), bc = conjugate_array_index(b, n);
        const std::size_t ic = grid_offset(ac, bc, n);
        if (i > ic || (a == 0 && b == 0)) continue;
        const double cv = cell_variance(s, p, wave_index(a, n), wave_index(b, n));
        const double cvc = cell_variance(s, p, wave_index(ac, n), wave_index(bc, n));
        const double expected = i == ic ? cv : 2.0 * (cv + cvc);
        if (!(expected > 1e-30)) continue;  // beyond the spectrum's reach in double precision
        const double mean = sum[i] / seeds;
        const double variance = (sum_sq[i] / seeds - mean * mean) * seeds / (seeds - 1);
        const double se = std::sqrt(variance / seeds);
        CAPTURE(a);
        CAPTURE(b);
        CAPTURE(mean);
        CAPTURE(expected);
        CHECK(std::fabs(mean - expected) < 5.0 * se);
        ratio_sum += mean / expected;
        ratio_var += variance / seeds / (expected * expected);
        ++pairs;
      }
    }
    REQUIRE(pairs > 100);
    const double pooled = ratio_sum / pairs;
    const double pooled_se = std::sqrt(ratio_var) / pairs;
    CAPTURE(pooled);
    CAPTURE(pooled_se);
    CHECK(std::fabs(pooled - 1.0) < 4.0 * pooled_se);
    CHECK(pooled_se < 0.01);  // the check resolves a 4% error in the filter's amplitude squared
  }
}

TEST_CASE("Mastin Figs. 2-3: the power-law filter's slope, normalisation and attenuation") {
  SpectrumSettings settings;
  settings.model = SpectrumModel::pierson_moskowitz;
  settings.wind_speed = 15.0;
  const Spectrum s = make_spectrum(settings);
  MastinSettings ms;
  ms.filter = MastinFilter::power_law;
  const MastinFilterModel f = make_mastin_filter(s, ms);
  // D = 2.1 (Mastin's figures) is H = 0.9: amplitude ∝ k^-1.9, power ∝ k^-3.8.
  CHECK(hurst_exponent(2.1) == doctest::Approx(0.9).epsilon(1e-15));
  const double kp = s.peak_wavenumber;
  const double slope = std::log(power_law_filter_power(4.0 * kp, kp, f.variance, f.hurst) /
                                power_law_filter_power(2.0 * kp, kp, f.variance, f.hurst)) /
                       std::log(2.0);
  CHECK(slope == doctest::Approx(-3.8).epsilon(1e-12));
  // Its variance above k_p equals the spectrum's m0: ∫_{k_p}^∞ Θ_f 2πk dk, here by the
  // substitution k = k_p/u (u in (0, 1], integrand 2π k_p² Θ_f(k_p/u)/u³), against PM's closed
  // form m0 = α g²/(4·(5/4)·ω_p⁴) = α g²/(5 ω_p⁴) (∫ω^-5 e^{-5/4 (ω_p/ω)^4} dω = 1/(5 ω_p⁴)).
  const double m0_pm = s.alpha * s.gravity * s.gravity / (5.0 * std::pow(s.peak_frequency, 4));
  CHECK(f.variance == doctest::Approx(m0_pm).epsilon(1e-9));
  const QuadratureResult above = integrate(
      [&](double u) {
        if (u <= 0.0) return 0.0;
        return 2.0 * std::numbers::pi * kp * kp *
               power_law_filter_power(kp / u, kp, f.variance, f.hurst) / (u * u * u);
      },
      {0.0, 0.25, 0.5, 1.0});
  REQUIRE(above.converged);
  CHECK(above.value == doctest::Approx(m0_pm).epsilon(1e-9));
  // The Gaussian below k_p: amplitude e^{-u²/2}, u = (k - k_p)/(k_p/3), 1 at the peak.
  CHECK(low_frequency_attenuation(kp, kp) == 1.0);
  CHECK(low_frequency_attenuation(0.0, kp) == doctest::Approx(std::exp(-9.0)).epsilon(1e-13));
  CHECK(low_frequency_attenuation(2.0 * kp / 3.0, kp) ==
        doctest::Approx(std::exp(-1.0)).epsilon(1e-13));
  // So the attenuated filter peaks at k_p (Fig. 3: the fineness of the roughness), meets the
  // power law there and equals it from there up; the plain one keeps growing towards k = 0
  // (Fig. 2).
  MastinFilterModel attenuated = f;
  attenuated.filter = MastinFilter::attenuated_power_law;
  double best_k = 0.0, best = 0.0;
  for (int i = 1; i <= 400; ++i) {
    const double k = kp * i / 200.0;
    const double v = mastin_filter_power(s, attenuated, k, 0.0);
    if (v > best) best = v, best_k = k;
    if (k >= kp) CHECK(v == mastin_filter_power(s, f, 0.0, k));
    if (k < kp) {
      CHECK(v == doctest::Approx(mastin_filter_power(s, f, kp, 0.0) *
                                 std::exp(-std::pow(3.0 * (k - kp) / kp, 2)))
                     .epsilon(1e-12));
    }
  }
  CHECK(best_k == doctest::Approx(kp).epsilon(1e-12));
  CHECK(mastin_filter_power(s, f, 0.5 * kp, 0.0) > mastin_filter_power(s, f, kp, 0.0));
  // Isotropic, whatever the wind: the same power in every direction.
  CHECK(mastin_filter_power(s, f, 0.6 * kp, 0.8 * kp) == mastin_filter_power(s, f, kp, 0.0));
}

TEST_CASE("Mastin's ad hoc animation: dominant components at one rate, the rest at another") {
  // Pierson-Moskowitz at 15 m/s: S(ω)/S(ω_p) = (ω_p/ω)^5 e^{5/4 (1 - (ω_p/ω)^4)}. The dominant
  // band, where this is >= 2/3, found here by bisection on each side of ω_p.
  SpectrumSettings settings;
  settings.model = SpectrumModel::pierson_moskowitz;
  settings.wind_speed = 15.0;
  const Spectrum s = make_spectrum(settings);
  const double wp = s.peak_frequency;
  const auto ratio = [&](double w) {
    const double r = wp / w;
    return std::pow(r, 5) * std::exp(1.25 * (1.0 - std::pow(r, 4)));
  };
  const auto edge = [&](double inside, double outside) {
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (inside + outside);
      (ratio(mid) >= 2.0 / 3.0 ? inside : outside) = mid;
    }
    return inside;
  };
  const double lower = edge(wp, 0.5 * wp), upper = edge(wp, 2.0 * wp);
  CAPTURE(lower / wp);
  CAPTURE(upper / wp);
  CHECK(is_dominant_component(s, wp));
  CHECK(is_dominant_component(s, lower * (1 + 1e-9)));
  CHECK(is_dominant_component(s, upper * (1 - 1e-9)));
  CHECK_FALSE(is_dominant_component(s, lower * (1 - 1e-6)));
  CHECK_FALSE(is_dominant_component(s, upper * (1 + 1e-6)));
  CHECK_FALSE(is_dominant_component(s, 0.0));
  // On a pattern: ω replaced by the two rates exactly where the band says; h(k, t) turns at
  // that rate (h0 is the same as with the dispersion animation: only the phase rate changes).
  MastinSettings shift;
  shift.animation = MastinAnimation::constant_shift;
  shift.dominant_phase_rate = 1.5;
  shift.background_phase_rate = 0.09;
  const Pattern p{0, 400.0, 32, Band{}};
  const PatternSpectrum dispersion = realize_pattern_mastin(s, {}, {}, 3, p, 1);
  const PatternSpectrum adhoc = realize_pattern_mastin(s, shift, {}, 3, p, 1);
  CHECK(adhoc.h0 == dispersion.h0);
  int dominant = 0, background = 0;
  for (std::size_t i = 0; i < adhoc.omega.size(); ++i) {
    const double w = dispersion.omega[i];
    const bool in_band = w >= lower && w <= upper;
    CHECK(adhoc.omega[i] == (in_band ? 1.5 : 0.09));
    (in_band ? dominant : background) += 1;
  }
  CHECK(dominant > 4);  // the test sees both kinds
  CHECK(background > 100);
  const double t = 0.7;
  const std::vector<Complex> h = spectrum_at_time(adhoc, t);
  for (int b = 0; b < 32; ++b) {
    for (int a = 0; a < 32; ++a) {
      const std::size_t i = grid_offset(a, b, 32);
      const std::size_t ic =
          grid_offset(conjugate_array_index(a, 32), conjugate_array_index(b, 32), 32);
      if (i == ic || !(norm(adhoc.h0[i]) > 0.0)) continue;
      // h(k, t) = ½h0(k)e^{-iω't} (the partner's h0 is 0).
      const double phase = -adhoc.omega[i] * t;
      CHECK(h[i].re == doctest::Approx(0.5 * (adhoc.h0[i].re * std::cos(phase) -
                                              adhoc.h0[i].im * std::sin(phase)))
                           .epsilon(1e-12));
      CHECK(h[i].im == doctest::Approx(0.5 * (adhoc.h0[i].re * std::sin(phase) +
                                              adhoc.h0[i].im * std::cos(phase)))
                           .epsilon(1e-12));
    }
  }
}
