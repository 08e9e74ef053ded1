// Wave fields: realization, spectral synthesis, direct summation, cascades (Gamper ch. 4).
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include <nlohmann/json.hpp>
#include <string>

#include "scene/scene.h"
#include "spectrum/moments.h"
#include "test_support.h"
#include "waves/direct_sum.h"
#include "waves/fft.h"
#include "waves/fields.h"
#include "waves/mastin.h"
#include "waves/ocean.h"
#include "waves/random.h"
#include "waves/surface.h"

using namespace oceanref;

namespace {
using testing::kPi;

Spectrum jonswap(double wind_direction = 0.3) {
  SpectrumSettings in;
  in.model = SpectrumModel::jonswap;
  in.wind_direction = wind_direction;
  in.fetch = 5.0e4;
  return make_spectrum(in);
}

Pattern pattern(double size, int n, Band band = {}) {
  return {0, size, n, band};
}

// A pattern holding one wave of amplitude A at (α, β): η = A cos(k·x − ωt).
PatternSpectrum single_wave(const Spectrum& s, double size, int n, int alpha, int beta, double a) {
  PatternSpectrum p = pattern_grid(s, pattern(size, n));
  p.h0[grid_offset(array_index(alpha, n), array_index(beta, n), n)] = a;
  return p;
}

// ΣΘ(k)Δk² over the grid wavevectors inside a band (eq. 3.34 restricted to what is sampled).
double band_energy(const Spectrum& s, const Pattern& p) {
  const int n = p.resolution;
  const double dk = wavenumber_spacing(p.size);
  double sum = 0.0;
  for (int b = 0; b < n; ++b) {
    for (int a = 0; a < n; ++a) {
      const double kx = wave_index(a, n) * dk;
      const double kz = wave_index(b, n) * dk;
      if (p.band.contains(std::hypot(kx, kz))) sum += wavevector_spectrum(s, kx, kz) * dk * dk;
    }
  }
  return sum;
}

// The mean over seeds 0…count−1 of the grid variance of η, and its standard error.
struct Estimate {
  double mean = 0.0;
  double standard_error = 0.0;
};
template <class Realize>
Estimate mean_height_variance(int count, const Realize& realize) {
  double mean = 0.0;
  double mean_square = 0.0;
  for (int seed = 0; seed < count; ++seed) {
    const PatternSpectrum r = realize(static_cast<std::uint64_t>(seed));
    const CascadeFields f = synthesize_cascade(r, r, 0.0, 1);
    double variance = 0.0;
    for (const double v : f.values[0]) variance += v * v;
    variance /= static_cast<double>(f.values[0].size());
    mean += variance / count;
    mean_square += variance * variance / count;
  }
  return {mean, std::sqrt((mean_square - mean * mean) / count)};
}

double field_at(const CascadeFields& f, Field which, int m, int n_index) {
  const int n = is_low_resolution_field(which) ? f.low_resolution : f.high_resolution;
  return f.values[static_cast<std::size_t>(which)][grid_offset(m, n_index, n)];
}
}  // namespace

TEST_CASE("random: bit-exact published mapping, open unit interval, normal moments") {
  // Reference words of the documented SplitMix64 mapping (mix64(0) is SplitMix64's first output
  // for seed 0, 0xE220A8397B1DCDAF, as in Vigna's reference implementation).
  CHECK(mix64(0) == 0xE220A8397B1DCDAFULL);
  CHECK(uniform_open(0) == 0x1.0p-54);
  CHECK(uniform_open(~0ULL) == 1.0 - 0x1.0p-54);
  CHECK(component_key(1, 0, 3, -4) != component_key(1, 0, -4, 3));
  CHECK(component_key(1, 0, 3, -4) != component_key(1, 1, 3, -4));
  CHECK(component_key(1, 0, 3, -4) != component_key(2, 0, 3, -4));
  // Mean 0, variance 1 of 2·10⁵ normals: standard errors 0.0022 and 0.0032; accept 5σ.
  double sum = 0.0;
  double squares = 0.0;
  const int count = 100000;
  for (int i = 0; i < count; ++i) {
    const NormalPair p = standard_normal_pair(component_key(7, 0, i, -i));
    sum += p.real + p.imag;
    squares += p.real * p.real + p.imag * p.imag;
  }
  CHECK(std::fabs(sum / (2 * count)) < 5 * 0.0022);
  CHECK(std::fabs(squares / (2 * count) - 1.0) < 5 * 0.0032);
}

TEST_CASE("index conventions: wave index, conjugate index (eq. 4.9), Nyquist") {
  CHECK(wave_index(0, 8) == 0);
  CHECK(wave_index(3, 8) == 3);
  CHECK(wave_index(4, 8) == -4);
  CHECK(wave_index(7, 8) == -1);
  for (int a = 0; a < 8; ++a) {
    CHECK(array_index(wave_index(a, 8), 8) == a);
    const int c = conjugate_array_index(a, 8);
    // The partner holds −α, except on the Nyquist line where −(−N/2) ≡ −N/2.
    CHECK(wave_index(c, 8) == (is_nyquist(wave_index(a, 8), 8) ? -4 : -wave_index(a, 8)));
  }
}

TEST_CASE("h(k, t) is Hermitian and the zero-frequency component is zero") {
  const Spectrum s = jonswap();
  const PatternSpectrum p = realize_pattern(s, 42, pattern(300.0, 16));
  CHECK(p.h0[0] == Complex(0.0));
  const std::vector<Complex> h = spectrum_at_time(p, 12.5);
  for (int b = 0; b < 16; ++b) {
    for (int a = 0; a < 16; ++a) {
      const Complex partner =
          h[grid_offset(conjugate_array_index(a, 16), conjugate_array_index(b, 16), 16)];
      CHECK(h[grid_offset(a, b, 16)] == conj(partner));
    }
  }
}

TEST_CASE("one wave: exact cosine, slopes, displacements, derivatives and Jacobian") {
  const Spectrum s = jonswap();
  const double size = 64.0;
  const int n = 16;
  const int alpha = 3;
  const int beta = -2;
  const double amplitude = 0.7;
  const PatternSpectrum p = single_wave(s, size, n, alpha, beta, amplitude);
  const double dk = wavenumber_spacing(size);
  const double kx = alpha * dk;
  const double kz = beta * dk;
  const double k = std::hypot(kx, kz);
  const double w = angular_frequency(s.dispersion, k);
  const double t = 3.7;
  const CascadeFields f = synthesize_cascade(p, p, t, 1);
  CHECK(f.transforms == 4);
  // Values are O(A k) ≤ 0.3; the FFT and the closed forms agree to a few ulp of that: 1e−14.
  for (int zn = 0; zn < n; ++zn) {
    for (int xm = 0; xm < n; ++xm) {
      const double x = xm * size / n;
      const double z = zn * size / n;
      const double phase = kx * x + kz * z - w * t;
      const double c = amplitude * std::cos(phase);
      const double sn = amplitude * std::sin(phase);
      CHECK(std::fabs(field_at(f, Field::height, xm, zn) - c) < 1e-14);
      CHECK(std::fabs(field_at(f, Field::slope_x, xm, zn) + kx * sn) < 1e-14);
      CHECK(std::fabs(field_at(f, Field::slope_z, xm, zn) + kz * sn) < 1e-14);
      CHECK(std::fabs(field_at(f, Field::displacement_x, xm, zn) - kx / k * sn) < 1e-14);
      CHECK(std::fabs(field_at(f, Field::displacement_z, xm, zn) - kz / k * sn) < 1e-14);
      CHECK(std::fabs(field_at(f, Field::ddx_dx, xm, zn) - kx * kx / k * c) < 1e-14);
      CHECK(std::fabs(field_at(f, Field::ddz_dz, xm, zn) - kz * kz / k * c) < 1e-14);
      CHECK(std::fabs(field_at(f, Field::ddx_dz, xm, zn) - kx * kz / k * c) < 1e-14);
      // Without choppiness J = 1 exactly; with u it is 1 + u·A·k·cos(phase) (cross terms cancel).
      std::array<double, kFieldCount> raw{};
      for (int q = 0; q < kFieldCount; ++q)
        raw[static_cast<std::size_t>(q)] = field_at(f, Field(q), xm, zn);
      PointFields flat;
      add_cascade(flat, raw, 0.0);
      finish_combination(flat);
      CHECK(flat.jacobian == 1.0);
      PointFields choppy;
      add_cascade(choppy, raw, -1.5);
      finish_combination(choppy);
      CHECK(std::fabs(choppy.jacobian - (1.0 - 1.5 * k * c)) < 1e-13);
    }
  }
}

TEST_CASE("one wave: the displaced surface's bounds are its amplitudes, axis by axis") {
  // η = A cos(k·x − ωt) along x, then along z, with choppiness u: D = u (k/|k|) A sin(·), so
  // |D_along| ≤ |u| A, |η| ≤ A and the crossed axis is flat (D_across = 0). Direct summation's
  // bounds, Σ|g h| and Σ|g h||k_x|, Σ|g h||k_z|, are then attained: offset = (|u| A, A, 0) and
  // lipschitz |u| A k, A k, 0 (x and z swapped for the wave along z).
  const Spectrum s = jonswap();
  const double size = 64.0, amplitude = 0.7, u = -0.8;
  const int n = 16;
  const double k = 3 * wavenumber_spacing(size);
  for (const bool along_x : {true, false}) {
    CAPTURE(along_x);
    Ocean ocean;
    ocean.spectrum = s;
    const PatternSpectrum p = single_wave(s, size, n, along_x ? 3 : 0, along_x ? 0 : 3, amplitude);
    ocean.cascades = {CascadeSpectra{p, p, u}};
    const std::vector<EvolvedCascade> evolved = evolve_ocean(ocean, 1.3);
    const DisplacedSurfaceBounds b =
        displaced_surface_bounds(ocean, {}, evolved, Interpolation::direct);
    const std::array<double, 3> offset{along_x ? -u * amplitude : 0.0, amplitude,
                                       along_x ? 0.0 : -u * amplitude};
    for (std::size_t c = 0; c < 3; ++c) {
      CAPTURE(c);
      CHECK(b.offset[c] == doctest::Approx(offset[c]).epsilon(1e-14));
      CHECK(b.lipschitz[c] == doctest::Approx(offset[c] * k).epsilon(1e-14));
    }
  }
}

TEST_CASE("Hermitian packing: single transforms are real, the packed pair equals both (eq. 4.8)") {
  const Spectrum s = jonswap();
  const int n = 32;
  const PatternSpectrum p = realize_pattern(s, 5, pattern(250.0, n));
  const std::vector<Complex> h = spectrum_at_time(p, 1.25);
  const double dk = wavenumber_spacing(250.0);
  const CascadeFields packed = synthesize_cascade(p, p, 1.25, 1);
  for (int q = 0; q < kFieldCount; ++q) {
    CAPTURE(kFieldNames[static_cast<std::size_t>(q)]);
    std::vector<Complex> c(h.size());
    double scale = 0.0;  // Σ|M h|, the bound of every sample
    for (int b = 0; b < n; ++b) {
      for (int a = 0; a < n; ++a) {
        const std::size_t i = grid_offset(a, b, n);
        c[i] = field_multiplier(Field(q), wave_index(a, n), wave_index(b, n), dk,
                                p.inverse_wavenumber[i], n) *
               h[i];
        scale += abs(c[i]);
      }
    }
    inverse_fft_2d(c, n, 1);
    double imaginary = 0.0;
    double difference = 0.0;
    for (std::size_t i = 0; i < c.size(); ++i) {
      imaginary = std::fmax(imaginary, std::fabs(c[i].im));
      difference =
          std::fmax(difference, std::fabs(c[i].re - packed.values[static_cast<std::size_t>(q)][i]));
    }
    // A radix-2/4 FFT of size N² has error ≲ ε·log₂(N²)·Σ|input| ≈ 1e−15·Σ|M h| here.
    CHECK(imaginary <= 1e-13 * scale);
    CHECK(difference <= 1e-13 * scale);
  }
}

TEST_CASE("FFT grid equals direct summation at every grid node for every field") {
  const Spectrum s = jonswap(1.1);
  const int n_high = 32;
  const int n_low = 16;
  const double size = 180.0;
  const PatternSpectrum high = realize_pattern(s, 9, pattern(size, n_high));
  const PatternSpectrum low = realize_pattern(s, 9, pattern(size, n_low));
  const double t = 4.2;
  for (const bool multires : {false, true}) {
    const PatternSpectrum& l = multires ? low : high;
    const CascadeFields f = synthesize_cascade(l, high, t, 2);
    CHECK(f.transforms == (multires ? 5 : 4));
    // Bound: FFT error ε·log₂N²·Σ|a| plus the direct sum's ≤ N²·ε·Σ|a| worst case (√N² typical)
    // and the phase rounding ε·N·π per term: all ≤ 1e−12·Σ|a| for N ≤ 64.
    for (int q = 0; q < kFieldCount; ++q) {
      const Field field = Field(q);
      const PatternSpectrum& src = is_low_resolution_field(field) ? l : high;
      const int n = src.pattern.resolution;
      const std::vector<Complex> h = spectrum_at_time(src, t);
      double scale = 0.0;
      for (int b = 0; b < n; ++b) {
        for (int a = 0; a < n; ++a) {
          scale += abs(field_multiplier(field, wave_index(a, n), wave_index(b, n),
                                        wavenumber_spacing(size),
                                        src.inverse_wavenumber[grid_offset(a, b, n)], n) *
                       h[grid_offset(a, b, n)]);
        }
      }
      double worst = 0.0;
      for (int zn = 0; zn < n; zn += 3) {
        for (int xm = 0; xm < n; xm += 3) {
          const auto exact = direct_sum(l, high, xm * size / n, zn * size / n, t);
          worst = std::fmax(
              worst, std::fabs(exact[static_cast<std::size_t>(q)] - field_at(f, field, xm, zn)));
        }
      }
      CAPTURE(kFieldNames[static_cast<std::size_t>(q)]);
      CHECK(scale > 0.0);
      CHECK(worst <= 1e-12 * scale);
    }
  }
}

TEST_CASE("direct summation: slopes are the derivatives of the height between nodes") {
  const Spectrum s = jonswap();
  // Inside the band |k| < πN/L (no Nyquist lines) the displacement is a gradient field, so
  // ∂D_z/∂x = ∂D_x/∂z everywhere; on a Nyquist line the rule of eq. 4.18 zeroes D_x but not D_z,
  // and the two agree only at the nodes.
  Band inside;
  inside.upper = nyquist_wavenumber(120.0, 16);
  const PatternSpectrum p = realize_pattern(s, 3, pattern(120.0, 16, inside));
  const double x = 17.123;
  const double z = -40.5;
  const double h = 1e-4;
  const auto at = [&](double px, double pz) { return direct_sum(p, p, px, pz, 2.0); };
  const auto c = at(x, z);
  // Central differences: error O(h²·k³A) ≈ 1e−8·Σ|k³ h| ≪ 1e−6.
  CHECK(std::fabs((at(x + h, z)[0] - at(x - h, z)[0]) / (2 * h) - c[1]) < 1e-6);
  CHECK(std::fabs((at(x, z + h)[0] - at(x, z - h)[0]) / (2 * h) - c[2]) < 1e-6);
  CHECK(std::fabs((at(x + h, z)[3] - at(x - h, z)[3]) / (2 * h) - c[5]) < 1e-6);
  CHECK(std::fabs((at(x, z + h)[4] - at(x, z - h)[4]) / (2 * h) - c[6]) < 1e-6);
  CHECK(std::fabs((at(x, z + h)[3] - at(x, z - h)[3]) / (2 * h) - c[7]) < 1e-6);
  CHECK(std::fabs((at(x + h, z)[4] - at(x - h, z)[4]) / (2 * h) - c[7]) < 1e-6);
}

TEST_CASE("statistics: mean sample variance of eta tends to sum Theta dk^2 (eq. 3.34)") {
  const Spectrum s = jonswap();
  const int n = 16;
  const double size = 400.0;
  Band inside;  // leave out the Nyquist lines, whose partner is themselves
  inside.upper = nyquist_wavenumber(size, n);
  const Pattern q = pattern(size, n, inside);
  const Estimate e =
      mean_height_variance(400, [&](std::uint64_t seed) { return realize_pattern(s, seed, q); });
  const double expected = band_energy(s, q);
  CAPTURE(e.mean);
  CAPTURE(expected);
  CAPTURE(e.standard_error);
  CHECK(std::fabs(e.mean - expected) < 4.0 * e.standard_error);
}

TEST_CASE("the discrete energy sum Theta dk^2 converges to m0 as L and N grow") {
  const Spectrum s = jonswap();
  double previous_error = 1.0;
  // Same Nyquist wavenumber πN/L = 0.4 rad/m (5 k_p), finer and finer sampling.
  for (const auto& [tile, grid] :
       std::vector<std::pair<double, int>>{{500.0, 64}, {1000.0, 128}, {2000.0, 256}}) {
    const double size = tile;  // plain copies: lambdas (CAPTURE) cannot capture bindings in C++20
    const int n = grid;
    const double k_max = nyquist_wavenumber(size, n);
    const double dk = wavenumber_spacing(size);
    double sum = 0.0;
    for (int b = -n / 2; b < n / 2; ++b) {
      for (int a = -n / 2; a < n / 2; ++a) {
        const double kx = a * dk;
        const double kz = b * dk;
        if (std::hypot(kx, kz) < k_max) sum += wavevector_spectrum(s, kx, kz) * dk * dk;
      }
    }
    const double m0 = zeroth_moment(s, k_max).value;
    const double error = std::fabs(sum / m0 - 1.0);
    CAPTURE(size);
    CAPTURE(error);
    CHECK(error < previous_error);
    previous_error = error;
  }
  CHECK(previous_error < 2e-3);
}

TEST_CASE("multi-resolution: a low-resolution h0 is a bit-exact subset of a high-resolution one") {
  const Spectrum s = jonswap();
  const PatternSpectrum low = realize_pattern(s, 77, pattern(150.0, 16));
  const PatternSpectrum high = realize_pattern(s, 77, pattern(150.0, 64));
  const std::vector<Complex> hl = spectrum_at_time(low, 3.0);
  const std::vector<Complex> hh = spectrum_at_time(high, 3.0);
  int compared = 0;
  for (int beta = -8; beta < 8; ++beta) {
    for (int alpha = -8; alpha < 8; ++alpha) {
      const std::size_t il = grid_offset(array_index(alpha, 16), array_index(beta, 16), 16);
      const std::size_t ih = grid_offset(array_index(alpha, 64), array_index(beta, 64), 64);
      CHECK(low.h0[il] == high.h0[ih]);
      // h(k, t) too, except on the low grid's Nyquist lines, whose partner differs.
      if (!is_nyquist(alpha, 16) && !is_nyquist(beta, 16)) {
        CHECK(hl[il] == hh[ih]);
        ++compared;
      }
    }
  }
  CHECK(compared == 15 * 15);
}

TEST_CASE("cascades: golden-ratio sizes (eq. 4.27) and band partitioning samples each k once") {
  const auto large = golden_ratio_sizes(1000.0, 4, GoldenFactor::large);
  const auto small = golden_ratio_sizes(1000.0, 4, GoldenFactor::small);
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
  CHECK(large[3] == doctest::Approx(1000.0 / (phi * phi * phi)).epsilon(1e-15));
  CHECK(small[2] == doctest::Approx(1000.0 / (phi * phi * phi * phi)).epsilon(1e-15));
  const int n = 32;
  const double k_floor = 2.0 * kPi / kMinimumWavelength;
  const auto bands = cascade_bands(large, n, true, k_floor);
  for (std::size_t i = 1; i < bands.size(); ++i) CHECK(bands[i].lower == bands[i - 1].upper);
  // Every wavevector of every cascade grid is sampled by exactly one cascade, or by none when
  // it is beyond the last band; and the bands leave out every Nyquist line.
  const Spectrum s = jonswap();
  int sampled = 0;
  for (std::size_t i = 0; i < large.size(); ++i) {
    const Pattern p{static_cast<std::uint32_t>(i), large[i], n, bands[i]};
    const PatternSpectrum r = realize_pattern(s, 1, p);
    const double dk = wavenumber_spacing(large[i]);
    for (int b = 0; b < n; ++b) {
      for (int a = 0; a < n; ++a) {
        const double k = std::hypot(wave_index(a, n) * dk, wave_index(b, n) * dk);
        int owners = 0;
        for (const Band& band : bands) owners += band.contains(k) ? 1 : 0;
        CHECK(owners <= 1);
        const bool here = r.h0[grid_offset(a, b, n)] != Complex(0.0);
        if (here) {
          ++sampled;
          CHECK(bands[i].contains(k));
          CHECK(!is_nyquist(wave_index(a, n), n));
          CHECK(!is_nyquist(wave_index(b, n), n));
        }
      }
    }
  }
  CHECK(sampled > 0);
  // A λ_min floor below the last band caps it.
  const auto capped = cascade_bands({10.0}, 256, true, 50.0);
  CHECK(capped[0].upper == 50.0);
}

TEST_CASE("cascades: chosen band edges (Lutz eq. 3) hand over where given; the scene checks them") {
  const std::vector<double> sizes{250.0, 210.0, 130.0};
  const auto bands = cascade_bands(sizes, 64, true, 1e9, {0.06, 0.12});
  CHECK(bands[0].lower == 0.0);
  CHECK(bands[0].upper == 0.06);
  CHECK(bands[1].lower == 0.06);
  CHECK(bands[1].upper == 0.12);
  CHECK(bands[2].lower == 0.12);
  CHECK(bands[2].upper == nyquist_wavenumber(130.0, 64));
  // The scene: edges reach the realized cascades (each h0 only inside its band) and are checked.
  const auto scene_with = [](const nlohmann::json& edges) {
    nlohmann::json s = {
        {"waves",
         {{"cascades", {{"sizes", {250, 210, 130}}, {"band_edges", edges}}}, {"resolution", 16}}}};
    return parse_scene(s);
  };
  const Scene scene = scene_with({0.06, 0.12});
  const Ocean ocean = realize_ocean(scene.waves, 1);
  int sampled = 0;
  for (std::size_t i = 0; i < ocean.cascades.size(); ++i) {
    const PatternSpectrum& r = ocean.cascades[i].low;
    const double dk = wavenumber_spacing(sizes[i]);
    for (int b = 0; b < 16; ++b) {
      for (int a = 0; a < 16; ++a) {
        if (r.h0[grid_offset(a, b, 16)] == Complex(0.0)) continue;
        const double k = std::hypot(wave_index(a, 16) * dk, wave_index(b, 16) * dk);
        CHECK(k >= (i == 0 ? 0.0 : std::vector<double>{0.06, 0.12}[i - 1]));
        CHECK(k < (i == 2 ? 1e9 : std::vector<double>{0.06, 0.12}[i]));
        ++sampled;
      }
    }
  }
  CHECK(sampled > 20);
  const auto error = [&](const nlohmann::json& edges) {
    try {
      (void)scene_with(edges);
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  CHECK(error({0.06}).find("waves.cascades.band_edges: expected an array of 2") !=
        std::string::npos);
  CHECK(error({0.12, 0.06}).find("waves.cascades.band_edges[1]: must be in (0.12, ") !=
        std::string::npos);
  // Cascade 0's Nyquist wavenumber on 16²: π·16/250 = 0.201 rad/m.
  CHECK(error({0.3, 0.35}).find("waves.cascades.band_edges[0]: must be in (0, 0.2010619") !=
        std::string::npos);
}

TEST_CASE("determinism: fields are bit-identical for 1, 2, 3 and 8 threads and across runs") {
  const Spectrum s = jonswap();
  const PatternSpectrum p = realize_pattern(s, 11, pattern(90.0, 64));
  const CascadeFields reference = synthesize_cascade(p, p, 7.0, 1);
  for (const int threads : {1, 2, 3, 8}) {
    const CascadeFields f = synthesize_cascade(p, p, 7.0, threads);
    for (int q = 0; q < kFieldCount; ++q) {
      CHECK(f.values[static_cast<std::size_t>(q)] == reference.values[static_cast<std::size_t>(q)]);
    }
  }
}

TEST_CASE("foam accumulation (Vincevicius listing 2.4) and normals") {
  CHECK(accumulated_foam(0.0, 1.0, 0.5, 0.1) == 1.0);
  CHECK(accumulated_foam(1.0, 0.0, 0.5, 0.1) == doctest::Approx(0.9));  // decays by decay·Δt/½
  CHECK(accumulated_foam(0.05, 0.0, 0.5, 0.1) == 0.0);
  const auto normal = surface_normal(0.3, -0.4);
  CHECK(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2] ==
        doctest::Approx(1.0).epsilon(1e-15));
  CHECK(normal[0] / normal[1] == doctest::Approx(-0.3));
}

TEST_CASE(
    "Mastin 1987: white noise has unit variance, the filtered field is real and has the "
    "spectrum's variance") {
  const Spectrum s = jonswap();
  const int n = 16;
  const double size = 400.0;
  Band inside;
  inside.upper = nyquist_wavenumber(size, n);
  const Pattern p = pattern(size, n, inside);
  const std::vector<double> noise = mastin_white_noise(3, p);
  for (const double v : noise) CHECK(std::fabs(v) < std::sqrt(3.0));
  // The filtered spectrum keeps the real image's Hermitian symmetry: h(k, t) = h(−k, t)*.
  const PatternSpectrum r = realize_pattern_mastin(s, {}, {}, 3, p, 2);
  const std::vector<Complex> h = spectrum_at_time(r, 5.0);
  for (int b = 0; b < n; ++b) {
    for (int a = 0; a < n; ++a) {
      CHECK(h[grid_offset(a, b, n)] ==
            conj(h[grid_offset(conjugate_array_index(a, n), conjugate_array_index(b, n), n)]));
    }
  }
  // Each pair travels downwind: |h(k, t)| is constant in time (a travelling, not standing, wave).
  const std::vector<Complex> later = spectrum_at_time(r, 17.0);
  for (std::size_t i = 0; i < h.size(); ++i) {
    CHECK(abs(later[i]) == doctest::Approx(abs(h[i])).epsilon(1e-12));
  }
  // Mean sample variance over seeds → ΣΘΔk² in the band, within 4 standard errors.
  const Estimate e = mean_height_variance(
      400, [&](std::uint64_t seed) { return realize_pattern_mastin(s, {}, {}, seed, p, 1); });
  const double expected = band_energy(s, p);
  CAPTURE(e.mean);
  CAPTURE(expected);
  CHECK(std::fabs(e.mean - expected) < 4.0 * e.standard_error);
}

TEST_CASE("finish_combination: foam is 1 where det J < 0 only, not on the fold itself") {
  // det J = (1 + ∂D_x/∂x)(1 + ∂D_z/∂z) − (∂D_x/∂z)² (eq. 4.26) at three hand-set points: exactly
  // 0 (∂D_x/∂x = −1: on the fold, not folded), just below 0 and just above.
  for (const auto& [ddx_dx, foam] :
       {std::pair{-1.0, 0.0}, std::pair{-1.0 - 0x1p-40, 1.0}, std::pair{-1.0 + 0x1p-40, 0.0}}) {
    const double slope = ddx_dx;  // a structured binding cannot be captured before C++20's P1091
    CAPTURE(slope);
    PointFields p;
    p.raw[static_cast<std::size_t>(Field::ddx_dx)] = ddx_dx;
    p.raw[static_cast<std::size_t>(Field::ddz_dz)] = 0.5;
    finish_combination(p);
    CHECK(p.jacobian == 1.5 * (1.0 + ddx_dx));
    CHECK(p.foam == foam);
  }
}

TEST_CASE("synthesis with a field mask: the wanted fields' bits, partners only, fewer transforms") {
  // A foam history synthesizes only the deformation's fields. Both resolutions differing (the
  // default scene: N_h 256, N_l 128) and equal; every single field wanted, and the history's
  // D_x, D_z: each computed field equals the full synthesis bit for bit, a field is computed
  // only when it or its transform's partner is wanted, and the transforms are counted.
  const Scene scene =
      load_scene(std::string(OCEANREF_SOURCE_DIR) + "/reference/scenes/default.json");
  for (const bool multi_resolution : {true, false}) {
    WaveSettings waves = scene.waves;
    if (!multi_resolution) waves.low_resolution = waves.resolution;
    const Ocean ocean = realize_ocean(waves, 2);
    const CascadeSpectra& c = ocean.cascades[1];
    const CascadeFields all = synthesize_cascade(c.low, c.high, 0.7, 2);
    // The transforms' pairs as synthesize_cascade makes them.
    const std::vector<std::vector<Field>> pairs =
        multi_resolution
            ? std::vector<std::vector<Field>>{{Field::height, Field::displacement_x},
                                              {Field::displacement_z},
                                              {Field::slope_x, Field::slope_z},
                                              {Field::ddx_dx, Field::ddz_dz},
                                              {Field::ddx_dz}}
            : std::vector<std::vector<Field>>{{Field::height, Field::ddx_dz},
                                              {Field::slope_x, Field::slope_z},
                                              {Field::displacement_x, Field::displacement_z},
                                              {Field::ddx_dx, Field::ddz_dz}};
    CHECK(all.transforms == static_cast<int>(pairs.size()));
    std::vector<FieldMask> masks;
    for (int q = 0; q < kFieldCount; ++q) {
      FieldMask one{};
      one[static_cast<std::size_t>(q)] = true;
      masks.push_back(one);
    }
    FieldMask history{};
    history[static_cast<std::size_t>(Field::displacement_x)] = true;
    history[static_cast<std::size_t>(Field::displacement_z)] = true;
    masks.push_back(history);
    for (const FieldMask& wanted : masks) {
      CascadeFields some = all;  // reused storage: what is not computed must be emptied
      SynthesisWorkspace work;
      synthesize_cascade(c.low, c.high, 0.7, 2, some, work, inverse_fft_2d, nullptr, wanted);
      int transforms = 0;
      for (const std::vector<Field>& pair : pairs) {
        bool computed = false;
        for (const Field q : pair) computed = computed || wanted[static_cast<std::size_t>(q)];
        transforms += computed ? 1 : 0;
        for (const Field q : pair) {
          const std::size_t i = static_cast<std::size_t>(q);
          CAPTURE(i);
          if (computed) {
            CHECK(testing::same_bits(some.values[i], all.values[i]));
          } else {
            CHECK(some.values[i].empty());
          }
        }
      }
      CHECK(some.transforms == transforms);
    }
  }
}
