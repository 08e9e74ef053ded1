// The exported synthesis stages (waves/stages.h) against independent computations: the spectrum
// stage against the continuous spectrum's m0, h0 against the random draws and its expectation,
// ω against the dispersion relation, h(k, t) against eq. 4.7, and the inverse DFT of h(k, t)
// against the synthesized height field.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "spectrum/moments.h"
#include "waves/cascades.h"
#include "waves/fields.h"
#include "waves/random.h"
#include "waves/stages.h"

using namespace oceanref;

namespace {
Spectrum stages_spectrum() {
  SpectrumSettings in;
  in.model = SpectrumModel::jonswap;
  in.wind_direction = 0.4;
  in.fetch = 5.0e4;
  return make_spectrum(in);
}

const StageChannel& channel(const std::vector<StageChannel>& channels, const std::string& name) {
  for (const StageChannel& c : channels) {
    if (c.name == name) return c;
  }
  FAIL("no channel " << name);
  return channels.front();
}
}  // namespace

TEST_CASE("stage spectrum: Theta dk^2 per cell sums to the band's m0") {
  const Spectrum s = stages_spectrum();
  // A grid fine enough for the discrete sum to converge (test_waves: 2e-3 at L = 2000 m, N = 256)
  // with its band ending at the Nyquist wavenumber πN/L = 0.4 rad/m.
  const double size = 2000.0;
  const int n = 256;
  const double k_max = nyquist_wavenumber(size, n);
  const Pattern p{0, size, n, {0.0, k_max}};
  const PatternSpectrum grid = realize_pattern(s, 5, p);
  const std::vector<StageChannel> c = stage_channels(s, grid, Stage::spectrum, 0.0, 2);
  REQUIRE(c.size() == 3);
  const StageChannel& variance = channel(c, "variance");
  const StageChannel& theta = channel(c, "theta");
  const StageChannel& in_band = channel(c, "in_band");
  CHECK(variance.unit == "m^2");
  CHECK(theta.unit == "m^4");
  double sum = 0.0;
  int mismatches = 0;
  const double dk = 2.0 * std::numbers::pi / size;
  for (int b = 0; b < n; ++b) {
    for (int a = 0; a < n; ++a) {
      const std::size_t i = grid_offset(a, b, n);
      sum += variance.values[i];
      const int alpha = a < n / 2 ? a : a - n;
      const int beta = b < n / 2 ? b : b - n;
      const double k = std::hypot(alpha * dk, beta * dk);
      const bool inside = k > 0.0 && k < k_max;
      mismatches += in_band.values[i] != (inside ? 1.0 : 0.0);
      const double expected =
          inside ? wavevector_spectrum(s, alpha * dk, beta * dk) * dk * dk : 0.0;
      mismatches += std::fabs(variance.values[i] - expected) > 1e-15 * std::fabs(expected);
      mismatches += variance.values[i] != theta.values[i] * dk * dk * in_band.values[i];
    }
  }
  CHECK(mismatches == 0);
  const double m0 = zeroth_moment(s, k_max).value;
  CAPTURE(sum);
  CAPTURE(m0);
  CHECK(std::fabs(sum / m0 - 1.0) < 2e-3);  // the discretization error measured in test_waves
  CHECK(theta.values[0] == 0.0);            // k = 0 at pixel (0, 0)
}

TEST_CASE("stage h0: the draws of eq. 4.2, with E|h0|^2 = 2 Theta dk^2") {
  const Spectrum s = stages_spectrum();
  const int n = 64;
  const double size = 300.0;
  const Pattern p{2, size, n, cascade_bands({size}, n, true, 1e9)[0]};
  const std::uint64_t seed = 1234;
  const PatternSpectrum grid = realize_pattern(s, seed, p);
  const std::vector<StageChannel> h0 = stage_channels(s, grid, Stage::h0, 0.0, 1);
  const std::vector<double> variance = cell_variances(s, p);
  const StageChannel& re = channel(h0, "h0.re");
  const StageChannel& im = channel(h0, "h0.im");
  double ratio_sum = 0.0;
  int cells = 0;
  int mismatches = 0;
  for (int b = 0; b < n; ++b) {
    for (int a = 0; a < n; ++a) {
      const std::size_t i = grid_offset(a, b, n);
      if (variance[i] == 0.0) {
        mismatches += re.values[i] != 0.0 || im.values[i] != 0.0;
        continue;
      }
      // h0 = (ξ_r + iξ_i)/√2 · √(2ΘΔk²) = (ξ_r + iξ_i)√(ΘΔk²), ξ keyed by (seed, cascade, α, β).
      const NormalPair xi = standard_normal_pair(
          component_key(seed, 2, a < n / 2 ? a : a - n, b < n / 2 ? b : b - n));
      const double scale = std::sqrt(variance[i]);
      mismatches += std::fabs(re.values[i] - xi.real * scale) > 1e-15 * scale * 8.0;
      mismatches += std::fabs(im.values[i] - xi.imag * scale) > 1e-15 * scale * 8.0;
      ratio_sum +=
          (re.values[i] * re.values[i] + im.values[i] * im.values[i]) / (2.0 * variance[i]);
      ++cells;
    }
  }
  CHECK(mismatches == 0);
  // |h0|²/(2ΘΔk²) = (ξ_r² + ξ_i²)/2 has mean 1 and variance 1: the mean of `cells` of them is
  // within 4 standard errors 4/√cells of 1.
  REQUIRE(cells > 1000);
  CHECK(std::fabs(ratio_sum / cells - 1.0) < 4.0 / std::sqrt(static_cast<double>(cells)));
}

TEST_CASE("stage omega: omega = sqrt(g k) (deep water) with k = (alpha, beta) 2 pi / L") {
  const Spectrum s = stages_spectrum();
  const int n = 32;
  const double size = 100.0;
  const PatternSpectrum grid = realize_pattern(s, 1, {0, size, n, {}});
  const std::vector<StageChannel> c = stage_channels(s, grid, Stage::omega, 0.0, 1);
  const StageChannel& omega = channel(c, "omega");
  const StageChannel& kx = channel(c, "kx");
  const StageChannel& kz = channel(c, "kz");
  const StageChannel& k = channel(c, "k");
  int mismatches = 0;
  for (int b = 0; b < n; ++b) {
    for (int a = 0; a < n; ++a) {
      const std::size_t i = grid_offset(a, b, n);
      const double ex = (a < n / 2 ? a : a - n) * 2.0 * std::numbers::pi / size;
      const double ez = (b < n / 2 ? b : b - n) * 2.0 * std::numbers::pi / size;
      mismatches += std::fabs(kx.values[i] - ex) > 1e-15 * std::fabs(ex);
      mismatches += std::fabs(kz.values[i] - ez) > 1e-15 * std::fabs(ez);
      const double kk = std::hypot(ex, ez);
      mismatches += std::fabs(k.values[i] - kk) > 1e-15 * kk;
      // The portable sqrt path is correctly rounded; allow 4 ulp for the different k rounding.
      mismatches +=
          std::fabs(omega.values[i] - std::sqrt(9.81 * kk)) > 4e-16 * std::sqrt(9.81 * kk);
    }
  }
  CHECK(mismatches == 0);
  CHECK(s.dispersion.kind == DispersionKind::deep);
  CHECK(s.dispersion.gravity == 9.81);
}

TEST_CASE("stage hkt: eq. 4.7 at every entry, Hermitian, and its inverse DFT is the height field") {
  const Spectrum s = stages_spectrum();
  const int n = 16;
  const double size = 60.0;
  const double time = 3.7;
  const PatternSpectrum grid = realize_pattern(s, 9, {0, size, n, {}});
  const std::vector<StageChannel> h0 = stage_channels(s, grid, Stage::h0, 0.0, 1);
  const std::vector<StageChannel> om = stage_channels(s, grid, Stage::omega, 0.0, 1);
  const std::vector<StageChannel> hk = stage_channels(s, grid, Stage::hkt, time, 2);
  const auto& h0r = channel(h0, "h0.re").values;
  const auto& h0i = channel(h0, "h0.im").values;
  const auto& w = channel(om, "omega").values;
  const auto& hr = channel(hk, "hkt.re").values;
  const auto& hi = channel(hk, "hkt.im").values;
  double scale = 0.0;
  for (std::size_t i = 0; i < h0r.size(); ++i) scale = std::fmax(scale, std::hypot(h0r[i], h0i[i]));
  REQUIRE(scale > 0.0);
  int mismatches = 0;
  for (int b = 0; b < n; ++b) {
    for (int a = 0; a < n; ++a) {
      const std::size_t i = grid_offset(a, b, n);
      const std::size_t j = grid_offset((n - a) % n, (n - b) % n, n);  // −k
      // ½h0(k)e^{−iωt} + ½conj(h0(−k))e^{+iωt}, with libm's cos and sin.
      const double c = std::cos(w[i] * time);
      const double sn = std::sin(w[i] * time);
      const double er = 0.5 * (h0r[i] * c + h0i[i] * sn) + 0.5 * (h0r[j] * c + h0i[j] * sn);
      const double ei = 0.5 * (h0i[i] * c - h0r[i] * sn) + 0.5 * (h0r[j] * sn - h0i[j] * c);
      mismatches += std::fabs(hr[i] - er) > 1e-14 * scale;
      mismatches += std::fabs(hi[i] - ei) > 1e-14 * scale;
      // Hermitian off the Nyquist lines: h(−k) = h(k)* exactly.
      if (a != n / 2 && b != n / 2) {
        mismatches += hr[j] != hr[i] || hi[j] != -hi[i];
      }
    }
  }
  CHECK(mismatches == 0);
  // η(m, n) = Σ_{a,b} h(a, b) e^{+2πi(am + bn)/N}, unnormalized: a naive DFT here.
  const CascadeFields fields = synthesize_cascade(grid, grid, time, 1);
  const std::vector<double>& height = fields.values[static_cast<std::size_t>(Field::height)];
  double worst = 0.0;
  double imaginary = 0.0;
  double sum_abs = 0.0;
  for (std::size_t i = 0; i < hr.size(); ++i) sum_abs += std::hypot(hr[i], hi[i]);
  for (int zn = 0; zn < n; ++zn) {
    for (int xm = 0; xm < n; ++xm) {
      double re = 0.0;
      double im = 0.0;
      for (int b = 0; b < n; ++b) {
        for (int a = 0; a < n; ++a) {
          const std::size_t i = grid_offset(a, b, n);
          const double phase = 2.0 * std::numbers::pi * ((a * xm + b * zn) % n) / n;
          re += hr[i] * std::cos(phase) - hi[i] * std::sin(phase);
          im += hr[i] * std::sin(phase) + hi[i] * std::cos(phase);
        }
      }
      worst = std::fmax(worst, std::fabs(re - height[grid_offset(xm, zn, n)]));
      imaginary = std::fmax(imaginary, std::fabs(im));
    }
  }
  CAPTURE(worst);
  CAPTURE(sum_abs);
  // Rounding of two O(N² log N) sums of terms bounded by Σ|h|: ≤ 1e-12 of Σ|h| (measured ~1e-16).
  CHECK(worst < 1e-12 * sum_abs);
  CHECK(imaginary < 1e-12 * sum_abs);  // Hermitian: the height field is real
  CHECK(stage_channels(s, grid, Stage::hkt, 0.0, 1)[0].values != hr);  // time changes h
}
