// The four-term water shading of Vincevičius 2024 (shading/four_term.h) against computations by
// hand: configurations built from Pythagorean triples (0.6, 0.8), (0.28, 0.96) so that every
// cosine of the model is a short decimal, and the expected value is the printed formula written
// out with those decimals. Then the structure of eq. 2.11: each parameter set to 0 removes its
// own term and leaves the other three bit for bit, and validate() names each parameter out of
// its range.
//
// Tolerances: the library and the test evaluate the same formula in different operation orders
// and from decimals that are not exact in binary (0.6 and 0.8 give a unit vector only to 1 ulp),
// so results agree to a few ulp per factor: 1e-14 relative covers products of up to ~20 factors.
// The shininess-50 lobe raises a cosine with 1-ulp error to the 50th power (50 ulp ≈ 1e-14), so
// its checks allow 1e-13. Each expected value differs from any misreading of the formula (another
// exponent, a missing factor, an unclamped cosine) by far more than that.
#include <doctest/doctest.h>

#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/errors.h"
#include "core/vec3.h"
#include "shading/four_term.h"

using namespace oceanref;

namespace {

constexpr double kFourTermTolerance = 1e-14;
constexpr double kFourTermLobeTolerance = 1e-13;

// |a − b| ≤ tolerance·|b| (exact equality when b = 0).
bool four_term_close(double a, double b, double tolerance = kFourTermTolerance) {
  return std::fabs(a - b) <= tolerance * std::fabs(b);
}
bool four_term_close(const Vec3& a, const Vec3& b, double tolerance = kFourTermTolerance) {
  return four_term_close(a[0], b[0], tolerance) && four_term_close(a[1], b[1], tolerance) &&
         four_term_close(a[2], b[2], tolerance);
}
bool four_term_zero(const Vec3& v) {
  return v[0] == 0.0 && v[1] == 0.0 && v[2] == 0.0;
}
bool four_term_positive(const Vec3& v) {
  return v[0] > 0.0 && v[1] > 0.0 && v[2] > 0.0;
}
bool four_term_same(const Vec3& a, const Vec3& b) {
  return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}
// a ⊙ b · s, the channel-by-channel product the model's colour products mean.
Vec3 four_term_product(const Vec3& a, const Vec3& b, double s) {
  return {a[0] * b[0] * s, a[1] * b[1] * s, a[2] * b[2] * s};
}
double four_term_power(double x, int n) {
  double p = 1.0;
  for (int i = 0; i < n; ++i) p *= x;
  return p;
}

const Vec3 kFourTermUp{0.0, 1.0, 0.0};
const Vec3 kFourTermLight{2.0, 3.0, 4.0};  // C_l, distinct per channel

// Parameters away from the defaults, every one nonzero and distinct per channel.
FourTermParameters four_term_test_parameters() {
  FourTermParameters p;
  p.ambient_intensity = 0.7;
  p.ambient_colour = {0.2, 0.4, 0.6};
  p.air_bubble_density = 0.3;
  p.air_bubble_colour = {0.1, 0.5, 0.9};
  p.subsurface_height_intensity = 2.0;
  p.subsurface_view_intensity = 0.9;
  p.water_scattering_colour = {0.05, 0.25, 0.45};
  p.specular_colour = {0.9, 0.8, 0.7};
  p.shininess = 5.0;
  p.reflection_intensity = 0.6;
  return p;
}

}  // namespace

TEST_CASE("four-term Fresnel: 0 facing the camera, 0.85^5 at and beyond the floor, (1 - c)^5") {
  // D_v = N: 1 − 1 = 0 exactly.
  CHECK(four_term_fresnel(kFourTermUp, kFourTermUp) == 0.0);
  const Vec3 tilted = normalize(Vec3{0.3, 1.0, 0.2});
  CHECK(four_term_fresnel(tilted, tilted) < 1e-70);  // (a few ulp)^5
  // Grazing (c = 0), below the floor (c = 0.1), at it (0.15) and behind the facet (c < 0).
  const double floor_value = 0.85 * 0.85 * 0.85 * 0.85 * 0.85;
  CHECK(four_term_close(four_term_fresnel({1.0, 0.0, 0.0}, kFourTermUp), floor_value));
  CHECK(four_term_close(four_term_fresnel({std::sqrt(0.99), 0.1, 0.0}, kFourTermUp), floor_value));
  CHECK(four_term_close(four_term_fresnel({std::sqrt(1.0 - 0.0225), 0.15, 0.0}, kFourTermUp),
                        floor_value));
  CHECK(four_term_close(four_term_fresnel({0.6, -0.8, 0.0}, kFourTermUp), floor_value));
  CHECK(four_term_close(floor_value, 0.4437053125));
  // c = 0.6: 0.4^5 = 0.01024; c = 0.28: 0.72^5.
  CHECK(four_term_close(four_term_fresnel({0.8, 0.6, 0.0}, kFourTermUp), 0.01024));
  CHECK(four_term_close(four_term_fresnel({0.96, 0.28, 0.0}, kFourTermUp), 0.1934917632));
  // Decreasing from the floor to normal incidence.
  double previous = 1.0;
  for (double c = 0.15; c <= 1.0; c += 0.05) {
    const double f = four_term_fresnel({std::sqrt(1.0 - c * c), c, 0.0}, kFourTermUp);
    CHECK(f < previous);
    previous = f;
  }
}

TEST_CASE("four-term mirror direction: reflect(-D_v, N), angle in = angle out, unit length") {
  // N up, D_v at 36.87° from the zenith towards +x: the mirror is at the same angle towards −x.
  const Vec3 m = mirror_direction({0.6, 0.8, 0.0}, kFourTermUp);
  CHECK(std::fabs(m[0] + 0.6) <= 1e-15);
  CHECK(std::fabs(m[1] - 0.8) <= 1e-15);
  CHECK(m[2] == 0.0);
  const Vec3 normal = normalize(Vec3{0.2, 1.0, -0.3});
  const std::vector<Vec3> views = {normalize(Vec3{0.5, 0.7, 0.1}), normalize(Vec3{-0.9, 0.2, 0.4}),
                                   normalize(Vec3{0.0, 0.3, -1.0}), normal};
  for (const Vec3& v : views) {
    const Vec3 r = mirror_direction(v, normal);
    // GLSL's reflect(I, N) = I − 2(N·I)N with I = D_i = −D_v, written out independently.
    const Vec3 incident = scaled(v, -1.0);
    const double ni = dot(normal, incident);
    const Vec3 glsl{incident[0] - 2.0 * ni * normal[0], incident[1] - 2.0 * ni * normal[1],
                    incident[2] - 2.0 * ni * normal[2]};
    for (std::size_t c = 0; c < 3; ++c) CHECK(std::fabs(r[c] - glsl[c]) <= 1e-15);
    CHECK(std::fabs(dot(r, normal) - dot(v, normal)) <= 1e-15);    // angle in = angle out
    const Vec3 in_plane = cross(combine(1.0, r, 1.0, v), normal);  // r + v ∥ N
    CHECK(length(in_plane) <= 1e-15);
    CHECK(std::fabs(length(r) - 1.0) <= 1e-15);
    const Vec3 back = mirror_direction(r, normal);  // an involution
    for (std::size_t c = 0; c < 3; ++c) CHECK(std::fabs(back[c] - v[c]) <= 1e-15);
  }
}

TEST_CASE("four-term ambient: k_a <N_y> C_a C_l + rho_a C_b C_l") {
  const FourTermParameters p = four_term_test_parameters();
  const Vec3 bubbles = four_term_product(p.air_bubble_colour, kFourTermLight, 0.3);
  // N up: N_y = 1.
  CHECK(four_term_close(
      four_term_ambient(p, kFourTermUp, kFourTermLight),
      combine(1.0, four_term_product(p.ambient_colour, kFourTermLight, 0.7), 1.0, bubbles)));
  // A facet tilted 36.87°: N_y = 0.8.
  CHECK(four_term_close(
      four_term_ambient(p, {0.6, 0.8, 0.0}, kFourTermLight),
      combine(1.0, four_term_product(p.ambient_colour, kFourTermLight, 0.7 * 0.8), 1.0, bubbles)));
  // A folded-over facet (N_y < 0): the clamp leaves the bubbles only.
  CHECK(four_term_close(four_term_ambient(p, {0.6, -0.8, 0.0}, kFourTermLight), bubbles));
  // The ambient term ignores the sun: the same bits for two suns.
  const Vec3 view{0.8, 0.6, 0.0};
  const FourTermRadiance a =
      four_term_shading(p, view, kFourTermUp, {-0.8, 0.6, 0.0}, 1.0, kFourTermLight, {1, 1, 1});
  const FourTermRadiance b =
      four_term_shading(p, view, kFourTermUp, {0.0, 1.0, 0.0}, 1.0, kFourTermLight, {1, 1, 1});
  CHECK(four_term_same(a.ambient, b.ambient));
  CHECK_FALSE(four_term_same(a.subsurface, b.subsurface));
}

TEST_CASE("four-term wave-peak scattering L_ss1: 0 at or below the mean level, closed form above") {
  // Sun low towards −x, viewer towards +x looking at the sun through the wave.
  const Vec3 sun{-0.8, 0.6, 0.0};
  const Vec3 view{0.8, 0.6, 0.0};
  // <D_s·(−D_v)> = 0.64 − 0.36 = 0.28; N up: 0.5 − 0.5·0.6 = 0.2.
  const double expected_up = 2.0 * 1.5 * four_term_power(0.28, 4) * four_term_power(0.2, 3);
  CHECK(four_term_close(wave_peak_scattering(2.0, 1.5, view, kFourTermUp, sun), expected_up));
  CHECK(four_term_close(expected_up, 1.4751744e-4));
  // Linear in H above the mean level, 0 at and below it.
  CHECK(four_term_close(wave_peak_scattering(2.0, 3.0, view, kFourTermUp, sun), 2.0 * expected_up));
  CHECK(wave_peak_scattering(2.0, 0.0, view, kFourTermUp, sun) == 0.0);
  CHECK(wave_peak_scattering(2.0, -1.0, view, kFourTermUp, sun) == 0.0);
  // A facet tilted away from the sun, N = (0.6, 0.8, 0): D_s·N = 0, (0.5)³ = 0.125.
  CHECK(four_term_close(wave_peak_scattering(2.0, 1.5, view, {0.6, 0.8, 0.0}, sun),
                        2.0 * 1.5 * four_term_power(0.28, 4) * 0.125));
  // The viewer with the sun behind: D_s·(−D_v) = −1 < 0, clamped to 0.
  CHECK(wave_peak_scattering(2.0, 1.5, {-0.8, 0.6, 0.0}, kFourTermUp, sun) == 0.0);
  CHECK(wave_peak_scattering(0.0, 1.5, view, kFourTermUp, sun) == 0.0);
}

TEST_CASE("four-term view scattering L_ss2 = k_ss2 <D_v.N>^2") {
  CHECK(four_term_close(view_scattering(0.9, kFourTermUp, kFourTermUp), 0.9));
  CHECK(four_term_close(view_scattering(0.9, {0.8, 0.6, 0.0}, kFourTermUp), 0.9 * 0.36));
  CHECK(view_scattering(0.9, {0.8, -0.6, 0.0}, kFourTermUp) == 0.0);  // clamped, not 0.324
}

TEST_CASE("four-term subsurface L_ss = (1 - F)(L_ss1 + L_ss2) C_ws C_l") {
  const FourTermParameters p = four_term_test_parameters();
  const Vec3 sun{-0.8, 0.6, 0.0};
  const Vec3 view{0.8, 0.6, 0.0};
  const double fresnel = 0.01024;  // D_v·N = 0.6
  const double peak = 2.0 * 1.5 * four_term_power(0.28, 4) * four_term_power(0.2, 3);
  const double facing = 0.9 * 0.36;
  const Vec3 expected = four_term_product(p.water_scattering_colour, kFourTermLight,
                                          (1.0 - fresnel) * (peak + facing));
  CHECK(four_term_close(
      four_term_subsurface(p, view, kFourTermUp, sun, 1.5, fresnel, kFourTermLight), expected));
  const FourTermRadiance r =
      four_term_shading(p, view, kFourTermUp, sun, 1.5, kFourTermLight, {0.0, 0.0, 0.0});
  CHECK(four_term_close(r.subsurface, expected));
}

TEST_CASE("four-term specular: F C_s C_l at the mirror direction, falling as cos^n") {
  FourTermParameters p = four_term_test_parameters();
  // Sun at 16.26° elevation towards −x; its mirror R = (0.96, 0.28, 0).
  const Vec3 sun{-0.96, 0.28, 0.0};
  const Vec3 mirror{0.96, 0.28, 0.0};
  const Vec3 peak = four_term_product(p.specular_colour, kFourTermLight, 0.1934917632);  // 0.72⁵
  for (const double n : {1.0, 5.0, 50.0, 500.0}) {
    p.shininess = n;
    const double f = four_term_fresnel(mirror, kFourTermUp);
    CHECK(four_term_close(four_term_specular(p, mirror, kFourTermUp, sun, f, kFourTermLight), peak,
                          kFourTermLobeTolerance));
  }
  // 36.87° from R (cos α = 0.8): D_v = 0.8 R + 0.6 (−0.28, 0.96, 0) = (0.6, 0.8, 0), where
  // F = 0.2⁵; the lobe is 0.8ⁿ.
  const Vec3 off{0.6, 0.8, 0.0};
  for (const int n : {1, 5, 50}) {
    p.shininess = n;
    const double f = four_term_fresnel(off, kFourTermUp);
    CHECK(four_term_close(f, 0.00032));
    CHECK(four_term_close(phong_specular_lobe(off, kFourTermUp, sun, n), four_term_power(0.8, n),
                          kFourTermLobeTolerance));
    CHECK(four_term_close(
        four_term_specular(p, off, kFourTermUp, sun, f, kFourTermLight),
        four_term_product(p.specular_colour, kFourTermLight, 0.00032 * four_term_power(0.8, n)),
        kFourTermLobeTolerance));
  }
  // Beyond 90° from R the clamp gives 0 (not a negative cosine to an odd power).
  p.shininess = 5.0;
  CHECK(phong_specular_lobe({-0.96, 0.28, 0.0}, kFourTermUp, {-0.6, 0.8, 0.0}, 5.0) == 0.0);
  // A sun below the facet's horizon lights no highlight, although its formal mirror direction
  // (0.6, −0.8, 0) makes a positive cosine 0.352 with this view.
  const Vec3 low_sun{-0.6, -0.8, 0.0};
  const Vec3 view{0.96, 0.28, 0.0};
  CHECK(four_term_close(dot(view, mirror_direction(low_sun, kFourTermUp)), 0.352));
  CHECK(phong_specular_lobe(view, kFourTermUp, low_sun, 5.0) == 0.0);
  CHECK(four_term_zero(four_term_specular(p, view, kFourTermUp, low_sun, 0.5, kFourTermLight)));
}

TEST_CASE("four-term reflection L_r = F k_r C_sky") {
  CHECK(four_term_close(four_term_reflection({1.0, 2.0, 4.0}, 0.3, 0.5), {0.15, 0.3, 0.6}));
  CHECK(four_term_zero(four_term_reflection({1.0, 2.0, 4.0}, 0.0, 0.5)));  // F = 0 at D_v = N
  const FourTermParameters p = four_term_test_parameters();
  const Vec3 sky{0.5, 1.5, 2.5};
  const FourTermRadiance r = four_term_shading(p, {0.96, 0.28, 0.0}, kFourTermUp, {0.0, 1.0, 0.0},
                                               0.0, kFourTermLight, sky);
  CHECK(four_term_close(r.reflection, scaled(sky, 0.1934917632 * 0.6)));  // 0.72⁵ k_r
}

TEST_CASE("four-term shading: the four terms and their sum, eq. 2.11") {
  const FourTermParameters p = four_term_test_parameters();
  const Vec3 normal = normalize(Vec3{0.1, 1.0, 0.05});
  const Vec3 view{0.8, 0.6, 0.0};
  const Vec3 sun{-0.8, 0.6, 0.0};
  const Vec3 sky{0.5, 1.5, 2.5};
  const FourTermRadiance r = four_term_shading(p, view, normal, sun, 0.7, kFourTermLight, sky);
  const double f = four_term_fresnel(view, normal);
  CHECK(four_term_same(r.ambient, four_term_ambient(p, normal, kFourTermLight)));
  CHECK(four_term_same(r.subsurface,
                       four_term_subsurface(p, view, normal, sun, 0.7, f, kFourTermLight)));
  CHECK(four_term_same(r.specular, four_term_specular(p, view, normal, sun, f, kFourTermLight)));
  CHECK(four_term_same(r.reflection, four_term_reflection(sky, f, p.reflection_intensity)));
  const Vec3 total = four_term_total(r);
  for (std::size_t c = 0; c < 3; ++c) {
    CHECK(total[c] == ((r.ambient[c] + r.subsurface[c]) + r.specular[c]) + r.reflection[c]);
  }
}

TEST_CASE("four-term shading: each parameter set to 0 removes exactly its term") {
  const FourTermParameters base = four_term_test_parameters();
  // Near the sun's mirror and looking towards the sun through a crest: all four terms lit.
  const Vec3 normal = normalize(Vec3{0.1, 1.0, 0.05});
  const Vec3 view{0.8, 0.6, 0.0};
  const Vec3 sun{-0.8, 0.6, 0.0};
  const Vec3 sky{0.5, 1.5, 2.5};
  const double height = 0.7;
  const auto shade = [&](const FourTermParameters& p) {
    return four_term_shading(p, view, normal, sun, height, kFourTermLight, sky);
  };
  const FourTermRadiance r0 = shade(base);
  REQUIRE(four_term_positive(r0.ambient));
  REQUIRE(four_term_positive(r0.subsurface));
  REQUIRE(four_term_positive(r0.specular));
  REQUIRE(four_term_positive(r0.reflection));
  REQUIRE(wave_peak_scattering(base.subsurface_height_intensity, height, view, normal, sun) > 0.0);

  const double f = four_term_fresnel(view, normal);
  const Vec3 bubbles =
      four_term_product(base.air_bubble_colour, kFourTermLight, base.air_bubble_density);
  const Vec3 sky_lit =
      four_term_product(base.ambient_colour, kFourTermLight, base.ambient_intensity * normal[1]);
  const double peak =
      wave_peak_scattering(base.subsurface_height_intensity, height, view, normal, sun);
  const double facing = view_scattering(base.subsurface_view_intensity, view, normal);
  const auto scattering = [&](double s) {
    return four_term_product(base.water_scattering_colour, kFourTermLight, (1.0 - f) * s);
  };

  // Which of the four terms a change should leave untouched.
  struct Case {
    const char* name;
    void (*zero)(FourTermParameters&);
    bool ambient, subsurface, specular, reflection;  // true: must stay bit for bit
  };
  const std::vector<Case> cases = {
      {"k_a", [](FourTermParameters& p) { p.ambient_intensity = 0.0; }, false, true, true, true},
      {"C_a", [](FourTermParameters& p) { p.ambient_colour = {}; }, false, true, true, true},
      {"rho_a", [](FourTermParameters& p) { p.air_bubble_density = 0.0; }, false, true, true, true},
      {"C_b", [](FourTermParameters& p) { p.air_bubble_colour = {}; }, false, true, true, true},
      {"k_ss1", [](FourTermParameters& p) { p.subsurface_height_intensity = 0.0; }, true, false,
       true, true},
      {"k_ss2", [](FourTermParameters& p) { p.subsurface_view_intensity = 0.0; }, true, false, true,
       true},
      {"C_ws", [](FourTermParameters& p) { p.water_scattering_colour = {}; }, true, false, true,
       true},
      {"C_s", [](FourTermParameters& p) { p.specular_colour = {}; }, true, true, false, true},
      {"k_r", [](FourTermParameters& p) { p.reflection_intensity = 0.0; }, true, true, true, false},
  };
  for (const Case& c : cases) {
    CAPTURE(c.name);
    FourTermParameters p = base;
    c.zero(p);
    const FourTermRadiance r = shade(p);
    if (c.ambient) CHECK(four_term_same(r.ambient, r0.ambient));
    if (c.subsurface) CHECK(four_term_same(r.subsurface, r0.subsurface));
    if (c.specular) CHECK(four_term_same(r.specular, r0.specular));
    if (c.reflection) CHECK(four_term_same(r.reflection, r0.reflection));
    const std::string name = c.name;
    // What is left of the changed term: exactly the other half of its sum, or nothing.
    if (name == "k_a" || name == "C_a") CHECK(four_term_close(r.ambient, bubbles));
    if (name == "rho_a" || name == "C_b") CHECK(four_term_close(r.ambient, sky_lit));
    if (name == "k_ss1") CHECK(four_term_close(r.subsurface, scattering(facing)));
    if (name == "k_ss2") CHECK(four_term_close(r.subsurface, scattering(peak)));
    if (name == "C_ws") CHECK(four_term_zero(r.subsurface));
    if (name == "C_s") CHECK(four_term_zero(r.specular));
    if (name == "k_r") CHECK(four_term_zero(r.reflection));
  }
  // Both halves of a term at 0: the term is exactly 0.
  FourTermParameters no_ambient = base;
  no_ambient.ambient_intensity = 0.0;
  no_ambient.air_bubble_density = 0.0;
  CHECK(four_term_zero(shade(no_ambient).ambient));
  FourTermParameters no_subsurface = base;
  no_subsurface.subsurface_height_intensity = 0.0;
  no_subsurface.subsurface_view_intensity = 0.0;
  CHECK(four_term_zero(shade(no_subsurface).subsurface));
  // No light: only the reflected sky is left.
  const FourTermRadiance dark =
      four_term_shading(base, view, normal, sun, height, {0.0, 0.0, 0.0}, sky);
  CHECK(four_term_zero(dark.ambient));
  CHECK(four_term_zero(dark.subsurface));
  CHECK(four_term_zero(dark.specular));
  CHECK(four_term_same(dark.reflection, r0.reflection));
  // At the mean level (H = 0) the crest term L_ss1 vanishes and L_ss2 is left.
  const FourTermRadiance flat =
      four_term_shading(base, view, normal, sun, 0.0, kFourTermLight, sky);
  CHECK(four_term_close(flat.subsurface, scattering(facing)));
  CHECK(four_term_same(flat.ambient, r0.ambient));
}

TEST_CASE("four-term shading: NaN in, NaN out") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Vec3 bad{nan, nan, nan};
  const FourTermParameters p;
  CHECK(std::isnan(four_term_fresnel(bad, kFourTermUp)));
  CHECK(std::isnan(four_term_ambient(p, bad, kFourTermLight)[1]));
  CHECK(std::isnan(wave_peak_scattering(1.0, nan, {0.8, 0.6, 0.0}, kFourTermUp, {-0.8, 0.6, 0.0})));
  CHECK(std::isnan(phong_specular_lobe(bad, kFourTermUp, {-0.8, 0.6, 0.0}, 50.0)));
  CHECK(std::isnan(phong_specular_lobe({0.8, 0.6, 0.0}, kFourTermUp, bad, 50.0)));
}

TEST_CASE(
    "four-term validate: defaults and range ends accepted, each parameter out of range named") {
  CHECK_NOTHROW(validate(FourTermParameters{}));
  FourTermParameters ends;
  ends.ambient_intensity = 0.0;
  ends.ambient_colour = {0.0, 1.0, 0.0};
  ends.air_bubble_density = 0.0;
  ends.air_bubble_colour = {1.0, 0.0, 1.0};
  ends.subsurface_height_intensity = 0.0;
  ends.subsurface_view_intensity = 1e6;
  ends.water_scattering_colour = {1.0, 1.0, 1.0};
  ends.specular_colour = {0.0, 0.0, 0.0};
  ends.shininess = 1.0;
  ends.reflection_intensity = 0.0;
  CHECK_NOTHROW(validate(ends));
  ends.shininess = 10000.0;
  CHECK_NOTHROW(validate(ends));

  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const auto rejects = [](const FourTermParameters& p, const std::string& key,
                          const std::string& range) {
    CAPTURE(key);
    CHECK_THROWS_AS(validate(p), std::invalid_argument);
    try {
      validate(p);
    } catch (const SettingError& e) {
      CHECK(e.key() == key);
      const std::string message = e.what();
      CAPTURE(message);
      CHECK(message.find(key) != std::string::npos);
      CHECK(message.find(range) != std::string::npos);
    }
  };

  struct Scalar {
    const char* key;
    double FourTermParameters::*field;
  };
  for (const Scalar& s :
       {Scalar{"ambient_intensity", &FourTermParameters::ambient_intensity},
        Scalar{"air_bubble_density", &FourTermParameters::air_bubble_density},
        Scalar{"subsurface_height_intensity", &FourTermParameters::subsurface_height_intensity},
        Scalar{"subsurface_view_intensity", &FourTermParameters::subsurface_view_intensity},
        Scalar{"reflection_intensity", &FourTermParameters::reflection_intensity}}) {
    for (const double bad : {-1e-9, -1.0, nan, inf}) {
      FourTermParameters p;
      p.*s.field = bad;
      rejects(p, s.key, "[0, inf)");
    }
  }
  struct Colour {
    const char* key;
    Vec3 FourTermParameters::*field;
  };
  for (const Colour& c :
       {Colour{"ambient_colour", &FourTermParameters::ambient_colour},
        Colour{"air_bubble_colour", &FourTermParameters::air_bubble_colour},
        Colour{"water_scattering_colour", &FourTermParameters::water_scattering_colour},
        Colour{"specular_colour", &FourTermParameters::specular_colour}}) {
    for (std::size_t channel = 0; channel < 3; ++channel) {
      for (const double bad : {-0.01, 1.01, nan}) {
        FourTermParameters p;
        (p.*c.field)[channel] = bad;
        rejects(p, c.key, "[0, 1]");
      }
    }
  }
  for (const double bad : {0.999, 0.0, 10000.5, nan, inf}) {
    FourTermParameters p;
    p.shininess = bad;
    rejects(p, "shininess", "[1, 10000]");
  }
  // The message quotes the value and the channel.
  FourTermParameters p;
  p.specular_colour[2] = 1.5;
  CHECK_THROWS_WITH_AS(validate(p), doctest::Contains("got 1.5 in the blue channel"),
                       std::invalid_argument);
}
