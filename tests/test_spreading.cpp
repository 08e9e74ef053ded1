// Directional spreading: unit integrals, printed integrals, closed forms and branch points.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "spectrum/model.h"
#include "spectrum/moments.h"
#include "spectrum/spreading.h"
#include "test_support.h"

using namespace oceanref;

namespace {
using testing::kGravity;
using testing::kPi;

// ∫_{−π}^{π} D(ω, θ) dθ by adaptive quadrature at 1e−13 (splits at the peak and ±π/2).
double integral_over_theta(const Spectrum& s, double omega) {
  const double k = wavenumber_from_frequency(s.dispersion, omega);
  return integrate_over_direction(s, k, [](double) { return 1.0; }, {1e-13, 0.0, 4000}).value;
}

const std::vector<SpreadingModel> kAll{
    SpreadingModel::cos2,       SpreadingModel::cos4,           SpreadingModel::mitsuyasu,
    SpreadingModel::hasselmann, SpreadingModel::mastin,         SpreadingModel::gamper,
    SpreadingModel::donelan,    SpreadingModel::donelan_banner, SpreadingModel::unified};
}  // namespace

TEST_CASE("every normalized spreading integrates to 1 over (-pi, pi]") {
  // Sweep ω/ω_p across every branch, winds, swell and blend; quadrature error ≤ 1e−13, so a
  // deviation above 1e−9 is a normalization error, not a numerical one.
  for (const SpreadingModel m : kAll) {
    for (const double u : {2.0, 10.0, 40.0}) {
      for (const double swell : {0.0, 0.5, 1.0}) {
        for (const double blend : {1.0, 0.5, 0.0}) {
          const bool cos_2s = is_cos_2s_family(m);
          if (!cos_2s && (swell != 0.0 || blend != 1.0)) continue;
          SpectrumSettings in;
          in.model = SpectrumModel::pierson_moskowitz;
          in.wind_speed = u;
          in.spreading = m;
          in.swell = swell;
          in.spread_blend = blend;
          in.wind_direction = 0.7;
          const Spectrum s = make_spectrum(in);
          for (const double r : {0.05, 0.3, 0.56, 0.8, 0.95, 1.0, 1.3, 1.6, 2.5, 8.0, 40.0}) {
            CAPTURE(to_string(m));
            CAPTURE(u);
            CAPTURE(swell);
            CAPTURE(blend);
            CAPTURE(r);
            CHECK(std::fabs(integral_over_theta(s, r * s.peak_frequency) - 1.0) < 1e-9);
          }
        }
      }
    }
  }
}

TEST_CASE("printed cos2, cos4 and Donelan integrate to pi, 3pi/4 and tanh(beta pi)") {
  // Gamper §3.4 reports π and 3π/4 for |k̂·ŵ|² and |k̂·ŵ|⁴; eq. 3.64 integrates to tanh(βπ).
  CHECK(cosine_power_integral(2.0) == doctest::Approx(kPi).epsilon(1e-15));
  CHECK(cosine_power_integral(4.0) == doctest::Approx(0.75 * kPi).epsilon(1e-15));
  for (const SpreadingModel m :
       {SpreadingModel::cos2, SpreadingModel::cos4, SpreadingModel::donelan}) {
    SpectrumSettings in;
    in.model = SpectrumModel::jonswap;
    in.spreading = m;
    in.printed_spreading = true;
    const Spectrum s = make_spectrum(in);
    for (const double r : {0.3, 0.8, 1.2, 3.0}) {
      const double w = r * s.peak_frequency;
      CHECK(std::fabs(integral_over_theta(s, w) - spreading_integral(s, w)) < 1e-10);
    }
  }
  CHECK(spreading_integral(make_spectrum({}), 1.0) == 1.0);
}

TEST_CASE("cos-2s normalization: closed form, s = 0 uniform, no overflow for large s") {
  // Q(1) = 2/(π)·1/2 = 1/π... from Q(s) = 2^{2s−1}/π Γ²(s+1)/Γ(2s+1): Q(1) = 2/π · 1/2 = 1/π.
  CHECK(cos_2s_normalization(1.0) == doctest::Approx(1.0 / kPi).epsilon(1e-14));
  CHECK(cos_2s_normalization(0.0) == doctest::Approx(0.5 / kPi).epsilon(1e-15));
  CHECK(cos_2s_spreading(1.0, 0.0) == doctest::Approx(0.5 / kPi).epsilon(1e-15));
  // Γ(2s+1) overflows a double at s ≈ 86; lgamma keeps D finite far beyond. For large s,
  // Q(s) → √(s/π)/2 (Stirling): relative gap ~1/(8s).
  for (const double s : {100.0, 1e3, 1e5}) {
    const double q = cos_2s_normalization(s);
    CHECK(std::isfinite(q));
    CHECK(std::fabs(q / (0.5 * std::sqrt(s / kPi)) - 1.0) < 1.0 / (4.0 * s));
  }
}

TEST_CASE("cos-2s: exactly 0 opposite the wind, accurate behind it, continuous at |θ| = π/2") {
  // atan2 gives fl(π) for a wavevector exactly opposite the wind; |cos(θ/2)| there must be the
  // true 0, not cos(fl(π)/2) = 6.1e-17 (which made D = Q·(6e-17)^{2s}, ~5e-5·Q for s = 0.13).
  CHECK(half_angle_cosine(kPi) == 0.0);
  CHECK(half_angle_cosine(-kPi) == 0.0);
  CHECK(half_angle_cosine(3.0 * kPi) == 0.0);  // wrapped first
  for (const double s : {0.13, 1.0, 20.0}) CHECK(cos_2s_spreading(kPi, s) == 0.0);
  // Behind the wind: |cos(θ/2)| = sin(d/2) with d = fl(π) − |θ| exact; sin x = x to rounding
  // for x < 1e-8 (x³/6 is below half an ulp of x).
  for (const double d : {1e-9, 1e-12, 1e-15, 4.440892098500626e-16}) {
    const double theta = kPi - d;
    const double exact_gap = kPi - theta;  // Sterbenz: exact
    CHECK(half_angle_cosine(theta) == doctest::Approx(0.5 * exact_gap).epsilon(1e-15));
    CHECK(half_angle_cosine(-theta) == half_angle_cosine(theta));
  }
  // Against the libm form where it has no cancellation, and continuity at the branch point.
  for (const double theta : {0.3, 1.0, 1.5707963267948966, 1.6, 2.5, 3.1}) {
    CHECK(half_angle_cosine(theta) ==
          doctest::Approx(std::fabs(std::cos(0.5 * theta))).epsilon(1e-15));
  }
  // A grid's wavevector straight upwind carries no energy under a cos-2s spread with the wind
  // along x (the golden scenes' wind); the one beside it does.
  SpectrumSettings in;
  in.spreading = SpreadingModel::mitsuyasu;
  const Spectrum s = make_spectrum(in);
  CHECK(wavevector_spectrum(s, -0.05, 0.0) == 0.0);
  CHECK(wavevector_spectrum(s, -0.05, 0.001) > 0.0);
  CHECK(wavevector_spectrum(s, 0.05, 0.0) > 0.0);
}

TEST_CASE("spread laws: published constants and branch points") {
  // Mitsuyasu s is continuous at ω_p (both branches give s_p).
  const double sp = mitsuyasu_peak_spread(1.0, 10.0, kGravity);
  CHECK(sp == doctest::Approx(11.5 * std::pow(10.0 / kGravity, -2.5)).epsilon(1e-15));
  CHECK(std::fabs(mitsuyasu_spread(1.0 - 1e-12, 1.0, sp) - mitsuyasu_spread(1.0, 1.0, sp)) < 1e-9);
  // Hasselmann et al. 1980 and Gamper eq. 3.57 jump from 6.97 to 9.77 at ω_p by design.
  CHECK(hasselmann_spread(1.0 - 1e-12, 1.0, 10.0, kGravity) == doctest::Approx(6.97).epsilon(1e-9));
  CHECK(hasselmann_spread(1.0, 1.0, 10.0, kGravity) == 9.77);
  CHECK(gamper_spread(1.0 - 1e-12, 1.0) == doctest::Approx(6.97).epsilon(1e-9));
  CHECK(gamper_spread(1.0, 1.0) == 9.77);
  // μ = −2.33 − 1.45(Uω_p/g − 1.17): at Uω_p/g = 1.17, μ = −2.33 exactly.
  CHECK(hasselmann_spread(2.0, 1.17 * kGravity / 10.0 * 1.0, 10.0, kGravity) / 9.77 ==
        doctest::Approx(std::pow(2.0 / (1.17 * kGravity / 10.0), -2.33)).epsilon(1e-12));
  // Mastin: 9.77 on both sides of f_m (continuous).
  CHECK(std::fabs(mastin_spread(1.0 - 1e-12, 1.0) - mastin_spread(1.0, 1.0)) < 1e-9);
  // Horvath swell: 16ξ² tanh(ω_p/ω), 16 tanh(1) ξ² at the peak.
  CHECK(horvath_swell_spread(1.0, 1.0, 0.5) == doctest::Approx(4.0 * std::tanh(1.0)));
}

TEST_CASE("Donelan beta: the published constants jump by < 1.3%; Donelan-Banner is continuous") {
  auto jump = [](double (*beta)(double), double r) {
    const double below = beta(r * (1.0 - 1e-12));
    const double above = beta(r);
    return std::fabs(above - below) / above;
  };
  // Gamper eq. 3.65 as printed: 2.61·0.56^1.3 = 1.2287 vs 1.24 (0.9%), 2.4417 vs 2.4372 at 0.95
  // (0.2%), 1.2376 vs 1.24 at 1.6 (0.2%): inherent to the 3-digit constants.
  for (const double r : {0.56, 0.95, 1.6}) CHECK(jump(donelan_beta, r) < 0.013);
  // Each branch point belongs to the branch eq. 3.65 gives it: 0.56 to "otherwise" (1.24),
  // 0.95 to 2.28 r^−1.3, 1.6 to "otherwise".
  CHECK(donelan_beta(0.56) == 1.24);
  CHECK(donelan_beta(0.95) == doctest::Approx(2.28 * std::pow(0.95, -1.3)).epsilon(1e-15));
  CHECK(donelan_beta(1.6) == 1.24);
  // Donelan–Banner with ε = −0.4 + 0.8393 exp(−0.567 ln(r²)): 10^ε(1.6) = 1.2376 meets
  // 2.28·1.6^−1.3 to 1e−3; reading ln(r)² instead would give 2.19, a 77% jump.
  CHECK(jump(donelan_banner_beta, 1.6) < 1e-3);
  CHECK(jump(donelan_banner_beta, 0.95) < 0.002);
  // β → 0 as ω → 0: the sech² spreading tends to the uniform 1/(2π).
  CHECK(sech2_spreading(2.0, donelan_banner_beta(1e-9)) ==
        doctest::Approx(0.5 / kPi).epsilon(1e-9));
  // Either side of βπ = 1e-4, where β/tanh(βπ) switches to its series (1 + x²/3)/π: the
  // normalization there is x/tanh x = 1 + x²/3 − x⁴/45 (the next term, 2x⁶/945, below 2e-25),
  // to 1e-15.
  for (const double x : {0.5e-4, 0.999e-4, 1.001e-4, 2e-4}) {
    CAPTURE(x);
    const double expected = (1.0 + x * x / 3.0 - x * x * x * x / 45.0) / (2.0 * kPi);
    CHECK(sech2_spreading(0.0, x / kPi) == doctest::Approx(expected).epsilon(1e-15));
  }
}

TEST_CASE("unified spreading: centrosymmetric, 1 + Delta cos 2theta, Delta in (0, 1]") {
  SpectrumSettings in;
  in.model = SpectrumModel::unified;
  const Spectrum s = make_spectrum(in);
  for (const double k : {0.01, 0.1, 1.0, 50.0, 370.0, 5000.0}) {
    for (const double t : {0.0, 0.4, 1.3, 2.9}) {
      CHECK(spreading_at_wavenumber(s, k, t) ==
            doctest::Approx(spreading_at_wavenumber(s, k, t + kPi)).epsilon(1e-14));
    }
    const double delta = 2.0 * kPi * spreading_at_wavenumber(s, k, 0.0) - 1.0;
    CHECK(delta > 0.0);
    CHECK(delta <= 1.0);  // tanh saturates to 1 in double far from the peak
  }
}

TEST_CASE("swell models: Lutz eq. 29 and Alimardanov Algorithm 2 against the printed formulas") {
  // Alimardanov: Δs = 16 tanh(min(ω/ω_p, 20)) ξ²; by hand at ξ = 0.5 (16ξ² = 4):
  // 4 tanh(0.5) = 1.848468629040039, 4 tanh(2) = 3.8561103203032675, 4 tanh(20) = 4 in double.
  CHECK(alimardanov_swell_spread(0.5, 1.0, 0.5) ==
        doctest::Approx(1.848468629040039).epsilon(1e-15));
  CHECK(alimardanov_swell_spread(2.0, 1.0, 0.5) ==
        doctest::Approx(3.8561103203032675).epsilon(1e-15));
  CHECK(alimardanov_swell_spread(1e9, 1.0, 0.5) == doctest::Approx(4.0).epsilon(1e-15));
  CHECK(alimardanov_swell_spread(0.0, 1.0, 0.5) == 0.0);
  CHECK(alimardanov_swell_spread(2.0, 1.0, 0.0) == 0.0);
  // Lutz eq. 29 has the ratio the other way round: the two mirror each other in ω/ω_p ↔ ω_p/ω.
  CHECK(horvath_swell_spread(0.5, 1.0, 0.5) == doctest::Approx(3.8561103203032675).epsilon(1e-15));
  CHECK(horvath_swell_spread(2.0, 1.0, 0.5) == doctest::Approx(1.848468629040039).epsilon(1e-15));

  // Through the spectrum: s = s_Hasselmann + Δs, D = Q(s)|cos(θ/2)|^{2s} with
  // Q(s) = 2^{2s−1}/π Γ²(s+1)/Γ(2s+1) (Alimardanov eq. 2.19–2.20), evaluated here with tgamma.
  SpectrumSettings in;
  in.model = SpectrumModel::jonswap;
  in.spreading = SpreadingModel::hasselmann;
  in.swell = 0.6;
  in.swell_model = SwellModel::alimardanov;
  const Spectrum s = make_spectrum(in);
  in.swell_model = SwellModel::lutz;
  const Spectrum lutz = make_spectrum(in);
  const double wp = s.peak_frequency;
  // r = 0.5: Hasselmann s = 6.97·0.5^4.06; 16·0.36·tanh(0.5) = 2.6617948258176562.
  const double s_low = 6.97 * std::pow(0.5, 4.06) + 2.6617948258176562;
  CHECK(cos_2s_spread(s, 0.5 * wp) == doctest::Approx(s_low).epsilon(1e-14));
  const double q = std::pow(2.0, 2.0 * s_low - 1.0) / kPi * std::tgamma(s_low + 1.0) *
                   std::tgamma(s_low + 1.0) / std::tgamma(2.0 * s_low + 1.0);
  for (const double theta : {0.0, 0.7, 2.0}) {
    const double expected = q * std::pow(std::cos(0.5 * theta), 2.0 * s_low);
    CHECK(spreading_at_frequency(s, 0.5 * wp, theta) == doctest::Approx(expected).epsilon(1e-12));
  }
  // At ω = ω_p both forms give 16 tanh(1) ξ² (the same bits); elsewhere they differ.
  CHECK(cos_2s_spread(s, wp) == cos_2s_spread(lutz, wp));
  for (const double r : {0.3, 0.8, 1.5, 4.0}) {
    CAPTURE(r);
    CHECK(cos_2s_spread(s, r * wp) - cos_2s_spread(lutz, r * wp) ==
          doctest::Approx(16.0 * 0.36 * (std::tanh(r) - std::tanh(1.0 / r))).epsilon(1e-12));
  }
  // The default is Lutz's form: unchanged output when the model is not chosen.
  in = SpectrumSettings{};
  in.swell = 0.6;
  const Spectrum unset = make_spectrum(in);
  for (const double r : {0.3, 1.0, 3.0}) {
    CHECK(spreading_at_frequency(unset, r * unset.peak_frequency, 0.4) ==
          spreading_at_frequency(lutz, r * lutz.peak_frequency, 0.4));
  }
}

TEST_CASE("swell models: every cos-2s spreading with Alimardanov's swell integrates to 1") {
  // As the normalization test above, for the other swell form (quadrature error ≤ 1e−13).
  for (const SpreadingModel m : kAll) {
    if (!is_cos_2s_family(m)) continue;
    for (const double swell : {0.5, 1.0}) {
      for (const double blend : {1.0, 0.5}) {
        SpectrumSettings in;
        in.model = SpectrumModel::pierson_moskowitz;
        in.spreading = m;
        in.swell = swell;
        in.swell_model = SwellModel::alimardanov;
        in.spread_blend = blend;
        in.wind_direction = -1.1;
        const Spectrum s = make_spectrum(in);
        for (const double r : {0.05, 0.5, 1.0, 2.0, 19.0, 25.0}) {
          CAPTURE(to_string(m));
          CAPTURE(swell);
          CAPTURE(blend);
          CAPTURE(r);
          CHECK(std::fabs(integral_over_theta(s, r * s.peak_frequency) - 1.0) < 1e-9);
        }
      }
    }
  }
}
