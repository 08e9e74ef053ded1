#include "shading/reference_lighting.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <numbers>
#include <span>
#include <stdexcept>
#include <vector>

#include "core/adaptive_cubature.h"
#include "core/math.h"
#include "core/vec3.h"
#include "shading/ocean_lighting.h"

namespace oceanref {

namespace {
constexpr double kPi = std::numbers::pi;
constexpr double kT = kSlopeTruncation;

// [lo, hi] split at the Gaussian's scale (t = −2, 0, 2: pieces on which e^{−t²} is smooth
// enough for one Kronrod rule) and at the given points, ascending.
std::vector<double> breakpoints_in(double lo, double hi, std::initializer_list<double> extra) {
  std::vector<double> b{lo, hi, -2.0, 0.0, 2.0};
  b.insert(b.end(), extra);
  std::sort(b.begin(), b.end());
  std::vector<double> inside;
  for (const double x : b) {
    if (x >= lo && x <= hi && (inside.empty() || x > inside.back())) inside.push_back(x);
  }
  return inside;
}

// An inner integral's tolerance such that, integrated over an outer range of the given length,
// its errors use at most a quarter of the outer budget. `scale` is an a-priori estimate of the
// outer integral (from a low-order rule): inner integrals whose share of it is small need not
// be accurate relative to themselves (a factor 2 off in the estimate costs only evaluations).
template <std::size_t N>
CubatureTolerance<N> inner_tolerance(const CubatureTolerance<N>& outer, double outer_length,
                                     const std::array<double, N>& scale) {
  CubatureTolerance<N> inner = outer;
  inner.relative = 0.25 * outer.relative;
  const double length = std::fmax(outer_length, 1e-300);
  for (std::size_t c = 0; c < N; ++c) {
    inner.absolute[c] =
        0.25 * std::fmax(outer.absolute[c], 0.5 * outer.relative * std::fabs(scale[c])) / length;
  }
  return inner;
}

// The Gauss–Hermite rules of integrate_line (immutable, built once).
std::span<const QuadratureRule> hermite_rules() {
  static const std::array<QuadratureRule, 4> rules{gauss_hermite(8), gauss_hermite(16),
                                                   gauss_hermite(32), gauss_hermite(64)};
  return rules;
}

// ∫ e^{−x²} h(x) dx over the line: Gauss–Hermite rules of increasing order, or adaptive Kronrod
// on [−6, 6] when they do not converge (an integrand that is not smooth on the Gaussian's scale).
template <std::size_t N, class H>
Estimate<N> integrate_line(const H& h, const CubatureTolerance<N>& tolerance) {
  Estimate<N> r = integrate_gauss_hermite<N>(h, hermite_rules(), tolerance);
  if (r.converged) return r;
  const long spent = r.evaluations;
  r = integrate_adaptive<N>(
      [&](double x) {
        Estimate<N> e = h(x);
        const double gaussian = math::exp(-x * x);
        for (std::size_t c = 0; c < N; ++c) {
          e.value[c] *= gaussian;
          e.error[c] *= gaussian;
        }
        return e;
      },
      breakpoints_in(-kT, kT, {}), tolerance);
  r.evaluations += spent;
  return r;
}

double clamp_unit(double x) {
  return std::fmin(std::fmax(x, -1.0), 1.0);
}

// The integrals are over a Gaussian of slopes: a perfect mirror (σ² = 0) has none.
void require_roughness(SlopeVariance s) {
  if (!(s.upwind > 0.0 && s.crosswind > 0.0 && std::isfinite(s.upwind) &&
        std::isfinite(s.crosswind))) {
    throw std::invalid_argument("reference lighting: slope variances must be finite and > 0");
  }
}
}  // namespace

namespace reference_geometry {

// The horizon L·N = 0 in ζ is the circle of centre −v_t/v_n and radius R = 1/v_n; in t an
// ellipse of centre t₀. n̂ points from t₀ towards the origin, which puts the boundary nearest to
// the Gaussian's mass across u. |S t − c|² = (Δu, Δw)ᵀ [[a, b], [b, c]] (Δu, Δw) < R²,
// S = diag(s_x, s_y); its u-extent is u₀ ± U, U = R √c/(s_x s_y) (ac − b² = s_x² s_y²).
SkyFrame sky_frame(const Vec3& view, const SurfaceFrame& f, SlopeVariance s) {
  SkyFrame k{};
  const double vn = dot(view, f.normal);
  k.sx = std::sqrt(2.0 * s.upwind);
  k.sy = std::sqrt(2.0 * s.crosswind);
  const double t0x = -dot(view, f.tangent_x) / (vn * k.sx);
  const double t0y = -dot(view, f.tangent_y) / (vn * k.sy);
  const double t0 = std::sqrt(t0x * t0x + t0y * t0y);
  k.nx = t0 > 0.0 ? -t0x / t0 : 1.0;
  k.ny = t0 > 0.0 ? -t0y / t0 : 0.0;
  k.radius = 1.0 / vn;
  k.b = k.nx * k.ny * (k.sy * k.sy - k.sx * k.sx);
  k.c = k.sx * k.sx * k.ny * k.ny + k.sy * k.sy * k.nx * k.nx;
  k.extent = k.radius * std::sqrt(k.c) / (k.sx * k.sy);
  k.u0 = -t0;
  return k;
}

std::array<double, 2> sky_frame_slope(const SkyFrame& k, double u, double w) {
  return {k.sx * (u * k.nx - w * k.ny), k.sy * (u * k.ny + w * k.nx)};
}

// With Δu = U sin θ the chord in w is centred at −b U sin θ/c with half-length R cos θ/√c.
std::array<double, 2> sky_frame_chord(const SkyFrame& k, const math::SinCos& angle) {
  return {-k.b * k.extent * angle.sin / k.c, k.radius * angle.cos / std::sqrt(k.c)};
}

ChordRange chord_in_slope_plane(double centre, double half_chord) {
  if (centre - half_chord <= -kT && centre + half_chord >= kT) return {true, -kT, kT};
  return {false, std::fmax(-kT, centre - half_chord), std::fmin(kT, centre + half_chord)};
}

// The facet that mirrors V into the sun: the circumsolar peak (a cusp of the Perez γ-term). Its
// normal is h = V + S, and in the convention ñ = N − ζ_x T_x − ζ_y T_y (reflected_sky_per_slope)
// its slope is ζ = −h_t/h_n.
std::array<double, 2> circumsolar_facet(const SkyFrame& k, const Vec3& view, const SurfaceFrame& f,
                                        const Vec3& sun) {
  Vec3 h{};
  for (std::size_t i = 0; i < 3; ++i) h[i] = view[i] + sun[i];
  const double hn = dot(h, f.normal);
  const bool sun_peak = dot(sun, f.normal) > 0.0 && hn > 0.0;
  const double tsx = sun_peak ? -dot(h, f.tangent_x) / hn / k.sx : 0.0;
  const double tsy = sun_peak ? -dot(h, f.tangent_y) / hn / k.sy : 0.0;
  return {tsx * k.nx + tsy * k.ny, -tsx * k.ny + tsy * k.nx};
}

// Centre ± half-chord = w is A sin θ + B cos θ = w with A = −b U/c, B = ±R/√c.
std::vector<double> chord_scale_crossings(const SkyFrame& k, double theta_lo, double theta_hi) {
  std::vector<double> crossings;
  for (const double side : {-1.0, 1.0}) {
    const double a_coef = -k.b * k.extent / k.c;
    const double b_coef = side * k.radius / std::sqrt(k.c);
    const double m = math::hypot(a_coef, b_coef);
    const double phase = math::atan2(b_coef, a_coef);
    for (const double w : {-kT, -2.0, 0.0, 2.0, kT}) {
      if (!(std::fabs(w) < m)) continue;
      const double base = math::asin(w / m);
      for (const double theta : {base - phase, kPi - base - phase, base - phase + 2.0 * kPi,
                                 kPi - base - phase - 2.0 * kPi}) {
        if (theta > theta_lo && theta < theta_hi) crossings.push_back(theta);
      }
    }
  }
  return crossings;
}

// To first order in ρ_s, L·N = cos ρ (S·N) + ρ_s (x u·N + y w·N) vanishes on this line.
double sun_disk_horizon(const Vec3& sun, double sun_radius, const SurfaceFrame& f) {
  return -dot(sun, f.normal) / sun_radius;
}

// A point (x, y) of the unit disk is the direction at angle ρ = ρ_s r (r = |(x, y)|) from the
// sun towards u x + w y: L = cos ρ S + (sin ρ/r)(x u + y w), dω = (sin ρ/ρ) ρ_s² dx dy.
Vec3 sun_disk_direction(const Vec3& sun, double sun_radius, const std::array<Vec3, 2>& axes,
                        double x, double y, double& solid_angle_density) {
  const double r = std::sqrt(x * x + y * y);
  const double rho = sun_radius * r;
  const math::SinCos a = math::sincos(rho);
  const double sinc = r > 0.0 ? a.sin / rho : 1.0;
  solid_angle_density = sinc * sun_radius * sun_radius;
  Vec3 l{};
  for (std::size_t i = 0; i < 3; ++i) {
    l[i] = a.cos * sun[i] + sinc * sun_radius * (x * axes[0][i] + y * axes[1][i]);
  }
  return l;
}

namespace {
// {lo, centre, hi} and centre ± lobe·4^j, those in [lo, hi], ascending without repeats.
std::vector<double> breaks_around(double centre, double lo, double hi, double lobe) {
  std::vector<double> b{lo, centre, hi};
  for (double d = lobe; d < hi - lo; d *= 4.0) {
    b.push_back(centre - d);
    b.push_back(centre + d);
  }
  std::sort(b.begin(), b.end());
  std::vector<double> inside;
  for (const double x : b) {
    if (x >= lo && x <= hi && (inside.empty() || x > inside.back())) inside.push_back(x);
  }
  return inside;
}
}  // namespace

// The lobe's peak at (x0, y0) = (sin θ0, η0 cos θ0); the horizon's θ when the line runs along y.
SunDiskBreaks sun_disk_breaks(double x0, double y0, double lobe, double horizon, double un,
                              double wn) {
  SunDiskBreaks b{{}, {}, horizon, un, wn, std::fabs(wn) >= std::fabs(un)};
  const double cos_theta0 = std::sqrt(std::fmax(0.0, 1.0 - x0 * x0));
  const double eta0 = cos_theta0 > 0.0 ? clamp_unit(y0 / cos_theta0) : 0.0;
  for (const double x : breaks_around(x0, -1.0, 1.0, lobe)) b.theta.push_back(math::asin(x));
  b.eta = breaks_around(eta0, -1.0, 1.0, lobe);
  if (!b.horizon_across_x && std::fabs(horizon) < std::fabs(un)) {
    b.theta.push_back(math::asin(horizon / un));
    std::sort(b.theta.begin(), b.theta.end());
  }
  return b;
}

// The line at θ: sin θ (u·N) + η cos θ (w·N) = h.
std::vector<double> sun_disk_eta_breaks(const SunDiskBreaks& b, const math::SinCos& angle) {
  const double eta_h = (b.horizon - b.un * angle.sin) / (b.wn * angle.cos);
  if (!b.horizon_across_x || !(std::fabs(eta_h) < 1.0)) return b.eta;
  std::vector<double> out = b.eta;
  out.insert(std::upper_bound(out.begin(), out.end(), eta_h), eta_h);
  return out;
}

}  // namespace reference_geometry

using namespace reference_geometry;

ScalarEstimate mean_fresnel_reference(const Vec3& view, const SurfaceFrame& f, SlopeVariance s,
                                      const BrdfOptions& options, double relative) {
  require_roughness(s);
  const double vn = dot(view, f.normal);
  if (!(vn > 0.0)) return {fresnel_reflectance(0.0, options.fresnel), 0.0, 0, true};
  const double sx = std::sqrt(2.0 * s.upwind);
  const double sy = std::sqrt(2.0 * s.crosswind);
  // V·ñ = v_n − a·t with a = (s_x v_x, s_y v_y): in the frame u = ê·t, w = ê⊥·t (ê = a/|a|)
  // the visible facets are u < d = v_n/|a|, for every w.
  const double ax = sx * dot(view, f.tangent_x);
  const double ay = sy * dot(view, f.tangent_y);
  const double alpha = std::sqrt(ax * ax + ay * ay);
  const double ex = alpha > 0.0 ? ax / alpha : 1.0;
  const double ey = alpha > 0.0 ? ay / alpha : 0.0;
  const double u_max = alpha > 0.0 ? std::fmin(vn / alpha, kT) : kT;
  const CubatureTolerance<2> outer{relative / 3.0, {0.0, 0.0}};
  // A priori: ∫e^{−|t|²} V·ñ dt = π v_n (1 + Λ_V) (Smith), and 1 − F̄ from the 8-point rule.
  const double visible = kPi * view_terms(view, f, s, options.erfc).smith.visible_area;
  const double transmitted_estimate =
      1.0 - mean_fresnel(view, f, s, hermite_rules().front(), options);
  const CubatureTolerance<2> inner =
      inner_tolerance(outer, u_max + kT, {transmitted_estimate * visible, visible});
  // Channels: the transmitted share (1 − F)·V·ñ and the visible area V·ñ, times e^{−u²} (the
  // inner rule carries e^{−w²}).
  const Estimate<2> r = integrate_adaptive<2>(
      [&](double u) {
        const double projected = vn - alpha * u;
        const double g = math::exp(-u * u) * projected;
        return integrate_line<2>(
            [&](double w) {
              const double zx = sx * (u * ex - w * ey);
              const double zy = sy * (u * ey + w * ex);
              const double cos_vm = projected / std::sqrt(1.0 + zx * zx + zy * zy);
              Estimate<2> e;
              e.value = {g * (1.0 - fresnel_reflectance(cos_vm, options.fresnel)), g};
              return e;
            },
            inner);
      },
      breakpoints_in(-kT, u_max, {}), outer);
  const double transmitted = r.value[0] / r.value[1];
  return {1.0 - transmitted, (r.error[0] + transmitted * r.error[1]) / r.value[1], r.evaluations,
          r.converged};
}

RgbEstimate reflected_sky_reference(const Vec3& view, const SurfaceFrame& f, SlopeVariance s,
                                    const Sky& sky, const BrdfOptions& options, double relative,
                                    const Vec3& absolute) {
  require_roughness(s);
  const ViewTerms v = view_terms(view, f, s, options.erfc);
  if (!(v.cos_theta > 0.0)) return {};
  const SkyFrame k = sky_frame(view, f, s);
  const std::array<double, 2> sun_facet = circumsolar_facet(k, view, f, sky.sun_direction);
  std::vector<double> theta_breaks;
  for (const double u : breakpoints_in(-kT, kT, {sun_facet[0]})) {
    theta_breaks.push_back(math::asin(clamp_unit((u - k.u0) / k.extent)));
  }
  // Where the chord's ends cross the Gaussian's scale lines w ∈ {0, ±2, ±kT}: there the inner
  // integral turns from the whole line to a cut one, steeply when the horizon is far (a grazing
  // view: the chord shrinks from ~R to 0 over a small range of θ). Without these breakpoints a
  // Kronrod rule can straddle that turn with G7 and K15 agreeing on a wrong value (the map
  // found estimates 2× too small at v_n = 0.01).
  const std::vector<double> crossings =
      chord_scale_crossings(k, theta_breaks.front(), theta_breaks.back());
  theta_breaks.insert(theta_breaks.end(), crossings.begin(), crossings.end());
  std::sort(theta_breaks.begin(), theta_breaks.end());
  const CubatureTolerance<3> outer{relative, absolute};
  const CubatureTolerance<3> inner =
      inner_tolerance(outer, theta_breaks.back() - theta_breaks.front(),
                      reflected_sky(view, f, s, sky, hermite_rules().front(), options));
  const Estimate<3> r = integrate_adaptive<3>(
      [&](double theta) {
        const math::SinCos angle = math::sincos(theta);
        const double u = k.u0 + k.extent * angle.sin;
        const auto [centre, half_chord] = sky_frame_chord(k, angle);
        // dt = U cos θ dθ dw; p dζ = e^{−|t|²}/π dt.
        const double g = k.extent * angle.cos / kPi * math::exp(-u * u);
        const auto per_slope = [&](double w) {
          Estimate<3> e;
          const std::array<double, 2> zeta = sky_frame_slope(k, u, w);
          e.value = reflected_sky_per_slope(zeta[0], zeta[1], view, v, f, s, sky, options);
          for (double& x : e.value) x *= g;
          return e;
        };
        const ChordRange chord = chord_in_slope_plane(centre, half_chord);
        if (chord.whole_line) {
          return integrate_line<3>(per_slope, inner);  // outside the chord L·N < 0: zero
        }
        const double lo = chord.lo, hi = chord.hi;
        if (!(hi > lo)) return Estimate<3>{};
        return integrate_adaptive<3>(
            [&](double w) {
              Estimate<3> e = per_slope(w);
              const double gaussian = math::exp(-w * w);
              for (double& x : e.value) x *= gaussian;
              return e;
            },
            breakpoints_in(lo, hi, {sun_facet[1]}), inner);
      },
      theta_breaks, outer);
  return {r.value, r.error, r.evaluations, r.converged};
}

double reflected_sun_bound(const Vec3& sun, double radius, const Vec3& view, const SurfaceFrame& f,
                           SlopeVariance s) {
  require_roughness(s);
  const double vn = dot(view, f.normal);
  if (!(vn > 0.0)) return 0.0;
  Vec3 h{};  // H_S = S + V, unnormalized
  for (std::size_t k = 0; k < 3; ++k) h[k] = sun[k] + view[k];
  const double hn = dot(h, f.normal);
  if (!(hn > radius)) return HUGE_VAL;
  const double zx = dot(h, f.tangent_x) / hn;
  const double zy = dot(h, f.tangent_y) / hn;
  const double shift = radius * std::sqrt(1.0 + zx * zx + zy * zy) / (hn - radius);
  const double distance = std::sqrt(zx * zx / s.upwind + zy * zy / s.crosswind);
  const double nearest =
      std::fmax(0.0, distance - shift / std::sqrt(std::fmin(s.upwind, s.crosswind)));
  const double density =
      math::exp(-0.5 * nearest * nearest) / (2.0 * kPi * std::sqrt(s.upwind * s.crosswind));
  const double cos_half = (hn - radius) / (std::sqrt(dot(h, h)) + radius);
  const double solid_angle = kPi * radius * radius;  // ≥ 2π(1 − cos ρ), without its cancellation
  return solid_angle * density / (4.0 * cos_half * cos_half * cos_half * cos_half * vn);
}

ScalarEstimate reflected_sun_reference(const Vec3& sun, double radius, const Vec3& view,
                                       const SurfaceFrame& f, SlopeVariance s,
                                       const BrdfOptions& options, double relative,
                                       double absolute) {
  require_roughness(s);
  const ViewTerms v = view_terms(view, f, s, options.erfc);
  if (!(v.cos_theta > 0.0)) return {};
  // Far from the glitter the whole disk reflects less than the tolerance.
  const double bound = reflected_sun_bound(sun, radius, view, f, s);
  if (bound <= absolute) return {0.0, bound, 0, true};
  const std::array<Vec3, 2> axes = sun_disk_axes(sun);  // (u, w); clang 15 cannot capture bindings
  const Vec3& u = axes[0];
  const Vec3& w = axes[1];
  // A point (x, y) of the unit disk is the direction at angle ρ = ρ_s r (r = |(x, y)|) from the
  // sun towards u x + w y: L = cos ρ S + (sin ρ/r)(x u + y w), dω = (sin ρ/ρ) ρ_s² dx dy.
  // The specular direction 2(V·N)N − V, where the lobe peaks, or the disk point nearest to it.
  Vec3 mirror{};
  for (std::size_t k = 0; k < 3; ++k) mirror[k] = 2.0 * v.cos_theta * f.normal[k] - view[k];
  const double qx = dot(mirror, u);
  const double qy = dot(mirror, w);
  const double q = std::sqrt(qx * qx + qy * qy);
  const double r0 = std::fmin(math::acos(clamp_unit(dot(mirror, sun))) / radius, 1.0);
  const double x0 = q > 0.0 ? r0 * qx / q : 0.0;
  const double y0 = q > 0.0 ? r0 * qy / q : 0.0;
  // The lobe's width in disk units, ~2σ/ρ_s along the plane of incidence. A lobe narrower than
  // the disk gets breakpoints at geometrically growing distances from its peak, so that no
  // Kronrod rule straddles it unseen (σ² is floored at 1e-10 by the slope budget). Across the
  // plane of incidence the lobe is narrower, 2 v_n σ (ζ moves by |dL_t|/(2 v_n) for a tangential
  // dL): a thin arc at grazing view, which the adaptive rule finds from these breakpoints —
  // checked against brute force along the arc, on and off the sun's azimuth, in the tests. (A
  // variant with breakpoints across the arc's own axes cost more and was no more accurate on
  // the map's sweep.)
  const double lobe = 2.0 * std::sqrt(std::fmin(s.upwind, s.crosswind)) / radius;
  const SunDiskBreaks breaks = sun_disk_breaks(x0, y0, lobe, sun_disk_horizon(sun, radius, f),
                                               dot(u, f.normal), dot(w, f.normal));
  // x = sin θ, y = η cos θ maps [−π/2, π/2] × [−1, 1] onto the disk, dx dy = cos²θ dθ dη.
  const CubatureTolerance<1> outer{relative, {absolute}};
  const CubatureTolerance<1> inner = inner_tolerance(outer, kPi, {0.0});
  const Estimate<1> r = integrate_adaptive<1>(
      [&](double theta) {
        const math::SinCos angle = math::sincos(theta);
        return integrate_adaptive<1>(
            [&](double eta) {
              Estimate<1> e;
              double solid_angle_density = 0.0;
              const Vec3 l = sun_disk_direction(sun, radius, axes, angle.sin, eta * angle.cos,
                                                solid_angle_density);
              e.value[0] = angle.cos * angle.cos * solid_angle_density *
                           ocean_brdf(l, view, v, f, s, options).brdf_cos;
              return e;
            },
            sun_disk_eta_breaks(breaks, angle), inner);
      },
      breaks.theta, outer);
  return {r.value[0], r.error[0], r.evaluations, r.converged};
}

}  // namespace oceanref
