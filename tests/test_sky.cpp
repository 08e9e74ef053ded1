// Preetham sky and sun: identities, published and independent values, limits.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "sky/preetham.h"
#include "sky/spectral_tables.h"
#include "test_support.h"

using namespace oceanref;

namespace {
using testing::kDeg;
using testing::kPi;
}  // namespace

TEST_CASE(
    "CIE 1931 observer table: the three functions have equal integrals (equal-energy white)") {
  // CIE normalizes x̄, ȳ, z̄ to equal areas (the equal-energy illuminant has x = y = 1/3); the
  // 5-nm sums of the published table agree to 0.1% (the table's own rounding), 106.86 nm.
  double x = 0.0, y = 0.0, z = 0.0;
  for (const ColorMatchingSample& c : kCie1931Observer) {
    x += 5.0 * c.x;
    y += 5.0 * c.y;
    z += 5.0 * c.z;
  }
  CHECK(y == doctest::Approx(106.86).epsilon(1e-3));
  CHECK(x == doctest::Approx(y).epsilon(1e-3));
  CHECK(z == doctest::Approx(y).epsilon(2e-3));
}

TEST_CASE("CIE 1931 observer table: the shapes of the published functions, row by row") {
  // What the published 1931 functions look like at every 5-nm row, from 380 to 780 nm: ȳ (the
  // photopic luminosity V(λ)) rises strictly to exactly 1 at 555 nm and falls strictly after; z̄
  // rises strictly to its peak at 445 nm, never rises after, and is 0 from 650 nm on; x̄ and ȳ
  // are positive everywhere. A transposed or mistyped entry breaks one of these (the sums above
  // move by far less than their rounding).
  REQUIRE(kCie1931Observer.size() == 81);
  std::size_t peak_y = 0, peak_z = 0;
  for (std::size_t i = 0; i < 81; ++i) {
    const ColorMatchingSample& c = kCie1931Observer[i];
    CHECK(c.wavelength == 380.0 + 5.0 * static_cast<double>(i));
    CHECK(c.x > 0.0);
    CHECK(c.y > 0.0);
    if (c.y > kCie1931Observer[peak_y].y) peak_y = i;
    if (c.z > kCie1931Observer[peak_z].z) peak_z = i;
    CHECK((c.z == 0.0) == (c.wavelength >= 650.0));
  }
  CHECK(kCie1931Observer[peak_y].wavelength == 555.0);
  CHECK(kCie1931Observer[peak_y].y == 1.0);
  CHECK(kCie1931Observer[peak_z].wavelength == 445.0);
  for (std::size_t i = 0; i + 1 < 81; ++i) {
    const ColorMatchingSample &a = kCie1931Observer[i], &b = kCie1931Observer[i + 1];
    CAPTURE(a.wavelength);
    CHECK((i < peak_y ? b.y > a.y : b.y < a.y));
    CHECK((i < peak_z ? b.z > a.z : b.z <= a.z));
  }
  // x̄: two lobes; rising to the blue peak at 440 nm, falling to the dip at 505 nm (0.0024),
  // rising to the main peak at 600 nm, falling after.
  for (std::size_t i = 0; i + 1 < 81; ++i) {
    const ColorMatchingSample &a = kCie1931Observer[i], &b = kCie1931Observer[i + 1];
    const bool rising = a.wavelength < 440.0 || (a.wavelength >= 505.0 && a.wavelength < 600.0);
    CAPTURE(a.wavelength);
    CHECK((rising ? b.x > a.x : b.x < a.x));
  }
}

TEST_CASE("CIE 1931 observer table: the 6-decimal rounding of CVRL's values, entry by entry") {
  // A second, independent transcription: the CIE 1931 2-degree functions as the Colour & Vision
  // Research Laboratory publishes them (cvrl.org, "CIE 1931 2-deg, XYZ CMFs", 5-nm rows, up to
  // 10 significant digits, e.g. 0.05795001). Wyszecki & Stiles print the same functions to 6
  // decimals, so every entry of ours must be exactly CVRL's value rounded to 6 decimals; a 1%
  // change anywhere, or a typo in either transcription, shows. (It found x-bar(485 nm) mistyped
  // as 0.058010 for 0.057950.)
  const std::array<std::array<double, 3>, 81> cvrl{{{0.001368, 0.000039, 0.006450001},
                                                    {0.002236, 0.000064, 0.01054999},
                                                    {0.004243, 0.00012, 0.02005001},
                                                    {0.00765, 0.000217, 0.03621},
                                                    {0.01431, 0.000396, 0.06785001},
                                                    {0.02319, 0.00064, 0.1102},
                                                    {0.04351, 0.00121, 0.2074},
                                                    {0.07763, 0.00218, 0.3713},
                                                    {0.13438, 0.004, 0.6456},
                                                    {0.21477, 0.0073, 1.0390501},
                                                    {0.2839, 0.0116, 1.3856},
                                                    {0.3285, 0.01684, 1.62296},
                                                    {0.34828, 0.023, 1.74706},
                                                    {0.34806, 0.0298, 1.7826},
                                                    {0.3362, 0.038, 1.77211},
                                                    {0.3187, 0.048, 1.7441},
                                                    {0.2908, 0.06, 1.6692},
                                                    {0.2511, 0.0739, 1.5281},
                                                    {0.19536, 0.09098, 1.28764},
                                                    {0.1421, 0.1126, 1.0419},
                                                    {0.09564, 0.13902, 0.8129501},
                                                    {0.05795001, 0.1693, 0.6162},
                                                    {0.03201, 0.20802, 0.46518},
                                                    {0.0147, 0.2586, 0.3533},
                                                    {0.0049, 0.323, 0.272},
                                                    {0.0024, 0.4073, 0.2123},
                                                    {0.0093, 0.503, 0.1582},
                                                    {0.0291, 0.6082, 0.1117},
                                                    {0.06327, 0.71, 0.07824999},
                                                    {0.1096, 0.7932, 0.05725001},
                                                    {0.1655, 0.862, 0.04216},
                                                    {0.2257499, 0.9148501, 0.02984},
                                                    {0.2904, 0.954, 0.0203},
                                                    {0.3597, 0.9803, 0.0134},
                                                    {0.4334499, 0.9949501, 0.008749999},
                                                    {0.5120501, 1.0, 0.005749999},
                                                    {0.5945, 0.995, 0.0039},
                                                    {0.6784, 0.9786, 0.002749999},
                                                    {0.7621, 0.952, 0.0021},
                                                    {0.8425, 0.9154, 0.0018},
                                                    {0.9163, 0.87, 0.001650001},
                                                    {0.9786, 0.8163, 0.0014},
                                                    {1.0263, 0.757, 0.0011},
                                                    {1.0567, 0.6949, 0.001},
                                                    {1.0622, 0.631, 0.0008},
                                                    {1.0456, 0.5668, 0.0006},
                                                    {1.0026, 0.503, 0.00034},
                                                    {0.9384, 0.4412, 0.00024},
                                                    {0.8544499, 0.381, 0.00019},
                                                    {0.7514, 0.321, 0.0001},
                                                    {0.6424, 0.265, 0.00004999999},
                                                    {0.5419, 0.217, 0.00003},
                                                    {0.4479, 0.175, 0.00002},
                                                    {0.3608, 0.1382, 0.00001},
                                                    {0.2835, 0.107, 0.0},
                                                    {0.2187, 0.0816, 0.0},
                                                    {0.1649, 0.061, 0.0},
                                                    {0.1212, 0.04458, 0.0},
                                                    {0.0874, 0.032, 0.0},
                                                    {0.0636, 0.0232, 0.0},
                                                    {0.04677, 0.017, 0.0},
                                                    {0.0329, 0.01192, 0.0},
                                                    {0.0227, 0.00821, 0.0},
                                                    {0.01584, 0.005723, 0.0},
                                                    {0.01135916, 0.004102, 0.0},
                                                    {0.008110916, 0.002929, 0.0},
                                                    {0.005790346, 0.002091, 0.0},
                                                    {0.004109457, 0.001484, 0.0},
                                                    {0.002899327, 0.001047, 0.0},
                                                    {0.00204919, 0.00074, 0.0},
                                                    {0.001439971, 0.00052, 0.0},
                                                    {0.0009999493, 0.0003611, 0.0},
                                                    {0.0006900786, 0.0002492, 0.0},
                                                    {0.0004760213, 0.0001719, 0.0},
                                                    {0.0003323011, 0.00012, 0.0},
                                                    {0.0002348261, 0.0000848, 0.0},
                                                    {0.0001661505, 0.00006, 0.0},
                                                    {0.000117413, 0.0000424, 0.0},
                                                    {0.00008307527, 0.00003, 0.0},
                                                    {0.00005870652, 0.0000212, 0.0},
                                                    {0.00004150994, 0.00001499, 0.0}}};
  REQUIRE(kCie1931Observer.size() == cvrl.size());
  for (std::size_t i = 0; i < cvrl.size(); ++i) {
    const ColorMatchingSample& c = kCie1931Observer[i];
    CAPTURE(c.wavelength);
    CHECK(c.wavelength == 380.0 + 5.0 * static_cast<double>(i));
    CHECK(c.x == std::round(cvrl[i][0] * 1e6) / 1e6);
    CHECK(c.y == std::round(cvrl[i][1] * 1e6) / 1e6);
    CHECK(c.z == std::round(cvrl[i][2] * 1e6) / 1e6);
  }
}

TEST_CASE("sRGB: the derived matrix maps D65 to (1, 1, 1) and matches IEC 61966-2-1") {
  const Matrix3 m = xyz_to_linear_srgb_matrix();
  const Vec3 white = xyz_to_linear_srgb(xyY_to_XYZ(0.3127, 0.3290, 1.0));
  for (const double c : white) CHECK(c == doctest::Approx(1.0).epsilon(1e-13));
  // The standard prints the matrix to 4 decimals.
  const double iec[3][3] = {
      {3.2406, -1.5372, -0.4986}, {-0.9689, 1.8758, 0.0415}, {0.0557, -0.2040, 1.0570}};
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::size_t j = 0; j < 3; ++j) CHECK(std::fabs(m[i][j] - iec[i][j]) < 5e-4);
  }
}

TEST_CASE(
    "extraterrestrial solar table: in W/(m^2 sr nm) it gives the measured visible irradiance") {
  // Ω_sun ∫ S₀ dλ over 380–750 nm vs the solar constant 1361 W/m² (Kopp & Lean 2011) times the
  // fraction of a 5772 K black body (IAU 2015 nominal solar T_eff) in that band, computed here by
  // Planck's law. The real sun deviates from a black body by a few percent in the visible: 6%.
  const double omega = 2.0 * kPi * (1.0 - std::cos(kSunAngularRadius));
  double band = 0.0;
  for (std::size_t i = 0; i + 1 < kExtraterrestrialSolarRadiance.size(); ++i) {
    band += 5.0 * (kExtraterrestrialSolarRadiance[i] + kExtraterrestrialSolarRadiance[i + 1]);
  }
  band *= kSolarRadianceUnit * omega;
  const auto planck = [](double lambda_nm) {
    const double l = lambda_nm * 1e-9, h = 6.62607015e-34, c = 2.99792458e8, k = 1.380649e-23;
    return 1.0 / (l * l * l * l * l * (std::exp(h * c / (l * k * 5772.0)) - 1.0));
  };
  double visible = 0.0, total = 0.0;
  for (double l = 1.0; l < 100000.0; l += 1.0) {
    const double p = planck(l + 0.5);
    total += p;
    if (l + 0.5 >= 380.0 && l + 0.5 < 750.0) visible += p;
  }
  const double expected = 1361.0 * visible / total;
  CAPTURE(band);
  CAPTURE(expected);
  CHECK(band == doctest::Approx(expected).epsilon(0.06));
}

TEST_CASE("Preetham sky: zenith value is Y_z, the Perez ratio is 1 there; published limits") {
  for (const double t : {2.0, 3.0, 6.0, 10.0}) {
    for (const double zs : {0.0, 30.0, 60.0, 85.0}) {
      const Sky sky = make_sky(t, zs * kDeg, 0.4);
      const Chromaticity c = sky_chromaticity(sky, {0.0, 1.0, 0.0});
      CHECK(c.Y == doctest::Approx(zenith_luminance(t, zs * kDeg)).epsilon(1e-13));
      CHECK(c.x == doctest::Approx(zenith_chromaticity_x(t, zs * kDeg)).epsilon(1e-13));
      CHECK(c.y == doctest::Approx(zenith_chromaticity_y(t, zs * kDeg)).epsilon(1e-13));
    }
  }
  // A clear sky (T = 2–3) is bluer than white: zenith x, y below the D65 point (0.3127, 0.3290)
  // and the sky brighter near the sun than opposite it.
  const Sky clear = make_sky(2.5, 30.0 * kDeg, 0.0);
  CHECK(clear.zenith_x < 0.3127);
  CHECK(clear.zenith_y < 0.3290);
  CHECK(sky_chromaticity(clear, direction_from_angles(40.0 * kDeg, 0.0)).Y >
        sky_chromaticity(clear, direction_from_angles(40.0 * kDeg, kPi)).Y);
}

TEST_CASE("Preetham: values of an independent public transcription of the coefficients") {
  // Computed (double precision) with the coefficient matrices of the public implementation
  // eiszapfen2000/tgda, Trunk/Matlab/preethamSky.m (mAY, mAx, mAy, mxz, myz, and Y_z in kcd/m² ×
  // 1000): a second transcription of Preetham's appendix A.2, so a typo in either shows here.
  struct Row {
    double t, zenith_deg, Y, x, y;
  };
  for (const Row& r : {Row{2, 0, 15500.67214, 0.26674, 0.2772},
                       Row{2, 30, 5886.743249, 0.2514214624, 0.2559238382},
                       Row{3, 45, 7320.358317, 0.245678338, 0.2514764397},
                       Row{6, 60, 9585.26981, 0.2654679472, 0.2817888139},
                       Row{10, 80, 4760.601044, 0.3063558292, 0.3314752944}}) {
    CAPTURE(r.t);
    CAPTURE(r.zenith_deg);
    CHECK(zenith_luminance(r.t, r.zenith_deg * kDeg) == doctest::Approx(r.Y).epsilon(1e-9));
    CHECK(zenith_chromaticity_x(r.t, r.zenith_deg * kDeg) == doctest::Approx(r.x).epsilon(1e-9));
    CHECK(zenith_chromaticity_y(r.t, r.zenith_deg * kDeg) == doctest::Approx(r.y).epsilon(1e-9));
  }
  // The full distribution at zenith 60°, 90° in azimuth from the sun (T = 3, θ_s = 45°).
  const Sky sky = make_sky(3.0, 45.0 * kDeg, 0.0);
  const Chromaticity c = sky_chromaticity(sky, direction_from_angles(60.0 * kDeg, 90.0 * kDeg));
  CHECK(c.Y == doctest::Approx(7318.747262).epsilon(1e-9));
  CHECK(c.x == doctest::Approx(0.2502703602).epsilon(1e-9));
  CHECK(c.y == doctest::Approx(0.2620254989).epsilon(1e-9));
}

TEST_CASE("sun: luminance at the zenith sun is the published ~1.6e9 cd/m^2; it reddens and dims") {
  // "Sun at noon: 1.6 × 10⁹ cd/m²" (e.g. Rea, IESNA Lighting Handbook, 9th ed., table 1-2); a
  // clear, moderately hazy atmosphere (T = 2–3) with the Preetham transmittances: within 20%.
  const Sky noon = make_sky(2.0, 0.0, 0.0);
  const Vec3 xyz = sun_radiance_xyz(noon);
  CHECK(xyz[1] == doctest::Approx(1.6e9).epsilon(0.2));
  double previous_y = xyz[1];
  double previous_x = xyz[0] / (xyz[0] + xyz[1] + xyz[2]);
  for (const double zs : {30.0, 60.0, 75.0, 85.0, 89.0}) {
    const Vec3 v = sun_radiance_xyz(make_sky(2.0, zs * kDeg, 0.0));
    const double chroma_x = v[0] / (v[0] + v[1] + v[2]);
    CHECK(v[1] < previous_y);
    CHECK(chroma_x > previous_x);
    previous_y = v[1];
    previous_x = chroma_x;
  }
  // Near the horizon, independently: Beer–Lambert at the luminance-weighted 555 nm with the
  // Rayleigh, Ångström and ozone optical depths per air mass (0.0963 + 0.0997 + 0.0333 for
  // T = 2) and Kasten's m(80°) = 5.58 gives L(80°)/L(0°) ≈ 0.35; the spectral integral weights
  // the bluer, more attenuated light too, so it is lower: accept 25%.
  const double ratio = sun_radiance_xyz(make_sky(2.0, 80.0 * kDeg, 0.0))[1] / xyz[1];
  const double m80 = relative_optical_mass(80.0 * kDeg);
  const double m0 = relative_optical_mass(0.0);
  const double tau =
      0.008735 * std::pow(0.555, -4.08) + angstrom_beta(2.0) * std::pow(0.555, -1.3) + 0.095 * 0.35;
  CHECK(m80 == doctest::Approx(5.58).epsilon(2e-3));
  CHECK(ratio == doctest::Approx(std::exp(-tau * (m80 - m0))).epsilon(0.25));
  // Below the horizon: no sun.
  CHECK(sun_radiance_xyz(make_sky(2.0, 95.0 * kDeg, 0.0))[1] == 0.0);
  // The printed transmittance equals the physical one for m = 1 (Rayleigh at any λ).
  CHECK(rayleigh_transmittance(500.0, 1.0, TransmittanceForm::printed) ==
        doctest::Approx(rayleigh_transmittance(500.0, 1.0, TransmittanceForm::physical)));
}

TEST_CASE("transmittances: Iqbal's formulas (Preetham A.5), written out with libm") {
  // In each absorption band and at two air masses: τ_o = exp(−k_o l m) with l = 0.35 cm,
  // τ_g = exp(−1.41 k_g m / (1 + 118.93 k_g m)^0.45), τ_wa = exp(−0.2385 k_wa w m /
  // (1 + 20.07 k_wa w m)^0.45) with w = 2 cm; Rayleigh and aerosol physical (m in front) and as
  // printed (m in the exponent). The tables' values: k_o(600) = 0.125, k_g(765) = 1.605 (midway
  // between 3.0 and 0.21), k_wa(730) = 0.87. Outside a band its transmittance is exactly 1.
  // Tolerance 1e-13: a few ulps of the exponent, well below any term (the O₂ band lies beyond
  // the solar table's 750 nm, so only this test sees τ_g).
  const double beta = angstrom_beta(3.0);
  for (const double m : {1.0, 2.5}) {
    CAPTURE(m);
    CHECK(ozone_transmittance(600.0, m) ==
          doctest::Approx(std::exp(-0.125 * 0.35 * m)).epsilon(1e-13));
    const double kg = 1.605 * m;
    CHECK(mixed_gas_transmittance(765.0, m) ==
          doctest::Approx(std::exp(-1.41 * kg / std::pow(1.0 + 118.93 * kg, 0.45))).epsilon(1e-13));
    const double kw = 0.87 * 2.0 * m;
    CHECK(
        water_vapour_transmittance(730.0, m) ==
        doctest::Approx(std::exp(-0.2385 * kw / std::pow(1.0 + 20.07 * kw, 0.45))).epsilon(1e-13));
    CHECK(rayleigh_transmittance(450.0, m, TransmittanceForm::physical) ==
          doctest::Approx(std::exp(-m * 0.008735 * std::pow(0.45, -4.08))).epsilon(1e-13));
    CHECK(rayleigh_transmittance(450.0, m, TransmittanceForm::printed) ==
          doctest::Approx(std::exp(-0.008735 * std::pow(0.45, -4.08 * m))).epsilon(1e-13));
    CHECK(aerosol_transmittance(450.0, m, beta, TransmittanceForm::physical) ==
          doctest::Approx(std::exp(-m * beta * std::pow(0.45, -1.3))).epsilon(1e-13));
    CHECK(aerosol_transmittance(450.0, m, beta, TransmittanceForm::printed) ==
          doctest::Approx(std::exp(-beta * std::pow(0.45, -1.3 * m))).epsilon(1e-13));
    CHECK(ozone_transmittance(290.0, m) == 1.0);
    CHECK(mixed_gas_transmittance(700.0, m) == 1.0);
    CHECK(water_vapour_transmittance(600.0, m) == 1.0);
  }
}

TEST_CASE("sky irradiance: adaptive quadrature converges and agrees with a plain product rule") {
  const Sky sky = make_sky(3.0, 40.0 * kDeg, 1.0);
  const SkyIrradiance fine = sky_irradiance(sky, 1e-10);
  const SkyIrradiance coarse = sky_irradiance(sky, 1e-6);
  CHECK(fine.relative_error < 1e-9);
  CHECK(coarse.xyz[1] == doctest::Approx(fine.xyz[1]).epsilon(1e-5));
  // Independent: midpoint rule on a 400 × 800 (θ, φ) grid, error O(h²) ~ 1e−4 of E.
  double e = 0.0;
  const int nt = 400, np = 800;
  for (int i = 0; i < nt; ++i) {
    const double theta = (i + 0.5) * 0.5 * kPi / nt;
    for (int j = 0; j < np; ++j) {
      const double phi = (j + 0.5) * 2.0 * kPi / np;
      e += sky_chromaticity(sky, direction_from_angles(theta, phi)).Y * std::cos(theta) *
           std::sin(theta);
    }
  }
  e *= (0.5 * kPi / nt) * (2.0 * kPi / np);
  CHECK(e == doctest::Approx(fine.xyz[1]).epsilon(1e-3));
}

TEST_CASE("extremes: turbidity limits, sun at and below the horizon, grazing directions") {
  for (const double t : {kMinTurbidity, 5.0, kMaxTurbidity}) {
    for (const double zs : {0.0, 45.0, 89.9, 90.0, 120.0, 180.0}) {
      const Sky sky = make_sky(t, zs * kDeg, 0.3);
      for (const double z : {0.0, 30.0, 60.0, 89.0, 89.999, 90.0, 100.0}) {
        for (const double a : {0.0, 0.3, 1.5, 3.0}) {
          const Chromaticity c = sky_chromaticity(sky, direction_from_angles(z * kDeg, a));
          CAPTURE(t);
          CAPTURE(zs);
          CAPTURE(z);
          CHECK(std::isfinite(c.Y));
          CHECK(c.Y >= 0.0);
          CHECK(c.x > 0.0);
          CHECK(c.y > 0.0);
        }
      }
      const Vec3 sun = sun_radiance_xyz(sky);
      for (const double v : sun) CHECK((std::isfinite(v) && v >= 0.0));
    }
  }
  CHECK_THROWS_AS(make_sky(1.5, 0.0, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(make_sky(11.0, 0.0, 0.0), std::invalid_argument);
  // The sun's angles, each refused alone (the scene checks degrees first; a library caller
  // passes radians): zenith outside [0, π] or NaN, azimuth not finite. The ends are accepted.
  for (const double zenith : {-1e-12, std::nextafter(kPi, 4.0), std::nan("")}) {
    CAPTURE(zenith);
    CHECK_THROWS_WITH_AS(make_sky(2.5, zenith, 0.0), doctest::Contains("sun zenith angle"),
                         std::invalid_argument);
  }
  for (const double azimuth : {HUGE_VAL, -HUGE_VAL, std::nan("")}) {
    CAPTURE(azimuth);
    CHECK_THROWS_WITH_AS(make_sky(2.5, 1.0, azimuth), doctest::Contains("sun azimuth"),
                         std::invalid_argument);
  }
  CHECK_NOTHROW(make_sky(2.5, 0.0, -7.0));
  CHECK_NOTHROW(make_sky(2.5, kPi, 7.0));
}

TEST_CASE("below the horizon the sky is its horizon limit, continued smoothly (no jump)") {
  // B < 0 for Y, x and y over the whole turbidity range: the gradation factor 1 + A e^{B/cos θ}
  // tends to 1 with every derivative (the continuation is C∞).
  for (const double t : {kMinTurbidity, 6.0, kMaxTurbidity}) {
    CHECK(perez_luminance_coefficients(t).b < 0.0);
    CHECK(perez_x_coefficients(t).b < 0.0);
    CHECK(perez_y_coefficients(t).b < 0.0);
  }
  const Sky sky = make_sky(2.5, 80.0 * kDeg, 0.4);
  for (const double a : {0.0, 0.4, 2.0, 3.5}) {
    CAPTURE(a);
    const Chromaticity above = sky_chromaticity(sky, direction_from_angles(89.9999 * kDeg, a));
    const Chromaticity at = sky_chromaticity(sky, direction_from_angles(90.0 * kDeg, a));
    const Chromaticity below = sky_chromaticity(sky, direction_from_angles(90.0001 * kDeg, a));
    const Chromaticity deep = sky_chromaticity(sky, direction_from_angles(120.0 * kDeg, a));
    // Continuous: 10⁻⁶ rad from the horizon, e^{B/cos θ} ≤ e^{−0.28·10⁶}; only γ moves.
    CHECK(below.Y == doctest::Approx(above.Y).epsilon(1e-5));
    CHECK(below.Y == doctest::Approx(at.Y).epsilon(1e-5));
    CHECK(below.Y > 0.0);
    // Below the horizon only γ varies: F = 1 + C e^{Dγ} + E cos²γ over F(0, θ_s), times Y_z.
    const Vec3 d = direction_from_angles(120.0 * kDeg, a);
    const double cos_gamma = d[0] * sky.model_sun_direction[0] + d[1] * sky.model_sun_direction[1] +
                             d[2] * sky.model_sun_direction[2];
    const double gamma = std::acos(cos_gamma);
    const PerezCoefficients& k = sky.luminance;
    const double f = 1.0 + k.c * std::exp(k.d * gamma) + k.e * cos_gamma * cos_gamma;
    CHECK(deep.Y ==
          doctest::Approx(sky.zenith_luminance * f / sky.perez_at_zenith_luminance).epsilon(1e-12));
  }
}

TEST_CASE("out-of-gamut sky colours stay negative in linear sRGB (no clamping)") {
  // Near a low sun Preetham's chromaticities leave the sRGB gamut; the conversion is the linear
  // matrix (documented): the radiance is what the model says, clamping belongs to display.
  const Sky sky = make_sky(2.0, 89.0 * kDeg, 0.0);
  bool negative = false;
  for (double z = 60.0; z < 90.0; z += 0.5) {
    for (double a = -0.5; a <= 0.5; a += 0.05) {
      const Vec3 d = direction_from_angles(z * kDeg, a);
      const Vec3 rgb = sky_radiance_rgb(sky, d);
      const Vec3 xyz = sky_radiance_xyz(sky, d);
      CHECK(rgb == xyz_to_linear_srgb(xyz));
      negative = negative || rgb[0] < 0.0 || rgb[1] < 0.0 || rgb[2] < 0.0;
    }
  }
  CHECK(negative);
}

TEST_CASE("spectral tables: linear interpolation between the published wavelengths, 0 outside") {
  // The absorption tables (Iqbal 1983) are read piecewise linearly: at a node its value, a
  // quarter of the way to the next node a quarter of the step, outside the table 0.
  for (const std::vector<SpectralPoint>* table :
       {&kOzoneAbsorption, &kMixedGasAbsorption, &kWaterVapourAbsorption}) {
    for (std::size_t i = 0; i < table->size(); ++i) {
      const SpectralPoint& a = (*table)[i];
      CHECK(interpolate(*table, a.wavelength) == doctest::Approx(a.value).epsilon(1e-14));
      if (i + 1 == table->size()) break;
      const SpectralPoint& b = (*table)[i + 1];
      const double quarter = a.wavelength + 0.25 * (b.wavelength - a.wavelength);
      CHECK(interpolate(*table, quarter) ==
            doctest::Approx(0.75 * a.value + 0.25 * b.value).epsilon(1e-14));
    }
    CHECK(interpolate(*table, table->front().wavelength - 0.5) == 0.0);
    CHECK(interpolate(*table, table->back().wavelength + 0.5) == 0.0);
    CHECK(std::isnan(interpolate(*table, std::nan(""))));
  }
  // A table of one point: its value at its wavelength, 0 beside it; no table: 0.
  const std::vector<SpectralPoint> one{{500.0, 2.5}};
  CHECK(interpolate(one, 500.0) == 2.5);
  CHECK(interpolate(one, std::nextafter(500.0, 0.0)) == 0.0);
  CHECK(interpolate(one, std::nextafter(500.0, 1e3)) == 0.0);
  CHECK(interpolate({}, 500.0) == 0.0);
  // Two published values: the oxygen band's k_g at 765 nm (between 3.0 at 760 and 0.210 at 770)
  // and water vapour's k_wa at 695 nm (between 0.016 and 0.024).
  CHECK(interpolate(kMixedGasAbsorption, 765.0) == doctest::Approx(1.605).epsilon(1e-14));
  CHECK(interpolate(kWaterVapourAbsorption, 695.0) == doctest::Approx(0.020).epsilon(1e-14));
}

TEST_CASE("solar and absorption tables: a second public transcription, entry by entry") {
  // Preetham's sample code as published in Sunflow (src/org/sunflow/core/light/SunSkyLight.java:
  // the solar table, and k_o, k_g and k_wa "from pg 127, 130, MI"): the same decimal numbers, so
  // every wavelength and value must be the same double; a typo in either transcription shows.
  struct Table {
    const std::vector<SpectralPoint>* ours;
    std::vector<double> wavelengths, values;
  };
  const std::vector<Table> tables = {
      {&kOzoneAbsorption,
       {300, 305, 310, 315, 320, 325, 330, 335, 340, 345, 350, 355, 445, 450, 455, 460,
        465, 470, 475, 480, 485, 490, 495, 500, 505, 510, 515, 520, 525, 530, 535, 540,
        545, 550, 555, 560, 565, 570, 575, 580, 585, 590, 595, 600, 605, 610, 620, 630,
        640, 650, 660, 670, 680, 690, 700, 710, 720, 730, 740, 750, 760, 770, 780, 790},
       {10.0, 4.8,  2.7,  1.35, .8,   .380, .160, .075, .04,  .019, .007, .0,   .003,
        .003, .004, .006, .008, .009, .012, .014, .017, .021, .025, .03,  .035, .04,
        .045, .048, .057, .063, .07,  .075, .08,  .085, .095, .103, .110, .12,  .122,
        .12,  .118, .115, .12,  .125, .130, .12,  .105, .09,  .079, .067, .057, .048,
        .036, .028, .023, .018, .014, .011, .010, .009, .007, .004, .0,   .0}},
      {&kMixedGasAbsorption, {759, 760, 770, 771}, {0, 3.0, 0.210, 0}},
      {&kWaterVapourAbsorption,
       {689, 690, 700, 710, 720, 730, 740, 750, 760, 770, 780, 790, 800},
       {0, 0.160e-1, 0.240e-1, 0.125e-1, 0.100e+1, 0.870, 0.610e-1, 0.100e-2, 0.100e-4, 0.100e-4,
        0.600e-3, 0.175e-1, 0.360e-1}},
  };
  // The extraterrestrial solar radiance, 380-750 nm every 10 nm (its "solAmplitudes", in
  // 100 W/(m^2 nm sr)).
  const std::vector<double> solar{
      165.5, 162.3, 211.2, 258.8, 258.2, 242.3, 267.6, 296.6, 305.4, 300.6, 306.6, 288.3, 287.1,
      278.2, 271.0, 272.3, 263.6, 255.0, 250.6, 253.1, 253.5, 251.3, 246.3, 241.7, 236.8, 232.1,
      228.2, 223.4, 219.7, 215.3, 211.0, 207.3, 202.4, 198.7, 194.3, 190.7, 186.3, 182.6};
  REQUIRE(kExtraterrestrialSolarRadiance.size() == solar.size());
  for (std::size_t i = 0; i < solar.size(); ++i) {
    CAPTURE(380 + 10 * i);
    CHECK(kExtraterrestrialSolarRadiance[i] == solar[i]);
  }
  for (const Table& table : tables) {
    REQUIRE(table.ours->size() == table.wavelengths.size());
    REQUIRE(table.values.size() == table.wavelengths.size());
    for (std::size_t i = 0; i < table.wavelengths.size(); ++i) {
      const SpectralPoint point = (*table.ours)[i];
      CAPTURE(point.wavelength);
      CHECK(point.wavelength == table.wavelengths[i]);
      CHECK(point.value == table.values[i]);
    }
  }
}

TEST_CASE("sun spectrum: the table's 380-750 nm and nothing outside it") {
  // Preetham's solar table (Smits 1999, from Iqbal) spans 380-750 nm in 10-nm steps; the sun's
  // spectral radiance is 0 beyond it (the observer table runs to 780 nm), not an extrapolation.
  for (const double wavelength : {379.0, 750.5, 755.0, 770.0, 780.0}) {
    CAPTURE(wavelength);
    CHECK(sun_spectral_radiance(wavelength, 0.3, 2.5, TransmittanceForm::physical) == 0.0);
  }
  // Inside, at the table's nodes, the table (W/(m^2 sr nm), × kSolarRadianceUnit) times the
  // transmittances, which are at most 1: positive, and below the extraterrestrial value.
  for (const double wavelength : {380.0, 550.0, 750.0}) {
    CAPTURE(wavelength);
    const double extraterrestrial =
        kSolarRadianceUnit *
        kExtraterrestrialSolarRadiance[static_cast<std::size_t>((wavelength - 380.0) / 10.0)];
    const double l = sun_spectral_radiance(wavelength, 0.3, 2.5, TransmittanceForm::physical);
    CHECK(l > 0.3 * extraterrestrial);
    CHECK(l < extraterrestrial);
  }
}

TEST_CASE("sun_radiance_xyz: the trapezoid rule over the observer's 5 nm table, ends halved") {
  // The same sum written out: 683 lm/W · Σ w_i L_sun(λ_i) (x̄, ȳ, z̄)(λ_i), w = 2.5 nm at the
  // table's two ends and 5 nm inside. The 380 nm end weighs ~1e-5 of the total, so the
  // expectation is exact to rounding; the 780 nm end lies beyond the solar table's 750 nm, where
  // L_sun = 0, and cannot show.
  for (const double zenith_deg : {0.0, 60.0, 85.0}) {
    CAPTURE(zenith_deg);
    const Sky sky = make_sky(2.5, zenith_deg * kDeg, 0.0);
    Vec3 expected{0.0, 0.0, 0.0};
    for (std::size_t i = 0; i < kCie1931Observer.size(); ++i) {
      const ColorMatchingSample& c = kCie1931Observer[i];
      const double w = i == 0 || i == kCie1931Observer.size() - 1 ? 2.5 : 5.0;
      const double l = sun_spectral_radiance(c.wavelength, sky.sun_zenith, sky.turbidity,
                                             TransmittanceForm::physical);
      expected[0] += w * l * c.x;
      expected[1] += w * l * c.y;
      expected[2] += w * l * c.z;
    }
    const Vec3 got = sun_radiance_xyz(sky);
    for (std::size_t j = 0; j < 3; ++j) {
      CHECK(got[j] == doctest::Approx(683.0 * expected[j]).epsilon(1e-14));
    }
  }
}
