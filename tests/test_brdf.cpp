// The ocean BRDF (Bruneton 2010): identities, limits, energy, quadrature convergence.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "core/quadrature.h"
#include "shading/ocean_lighting.h"
#include "shading/tone_mapping.h"
#include "test_support.h"

using namespace oceanref;

namespace {
using testing::direction_deg;
using testing::kDeg;
using testing::kPi;
const SurfaceFrame kUp = wind_frame({0.0, 1.0, 0.0}, 0.3);

// ∫ f(L, V) cos θ_L dω_L over the upper hemisphere, by adaptive quadrature in polar coordinates
// around the mirror direction (independent of the slope-space Gauss–Hermite path).
double hemisphere_albedo(const Vec3& view, SlopeVariance s, FresnelForm fresnel) {
  const Vec3 mirror{-view[0], view[1], -view[2]};
  // Basis around the mirror direction.
  const Vec3 a = std::fabs(mirror[1]) < 0.9 ? Vec3{0.0, 1.0, 0.0} : Vec3{1.0, 0.0, 0.0};
  Vec3 e1{mirror[1] * a[2] - mirror[2] * a[1], mirror[2] * a[0] - mirror[0] * a[2],
          mirror[0] * a[1] - mirror[1] * a[0]};
  const double l = std::sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
  for (double& c : e1) c /= l;
  const Vec3 e2{mirror[1] * e1[2] - mirror[2] * e1[1], mirror[2] * e1[0] - mirror[0] * e1[2],
                mirror[0] * e1[1] - mirror[1] * e1[0]};
  const double sigma = std::sqrt(std::fmax(s.upwind, s.crosswind));
  std::vector<double> radii{0.0};
  for (double r = sigma; r < kPi; r *= 2.0) radii.push_back(r);
  radii.push_back(kPi);
  BrdfOptions options;
  options.fresnel = fresnel;
  const QuadratureTolerance tol{1e-8, 0.0, 4000};
  return integrate(
             [&](double r) {
               return std::sin(r) * integrate(
                                        [&](double psi) {
                                          Vec3 light{};
                                          for (std::size_t k = 0; k < 3; ++k) {
                                            light[k] = std::cos(r) * mirror[k] +
                                                       std::sin(r) * (std::cos(psi) * e1[k] +
                                                                      std::sin(psi) * e2[k]);
                                          }
                                          return ocean_brdf(light, view, kUp, s, options).brdf_cos;
                                        },
                                        {0.0, kPi / 2, kPi, 3 * kPi / 2, 2 * kPi}, tol)
                                        .value;
             },
             radii, tol)
      .value;
}
}  // namespace

TEST_CASE("wind frame: T_x the wind projected on the plane of N, +Z's where the wind is along N") {
  const auto check_frame = [](const SurfaceFrame& f, const Vec3& n, const Vec3& tx) {
    for (std::size_t i = 0; i < 3; ++i) {
      CHECK(f.normal[i] == doctest::Approx(n[i]).epsilon(1e-12));
      CHECK(f.tangent_x[i] == doctest::Approx(tx[i]).epsilon(1e-12));
    }
    // T_y = N × T_x.
    CHECK(f.tangent_y[0] == doctest::Approx(n[1] * tx[2] - n[2] * tx[1]).epsilon(1e-12));
    CHECK(f.tangent_y[1] == doctest::Approx(n[2] * tx[0] - n[0] * tx[2]).epsilon(1e-12));
    CHECK(f.tangent_y[2] == doctest::Approx(n[0] * tx[1] - n[1] * tx[0]).epsilon(1e-12));
  };
  // Flat: T_x is the wind (cos A, 0, sin A) itself.
  check_frame(wind_frame({0.0, 1.0, 0.0}, 0.3), {0.0, 1.0, 0.0},
              {std::cos(0.3), 0.0, std::sin(0.3)});
  // N = (0.6, 0.8, 0) (not unit on input: normalised), wind +X: T_x = X − (X·N) N, normalised.
  check_frame(wind_frame({1.2, 1.6, 0.0}, 0.0), {0.6, 0.8, 0.0}, {0.8, -0.6, 0.0});
  // N = (1, 0, s) with s² below double's resolution, so N is unit as given and the wind +X has
  // the projection (0, 0, −s), squared length s²: T_x = −Z down to s² = 1e-20 ...
  check_frame(wind_frame({1.0, 0.0, 1.002e-10}, 0.0), {1.0, 0.0, 1.002e-10}, {0.0, 0.0, -1.0});
  // ... and below it the projection of +Z, (−s, 0, 1) normalised: T_x flips sign there, which
  // the BRDF does not see (the slope distribution is even in each slope).
  check_frame(wind_frame({1.0, 0.0, 0.998e-10}, 0.0), {1.0, 0.0, 0.998e-10},
              {-0.998e-10, 0.0, 1.0});
  check_frame(wind_frame({1.0, 0.0, 0.0}, 0.0), {1.0, 0.0, 0.0}, {0.0, 0.0, 1.0});
}

TEST_CASE("quadrature rules: Gauss-Legendre and Gauss-Hermite integrate polynomials exactly") {
  for (const int n : {1, 2, 5, 12, 40}) {
    const QuadratureRule gl = gauss_legendre(n);
    const QuadratureRule gh = gauss_hermite(n);
    double l0 = 0.0, l2 = 0.0, h0 = 0.0, h2 = 0.0;
    for (std::size_t i = 0; i < gl.nodes.size(); ++i) {
      l0 += gl.weights[i];
      l2 += gl.weights[i] * gl.nodes[i] * gl.nodes[i];
      h0 += gh.weights[i];
      h2 += gh.weights[i] * gh.nodes[i] * gh.nodes[i];
    }
    CHECK(l0 == doctest::Approx(2.0).epsilon(1e-14));
    CHECK(h0 == doctest::Approx(std::sqrt(kPi)).epsilon(1e-13));  // ∫ e^{−t²} = √π
    if (n >= 2) {
      CHECK(l2 == doctest::Approx(2.0 / 3.0).epsilon(1e-14));
      CHECK(h2 == doctest::Approx(std::sqrt(kPi) / 2.0).epsilon(1e-13));  // ∫ t² e^{−t²}
    }
  }
}

TEST_CASE("Fresnel of water: normal incidence ((n - 1)/(n + 1))^2, grazing 1, Schlick close") {
  const double r0 = std::pow((1.333 - 1.0) / (1.333 + 1.0), 2.0);
  CHECK(fresnel_reflectance(1.0) == doctest::Approx(r0).epsilon(1e-14));
  CHECK(fresnel_reflectance(0.0) == doctest::Approx(1.0).epsilon(1e-14));
  // Brewster angle tan θ_B = n: r_p = 0, so F = r_s²/2.
  const double brewster = std::atan(1.333);
  const double ci = std::cos(brewster),
               ct = std::sqrt(1.0 - std::pow(std::sin(brewster) / 1.333, 2));
  const double rs = (ci - 1.333 * ct) / (ci + 1.333 * ct);
  CHECK(fresnel_reflectance(ci) == doctest::Approx(0.5 * rs * rs).epsilon(1e-12));
  CHECK(std::fabs(fresnel_reflectance(0.7, FresnelForm::schlick) - fresnel_reflectance(0.7)) <
        0.01);
}

TEST_CASE("Smith Lambda: 0 at normal incidence, the exact erfc form, grazing limit of cos(1+L)") {
  CHECK(smith_lambda(1.0, 0.02) == 0.0);
  // Λ(ν) for ν = 1: (e^{−1} − √π erfc 1)/(2√π) = 0.0333… (erfc 1 = 0.157299207050285).
  const double c = std::sqrt(0.04 / 1.04);  // ν = c/√(2σ²(1 − c²)) = 1 for σ² = 0.02
  const double expected =
      (std::exp(-1.0) - std::sqrt(kPi) * 0.157299207050285) / (2.0 * std::sqrt(kPi));
  CHECK(smith_lambda(c, 0.02) == doctest::Approx(expected).epsilon(1e-12));
  CHECK(visible_projected_area(0.0, 0.02) ==
        doctest::Approx(std::sqrt(0.02 / (2.0 * kPi))).epsilon(1e-12));
  CHECK(visible_projected_area(1e-9, 0.02) ==
        doctest::Approx(std::sqrt(0.02 / (2.0 * kPi))).epsilon(1e-6));
}

TEST_CASE("smith_terms (one erfc for both) equals smith_lambda and visible_projected_area") {
  for (const double c : {1e-9, 0.01, 0.3, 0.7, 0.999999, 1.0}) {
    for (const double s2 : {1e-6, 0.02, 0.5}) {
      const SmithTerms t = smith_terms(c, s2);
      CHECK(t.lambda == smith_lambda(c, s2));
      CHECK(t.visible_area == visible_projected_area(c, s2));
    }
  }
}

TEST_CASE("BRDF: reciprocity, isotropic rotation symmetry, zero below the surface") {
  const SlopeVariance s{0.02, 0.01};
  for (const auto& [l, v] : {std::pair{direction_deg(30, 10), direction_deg(50, 200)},
                             std::pair{direction_deg(75, 40), direction_deg(10, 0)},
                             std::pair{direction_deg(85, 300), direction_deg(88, 120)}}) {
    const double f_lv = ocean_brdf(l, v, kUp, s).brdf_cos / l[1];
    const double f_vl = ocean_brdf(v, l, kUp, s).brdf_cos / v[1];
    CHECK(f_lv == doctest::Approx(f_vl).epsilon(1e-12));
  }
  const SlopeVariance iso{0.015, 0.015};
  const double a = ocean_brdf(direction_deg(40, 10), direction_deg(60, 170), kUp, iso).brdf_cos;
  const double b = ocean_brdf(direction_deg(40, 77), direction_deg(60, 237), kUp, iso).brdf_cos;
  CHECK(a == doctest::Approx(b).epsilon(1e-12));
  CHECK(ocean_brdf(direction_deg(95, 0), direction_deg(40, 180), kUp, s).brdf_cos == 0.0);
  CHECK(ocean_brdf(direction_deg(40, 0), direction_deg(91, 180), kUp, s).brdf_cos == 0.0);
}

TEST_CASE("BRDF energy: with F = 1 the albedo is <= 1, -> 1 for smooth water; F-weighted -> F") {
  for (const double view_zenith : {0.0, 30.0, 60.0, 80.0}) {
    const Vec3 v = direction_deg(view_zenith, 20);
    const double smooth = hemisphere_albedo(v, {1e-4, 1e-4}, FresnelForm::unity);
    CAPTURE(view_zenith);
    CHECK(smooth <= 1.0 + 1e-6);
    CHECK(smooth > (view_zenith < 70 ? 0.99 : 0.9));  // masking removes a little at grazing
    for (const double s2 : {0.01, 0.05, 0.2}) {
      CHECK(hemisphere_albedo(v, {s2, 0.5 * s2}, FresnelForm::unity) <= 1.0 + 1e-6);
    }
    // As σ² → 0 the reflection concentrates on the mirror direction: ∫ f cos = F(V·N)·(≈1).
    const double fresnel_weighted = hemisphere_albedo(v, {1e-5, 1e-5}, FresnelForm::exact);
    CHECK(fresnel_weighted ==
          doctest::Approx(fresnel_reflectance(v[1])).epsilon(view_zenith < 70 ? 0.01 : 0.05));
  }
}

TEST_CASE("reflected sky: Gauss-Hermite converges to the hemisphere integral") {
  const Sky sky = make_sky(2.5, 35.0 * kDeg, 0.0);
  const SlopeVariance s{0.02, 0.012};
  const Vec3 v = direction_deg(70, 160);
  Vec3 previous{};
  double previous_change = 1e300;
  for (const int order : {8, 16, 32, 64}) {
    const Vec3 l = reflected_sky(v, kUp, s, sky, order);
    const double change = std::fabs(l[1] - previous[1]);
    if (order > 8) CHECK(change < previous_change * 1.5);
    previous_change = change;
    previous = l;
  }
  // Independent: the same integral over the hemisphere of incoming directions.
  const QuadratureTolerance tol{1e-7, 0.0, 4000};
  const double direct =
      integrate(
          [&](double theta) {
            return std::sin(theta) * integrate(
                                         [&](double phi) {
                                           const Vec3 light = direction_from_angles(theta, phi);
                                           return ocean_brdf(light, v, kUp, s).brdf_cos *
                                                  sky_radiance_rgb(sky, light)[1];
                                         },
                                         {-kPi, -kPi / 2, 0.0, kPi / 2, kPi}, tol)
                                         .value;
          },
          {0.0, 0.35, 0.6, 0.9, 1.2, kPi / 2}, tol)
          .value;
  CHECK(previous[1] == doctest::Approx(direct).epsilon(2e-3));
}

TEST_CASE("sun disk: the point-sun limit and convergence of the disk quadrature") {
  const SlopeVariance s{0.01, 0.006};
  const Vec3 sun = direction_deg(40, 0);
  const Vec3 v = direction_deg(42, 180.5);
  const double point = reflected_sun(sun, kSunAngularRadius, v, kUp, s, 0);
  const double disk8 = reflected_sun(sun, kSunAngularRadius, v, kUp, s, 8);
  const double disk16 = reflected_sun(sun, kSunAngularRadius, v, kUp, s, 16);
  CHECK(disk16 == doctest::Approx(disk8).epsilon(1e-10));
  CHECK(disk16 == doctest::Approx(point).epsilon(1e-3));  // smooth lobe ≫ the 0.27° disk
}

TEST_CASE("whitecaps and sea light: coverage is a Gaussian tail; energy split") {
  CHECK(whitecap_coverage(0.0, 0.0, 0.0) == 0.0);
  CHECK(whitecap_coverage(-1.0, 0.0, 0.0) == 1.0);
  CHECK(whitecap_coverage(0.5, 0.04, 0.5) == doctest::Approx(0.5));
  CHECK(whitecap_coverage(1.0, 0.25, 0.0) ==
        doctest::Approx(0.5 * std::erfc(2.0 / std::sqrt(2.0))));
  const Vec3 sea = refracted_sea(0.1, {0.1, 0.2, 0.3}, {1000.0, 1000.0, 1000.0});
  CHECK(sea[2] == doctest::Approx(0.9 * 0.3 * 1000.0 / kPi));
}

TEST_CASE("extremes: grazing view, sun at and below the horizon, sigma^2 from 1e-6 to 1") {
  const Sky sky = make_sky(2.0, 60.0 * kDeg, 0.0);
  Vec3 brightest = sky_radiance_rgb(sky, sky.sun_direction);
  for (int z = 0; z <= 180; ++z) {  // 0.5° × 1°, and the sun's own direction
    for (int a = 0; a < 360; ++a) {
      const Vec3 l = sky_radiance_rgb(sky, direction_deg(0.5 * z, a));
      for (std::size_t c = 0; c < 3; ++c) brightest[c] = std::fmax(brightest[c], l[c]);
    }
  }
  for (const double s2 : {1e-6, 1e-3, 0.1, 1.0}) {
    for (const double vz : {0.0, 45.0, 89.0, 89.9999, 90.0}) {
      for (const double sz : {0.0, 60.0, 89.999, 90.0, 100.0}) {
        const SlopeVariance s{s2, 0.5 * s2};
        const Vec3 v = direction_deg(vz, 180);
        const double sun = reflected_sun(direction_deg(sz, 0), kSunAngularRadius, v, kUp, s, 4);
        const double f = mean_fresnel(v, kUp, s, 16);
        const Vec3 sk = reflected_sky(v, kUp, s, sky, 16);
        CAPTURE(s2);
        CAPTURE(vz);
        CAPTURE(sz);
        // Values, not only finiteness: the sun's reflectance is part of an albedo ≤ 1 and 0 with
        // the whole disk below the horizon (100°); F̄ is a mean of F over facets, in [F(0°), 1];
        // the reflected sky is at most F̄ times the brightest sky (energy; 1 % for the order-16
        // Gauss–Hermite normalization) — test_limits.cpp derives each bound.
        CHECK((std::isfinite(sun) && sun >= 0.0 && sun <= 1.0));
        if (sz == 100.0) CHECK(sun == 0.0);
        CHECK((std::isfinite(f) && f >= fresnel_reflectance(1.0) && f <= 1.0));
        for (std::size_t c = 0; c < 3; ++c) {
          CHECK((std::isfinite(sk[c]) && sk[c] >= 0.0 && sk[c] <= 1.01 * f * brightest[c]));
        }
      }
    }
  }
}

TEST_CASE("tone mapping: Reinhard maps the log-average to a/(1+a) (L_white = inf) and white to 1") {
  const std::vector<Vec3> image{
      {100.0, 100.0, 100.0}, {1.0, 1.0, 1.0}, {10000.0, 10000.0, 10000.0}};
  const double average = log_average_luminance(image, 0.0);
  CHECK(average == doctest::Approx(100.0).epsilon(1e-12));  // geometric mean of 1, 100, 10⁴
  const Vec3 mid = reinhard({100.0, 100.0, 100.0}, average, 0.18, 1e300);
  CHECK(mid[1] == doctest::Approx(0.18 / 1.18).epsilon(1e-12));
  // L = L_white maps to exactly 1 (Reinhard eq. 4).
  const double white = 5.0;
  const Vec3 top = reinhard({100.0 * white / 0.18, 100.0 * white / 0.18, 100.0 * white / 0.18},
                            average, 0.18, white);
  CHECK(top[0] == doctest::Approx(1.0).epsilon(1e-12));
  // Temporal adaptation approaches the scene luminance monotonically, faster in bright light.
  double la = 1.0;
  for (int i = 0; i < 100; ++i) {
    const double next = adapt_luminance(la, 1000.0, 1.0 / 30.0);
    CHECK(next > la);
    CHECK(next <= 1000.0);
    la = next;
  }
  CHECK(la == doctest::Approx(1000.0).epsilon(1e-6));
  CHECK(adaptation_time_constant(1e6) == doctest::Approx(0.1).epsilon(1e-6));
  CHECK(adaptation_time_constant(0.0) == doctest::Approx(0.4));
  CHECK(srgb_encode(1.0) == doctest::Approx(1.0));
  CHECK(srgb_encode(0.001) == doctest::Approx(0.01292));
}
