// Numerical stability at the edges of the parameter space: every value finite and ≥ 0, and the
// spectra exactly 0 at the ends (their k → 0 and k → ∞ limits; the asymptotic forms are checked
// in test_limits.cpp).
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "spectrum/model.h"

using namespace oceanref;

namespace {
bool finite_non_negative(double v) {
  return std::isfinite(v) && v >= 0.0;
}
}  // namespace

TEST_CASE("extremes sweep: U10 0.1..60 m/s, fetch 1..1e7 m, depth 0.01 m..inf, omega/k 0..inf") {
  const double inf = std::numeric_limits<double>::infinity();
  const double tiny = std::numeric_limits<double>::denorm_min();
  const std::vector<double> samples{0.0,  tiny, 1e-300, 1e-10,
                                    1e-3, 0.5,  1.0,    7.0,
                                    1e3,  1e10, 1e300,  std::numeric_limits<double>::max(),
                                    inf};
  int evaluated = 0;
  for (const SpectrumModel m :
       {SpectrumModel::phillips, SpectrumModel::pierson_moskowitz, SpectrumModel::jonswap,
        SpectrumModel::tma, SpectrumModel::donelan, SpectrumModel::unified}) {
    for (const SpreadingModel spreading :
         {SpreadingModel::cos2, SpreadingModel::cos4, SpreadingModel::mitsuyasu,
          SpreadingModel::hasselmann, SpreadingModel::mastin, SpreadingModel::gamper,
          SpreadingModel::donelan, SpreadingModel::donelan_banner, SpreadingModel::unified}) {
      for (const DispersionKind d :
           {DispersionKind::deep, DispersionKind::finite_depth, DispersionKind::capillary}) {
        for (const double u : {0.1, 1.0, 10.0, 60.0}) {
          for (const double fetch : {1.0, 1e3, 1e7}) {
            for (const double depth : {0.01, 1.0, inf}) {
              SpectrumSettings in;
              in.model = m;
              in.spreading = spreading;
              in.dispersion = d;
              in.wind_speed = u;
              in.fetch = fetch;
              in.depth = depth;
              in.allow_extrapolation = true;
              if (is_cos_2s_family(spreading)) in.swell = 1.0;
              const Spectrum s = make_spectrum(in);
              CAPTURE(to_string(m));
              CAPTURE(to_string(spreading));
              CAPTURE(to_string(d));
              CAPTURE(u);
              CAPTURE(fetch);
              CAPTURE(depth);
              REQUIRE(finite_non_negative(s.peak_frequency));
              REQUIRE(finite_non_negative(s.peak_wavenumber));
              for (const double x : samples) {
                CAPTURE(x);
                CHECK(finite_non_negative(frequency_spectrum(s, x)));
                CHECK(finite_non_negative(wavenumber_spectrum(s, x)));
                CHECK(finite_non_negative(spreading_at_frequency(s, x, 0.3)));
                CHECK(finite_non_negative(spreading_at_wavenumber(s, x, 3.1)));
                CHECK(finite_non_negative(wavevector_spectrum(s, x, -0.5 * x)));
                CHECK(finite_non_negative(wavevector_spectrum(s, 0.0, x)));
                // The limits, not only finiteness: every model's low-frequency cut-off is
                // exp(−c(k_p/k)²) or steeper, 0 in double precision for k, ω ≤ 1e-10 (k_p ≥
                // 2.7e-3 rad/m at 60 m/s); the tails fall as k⁻³ or faster, 0 beyond 1e300.
                if (x <= 1e-10 || x >= 1e300) {
                  CHECK(frequency_spectrum(s, x) == 0.0);
                  CHECK(wavenumber_spectrum(s, x) == 0.0);
                  CHECK(wavevector_spectrum(s, x, -0.5 * x) == 0.0);
                  CHECK(wavevector_spectrum(s, 0.0, x) == 0.0);
                }
                ++evaluated;
              }
            }
          }
        }
      }
    }
  }
  CHECK(evaluated == 6 * 9 * 3 * 4 * 3 * 3 * 13);
}

TEST_CASE("out-of-range settings are rejected with the key and the range") {
  auto key_of = [](SpectrumSettings in) -> std::string {
    try {
      make_spectrum(in);
    } catch (const SettingError& e) {
      return e.key();
    }
    return "";
  };
  SpectrumSettings in;
  in.wind_speed = 0.05;
  CHECK(key_of(in) == "wind_speed");
  in = {};
  in.wind_speed = std::nan("");
  CHECK(key_of(in) == "wind_speed");
  in = {};
  in.fetch = 2e7;
  CHECK(key_of(in) == "fetch");
  in = {};
  in.depth = 0.001;
  CHECK(key_of(in) == "depth");
  in = {};
  in.fetch = 1e6;  // χ > 1e4 for JONSWAP at 10 m/s
  CHECK(key_of(in) == "fetch");
  in.allow_extrapolation = true;
  CHECK(key_of(in).empty());
  in = {};
  in.model = SpectrumModel::donelan;
  in.fetch = 5e6;  // Ω_c < 0.83
  CHECK(key_of(in) == "fetch");
  in = {};
  in.model = SpectrumModel::unified;
  in.wind_speed = 1.0;  // α_m < 0
  CHECK(key_of(in) == "wind_speed");
  in = {};
  in.spreading = SpreadingModel::donelan;
  in.swell = 0.5;
  CHECK(key_of(in) == "swell");
  in = {};
  in.model = SpectrumModel::donelan;
  in.gamma = 2.0;
  CHECK(key_of(in) == "gamma");
  try {
    SpectrumSettings bad;
    bad.wind_speed = 75.0;
    make_spectrum(bad);
    FAIL("no error");
  } catch (const SettingError& e) {
    CHECK(std::string(e.what()) == "must be in [0.1, 60] m/s, got 75");
  }
}
