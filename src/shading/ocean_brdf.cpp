#include "shading/ocean_brdf.h"

#include <cmath>
#include <limits>
#include <numbers>

#include "core/check.h"
#include "core/math.h"
#include "core/quadrature.h"
#include "core/vec3.h"

namespace oceanref {

namespace {
constexpr double kPi = std::numbers::pi;
const double kSqrtPi = std::sqrt(kPi);

// A direction the formulas read as a unit vector (its dot products as cosines); 1e-6 in |d|²
// admits any rounding of a normalization and catches a vector that was never normalized.
bool is_unit(const Vec3& d) {
  return std::fabs(dot(d, d) - 1.0) <= 1e-6;
}
}  // namespace

SurfaceFrame wind_frame(const Vec3& normal, double wind_angle) {
  const Vec3 n = normalize(normal);
  const Vec3 wind{math::cos(wind_angle), 0.0, math::sin(wind_angle)};
  Vec3 tx = combine(1.0, wind, -dot(wind, n), n, 0.0, n);
  if (dot(tx, tx) < 1e-20) tx = combine(1.0, Vec3{0.0, 0.0, 1.0}, -n[2], n, 0.0, n);
  tx = normalize(tx);
  return {n, tx, cross(n, tx)};
}

double slope_density(double zeta_x, double zeta_y, SlopeVariance s) {
  return math::exp(-0.5 * (zeta_x * zeta_x / s.upwind + zeta_y * zeta_y / s.crosswind)) /
         (2.0 * kPi * std::sqrt(s.upwind * s.crosswind));
}

double directional_slope_variance(const Vec3& d, const SurfaceFrame& f, SlopeVariance s) {
  const double a = dot(d, f.tangent_x);
  const double b = dot(d, f.tangent_y);
  const double horizontal = a * a + b * b;
  if (!(horizontal > 0.0))
    return 0.5 * (s.upwind + s.crosswind);  // along N: any azimuth; Λ = 0 there
  return (s.upwind * a * a + s.crosswind * b * b) / horizontal;
}

double rational_erfc(double x) {
  return 2.0 * math::exp(-x * x) / (2.319 * x + std::sqrt(4.0 + 1.52 * x * x));
}

namespace {
// (e^{−ν²} − ν√π erfc ν)/(2√π): Λ·ν, finite at ν = 0.
double lambda_times_nu(double nu, ErfcForm form) {
  const double e = form == ErfcForm::exact ? math::erfc(nu) : rational_erfc(nu);
  return (math::exp(-nu * nu) - nu * kSqrtPi * e) / (2.0 * kSqrtPi);
}
}  // namespace

double smith_lambda(double cos_theta, double sigma2, ErfcForm form) {
  if (!(cos_theta < 1.0)) return 0.0;
  if (!(cos_theta > 0.0)) return std::numeric_limits<double>::infinity();
  const double nu = cos_theta / std::sqrt(2.0 * sigma2 * (1.0 - cos_theta * cos_theta));
  return std::fmax(0.0, lambda_times_nu(nu, form) / nu);
}

SmithTerms smith_terms(double cos_theta, double sigma2, ErfcForm form) {
  if (!(cos_theta < 1.0)) return {0.0, 1.0};
  const double width = std::sqrt(2.0 * sigma2 * (1.0 - cos_theta * cos_theta));
  const double nu = cos_theta / width;
  const double lambda_nu = std::fmax(0.0, lambda_times_nu(nu, form));
  return {lambda_nu / nu, cos_theta + width * lambda_nu};
}

double visible_projected_area(double cos_theta, double sigma2, ErfcForm form) {
  const double c = std::fmin(std::fmax(cos_theta, 0.0), 1.0);
  if (c == 1.0) return 1.0;
  // cos θ·Λ = (cos θ/ν)·(Λν) with cos θ/ν = √(2σ²(1 − cos²θ)).
  const double width = std::sqrt(2.0 * sigma2 * (1.0 - c * c));
  return c + width * std::fmax(0.0, lambda_times_nu(c / width, form));
}

double fresnel_reflectance(double cos_i, FresnelForm form) {
  const double c = std::fmin(std::fmax(cos_i, 0.0), 1.0);
  if (form == FresnelForm::unity) return 1.0;
  if (form == FresnelForm::schlick) {
    const double m = 1.0 - c;
    return 0.02 + 0.98 * m * m * m * m * m;
  }
  const double n = kWaterRefractiveIndex;
  const double sin_t2 = (1.0 - c * c) / (n * n);
  const double cos_t = std::sqrt(1.0 - sin_t2);
  const double rs = (c - n * cos_t) / (c + n * cos_t);
  const double rp = (n * c - cos_t) / (n * c + cos_t);
  return 0.5 * (rs * rs + rp * rp);
}

ViewTerms view_terms(const Vec3& view, const SurfaceFrame& f, SlopeVariance s, ErfcForm form) {
  OCEANREF_EXPECTS(is_unit(view) && is_unit(f.normal), "view and normal are unit vectors");
  OCEANREF_EXPECTS(s.upwind > 0.0 && s.crosswind > 0.0, "slope variances are positive, got " +
                                                            std::to_string(s.upwind) + ", " +
                                                            std::to_string(s.crosswind));
  ViewTerms v;
  v.cos_theta = dot(view, f.normal);
  v.sigma2 = directional_slope_variance(view, f, s);
  if (v.cos_theta > 0.0) v.smith = smith_terms(v.cos_theta, v.sigma2, form);
  return v;
}

BrdfTerms ocean_brdf(const Vec3& light, const Vec3& view, const SurfaceFrame& f, SlopeVariance s,
                     const BrdfOptions& options) {
  return ocean_brdf(light, view, view_terms(view, f, s, options.erfc), f, s, options);
}

BrdfTerms ocean_brdf(const Vec3& light, const Vec3& view, const ViewTerms& v, const SurfaceFrame& f,
                     SlopeVariance s, const BrdfOptions& options) {
  BrdfTerms t{};
  const double zl = dot(light, f.normal);
  const double zv = v.cos_theta;
  if (!(zl > 0.0) || !(zv > 0.0)) return t;
  const Vec3 h = normalize(combine(1.0, light, 1.0, view, 0.0, view));
  const double zh = dot(h, f.normal);
  t.zeta_x = dot(h, f.tangent_x) / zh;
  t.zeta_y = dot(h, f.tangent_y) / zh;
  t.p = slope_density(t.zeta_x, t.zeta_y, s);
  t.sigma2_view = v.sigma2;
  t.sigma2_light = directional_slope_variance(light, f, s);
  t.lambda_view = v.smith.lambda;
  t.lambda_light = smith_lambda(zl, t.sigma2_light, options.erfc);
  t.fresnel = fresnel_reflectance(dot(view, h), options.fresnel);
  // zV(1 + Λ_V + Λ_L) written so that it stays finite as zV → 0.
  const double denominator = v.smith.visible_area + zv * t.lambda_light;
  const double zh2 = zh * zh;
  t.brdf_cos = t.fresnel * t.p / (4.0 * zh2 * zh2 * denominator);
  return t;
}

double reflected_sun(const Vec3& sun, double radius, const Vec3& view, const SurfaceFrame& f,
                     SlopeVariance s, int order, const BrdfOptions& options) {
  return reflected_sun(sun, radius, view, f, s,
                       order > 0 ? gauss_legendre(order) : QuadratureRule{}, options);
}

double reflected_sun(const Vec3& sun, double radius, const Vec3& view, const SurfaceFrame& f,
                     SlopeVariance s, const QuadratureRule& r, const BrdfOptions& options) {
  return reflected_sun(sun_disk_nodes(sun, radius, r), view, f, s, options);
}

std::array<Vec3, 2> sun_disk_axes(const Vec3& sun) {
  const Vec3 u = normalize(std::fabs(sun[1]) < 0.9 ? cross(sun, Vec3{0.0, 1.0, 0.0})
                                                   : cross(sun, Vec3{1.0, 0.0, 0.0}));
  return {u, cross(sun, u)};
}

std::vector<SunDiskNode> sun_disk_nodes(const Vec3& sun, double radius, const QuadratureRule& r) {
  OCEANREF_EXPECTS(is_unit(sun) && radius > 0.0 && r.nodes.size() == r.weights.size(),
                   "a unit sun direction, a positive radius and a rule of nodes and weights");
  if (r.nodes.empty()) return {{sun, 2.0 * kPi * (1.0 - math::cos(radius))}};
  const auto [u, w] = sun_disk_axes(sun);
  const int azimuths = 4 * static_cast<int>(r.nodes.size());
  std::vector<SunDiskNode> nodes;
  for (std::size_t i = 0; i < r.nodes.size(); ++i) {
    const math::SinCos rho = math::sincos(0.5 * radius * (r.nodes[i] + 1.0));  // [−1, 1] → [0, ρ]
    // Polar coordinates: dω = sin ρ dρ dψ; the azimuth is periodic, so the trapezoid rule in ψ
    // is spectrally accurate.
    const double weight = 0.5 * radius * r.weights[i] * rho.sin * (2.0 * kPi / azimuths);
    for (int j = 0; j < azimuths; ++j) {
      const math::SinCos psi = math::sincos(2.0 * kPi * (j + 0.5) / azimuths);
      nodes.push_back({combine(rho.cos, sun, rho.sin * psi.cos, u, rho.sin * psi.sin, w), weight});
    }
  }
  return nodes;
}

double reflected_sun(const std::vector<SunDiskNode>& nodes, const Vec3& view, const SurfaceFrame& f,
                     SlopeVariance s, const BrdfOptions& options) {
  const ViewTerms v = view_terms(view, f, s, options.erfc);
  double sum = 0.0;
  for (const SunDiskNode& node : nodes) {
    sum += node.weight * ocean_brdf(node.direction, view, v, f, s, options).brdf_cos;
  }
  return sum;
}

double mean_fresnel(const Vec3& view, const SurfaceFrame& f, SlopeVariance s, int order,
                    const BrdfOptions& options) {
  return mean_fresnel(view, f, s, gauss_hermite(order), options);
}

double mean_fresnel(const Vec3& view, const SurfaceFrame& f, SlopeVariance s,
                    const QuadratureRule& g, const BrdfOptions& options) {
  OCEANREF_EXPECTS(is_unit(view) && s.upwind >= 0.0 && s.crosswind >= 0.0 && !g.nodes.empty() &&
                       g.nodes.size() == g.weights.size(),
                   "a unit view, slope variances >= 0 and a Gauss-Hermite rule");
  const double vx = dot(view, f.tangent_x);
  const double vy = dot(view, f.tangent_y);
  const double vn = dot(view, f.normal);
  double numerator = 0.0;
  double visible = 0.0;
  for_each_hermite_slope(g, s, [&](double zx, double zy, double w) {
    // Facet normal m ∝ ñ = N − ζ_x T_x − ζ_y T_y; V·ñ its projected area towards V.
    const double projected = vn - zx * vx - zy * vy;
    if (!(projected > 0.0)) return;
    const double weight = w * projected;
    const double cos_vm = projected / std::sqrt(1.0 + zx * zx + zy * zy);
    numerator += weight * fresnel_reflectance(cos_vm, options.fresnel);
    visible += weight;
  });
  return visible > 0.0 ? numerator / visible : fresnel_reflectance(0.0, options.fresnel);
}

double mean_fresnel_fit(const Vec3& view, const SurfaceFrame& f, SlopeVariance s) {
  const double sigma_v = std::sqrt(directional_slope_variance(view, f, s));
  const double cos_v = std::fmax(dot(view, f.normal), 0.0);
  const double fit = math::pow(1.0 - cos_v, 5.0 * math::exp(-2.69 * sigma_v)) /
                     (1.0 + 22.7 * math::pow(sigma_v, 1.5));
  return 0.02 + 0.98 * fit;
}

}  // namespace oceanref
