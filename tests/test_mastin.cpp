// Mastin, Watterberg and Mareda 1987 as a scene realization (waves.realization = "mastin",
// issue 17): the setting reaches realize_ocean, and the filtered white noise has the statistics of
// the filter (src/waves/mastin.h).
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <vector>

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
    CHECK(mastin.cascades[i].high.h0 == realize_pattern_mastin(mastin.spectrum, 5, ph, 1).h0);
    CHECK(mastin.cascades[i].low.h0 == realize_pattern_mastin(mastin.spectrum, 5, pl, 1).h0);
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
  // E|W(k)|² = N² for unit-variance white noise (unnormalized transform), H = W·√(½(Θ(k) +
  // Θ(−k))Δk²)/N and h0 = 2H on the pair's downwind member, 0 on the other: so per pair
  // E(|h0(k)|² + |h0(−k)|²) = 2(Θ(k) + Θ(−k))Δk², and E|h0|² = ΘΔk² on a self-partner (Nyquist
  // corner, h0 = H). Every grid entry is in the band (no partitioning), k = 0 excluded.
  SpectrumSettings settings;
  settings.model = SpectrumModel::jonswap;
  settings.wind_direction = 0.7;
  const Spectrum s = make_spectrum(settings);
  const int n = 16;
  const Pattern p{0, 150.0, n, Band{}};
  const int seeds = 400;
  std::vector<double> sum(grid_cells(n)), sum_sq(grid_cells(n));
  for (int seed = 0; seed < seeds; ++seed) {
    const PatternSpectrum r = realize_pattern_mastin(s, static_cast<std::uint64_t>(seed), p, 1);
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
