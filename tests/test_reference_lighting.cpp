// The reference lighting integrals (shading/reference_lighting.h) against independent
// computations: the reflected sky as an integral over light directions of the point BRDF (not
// over slopes), the mean Fresnel and Smith's visible area by brute force in axis-aligned slope
// coordinates, the sun disk in polar coordinates, all with the scalar adaptive integrator of
// core/quadrature.h at a far tighter tolerance. Then the contract itself: tightening the
// tolerance 100× moves no value by more than its error estimate.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/quadrature.h"
#include "core/vec3.h"
#include "shading/lighting_terms.h"
#include "shading/ocean_lighting.h"
#include "shading/reference_lighting.h"
#include "test_support.h"

using namespace oceanref;

namespace {
using testing::kPi;

Vec3 in_frame(const SurfaceFrame& f, double x, double n, double y) {
  Vec3 v{};
  for (std::size_t k = 0; k < 3; ++k)
    v[k] = x * f.tangent_x[k] + n * f.normal[k] + y * f.tangent_y[k];
  return v;
}
// The unit vector at zenith angle θ and azimuth φ from T_x in the frame.
Vec3 polar(const SurfaceFrame& f, double theta, double phi) {
  return in_frame(f, std::sin(theta) * std::cos(phi), std::cos(theta),
                  std::sin(theta) * std::sin(phi));
}
Vec3 unit_cross(const Vec3& a, const Vec3& b) {
  const Vec3 c{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  const double n = std::sqrt(dot(c, c));
  return {c[0] / n, c[1] / n, c[2] / n};
}
double azimuth(const SurfaceFrame& f, const Vec3& d) {
  const double a = std::atan2(dot(d, f.tangent_y), dot(d, f.tangent_x));
  return a < 0.0 ? a + 2.0 * kPi : a;
}
std::vector<double> sorted_inside(double lo, double hi, std::vector<double> points) {
  std::vector<double> b{lo};
  std::sort(points.begin(), points.end());
  for (const double p : points) {
    if (p > b.back() + 1e-12 && p < hi - 1e-12) b.push_back(p);
  }
  b.push_back(hi);
  return b;
}

const QuadratureTolerance kTight{1e-11, 0.0, 20000};

// Breakpoints at geometrically spaced distances from `finest` around the peaks, so that the
// adaptive rule sees lobes as narrow as the BRDF's (~√σ² rad).
std::vector<double> around(const std::vector<double>& centres, double finest) {
  std::vector<double> points;
  for (const double c : centres) {
    points.push_back(c);
    for (double d = finest; d < 1.0; d *= 3.0) {
      points.push_back(c - d);
      points.push_back(c + d);
    }
  }
  return points;
}

// ∫_{L·N > 0} f(L, V) cos θ_L L_sky,G(L) dω in polar coordinates about N, split at the specular
// direction and the sun (the lobe's and the circumsolar peaks).
double sky_over_directions(const Vec3& view, const SurfaceFrame& f, SlopeVariance s,
                           const Sky& sky) {
  Vec3 mirror{};
  const double vn = dot(view, f.normal);
  for (std::size_t k = 0; k < 3; ++k) mirror[k] = 2.0 * vn * f.normal[k] - view[k];
  const double theta_m = std::acos(std::fmin(1.0, dot(mirror, f.normal)));
  const double theta_s =
      std::acos(std::fmax(-1.0, std::fmin(1.0, dot(sky.sun_direction, f.normal))));
  const double finest = 0.1 * std::sqrt(std::fmin(s.upwind, s.crosswind));
  const std::vector<double> phis = sorted_inside(
      0.0, 2.0 * kPi, around({azimuth(f, mirror), azimuth(f, sky.sun_direction)}, finest));
  const std::vector<double> thetas =
      sorted_inside(0.0, 0.5 * kPi, around({theta_m, theta_s}, finest));
  return integrate(
             [&](double theta) {
               return integrate(
                          [&](double phi) {
                            const Vec3 l = polar(f, theta, phi);
                            return ocean_brdf(l, view, f, s).brdf_cos *
                                   sky_radiance_rgb(sky, l)[1] * std::sin(theta);
                          },
                          phis, kTight)
                   .value;
             },
             thetas, kTight)
      .value;
}

// ∫⟨V·ñ⟩₊ p dζ and ∫ F ⟨V·ñ⟩₊ p dζ in axis-aligned slopes, the inner range cut at V·ñ = 0.
std::array<double, 2> fresnel_by_slopes(const Vec3& view, const SurfaceFrame& f, SlopeVariance s) {
  const double vx = dot(view, f.tangent_x);
  const double vy = dot(view, f.tangent_y);
  const double vn = dot(view, f.normal);
  const double hx = 7.0 * std::sqrt(s.upwind);
  const double hy = 7.0 * std::sqrt(s.crosswind);
  std::array<double, 2> r{};
  for (int channel = 0; channel < 2; ++channel) {
    r[static_cast<std::size_t>(channel)] =
        integrate(
            [&](double zx) {
              double lo = -hy;
              double hi = hy;
              if (vy > 0.0) hi = std::fmin(hi, (vn - zx * vx) / vy);
              if (vy < 0.0) lo = std::fmax(lo, (vn - zx * vx) / vy);
              if (!(hi > lo)) return 0.0;
              return integrate(
                         [&](double zy) {
                           const double projected = vn - zx * vx - zy * vy;
                           if (!(projected > 0.0)) return 0.0;
                           const double weight = projected * slope_density(zx, zy, s);
                           if (channel == 1) return weight;
                           return weight * fresnel_reflectance(projected /
                                                               std::sqrt(1.0 + zx * zx + zy * zy));
                         },
                         sorted_inside(lo, hi, {0.0}), kTight)
                  .value;
            },
            sorted_inside(-hx, hx, {0.0}), kTight)
            .value;
  }
  return r;
}

// ∫_disk f cos θ_L dω in polar coordinates (ρ, ψ) about the sun, dω = sin ρ dρ dψ.
double sun_by_polar(const Vec3& sun, double radius, const Vec3& view, const SurfaceFrame& f,
                    SlopeVariance s) {
  const std::array<Vec3, 2> axes = sun_disk_axes(sun);  // (u, w); clang 15 cannot capture bindings
  const Vec3& u = axes[0];
  const Vec3& w = axes[1];
  Vec3 mirror{};
  const double vn = dot(view, f.normal);
  for (std::size_t k = 0; k < 3; ++k) mirror[k] = 2.0 * vn * f.normal[k] - view[k];
  const double rho_m = std::acos(std::fmin(1.0, dot(mirror, sun)));
  double psi_m = std::atan2(dot(mirror, w), dot(mirror, u));
  if (psi_m < 0.0) psi_m += 2.0 * kPi;
  // The lobe is 2 v_n σ wide across the plane of incidence: a thin arc at grazing view.
  const double finest = 0.1 * vn * std::sqrt(std::fmin(s.upwind, s.crosswind));
  const std::vector<double> rhos = sorted_inside(0.0, radius, around({rho_m}, finest));
  // A thin arc through the disk's centre crosses each circle ρ = const twice: at ψ_m and
  // ψ_m ± π. (An arc that misses the centre crosses elsewhere; there these breakpoints miss it
  // and this brute force is wrong by up to 2.5% — the gnomonic strips below follow any arc.)
  const double psi_opposite = psi_m < kPi ? psi_m + kPi : psi_m - kPi;
  const std::vector<double> psis =
      sorted_inside(0.0, 2.0 * kPi, around({psi_m, psi_opposite}, finest / radius));
  return integrate(
             [&](double rho) {
               return integrate(
                          [&](double psi) {
                            Vec3 l{};
                            for (std::size_t k = 0; k < 3; ++k) {
                              l[k] = std::cos(rho) * sun[k] +
                                     std::sin(rho) * (std::cos(psi) * u[k] + std::sin(psi) * w[k]);
                            }
                            return ocean_brdf(l, view, f, s).brdf_cos * std::sin(rho);
                          },
                          psis, kTight)
                   .value;
             },
             rhos, kTight)
      .value;
}

// ∫_disk f cos θ_L dω in the gnomonic plane of the sun, independently of the reference's
// parametrization and lobe analysis: L = normalize(S + τ (x e₁ + y e₂)) with τ = tan ρ_s (the
// disk is the unit circle) and dω = τ² dx dy/(1 + τ² r²)^{3/2}; axes (a, b) rotated to the
// lobe's narrow and broad directions found from a finite-difference Jacobian of the facet slope
// ζ(x, y) that the BRDF reports, and its peak by Newton steps on ζ = 0. The outer integral
// crosses the lobe, with breakpoints at geometrically growing distances from its peak; the
// inner one runs along it between the disk's edges.
double sun_by_gnomonic_strips(const Vec3& sun, double radius, const Vec3& view,
                              const SurfaceFrame& f, SlopeVariance s) {
  // Axes ⟂ S, deliberately not those of sun_disk_axes: rotated by an arbitrary angle.
  Vec3 e1 = std::fabs(sun[2]) < 0.9 ? unit_cross(sun, Vec3{0.3, 0.0, 1.0})
                                    : unit_cross(sun, Vec3{1.0, 0.2, 0.0});
  const Vec3 e2 = unit_cross(sun, e1);
  const double tau = std::tan(radius);
  const auto direction = [&](double x, double y) {
    Vec3 l{};
    for (std::size_t k = 0; k < 3; ++k) l[k] = sun[k] + tau * (x * e1[k] + y * e2[k]);
    const double n = std::sqrt(dot(l, l));
    for (double& c : l) c /= n;
    return l;
  };
  const auto zeta = [&](double x, double y) {
    const BrdfTerms t = ocean_brdf(direction(x, y), view, f, s);
    return std::array<double, 2>{t.zeta_x, t.zeta_y};
  };
  // Newton on ζ(x, y) = 0 from the centre, the Jacobian by central differences.
  double px = 0.0, py = 0.0;
  std::array<std::array<double, 2>, 2> j{};
  for (int step = 0; step < 4; ++step) {
    const double d = 1e-4;
    const std::array<double, 2> z = zeta(px, py);
    const std::array<double, 2> zxp = zeta(px + d, py), zxm = zeta(px - d, py);
    const std::array<double, 2> zyp = zeta(px, py + d), zym = zeta(px, py - d);
    for (std::size_t c = 0; c < 2; ++c) {
      j[c][0] = (zxp[c] - zxm[c]) / (2.0 * d);
      j[c][1] = (zyp[c] - zym[c]) / (2.0 * d);
    }
    const double det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    px -= (j[1][1] * z[0] - j[0][1] * z[1]) / det;
    py -= (-j[1][0] * z[0] + j[0][0] * z[1]) / det;
  }
  // Precision of the Gaussian in (x, y): M = Jᵀ diag(1/σ_x², 1/σ_y²) J; its principal angle.
  const double m11 = j[0][0] * j[0][0] / s.upwind + j[1][0] * j[1][0] / s.crosswind;
  const double m12 = j[0][0] * j[0][1] / s.upwind + j[1][0] * j[1][1] / s.crosswind;
  const double m22 = j[0][1] * j[0][1] / s.upwind + j[1][1] * j[1][1] / s.crosswind;
  const double angle = 0.5 * std::atan2(2.0 * m12, m11 - m22);  // the largest eigenvalue's axis
  const double ca = std::cos(angle), sa = std::sin(angle);
  const double across = m11 * ca * ca + 2.0 * m12 * ca * sa + m22 * sa * sa;
  const double along = m11 * sa * sa - 2.0 * m12 * ca * sa + m22 * ca * ca;
  const double a0 = std::fmax(-1.0, std::fmin(1.0, px * ca + py * sa));
  const double b0 = -px * sa + py * ca;
  const auto family = [](double centre, double width, double lo, double hi) {
    std::vector<double> points{centre};
    for (double d = 0.1 * width; d < hi - lo; d *= 3.0) {
      points.push_back(centre - d);
      points.push_back(centre + d);
    }
    return sorted_inside(lo, hi, points);
  };
  const double width_a = 1.0 / std::sqrt(across);
  const double width_b = along > 0.0 ? 1.0 / std::sqrt(along) : 10.0;
  return integrate(
             [&](double a) {
               const double chord = std::sqrt(std::fmax(0.0, 1.0 - a * a));
               if (!(chord > 0.0)) return 0.0;
               return integrate(
                          [&](double b) {
                            const double x = a * ca - b * sa;
                            const double y = a * sa + b * ca;
                            const double q = 1.0 + tau * tau * (x * x + y * y);
                            return ocean_brdf(direction(x, y), view, f, s).brdf_cos * tau * tau /
                                   (q * std::sqrt(q));
                          },
                          family(std::fmax(-chord, std::fmin(chord, b0)), width_b, -chord, chord),
                          kTight)
                   .value;
             },
             family(a0, width_a, -1.0, 1.0), kTight)
      .value;
}

struct Case {
  Vec3 view;
  Vec3 normal;
  SlopeVariance s;
  double sun_zenith_deg;
};
std::string describe(const Case& c) {
  return "view (" + std::to_string(c.view[0]) + ", " + std::to_string(c.view[1]) + ", " +
         std::to_string(c.view[2]) + ") normal_y " + std::to_string(c.normal[1]) + " sigma2 " +
         std::to_string(c.s.upwind) + "," + std::to_string(c.s.crosswind) + " sun " +
         std::to_string(c.sun_zenith_deg);
}
Vec3 unit(double x, double y, double z) {
  const double l = std::sqrt(x * x + y * y + z * z);
  return {x / l, y / l, z / l};
}
// Grazing and steep views, tilted normals, isotropic and anisotropic σ² from 1e-6 to 1, the sun
// high, at the horizon and below it.
const std::vector<Case> kSweep = {
    {unit(0.3, 0.5, 0.8), unit(0, 1, 0), {0.02, 0.015}, 60.0},
    {unit(0.0, 0.05, 1.0), unit(0, 1, 0), {0.01, 0.01}, 78.0},
    {unit(0.6, 0.005, -0.8), unit(-0.05, 1, -0.1), {0.005, 0.003}, 85.0},
    {unit(-0.2, 0.9, 0.1), unit(0, 1, 0), {1e-4, 1e-4}, 30.0},
    {unit(0.5, 0.2, 0.5), unit(-0.2, 1, 0.1), {0.3, 0.1}, 90.0},
    {unit(0.1, 0.02, -1.0), unit(0, 1, 0), {1.0, 1.0}, 95.0},
    {unit(0.7, 0.3, 0.2), unit(0.3, 1, 0), {0.05, 0.08}, 45.0},
    {unit(0.4, 0.002, 0.9), unit(0, 1, 0), {1e-6, 1e-6}, 88.0},
    {unit(-0.9, 0.01, 0.4), unit(0, 1, 0), {1e-5, 2e-5}, 70.0},
};
Sky sky_of(const Case& c) {
  return make_sky(2.5, c.sun_zenith_deg * kPi / 180.0, 85.0 * kPi / 180.0);
}
}  // namespace

TEST_CASE("reference reflected sky equals the integral of the BRDF over light directions") {
  // Independent: the point BRDF (Bruneton eq. 8) over the hemisphere, versus the slope-space
  // form with its half-vector Jacobian. The direction form is converged to 1e-11, so the
  // difference must be within the reference's own estimate (plus 1e-9 relative for the
  // direction form's accuracy).
  for (const Case& c : kSweep) {
    CAPTURE(describe(c));
    const Sky sky = sky_of(c);
    const SurfaceFrame f = wind_frame(c.normal, 0.3);
    const RgbEstimate r = reflected_sky_reference(c.view, f, c.s, sky, {}, 1e-7, {0, 0, 0});
    CHECK(r.converged);
    const double brute = sky_over_directions(c.view, f, c.s, sky);
    CHECK(brute > 0.0);
    CHECK(std::fabs(r.value[1] - brute) <= r.error[1] + 1e-9 * brute);
    CHECK(r.error[1] <= 1e-7 * r.value[1]);
  }
}

TEST_CASE("reference mean Fresnel and the visible area against axis-aligned brute force") {
  for (const Case& c : kSweep) {
    CAPTURE(describe(c));
    const SurfaceFrame f = wind_frame(c.normal, 0.3);
    const std::array<double, 2> brute = fresnel_by_slopes(c.view, f, c.s);
    // Smith: ∫⟨V·ñ⟩₊ p dζ = cos θ_V (1 + Λ_V), Bruneton eq. 7 (independent of the integrator).
    const ViewTerms v = view_terms(c.view, f, c.s);
    CHECK(brute[1] == doctest::Approx(v.smith.visible_area).epsilon(1e-9));
    const ScalarEstimate r = mean_fresnel_reference(c.view, f, c.s, {}, 1e-7);
    CHECK(r.converged);
    const double fresnel = brute[0] / brute[1];
    CHECK(std::fabs(r.value - fresnel) <= r.error + 1e-9 * (1.0 - fresnel));
    CHECK(r.error <= 1e-7 * (1.0 - r.value));
  }
}

TEST_CASE("reference sun disk against polar brute force, down to sigma2 = 1e-10") {
  // The narrowest lobes (σ² ≤ 1e-5) are smaller than the sun disk: the case the order-2 rule got
  // 26% wrong. Views chosen so that the specular direction lies inside, at the edge of and
  // outside the disk.
  const Vec3 sun = unit(0.2, 0.4, 0.9);
  const SurfaceFrame f = wind_frame(unit(0, 1, 0), 0.0);
  const Vec3 mirror_of_sun = unit(-0.2, 0.4, -0.9);  // V for which L = sun is specular
  for (const double s2 : {1e-10, 1e-8, 1e-6, 1e-5, 1e-3, 0.05}) {
    for (const double offset : {0.0, 0.003, 0.0046, 0.01}) {
      Vec3 view = mirror_of_sun;
      view[0] += offset;
      view = unit(view[0], view[1], view[2]);
      CAPTURE(s2);
      CAPTURE(offset);
      const SlopeVariance s{s2, 0.8 * s2};
      const ScalarEstimate r =
          reflected_sun_reference(sun, kSunAngularRadius, view, f, s, {}, 1e-7, 0.0);
      CHECK(r.converged);
      const double brute = sun_by_polar(sun, kSunAngularRadius, view, f, s);
      CHECK(std::fabs(r.value - brute) <= r.error + 1e-9 * brute);
    }
  }
}

TEST_CASE("reference sun disk: the thin arc of a grazing view on a near-mirror sea") {
  // The sun 1° above the horizon, a grazing view (V·N ≈ 0.017) and σ² = 1e-6: the lobe is
  // 2 v_n σ ≈ 3.5e-5 rad wide across the plane of incidence, 130 times narrower than the disk,
  // and ~2σ along it: a thin arc. The specular direction is moved across the disk in elevation
  // and azimuth (inside, at the edge, just outside; off the sun's azimuth the arc misses the
  // disk's centre), on a flat and a tilted normal, with isotropic and anisotropic σ². Checked
  // against polar brute force where the arc passes the centre, and against the gnomonic strips
  // everywhere.
  const double elevation = 1.0 * kPi / 180.0;
  const Vec3 sun{std::cos(elevation), std::sin(elevation), 0.0};
  struct Arc {
    double d_elevation, d_azimuth;  // of the specular direction from the sun's centre [ρ_s]
    Vec3 normal;
    SlopeVariance s;
  };
  const std::vector<Arc> arcs = {
      {0.0, 0.0, unit(0, 1, 0), {1e-6, 1e-6}},   {-0.43, 0.0, unit(0, 1, 0), {1e-6, 1e-6}},
      {-0.97, 0.0, unit(0, 1, 0), {1e-6, 1e-6}}, {-1.3, 0.0, unit(0, 1, 0), {1e-6, 1e-6}},
      {0.0, 0.5, unit(0, 1, 0), {1e-6, 1e-6}},   {0.3, -0.8, unit(0, 1, 0), {1e-6, 1e-6}},
      {0.0, 0.98, unit(0, 1, 0), {1e-6, 1e-6}},  {0.0, 1.05, unit(0, 1, 0), {1e-6, 1e-6}},
      {-0.5, 0.6, unit(0, 1, 0), {1e-6, 4e-7}},  {0.2, 0.4, unit(0.01, 1, 0.02), {1e-6, 1e-6}},
      {0.0, -0.7, unit(0, 1, 0), {1e-8, 1e-8}},  {0.1, 0.3, unit(0, 1, 0), {1e-4, 1e-4}},
  };
  for (const Arc& arc : arcs) {
    CAPTURE(arc.d_elevation);
    CAPTURE(arc.d_azimuth);
    CAPTURE(arc.normal[0]);
    CAPTURE(arc.s.crosswind);
    const SurfaceFrame f = wind_frame(arc.normal, 0.4);
    // The specular direction m, then V = 2(m·N)N − m.
    const double e = elevation + arc.d_elevation * kSunAngularRadius;
    const double a = arc.d_azimuth * kSunAngularRadius;
    const Vec3 m{std::cos(e) * std::cos(a), std::sin(e), std::cos(e) * std::sin(a)};
    const double mn = dot(m, f.normal);
    const Vec3 view = unit(2.0 * mn * f.normal[0] - m[0], 2.0 * mn * f.normal[1] - m[1],
                           2.0 * mn * f.normal[2] - m[2]);
    const ScalarEstimate r =
        reflected_sun_reference(sun, kSunAngularRadius, view, f, arc.s, {}, 1e-7, 0.0);
    CHECK(r.converged);
    const double strips = sun_by_gnomonic_strips(sun, kSunAngularRadius, view, f, arc.s);
    CHECK(strips > 0.0);
    CHECK(std::fabs(r.value - strips) <= r.error + 1e-8 * strips);
    if (arc.d_azimuth == 0.0 && arc.normal[0] == 0.0) {
      const double polar_brute = sun_by_polar(sun, kSunAngularRadius, view, f, arc.s);
      CHECK(std::fabs(r.value - polar_brute) <= r.error + 1e-8 * polar_brute);
    }
  }
}

TEST_CASE("reflected_sun_bound bounds the sun disk's integral; below the tolerance it is skipped") {
  // Over the sweep, glints and grazing views included, and views moved across and away from the
  // sun's mirror direction: the bound is never below the converged integral. Far from the
  // glitter it is tiny, and an absolute tolerance above it returns 0 with the bound as the error,
  // without an evaluation; a tolerance below it integrates.
  for (const Case& c : kSweep) {
    CAPTURE(describe(c));
    const Sky sky = sky_of(c);
    const SurfaceFrame f = wind_frame(c.normal, 0.3);
    const ScalarEstimate r = reflected_sun_reference(sky.sun_direction, kSunAngularRadius, c.view,
                                                     f, c.s, {}, 1e-8, 0.0);
    const double bound = reflected_sun_bound(sky.sun_direction, kSunAngularRadius, c.view, f, c.s);
    CHECK(r.value <= bound);
  }
  const Vec3 sun = unit(0.2, 0.4, 0.9);
  const SurfaceFrame flat = wind_frame(unit(0, 1, 0), 0.0);
  for (const double s2 : {1e-6, 1e-4, 0.01, 0.1}) {
    for (const double offset : {0.0, 0.002, 0.01, 0.03, 0.1, 0.3}) {
      CAPTURE(s2);
      CAPTURE(offset);
      const Vec3 view = unit(-0.2 + offset, 0.4, -0.9 + offset);
      const SlopeVariance s{s2, 0.7 * s2};
      const ScalarEstimate r =
          reflected_sun_reference(sun, kSunAngularRadius, view, flat, s, {}, 1e-8, 0.0);
      CHECK(r.value <= reflected_sun_bound(sun, kSunAngularRadius, view, flat, s));
    }
  }
  const Vec3 away = unit(0.6, 0.3, 0.5);  // far from the glint of a calm sea
  const SlopeVariance calm{0.01, 0.01};
  const double bound = reflected_sun_bound(sun, kSunAngularRadius, away, flat, calm);
  CHECK(bound > 0.0);
  CHECK(bound < 1e-20);
  const ScalarEstimate skipped =
      reflected_sun_reference(sun, kSunAngularRadius, away, flat, calm, {}, 1e-6, 2.0 * bound);
  CHECK(skipped.value == 0.0);
  CHECK(skipped.error == bound);
  CHECK(skipped.evaluations == 0);
  const ScalarEstimate integrated =
      reflected_sun_reference(sun, kSunAngularRadius, away, flat, calm, {}, 1e-6, 0.5 * bound);
  CHECK(integrated.evaluations > 0);
  CHECK(integrated.value <= bound);
  // No bound (+∞) where H_S·N ≤ ρ, the equality included: for a sun of radius 0.25 with
  // H_S·N = 0.25 exactly, and for a point sun (ρ = 0) with H_S·N = 0 (the sun as far below the
  // surface's plane as the view is above it).
  const Vec3 view{0.0, 0.5, std::sqrt(0.75)};
  REQUIRE(flat.normal[1] == 1.0);
  CHECK(reflected_sun_bound({std::sqrt(1.0 - 0.0625), -0.25, 0.0}, 0.25, view, flat, calm) ==
        HUGE_VAL);
  CHECK(reflected_sun_bound({0.0, -0.5, -std::sqrt(0.75)}, 0.0, view, flat, calm) == HUGE_VAL);
}

TEST_CASE("tightening the tolerance 100x moves no value by more than its error estimate") {
  for (const Case& c : kSweep) {
    CAPTURE(describe(c));
    const Sky sky = sky_of(c);
    const SurfaceFrame f = wind_frame(c.normal, 0.3);
    for (const double tolerance : {1e-4, 1e-6}) {
      CAPTURE(tolerance);
      const RgbEstimate loose = reflected_sky_reference(c.view, f, c.s, sky, {}, tolerance, {});
      const RgbEstimate tight =
          reflected_sky_reference(c.view, f, c.s, sky, {}, tolerance / 100.0, {});
      for (std::size_t k = 0; k < 3; ++k) {
        CHECK(std::fabs(loose.value[k] - tight.value[k]) <= loose.error[k] + tight.error[k]);
        CHECK(loose.error[k] <= tolerance * loose.value[k]);
      }
      const ScalarEstimate a = mean_fresnel_reference(c.view, f, c.s, {}, tolerance);
      const ScalarEstimate b = mean_fresnel_reference(c.view, f, c.s, {}, tolerance / 100.0);
      CHECK(std::fabs(a.value - b.value) <= a.error + b.error);
      const ScalarEstimate p = reflected_sun_reference(sky.sun_direction, kSunAngularRadius, c.view,
                                                       f, c.s, {}, tolerance, 0.0);
      const ScalarEstimate q = reflected_sun_reference(sky.sun_direction, kSunAngularRadius, c.view,
                                                       f, c.s, {}, tolerance / 100.0, 0.0);
      CHECK(std::fabs(p.value - q.value) <= p.error + q.error);
    }
  }
}

TEST_CASE("reflected sky at tight tolerances: the cases where the map found estimates too small") {
  // Two cases of the lighting map's sweep (src/cli/lighting_map.cpp) whose 1e-7..1e-9 results
  // were off by 2-5x their estimates before two fixes: a grazing view (V·N = 0.01, σ² = 1e-4)
  // where the horizon cuts the Gaussian within a tiny range of the outer angle (now a
  // breakpoint), and a rough sea (σ² = 1) on a tilted normal where the circumsolar cusp's
  // breakpoint had the wrong slope sign. Each must agree with the direction-space brute force
  // and with itself 100x tighter, within the estimates.
  struct Tight {
    Vec3 view, normal;
    SlopeVariance s;
  };
  const double deg = kPi / 180.0;
  const Vec3 tilted{std::sin(30 * deg) * std::cos(45 * deg), std::cos(30 * deg),
                    std::sin(30 * deg) * std::sin(45 * deg)};
  const Sky sky = make_sky(2.5, 30 * deg, 90 * deg);
  for (const Tight& c : {Tight{unit(0.0, 0.01, -0.99995), unit(0, 1, 0), {1e-4, 1e-4}},
                         Tight{unit(0.976338, -0.200612, 0.0807448), tilted, {1.0, 1.0}}}) {
    CAPTURE(c.s.upwind);
    const SurfaceFrame f = wind_frame(c.normal, 20 * deg);
    const RgbEstimate loose = reflected_sky_reference(c.view, f, c.s, sky, {}, 1e-9, {});
    const RgbEstimate tight = reflected_sky_reference(c.view, f, c.s, sky, {}, 1e-11, {});
    CHECK(loose.converged);
    CHECK(tight.converged);
    for (std::size_t k = 0; k < 3; ++k) {
      CHECK(std::fabs(loose.value[k] - tight.value[k]) <= loose.error[k] + tight.error[k]);
    }
    const double brute = sky_over_directions(c.view, f, c.s, sky);
    CHECK(std::fabs(loose.value[1] - brute) <= loose.error[1] + 1e-11 * brute);
  }
}

TEST_CASE("the fast rules converge to the reference where the integrand is smooth") {
  // A steep view and small σ²: the horizon and the visibility line are far outside the
  // Gaussian, so Gauss–Hermite converges exponentially; order 32 must agree to 1e-10.
  const Sky sky = make_sky(2.5, 40.0 * kPi / 180.0, 1.0);
  const SurfaceFrame f = wind_frame(unit(0, 1, 0), 0.3);
  const Vec3 view = unit(0.2, 0.9, 0.3);
  const SlopeVariance s{1e-3, 8e-4};
  const RgbEstimate r = reflected_sky_reference(view, f, s, sky, {}, 1e-10, {});
  const Vec3 fast = reflected_sky(view, f, s, sky, 32);
  for (std::size_t k = 0; k < 3; ++k) CHECK(fast[k] == doctest::Approx(r.value[k]).epsilon(1e-10));
  const ScalarEstimate m = mean_fresnel_reference(view, f, s, {}, 1e-10);
  CHECK(mean_fresnel(view, f, s, 32) == doctest::Approx(m.value).epsilon(1e-10));
}

TEST_CASE("nothing is reflected towards a viewer below the surface") {
  const Sky sky = make_sky(2.5, 1.0, 1.0);
  const SurfaceFrame f = wind_frame(unit(0, 1, 0), 0.0);
  const Vec3 below = unit(0.3, -0.1, 0.5);
  const SlopeVariance s{0.01, 0.01};
  const RgbEstimate r = reflected_sky_reference(below, f, s, sky, {}, 1e-6, {});
  CHECK(r.value[0] == 0.0);
  CHECK(reflected_sun_reference(sky.sun_direction, kSunAngularRadius, below, f, s, {}, 1e-6, 0.0)
            .value == 0.0);
  CHECK(mean_fresnel_reference(below, f, s, {}, 1e-6).value == 1.0);
}

TEST_CASE("the fast rules are finite and converge to the reference at every order 1..1024") {
  // The case of the issue (brdf --view 0.3,0.5,0.8 --sun 0.2,0.4,0.9 --sigma2 0.02,0.015), where
  // the old rule gave F̄ = 0 at order 199 and L_sky.R = 9.2 instead of 228.4 at order 400.
  // Gauss–Hermite meets the kinks of the integrand (horizon, visibility), so it converges
  // algebraically: the bounds below are what it reaches, checked at every order up to 64 and
  // every 16th beyond (plus 199, 200, 1024); the sky, costlier, at a sample of orders.
  const Sky sky = make_sky(2.5, std::acos(0.4 / std::sqrt(1.01)), std::atan2(0.9, 0.2));
  const SurfaceFrame f = wind_frame(unit(0, 1, 0), 0.0);
  const Vec3 view = unit(0.3, 0.5, 0.8);
  const SlopeVariance s{0.02, 0.015};
  const double fresnel = mean_fresnel_reference(view, f, s, {}, 1e-10).value;
  const double sky_r = reflected_sky_reference(view, f, s, sky, {}, 1e-10, {}).value[0];
  std::vector<int> orders;
  for (int n = 1; n <= 64; ++n) orders.push_back(n);
  for (int n = 80; n <= kMaxQuadratureOrder; n += 16) orders.push_back(n);
  orders.push_back(199);
  orders.push_back(200);
  for (const int n : orders) {
    CAPTURE(n);
    const QuadratureRule rule = gauss_hermite(n);
    const double m = mean_fresnel(view, f, s, rule);
    REQUIRE(std::isfinite(m));
    CHECK(std::fabs(m - fresnel) <= (n < 4 ? 0.1 : n < 16 ? 1e-4 : 1e-7) * fresnel);
    if (n <= 16 || n % 64 == 0 || n == 199 || n == 200) {
      const double l = reflected_sky(view, f, s, sky, rule)[0];
      REQUIRE(std::isfinite(l));
      CHECK(std::fabs(l - sky_r) <= (n < 4     ? 0.3
                                     : n < 8   ? 0.05
                                     : n < 32  ? 0.03
                                     : n < 256 ? 1e-3
                                               : 2e-4) *
                                        sky_r);
    }
  }
}

TEST_CASE("lighting_terms, reference: each term its integral's, evaluations their sum, toggles") {
  // The terms of a sample are the three reference integrals, called here one by one with the
  // frame's floors; the evaluations are their sum; each toggle removes its term and its work.
  // The sun is integrated only while it lights the frame (a finite floor, sun above the horizon).
  for (const Case& c : kSweep) {
    CAPTURE(describe(c));
    const Sky sky = sky_of(c);
    const SurfaceFrame f = wind_frame(c.normal, 0.3);
    ShadingSettings sh;
    const FrameLighting light = frame_lighting(sky, sh);
    const bool sun_lit = light.sun_reflectance_floor < HUGE_VAL;
    CHECK(sun_lit == (c.sun_zenith_deg < 90.0));
    const ScalarEstimate sun =
        reflected_sun_reference(light.sun_direction, kSunAngularRadius, c.view, f, c.s, sh.brdf,
                                sh.tolerance, light.sun_reflectance_floor);
    const RgbEstimate reflected =
        reflected_sky_reference(c.view, f, c.s, sky, sh.brdf, sh.tolerance, light.radiance_floor);
    const ScalarEstimate fresnel = mean_fresnel_reference(c.view, f, c.s, sh.brdf, sh.tolerance);
    const long sun_work = sun_lit ? sun.evaluations : 0;
    const LightingTerms all = lighting_terms(sh, sky, light, c.view, f, c.s, false);
    CHECK(all.evaluations == sun_work + reflected.evaluations + fresnel.evaluations);
    CHECK(all.sun_reflectance == (sun_lit ? sun.value : 0.0));
    CHECK(all.sky[1] == reflected.value[1]);
    CHECK(all.mean_fresnel == fresnel.value);
    CHECK(all.sea[2] == refracted_sea(fresnel.value, sh.sea_colour, light.sky_irradiance)[2]);
    sh.sun = false;
    const LightingTerms no_sun = lighting_terms(sh, sky, light, c.view, f, c.s, false);
    CHECK(no_sun.evaluations == reflected.evaluations + fresnel.evaluations);
    CHECK(no_sun.sun[1] == 0.0);
    sh.sun = true;
    sh.sky = false;
    const LightingTerms no_sky = lighting_terms(sh, sky, light, c.view, f, c.s, false);
    CHECK(no_sky.evaluations == sun_work + fresnel.evaluations);
    CHECK(no_sky.sky[0] == 0.0);
    sh.sky = true;
    sh.sea = false;
    const LightingTerms no_sea = lighting_terms(sh, sky, light, c.view, f, c.s, false);
    CHECK(no_sea.evaluations == sun_work + reflected.evaluations);
    CHECK(no_sea.sea[2] == 0.0);
    CHECK(no_sea.mean_fresnel == 0.0);
  }
}

TEST_CASE("lighting_terms, reference: a term that misses its tolerance marks the sample") {
  // At a relative tolerance of 1e-14 and no absolute floor, below what each integral's
  // quadrature resolves in double precision, every term stops at its cap unconverged; with that
  // term alone on, the sample is unconverged, and at the default tolerance it is converged.
  const Case& c = kSweep.front();
  const Sky sky = sky_of(c);
  const SurfaceFrame f = wind_frame(c.normal, 0.3);
  for (const std::string term : {"sun", "sky", "sea"}) {
    CAPTURE(term);
    ShadingSettings sh;
    sh.sun = term == "sun";
    sh.sky = term == "sky";
    sh.sea = term == "sea";
    FrameLighting light = frame_lighting(sky, sh);
    CHECK(lighting_terms(sh, sky, light, c.view, f, c.s, false).converged);
    sh.tolerance = 1e-14;
    light.sun_reflectance_floor = 0.0;
    light.radiance_floor = {0.0, 0.0, 0.0};
    const bool alone =
        sh.sun ? reflected_sun_reference(light.sun_direction, kSunAngularRadius, c.view, f, c.s,
                                         sh.brdf, sh.tolerance, light.sun_reflectance_floor)
                     .converged
        : sh.sky ? reflected_sky_reference(c.view, f, c.s, sky, sh.brdf, sh.tolerance,
                                           light.radiance_floor)
                       .converged
                 : mean_fresnel_reference(c.view, f, c.s, sh.brdf, sh.tolerance).converged;
    REQUIRE_FALSE(alone);
    CHECK_FALSE(lighting_terms(sh, sky, light, c.view, f, c.s, false).converged);
  }
}

TEST_CASE("a perfect mirror (sigma2 = 0) is rejected, not integrated") {
  const Sky sky = make_sky(2.5, 1.0, 1.0);
  const SurfaceFrame f = wind_frame(unit(0, 1, 0), 0.0);
  const Vec3 view = unit(0.3, 0.5, 0.5);
  for (const SlopeVariance s : {SlopeVariance{0.0, 0.01}, SlopeVariance{0.01, -1.0},
                                SlopeVariance{std::nan(""), 0.01}, SlopeVariance{0.01, HUGE_VAL}}) {
    CHECK_THROWS_AS(mean_fresnel_reference(view, f, s, {}, 1e-6), std::invalid_argument);
    CHECK_THROWS_AS(reflected_sun_bound(sky.sun_direction, kSunAngularRadius, view, f, s),
                    std::invalid_argument);
    CHECK_THROWS_AS(reflected_sky_reference(view, f, s, sky, {}, 1e-6, {}), std::invalid_argument);
    CHECK_THROWS_AS(
        reflected_sun_reference(sky.sun_direction, kSunAngularRadius, view, f, s, {}, 1e-6, 0.0),
        std::invalid_argument);
  }
}

// ---- The geometry of the integrals' coordinates and breakpoints (reference_geometry) ---------

TEST_CASE("reference geometry: the chord's part of the slope plane [-T, T]") {
  using namespace reference_geometry;
  const double t = kSlopeTruncation;
  // Covering [−T, T] (also exactly at both ends): the whole line.
  for (const std::pair<double, double>& chord :
       {std::pair{0.0, 10.0}, std::pair{0.0, t}, std::pair{1.0, t + 1}, std::pair{-2.5, 9.0}}) {
    const double centre = chord.first, half = chord.second;  // copies: CAPTURE under clang 14
    CAPTURE(centre);
    CAPTURE(half);
    const ChordRange r = chord_in_slope_plane(centre, half);
    CHECK(r.whole_line);
    CHECK(r.lo == -t);
    CHECK(r.hi == t);
  }
  // Not covering it: the chord clipped to [−T, T], empty when outside.
  const auto clipped = [](double centre, double half) {
    const ChordRange r = chord_in_slope_plane(centre, half);
    CHECK_FALSE(r.whole_line);
    return std::array{r.lo, r.hi};
  };
  CHECK(clipped(0.0, 2.0) == std::array{-2.0, 2.0});
  CHECK(clipped(5.0, 2.0) == std::array{3.0, t});
  CHECK(clipped(-5.0, 2.0) == std::array{-t, -3.0});
  CHECK(clipped(1.0, t) == std::array{1.0 - t, t});  // reaches T, not −T
  CHECK(clipped(-1.0, t) == std::array{-t, t - 1.0});
  const std::array<double, 2> outside = clipped(20.0, 3.0);
  CHECK_FALSE(outside[1] > outside[0]);
}

namespace {
// The facet normal of slope ζ in the convention ñ = N − ζ_x T_x − ζ_y T_y, normalised, and V
// mirrored about it.
Vec3 mirrored_about_slope(const SurfaceFrame& f, const Vec3& view, double zx, double zy) {
  Vec3 n = in_frame(f, -zx, 1.0, -zy);
  const double length = std::sqrt(dot(n, n));
  for (double& x : n) x /= length;
  const double vn = dot(view, n);
  Vec3 l{};
  for (std::size_t k = 0; k < 3; ++k) l[k] = 2.0 * vn * n[k] - view[k];
  return l;
}
}  // namespace

TEST_CASE("reference geometry: the sky frame's ellipse is the horizon, its peak mirrors the sun") {
  // For views from steep to grazing, tilted and anisotropic: every point of the ellipse
  // (u₀ + U sin θ, centre ± half-chord) is a facet that mirrors V into the horizon (L·N = 0);
  // the circumsolar facet mirrors V into the sun; each θ of chord_scale_crossings puts an end
  // of the chord on a scale line w ∈ {0, ±2, ±6}, and between consecutive θ of a fine grid an
  // end crosses a line only where a returned θ lies.
  using namespace reference_geometry;
  const SurfaceFrame f = wind_frame(unit(0.2, 1.0, -0.3), 0.4);
  const SlopeVariance s{0.02, 0.006};
  const Vec3 sun = polar(f, 1.1, 2.0);
  for (const double theta_v : {0.3, 1.0, 1.45, 1.56}) {
    for (const double phi_v : {0.0, 1.0, 4.0}) {
      const Vec3 view = polar(f, theta_v, phi_v);
      CAPTURE(theta_v);
      CAPTURE(phi_v);
      const SkyFrame k = sky_frame(view, f, s);
      for (int i = -10; i <= 10; ++i) {
        const double theta = 0.157 * i;
        const math::SinCos angle{std::sin(theta), std::cos(theta)};
        const auto [centre, half] = sky_frame_chord(k, angle);
        for (const double end : {centre - half, centre + half}) {
          const std::array<double, 2> zeta = sky_frame_slope(k, k.u0 + k.extent * angle.sin, end);
          const Vec3 l = mirrored_about_slope(f, view, zeta[0], zeta[1]);
          CHECK(std::fabs(dot(l, f.normal)) < 1e-12);
        }
      }
      const std::array<double, 2> peak = circumsolar_facet(k, view, f, sun);
      const std::array<double, 2> zeta = sky_frame_slope(k, peak[0], peak[1]);
      const Vec3 l = mirrored_about_slope(f, view, zeta[0], zeta[1]);
      for (std::size_t c = 0; c < 3; ++c) CHECK(l[c] == doctest::Approx(sun[c]).epsilon(1e-12));
      const Vec3 below = polar(f, 1.8, 2.0);  // the sun under the surface's plane: no peak
      CHECK(circumsolar_facet(k, view, f, below) == std::array<double, 2>{0.0, 0.0});
      // Crossings over all of (−π/2, π/2).
      const std::vector<double> crossings = chord_scale_crossings(k, -kPi / 2, kPi / 2);
      const auto ends = [&](double theta) {
        const auto [centre, half] = sky_frame_chord(k, {std::sin(theta), std::cos(theta)});
        return std::array<double, 2>{centre - half, centre + half};
      };
      for (const double theta : crossings) {
        const std::array<double, 2> e = ends(theta);
        double nearest = HUGE_VAL;
        for (const double w : {-6.0, -2.0, 0.0, 2.0, 6.0}) {
          for (const double x : e) nearest = std::fmin(nearest, std::fabs(x - w));
        }
        CHECK(nearest < 1e-12 * k.radius);
      }
      // (The tips θ = ±π/2, where the chord shrinks to a point, are left out: a scale line
      // through a tip is touched there, not crossed.)
      const int steps = 20000;
      const double first = -kPi / 2 + 1e-6, step = (kPi - 2e-6) / steps;
      for (int j = 0; j < steps; ++j) {
        const double a = first + step * j, b = a + step;
        for (std::size_t side = 0; side < 2; ++side) {
          for (const double w : {-6.0, -2.0, 0.0, 2.0, 6.0}) {
            if ((ends(a)[side] - w) * (ends(b)[side] - w) >= 0.0) continue;
            bool found = false;
            for (const double theta : crossings) found = found || (theta >= a && theta <= b);
            CHECK_MESSAGE(found, "no crossing of w = " << w << " in [" << a << ", " << b << "]");
          }
        }
      }
    }
  }
}

TEST_CASE("reference geometry: a view along the normal has the horizon's ellipse centred") {
  // t₀ = 0 exactly: n̂ is T_x by convention (no direction from t₀ to the origin), and the
  // horizon is the circle |ζ| = 1 (a facet at 45° mirrors V into the surface's plane).
  using namespace reference_geometry;
  const SurfaceFrame f = wind_frame(unit(0.0, 1.0, 0.0), 0.7);
  const SlopeVariance s{0.02, 0.006};
  const SkyFrame k = sky_frame(f.normal, f, s);
  CHECK(k.nx == 1.0);
  CHECK(k.ny == 0.0);
  CHECK(k.u0 == 0.0);
  for (const double theta : {-1.2, 0.0, 0.5}) {
    const auto [centre, half] = sky_frame_chord(k, {std::sin(theta), std::cos(theta)});
    const std::array<double, 2> zeta =
        sky_frame_slope(k, k.extent * std::sin(theta), centre + half);
    const Vec3 l = mirrored_about_slope(f, f.normal, zeta[0], zeta[1]);
    CHECK(std::fabs(dot(l, f.normal)) < 1e-12);
  }
}

TEST_CASE("reference geometry: the sun disk's points and its horizon line") {
  // sun_disk_direction: a unit vector at angle ρ_s r from the sun towards x u + y w, with
  // dω/(dx dy) = (sin ρ/ρ) ρ_s²; on the line x (u·N) + y (w·N) = sun_disk_horizon the direction
  // lies in the surface's plane to O(ρ²) (L·N = (S·N)(cos ρ − sin ρ/ρ)), for a sun setting
  // across the tilted surface's horizon.
  using namespace reference_geometry;
  const double radius = 0.00465;
  const SurfaceFrame f = wind_frame(unit(0.2, 1.0, -0.3), 0.4);
  const Vec3 sun =
      polar(f, kPi / 2 - 0.5 * radius, 1.0);  // S·N = sin(ρ/2): the disk's centre above
  const std::array<Vec3, 2> axes = sun_disk_axes(sun);
  for (const auto& [x, y] : std::vector<std::array<double, 2>>{
           {0.0, 0.0}, {1.0, 0.0}, {0.0, -1.0}, {0.6, 0.3}, {-0.2, 0.9}}) {
    double density = 0.0;
    const Vec3 l = sun_disk_direction(sun, radius, axes, x, y, density);
    const double r = std::hypot(x, y);
    CHECK(dot(l, l) == doctest::Approx(1.0).epsilon(1e-15));
    CHECK(std::acos(std::fmin(1.0, dot(l, sun))) == doctest::Approx(radius * r).epsilon(1e-6));
    if (r > 0.0) {  // towards x u + y w
      CHECK(std::fabs(dot(l, axes[0]) * y - dot(l, axes[1]) * x) < 1e-15);
      CHECK(dot(l, axes[0]) * x + dot(l, axes[1]) * y > 0.0);
    }
    const double rho = radius * r;
    CHECK(density ==
          doctest::Approx((r > 0.0 ? std::sin(rho) / rho : 1.0) * radius * radius).epsilon(1e-15));
  }
  const double h = sun_disk_horizon(sun, radius, f);
  const double un = dot(axes[0], f.normal), wn = dot(axes[1], f.normal);
  CHECK(std::fabs(h) < std::hypot(un, wn));  // the horizon crosses the disk
  for (const double t : {-0.8, -0.3, 0.0, 0.4, 0.7}) {
    // The point of the line at parameter t along it, inside the disk.
    const double norm2 = un * un + wn * wn;
    const double x = h * un / norm2 - t * wn / std::sqrt(norm2);
    const double y = h * wn / norm2 + t * un / std::sqrt(norm2);
    if (std::hypot(x, y) > 1.0) continue;
    double density = 0.0;
    const Vec3 l = sun_disk_direction(sun, radius, axes, x, y, density);
    CHECK(std::fabs(dot(l, f.normal)) < radius * radius);
  }
}

TEST_CASE("reference geometry: the sun disk's breakpoints, around the lobe and on the horizon") {
  using namespace reference_geometry;
  const auto ascending_within = [](const std::vector<double>& b, double end) {
    REQUIRE(b.size() >= 2);
    CHECK(b.front() == -end);
    CHECK(b.back() == end);
    for (std::size_t i = 1; i < b.size(); ++i) CHECK(b[i] > b[i - 1]);
  };
  const auto contains = [](const std::vector<double>& b, double x) {
    return std::find(b.begin(), b.end(), x) != b.end();
  };
  // The lobe's peak at (x0, y0) = (0.3, 0.2), lobe 0.01: the ends, x0 and x0 ± 0.01·4^j for
  // j = 0 … 3, all inside [−1, 1] (as θ = asin x); η likewise around η0 = y0/cos θ0.
  const double x0 = 0.3, y0 = 0.2, lobe = 0.01;
  const double eta0 = y0 / std::sqrt(1.0 - x0 * x0);
  // The horizon along x (|w·N| ≥ |u·N|): at each θ the inner rule gets the η where the line
  // sin θ (u·N) + η cos θ (w·N) = h crosses the chord, in order; the outer rule nothing.
  const SunDiskBreaks along_x = sun_disk_breaks(x0, y0, lobe, 0.1, 0.2, 0.9);
  CHECK(along_x.horizon_across_x);
  ascending_within(along_x.theta, kPi / 2);
  ascending_within(along_x.eta, 1.0);
  CHECK(along_x.theta.size() == 11);
  CHECK(along_x.eta.size() == 11);
  CHECK(contains(along_x.theta, math::asin(x0)));
  CHECK(contains(along_x.eta, eta0));
  for (double d = lobe; d < 2.0; d *= 4.0) {
    CAPTURE(d);
    for (const double side : {-1.0, 1.0}) {
      CHECK(contains(along_x.theta, math::asin(x0 + side * d)));
      CHECK(contains(along_x.eta, eta0 + side * d));
    }
  }
  int crossed = 0;
  for (const double theta : {-1.5, -1.0, -0.3, 0.0, 0.2, 0.9, 1.4}) {
    CAPTURE(theta);
    const math::SinCos angle = math::sincos(theta);
    const std::vector<double> b = sun_disk_eta_breaks(along_x, angle);
    const double eta_h = (0.1 - 0.2 * angle.sin) / (0.9 * angle.cos);
    ascending_within(b, 1.0);
    if (std::fabs(eta_h) < 1.0) {
      ++crossed;
      REQUIRE(b.size() == along_x.eta.size() + 1);
      CHECK(contains(b, eta_h));
      CHECK(std::fabs(angle.sin * 0.2 + eta_h * angle.cos * 0.9 - 0.1) < 1e-16);
    } else {
      CHECK(b == along_x.eta);
    }
  }
  CHECK(crossed == 6);  // at θ = −1.5 the line passes outside the disk (η_h = 4.7)
  // The horizon along y: the outer rule gets θ = asin(h/(u·N)), the inner rule nothing.
  const SunDiskBreaks along_y = sun_disk_breaks(x0, y0, lobe, 0.3, 0.9, 0.2);
  CHECK(!along_y.horizon_across_x);
  ascending_within(along_y.theta, kPi / 2);
  CHECK(along_y.theta.size() == along_x.theta.size() + 1);
  CHECK(contains(along_y.theta, math::asin(0.3 / 0.9)));
  CHECK(along_y.eta == along_x.eta);
  for (const double theta : {-1.0, 0.0, 0.34, 1.2}) {
    CHECK(sun_disk_eta_breaks(along_y, math::sincos(theta)) == along_y.eta);
  }
  // A peak on the disk's rim (the mirror direction outside the disk: r0 is clamped to 1), at
  // x0 = 1 and at η0 = −1: each end is a breakpoint once, not twice.
  const SunDiskBreaks rim = sun_disk_breaks(1.0, 0.0, 0.5, 2.0, 0.2, 0.9);
  ascending_within(rim.theta, kPi / 2);
  ascending_within(rim.eta, 1.0);
  const SunDiskBreaks rim_eta = sun_disk_breaks(0.0, -1.0, 0.5, 2.0, 0.2, 0.9);
  ascending_within(rim_eta.eta, 1.0);
  CHECK(rim_eta.eta == std::vector<double>{-1.0, -0.5, 1.0});  // −1 ± 0.5 and the ends
}
