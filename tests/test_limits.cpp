// Known limits and bounds of the shading and of the spectra, checked against values (the sweeps
// of test_extremes.cpp, test_brdf.cpp and test_render.cpp check the same quantities at the
// edges of the parameter space). Each check states its tolerance and why.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "shading/lighting_terms.h"
#include "shading/ocean_lighting.h"
#include "sky/preetham.h"
#include "spectrum/model.h"
#include "test_support.h"

using namespace oceanref;

namespace {
using testing::direction_deg;
using testing::kDeg;
using testing::kPi;
// Two frames: the flat sea, and a tilted facet normal with another wind angle.
const SurfaceFrame kFlat = wind_frame({0.0, 1.0, 0.0}, 0.3);
const SurfaceFrame kTilted = wind_frame({0.2, 0.95, -0.1}, 2.0);
}  // namespace

TEST_CASE("Fresnel of water: ((n - 1)/(n + 1))^2 at normal incidence, 1 at grazing, monotone") {
  const double n = kWaterRefractiveIndex;
  const double r0 = (n - 1.0) * (n - 1.0) / ((n + 1.0) * (n + 1.0));
  // Normal incidence: exactly the textbook value (r_s = −r_p = (1 − n)/(1 + n)), to rounding.
  CHECK(fresnel_reflectance(1.0) == doctest::Approx(r0).epsilon(1e-15));
  CHECK(fresnel_reflectance(0.0) == 1.0);
  // Grazing: 1 − F ≈ 2(1 + n²)/√(n² − 1)·cos θ (expand r_s and r_p to first order in cos θ);
  // the next term is O(cos²θ), so at cos θ = 1e-7 the ratio agrees to ~1e-6.
  const double slope = 2.0 * (1.0 + n * n) / std::sqrt(n * n - 1.0);
  CHECK((1.0 - fresnel_reflectance(1e-7)) / 1e-7 == doctest::Approx(slope).epsilon(1e-5));
  // In [r0, 1] and non-increasing in cos θ over 10⁵ steps (unpolarized external reflection).
  double previous = 1.0;
  for (int i = 0; i <= 100000; ++i) {
    const double f = fresnel_reflectance(i * 1e-5);
    CHECK((f >= r0 * (1.0 - 1e-15) && f <= 1.0));
    CHECK(f <= previous);
    previous = f;
  }
  // Schlick with the demo's constants: 0.02 at normal incidence, 1 at grazing.
  CHECK(fresnel_reflectance(1.0, FresnelForm::schlick) == 0.02);
  CHECK(fresnel_reflectance(0.0, FresnelForm::schlick) == 1.0);
}

TEST_CASE("BRDF reciprocity f(L, V) = f(V, L) over a sweep of directions, roughness and frames") {
  // f = brdf_cos/(L·N): Fresnel of V·h = L·h, p(ζ) of the half vector and the masking
  // 1/(1 + Λ_V + Λ_L) are symmetric in L and V; the two orders compute Λ_V and Λ_L by different
  // routes (smith_terms vs smith_lambda), so they agree to rounding: 1e-12 relative.
  int checked = 0;
  for (const SurfaceFrame& frame : {kFlat, kTilted}) {
    for (const SlopeVariance s :
         {SlopeVariance{1e-4, 5e-5}, SlopeVariance{0.02, 0.01}, SlopeVariance{0.3, 0.05}}) {
      for (const double lz : {5.0, 30.0, 60.0, 85.0, 89.5}) {
        for (const double vz : {0.0, 25.0, 50.0, 80.0, 89.9}) {
          for (const double la : {0.0, 70.0, 200.0}) {
            for (const double va : {15.0, 180.0, 290.0}) {
              const Vec3 l = direction_deg(lz, la), v = direction_deg(vz, va);
              const auto cosine = [&](const Vec3& d) {
                return d[0] * frame.normal[0] + d[1] * frame.normal[1] + d[2] * frame.normal[2];
              };
              if (!(cosine(l) > 0.0 && cosine(v) > 0.0)) continue;
              for (const ErfcForm erfc : {ErfcForm::exact, ErfcForm::rational}) {
                BrdfOptions o;
                o.erfc = erfc;
                const double f_lv = ocean_brdf(l, v, frame, s, o).brdf_cos / cosine(l);
                const double f_vl = ocean_brdf(v, l, frame, s, o).brdf_cos / cosine(v);
                CAPTURE(lz);
                CAPTURE(vz);
                CAPTURE(la);
                CAPTURE(va);
                CHECK(f_lv >= 0.0);
                CHECK(f_lv == doctest::Approx(f_vl).epsilon(1e-12).scale(1e-300));
                ++checked;
              }
            }
          }
        }
      }
    }
  }
  CHECK(checked > 1000);
}

TEST_CASE("mean Fresnel: between F(0 deg) and 1; tends to F(V.N) as sigma^2 -> 0, linearly") {
  // F̄ is a weighted mean of F over the visible facets (positive weights), so it lies in
  // [F(1), 1] for every view, roughness and quadrature order, to rounding.
  const double f_normal = fresnel_reflectance(1.0);
  for (const SurfaceFrame& frame : {kFlat, kTilted}) {
    for (const double s2 : {1e-8, 1e-4, 0.02, 0.3, 1.0}) {
      for (const double vz : {0.0, 30.0, 60.0, 80.0, 89.0, 89.99}) {
        for (const int order : {1, 4, 16}) {
          const double f = mean_fresnel(direction_deg(vz, 40), frame, {s2, 0.6 * s2}, order);
          CAPTURE(s2);
          CAPTURE(vz);
          CAPTURE(order);
          CHECK(f >= f_normal * (1.0 - 1e-15));
          CHECK(f <= 1.0);
        }
      }
    }
  }
  // The smooth limit: facets ~σ from N change V·m by O(σ), the mean over ±ζ cancels the first
  // order, so F̄ − F(V·N) = O(σ²): measured at σ² = 1e-4 and 1e-5 the relative deviation falls
  // by 10 ± 1 (0 ≤ θ_V ≤ 80°; at normal incidence it is O(σ⁴)), and at σ² = 1e-5 it is below
  // 1e-3 (measured 1.5e-4 at 80°).
  for (const double vz : {0.0, 30.0, 60.0, 80.0}) {
    CAPTURE(vz);
    const Vec3 v = direction_deg(vz, 20);
    const double f0 = fresnel_reflectance(v[1]);
    const double e4 = std::fabs(mean_fresnel(v, kFlat, {1e-4, 7e-5}, 16) / f0 - 1.0);
    const double e5 = std::fabs(mean_fresnel(v, kFlat, {1e-5, 7e-6}, 16) / f0 - 1.0);
    CHECK(e5 < 1e-3);
    CHECK(e4 / e5 > (vz == 0.0 ? 50.0 : 9.0));
    if (vz > 0.0) CHECK(e4 / e5 < 11.0);
  }
  // Grazing and smooth: the visible facets are tilted towards V by ~σ, F̄ → 1 as σ → 0.
  CHECK(mean_fresnel(direction_deg(90, 0), kFlat, {1e-8, 1e-8}, 16) > 0.999);
}

TEST_CASE("energy: reflected sky <= F_mean x the brightest sky; sun reflectance in [0, 1]") {
  // ∫f cos θ_L L_sky dω ≤ max L_sky · ∫ F G ⟨V·ñ⟩₊ p dζ/(V·N) ≤ max L_sky · F̄ (G ≤ 1/(1 + Λ_V)),
  // up to the Gauss–Hermite error of the visible-area normalization (< 1 % at order 16; the
  // largest ratio measured over this sweep is 0.989). The sun's reflectance ∫_disk f cos dω is
  // part of the albedo ≤ 1, and exactly 0 when the whole disk is below the horizon.
  const Sky sky = make_sky(2.5, 60.0 * kDeg, 0.0);
  Vec3 brightest{};
  for (int z = 0; z <= 900; ++z) {  // 0.1° × 1°, and the sun's own direction (the maximum)
    for (int a = 0; a < 360; ++a) {
      const Vec3 l = sky_radiance_rgb(sky, direction_deg(0.1 * z, a));
      for (std::size_t c = 0; c < 3; ++c) brightest[c] = std::fmax(brightest[c], l[c]);
    }
  }
  const Vec3 at_sun = sky_radiance_rgb(sky, sky.sun_direction);
  for (std::size_t c = 0; c < 3; ++c) brightest[c] = std::fmax(brightest[c], at_sun[c]);
  for (const double s2 : {1e-6, 1e-3, 0.02, 0.1, 1.0}) {
    for (const double vz : {0.0, 45.0, 80.0, 89.0, 89.9999, 90.0}) {
      for (const double va : {0.0, 90.0, 180.0}) {
        CAPTURE(s2);
        CAPTURE(vz);
        CAPTURE(va);
        const Vec3 v = direction_deg(vz, va);
        const SlopeVariance s{s2, 0.5 * s2};
        const Vec3 r = reflected_sky(v, kFlat, s, sky, 16);
        const double f = mean_fresnel(v, kFlat, s, 16);
        for (std::size_t c = 0; c < 3; ++c) {
          CHECK(r[c] >= 0.0);
          CHECK(r[c] <= 1.01 * f * brightest[c]);
        }
        for (const double sz : {0.0, 60.0, 89.0}) {
          const double sun =
              reflected_sun(direction_deg(sz, 10), kSunAngularRadius, v, kFlat, s, 4);
          CHECK((sun >= 0.0 && sun <= 1.0));
        }
        CHECK(reflected_sun(direction_deg(100.0, 10), kSunAngularRadius, v, kFlat, s, 4) == 0.0);
      }
    }
  }
  // Away from the mirror direction a smooth sea reflects no sun: 20° off-specular is ~10³σ at
  // σ² = 1e-7, p(ζ) underflows to 0.
  CHECK(reflected_sun(direction_deg(40, 0), kSunAngularRadius, direction_deg(60, 180), kFlat,
                      {1e-7, 1e-7}, 4) == 0.0);
}

namespace {
Spectrum spectrum_of(SpectrumModel m) {
  SpectrumSettings in;
  in.model = m;
  in.dispersion = DispersionKind::deep;
  if (m == SpectrumModel::tma) {
    in.depth = 10.0;
    in.dispersion = DispersionKind::finite_depth;
  }
  if (m == SpectrumModel::phillips) in.phillips_suppression = 0.0;
  return make_spectrum(in);
}
}  // namespace

TEST_CASE("spectra: k -> 0 exponentially small; k -> infinity the model's power law") {
  constexpr double g = 9.81;
  for (const SpectrumModel m :
       {SpectrumModel::phillips, SpectrumModel::pierson_moskowitz, SpectrumModel::jonswap,
        SpectrumModel::tma, SpectrumModel::donelan, SpectrumModel::unified}) {
    CAPTURE(to_string(m));
    const Spectrum s = spectrum_of(m);
    const double kp = s.peak_wavenumber;
    // Long waves: every model's low-frequency cut-off is exp(−c(k_p/k)²) with c ≥ 1 (PM/JONSWAP
    // 5/4, Donelan 1, Unified 5/4, Phillips (k_pL)⁻² = 3/2): at k_p/10, e^{−100} ≈ 4e-44 times
    // polynomial factors < 10⁶, so below 1e-30 of the peak; at 0 and below, exactly 0.
    CHECK(wavenumber_spectrum(s, 0.1 * kp) < 1e-30 * wavenumber_spectrum(s, kp));
    CHECK(wavenumber_spectrum(s, 0.0) == 0.0);
    CHECK(wavenumber_spectrum(s, -1.0) == 0.0);
    // Short waves: the asymptotic form, to 1e-10 relative (rounding of the exp/pow chains ~1e-15).
    for (const double r : {100.0, 1e4}) {
      CAPTURE(r);
      const double k = r * kp;
      const double psi = wavenumber_spectrum(s, k);
      switch (m) {
        case SpectrumModel::pierson_moskowitz:
        case SpectrumModel::jonswap:
        case SpectrumModel::tma: {
          // S → αg²ω⁻⁵exp(−5/4(ω_p/ω)⁴) (γ^r → 1, TMA's Φ → 1 and tanh kh → 1), ω² = gk:
          // Ψ = S dω/dk → (α/2)k⁻³exp(−5/4(ω_p²/(gk))²).
          const double x = s.peak_frequency * s.peak_frequency / (g * k);
          CHECK(k * k * k * psi ==
                doctest::Approx(0.5 * s.alpha * std::exp(-1.25 * x * x)).epsilon(1e-10));
          break;
        }
        case SpectrumModel::donelan: {
          // S → αg²ω⁻⁴ω_p⁻¹exp(−(ω_p/ω)⁴): Ψ → (α√g/(2ω_p))k^(−5/2)exp(−(ω_p²/(gk))²).
          const double x = s.peak_frequency * s.peak_frequency / (g * k);
          CHECK(std::pow(k, 2.5) * psi ==
                doctest::Approx(0.5 * s.alpha * std::sqrt(g) / s.peak_frequency * std::exp(-x * x))
                    .epsilon(1e-10));
          break;
        }
        case SpectrumModel::phillips: {
          // l = 0: Ψ = A exp(−(kL)⁻²)/k³ → A k⁻³.
          const double kl = k * s.phillips_largest_wave;
          CHECK(k * k * k * psi ==
                doctest::Approx(s.phillips_amplitude * std::exp(-1.0 / (kl * kl))).epsilon(1e-10));
          break;
        }
        case SpectrumModel::unified:
          break;
      }
    }
    // Unified: past the capillary peak at k_m = 370 rad/m both curvature terms die faster than
    // any power — the short-wave one as exp(−¼(k/k_m − 1)²), the long-wave one as
    // exp(−Ω_c/√10·(√(k/k_p) − 1)) ≈ e^{−135} at 100 k_m — so k³Ψ there is below 1e-40 of its
    // value at k_m.
    if (m == SpectrumModel::unified) {
      const double km = s.unified.capillary_wavenumber;
      const double peak = km * km * km * wavenumber_spectrum(s, km);
      REQUIRE(peak > 0.0);
      CHECK(1e6 * km * km * km * wavenumber_spectrum(s, 100.0 * km) < 1e-40 * peak);
    }
  }
  // Phillips' small-wave suppression exp(−(kl)²): 10/l is e^{−100} below the suppression-free
  // form.
  SpectrumSettings in;
  in.model = SpectrumModel::phillips;
  in.phillips_suppression = 0.01;
  const Spectrum s = make_spectrum(in);
  const double k = 10.0 / s.phillips_smallest_wave;
  CHECK(k * k * k * wavenumber_spectrum(s, k) < 1e-40 * s.phillips_amplitude);
}
