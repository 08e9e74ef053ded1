// One consistent surface (issue 12, point 5): the shading normal is the gradient of the
// rasterized surface, the slope variance the shaded fields do not carry goes to the BRDF's σ²
// (resolved + σ² = the spectrum's moment), the interpolation's variance transfer against a
// brute-force mean over positions, and Hs of the combined footprint height.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>

#include <nlohmann/json.hpp>

#include "core/math.h"
#include "core/quadrature.h"
#include "raster/renderer.h"
#include "scene/scene.h"
#include "waves/slope_budget.h"

using namespace oceanref;
using nlohmann::json;

namespace {

Scene default_scene() {
  return load_scene(std::string(OCEANREF_SOURCE_DIR) + "/reference/scenes/default.json");
}

// Gauss–Legendre nodes and weights on [0, 1] (4 points: exact for degree ≤ 7 per axis, and the
// square of a bicubic interpolant's derivative has degree ≤ 6 per axis within a cell).
struct UnitRule {
  std::vector<double> t, w;
};
UnitRule unit_rule(int order) {
  const QuadratureRule r = gauss_legendre(order);
  UnitRule u;
  for (std::size_t i = 0; i < r.nodes.size(); ++i) {
    u.t.push_back(0.5 * (r.nodes[i] + 1.0));
    u.w.push_back(0.5 * r.weights[i]);
  }
  return u;
}

// The exact mean over one tile (= over uniformly random positions) of a per-point quantity that
// is a polynomial of degree ≤ 7 per axis inside each grid cell: Gauss–Legendre in every cell.
template <class F>
double tile_mean(int cells, double size, const F& quantity) {
  const UnitRule r = unit_rule(4);
  const double spacing = size / cells;
  double sum = 0.0;
  for (int n = 0; n < cells; ++n) {
    for (int m = 0; m < cells; ++m) {
      for (std::size_t j = 0; j < r.t.size(); ++j) {
        for (std::size_t i = 0; i < r.t.size(); ++i) {
          sum += r.w[i] * r.w[j] * quantity((m + r.t[i]) * spacing, (n + r.t[j]) * spacing);
        }
      }
    }
  }
  return sum / (static_cast<double>(cells) * cells);
}

// A unit vector along the wind and across it.
struct WindAxes {
  double ux, uz, cx, cz;
};
WindAxes wind_axes(double phi) {
  const math::SinCos s = math::sincos(phi);
  return {s.cos, s.sin, -s.sin, s.cos};
}

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  double ma = 0.0, mb = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ma += a[i];
    mb += b[i];
  }
  ma /= static_cast<double>(a.size());
  mb /= static_cast<double>(b.size());
  double sab = 0.0, saa = 0.0, sbb = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return sab / std::sqrt(saa * sbb);
}

// Quasi-random points (R2 sequence) in a rectangle.
std::vector<std::array<double, 2>> r2_points(int count, double x0, double z0, double width,
                                             double depth) {
  const double g = 1.32471795724474602596;
  std::vector<std::array<double, 2>> p;
  for (int i = 0; i < count; ++i) {
    p.push_back({x0 + width * std::fmod(0.5 + (i + 1) / g, 1.0),
                 z0 + depth * std::fmod(0.5 + (i + 1) / (g * g), 1.0)});
  }
  return p;
}

}  // namespace

TEST_CASE("interpolation variance transfer: closed forms against the 1-D integral") {
  // V = ∫|a|², W = ∫|a'|², c = Im ∫a'a* for a(t) = Σ_j w_j(t) e^{iθj}, by 200-point
  // Gauss–Legendre (exact: polynomials in t of degree ≤ 6).
  const QuadratureRule r = gauss_legendre(8);
  for (const double theta : {0.0, 0.3, 1.1, 2.0, 2.9, std::numbers::pi, -1.7}) {
    CAPTURE(theta);
    double v = 0.0, w = 0.0, c = 0.0, vl = 0.0, wl = 0.0, cl = 0.0;
    for (std::size_t q = 0; q < r.nodes.size(); ++q) {
      const double t = 0.5 * (r.nodes[q] + 1.0);
      const double weight = 0.5 * r.weights[q];
      const auto wt = catmull_rom_weights(t);
      const auto dt = catmull_rom_weight_derivatives(t);
      Complex a, da;
      for (int j = 0; j < 4; ++j) {
        const Complex e = unit_phasor(theta * (j - 1));
        a += wt[static_cast<std::size_t>(j)] * e;
        da += dt[static_cast<std::size_t>(j)] * e;
      }
      v += weight * (a.re * a.re + a.im * a.im);
      w += weight * (da.re * da.re + da.im * da.im);
      c += weight * (da * conj(a)).im;
      const Complex al = (1.0 - t) * Complex(1.0) + t * unit_phasor(theta);
      const Complex dal = unit_phasor(theta) - Complex(1.0);
      vl += weight * (al.re * al.re + al.im * al.im);
      wl += weight * (dal.re * dal.re + dal.im * dal.im);
      cl += weight * (dal * conj(al)).im;
    }
    const AxisTransfer cr = catmull_rom_axis_transfer(theta);
    CHECK(cr.value == doctest::Approx(v).epsilon(1e-13));
    CHECK(cr.derivative == doctest::Approx(w).epsilon(1e-13).scale(1.0));
    CHECK(cr.cross == doctest::Approx(c).epsilon(1e-13).scale(1.0));
    const AxisTransfer li = linear_axis_transfer(theta);
    CHECK(li.value == doctest::Approx(vl).epsilon(1e-13));
    CHECK(li.derivative == doctest::Approx(wl).epsilon(1e-13).scale(1.0));
    CHECK(li.cross == doctest::Approx(cl).epsilon(1e-13).scale(1.0));
  }
  // Small θ: the exact reading (V → 1, W → θ², c → θ).
  const AxisTransfer small = catmull_rom_axis_transfer(1e-3);
  CHECK(small.value == doctest::Approx(1.0).epsilon(1e-9));
  CHECK(small.derivative == doctest::Approx(1e-6).epsilon(1e-5));
  CHECK(small.cross == doctest::Approx(1e-3).epsilon(1e-5));
}

TEST_CASE(
    "interpolation slope loss: the spectral formula equals the brute-force mean over positions") {
  // One cascade of the default scene's spectrum (not band-partitioned: every grid mode up to
  // the Nyquist lines carries a wave, the worst case for interpolation).
  json j = json::parse(R"({"seed": 7, "time": 3.0,
      "waves": {"spectrum": {"model": "jonswap", "wind_speed": 10, "fetch": 100000,
                             "wind_direction_deg": 80},
                "cascades": {"sizes": [60]}, "resolution": 32, "band_partitioning": false}})");
  const Scene scene = parse_scene(j);
  const Ocean ocean = realize_ocean(scene.waves, 1);
  const CascadeSpectra& c = ocean.cascades[0];
  const std::vector<CascadeFields> fields = synthesize_ocean(ocean, scene.time, 1);
  const CascadeFields& f = fields[0];
  const std::vector<Complex> h = spectrum_at_time(c.low, scene.time);
  const WindAxes w = wind_axes(ocean.spectrum.wind_direction);
  const int n = f.low_resolution;
  const double size = f.size;
  for (const Interpolation mode : {Interpolation::bilinear, Interpolation::bicubic}) {
    CAPTURE(static_cast<int>(mode));
    // Derivative of the interpolated height (the surface normals).
    const auto grad = [&](double x, double z) {
      return sample_periodic_gradient(f.values[0], n, size, x, z, mode);
    };
    const double up = tile_mean(n, size, [&](double x, double z) {
      const GridSample g = grad(x, z);
      const double s = w.ux * g.d_dx + w.uz * g.d_dz;
      return s * s;
    });
    const double across = tile_mean(n, size, [&](double x, double z) {
      const GridSample g = grad(x, z);
      const double s = w.cx * g.d_dx + w.cz * g.d_dz;
      return s * s;
    });
    const SlopeVariance formula = resolved_slope_variance(c.low, h, ocean.spectrum.wind_direction,
                                                          mode, SlopeReading::derivative_of_height);
    // Both are exact: they differ by rounding only.
    CHECK(formula.upwind == doctest::Approx(up).epsilon(1e-10));
    CHECK(formula.crosswind == doctest::Approx(across).epsilon(1e-10));
    // Interpolated spectral slope fields (the high-resolution normals).
    const auto slope = [&](Field q, double x, double z) {
      return sample_periodic_gradient(f.values[static_cast<std::size_t>(q)], f.high_resolution,
                                      size, x, z, mode)
          .value;
    };
    const double up_h = tile_mean(n, size, [&](double x, double z) {
      const double s = w.ux * slope(Field::slope_x, x, z) + w.uz * slope(Field::slope_z, x, z);
      return s * s;
    });
    const SlopeVariance formula_h = resolved_slope_variance(
        c.high, spectrum_at_time(c.high, scene.time), ocean.spectrum.wind_direction, mode,
        SlopeReading::interpolated_slopes);
    CHECK(formula_h.upwind == doctest::Approx(up_h).epsilon(1e-10));
    // And the loss is real: interpolation keeps clearly less than the exact reading.
    const SlopeVariance exact =
        resolved_slope_variance(c.low, h, ocean.spectrum.wind_direction, Interpolation::direct,
                                SlopeReading::derivative_of_height);
    CHECK(formula.upwind < 0.95 * exact.upwind);
    // Random positions (an independent estimate): within 5 standard errors.
    const auto points = r2_points(20000, -37.0, 11.0, 400.0, 300.0);
    double sum = 0.0, sum2 = 0.0;
    for (const auto& p : points) {
      const GridSample g = grad(p[0], p[1]);
      const double s = (w.ux * g.d_dx + w.uz * g.d_dz) * (w.ux * g.d_dx + w.uz * g.d_dz);
      sum += s;
      sum2 += s * s;
    }
    const double mean = sum / static_cast<double>(points.size());
    const double error = std::sqrt((sum2 / static_cast<double>(points.size()) - mean * mean) /
                                   static_cast<double>(points.size()));
    CHECK(std::fabs(mean - formula.upwind) < 5.0 * error);
  }
}

TEST_CASE("the normal of the displaced surface is the cross product of its tangents, upward") {
  // p(x0) = (x0 + uD, η): ∂p/∂x0 = (J_xx, η_x, J_zx), ∂p/∂z0 = (J_xz, η_z, J_zz).
  const auto check = [](double ex, double ez, double jxx, double jxz, double jzx, double jzz) {
    const std::array<double, 3> tx{jxx, ex, jzx}, tz{jxz, ez, jzz};
    std::array<double, 3> c{tz[1] * tx[2] - tz[2] * tx[1], tz[2] * tx[0] - tz[0] * tx[2],
                            tz[0] * tx[1] - tz[1] * tx[0]};
    const double len = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    const double sign = c[1] < 0.0 ? -1.0 : 1.0;
    const auto n = displaced_surface_normal(ex, ez, jxx, jxz, jzx, jzz);
    for (std::size_t i = 0; i < 3; ++i) CHECK(n[i] == doctest::Approx(sign * c[i] / len));
    CHECK(n[1] >= 0.0);
  };
  check(0.3, -0.2, 1.0, 0.0, 0.0, 1.0);    // no displacement: (−η_x, 1, −η_z)/‖·‖
  check(0.3, -0.2, 0.7, 0.15, 0.1, 1.2);   // asymmetric J (interpolated D)
  check(0.3, -0.2, -0.4, 0.2, 0.25, 0.9);  // folded (det J < 0): the sheet seen from above
  const auto flat = displaced_surface_normal(0.3, -0.2, 1.0, 0.0, 0.0, 1.0);
  const auto gamper = surface_normal(0.3, -0.2);
  for (std::size_t i = 0; i < 3; ++i) CHECK(flat[i] == doctest::Approx(gamper[i]));
  // det J = 0: horizontal; no gradient at all: up.
  CHECK(displaced_surface_normal(0.3, 0.0, 0.0, 0.0, 0.0, 1.0)[1] == 0.0);
  CHECK(displaced_surface_normal(0.0, 0.0, 0.0, 0.0, 0.0, 0.0)[1] == 1.0);
}

TEST_CASE("the exact lattice evaluation equals the direct sum at every lattice point") {
  json j = json::parse(R"({"seed": 2, "time": 1.25, "waves": {"resolution": 16,
      "cascades": {"sizes": [50, 19]}, "choppiness": -0.8, "band_partitioning": false}})");
  const Scene scene = parse_scene(j);
  const Ocean ocean = realize_ocean(scene.waves, 1);
  const std::vector<Field> all{Field::height,         Field::slope_x,        Field::slope_z,
                               Field::displacement_x, Field::displacement_z, Field::ddx_dx,
                               Field::ddz_dz,         Field::ddx_dz};
  for (const CascadeSpectra& c : ocean.cascades) {
    const std::vector<Complex> h = spectrum_at_time(c.low, scene.time);
    const LatticeFields l = direct_sum_on_lattice(c.low, h, 12, 50.0 / 12, all, true, 2);
    for (int n = 0; n < 12; ++n) {
      for (int m = 0; m < 12; ++m) {
        const CascadeSurface d = direct_sum_surface(c.low, h, m * 50.0 / 12, n * 50.0 / 12);
        const std::size_t p = static_cast<std::size_t>(n * 12 + m);
        for (const Field f : all) {
          CHECK(l.values[static_cast<std::size_t>(f)][p] ==
                doctest::Approx(d.raw[static_cast<std::size_t>(f)]).scale(1.0).epsilon(1e-12));
        }
        CHECK(l.ddz_dx[p] == doctest::Approx(d.ddz_dx).scale(1.0).epsilon(1e-12));
      }
    }
  }
}

TEST_CASE("default scene: resolved slope variance + the BRDF's sigma^2 = the spectrum's moment") {
  // The identity per wind axis, within 0.1%: the resolved part measured by brute force (the
  // exact mean over every cell of every cascade's shaded height gradient, as the renderer reads
  // it), σ² as the renderer gets it, the moment by adaptive quadrature (relative 1e−10). The
  // cross terms between cascades vanish in the mean over positions (band partitioning: no
  // wavevector in two cascades); a random-position estimate of the combined field checks that.
  const Scene scene = default_scene();
  const Ocean ocean = realize_ocean(scene.waves, 2);
  for (const ShadingNormals normals : {ShadingNormals::surface, ShadingNormals::high_resolution}) {
    CAPTURE(static_cast<int>(normals));
    Scene s = scene;
    s.shading.normals = normals;
    const RenderJob job = scene_render_job(s, ocean, 2);
    const SlopeVarianceBudget b = slope_budget(job, s.waves);
    const SlopeVariance sigma2 = unresolved_slope_variance(job, s.waves);
    CHECK_FALSE(b.clamped);
    const std::vector<CascadeFields> fields = synthesize_ocean(ocean, job.time, 2);
    const WindAxes w = wind_axes(ocean.spectrum.wind_direction);
    double up = 0.0, across = 0.0;
    for (const CascadeFields& f : fields) {
      const bool surface = normals == ShadingNormals::surface;
      const int n = surface ? f.low_resolution : f.high_resolution;
      const auto gradient = [&](double x, double z) {
        if (surface) {
          const GridSample g =
              sample_periodic_gradient(f.values[0], n, f.size, x, z, Interpolation::bicubic);
          return std::array<double, 2>{g.d_dx, g.d_dz};
        }
        return std::array<double, 2>{
            sample_periodic_bicubic(f.values[static_cast<std::size_t>(Field::slope_x)], n, f.size,
                                    x, z),
            sample_periodic_bicubic(f.values[static_cast<std::size_t>(Field::slope_z)], n, f.size,
                                    x, z)};
      };
      up += tile_mean(n, f.size, [&](double x, double z) {
        const auto g = gradient(x, z);
        return (w.ux * g[0] + w.uz * g[1]) * (w.ux * g[0] + w.uz * g[1]);
      });
      across += tile_mean(n, f.size, [&](double x, double z) {
        const auto g = gradient(x, z);
        return (w.cx * g[0] + w.cz * g[1]) * (w.cx * g[0] + w.cz * g[1]);
      });
    }
    const double error_up = (up + sigma2.upwind) / b.moment.upwind - 1.0;
    const double error_across = (across + sigma2.crosswind) / b.moment.crosswind - 1.0;
    MESSAGE("normals " << std::string(normals == ShadingNormals::surface ? "surface"
                                                                         : "high_resolution")
                       << ": moment " << b.moment.upwind << " / " << b.moment.crosswind
                       << ", resolved (brute force) " << up << " / " << across << ", sigma^2 "
                       << sigma2.upwind << " / " << sigma2.crosswind << " = above cut-off "
                       << b.above_cutoff.upwind << " / " << b.above_cutoff.crosswind
                       << " + interpolation loss " << b.interpolation_loss.upwind << " / "
                       << b.interpolation_loss.crosswind << " + sampling " << b.sampling.upwind
                       << " / " << b.sampling.crosswind << "; identity error " << error_up << " / "
                       << error_across);
    CHECK(std::fabs(error_up) < 1e-3);
    CHECK(std::fabs(error_across) < 1e-3);
    // The parts add up, and the loss is a visible share of what the grids carry.
    CHECK(b.above_cutoff.upwind + b.interpolation_loss.upwind + b.sampling.upwind ==
          doctest::Approx(sigma2.upwind).epsilon(1e-9));
    CHECK(b.interpolation_loss.upwind > 0.05 * b.discrete.upwind);
    // The combined field at random positions over a wide area (cross terms included): within
    // 5 standard errors of the per-cascade sum.
    if (normals == ShadingNormals::surface) {
      const auto points = r2_points(100000, -5000.0, -3000.0, 10000.0, 9000.0);
      double sum = 0.0, sum2 = 0.0;
      for (const auto& p : points) {
        const PointFields f =
            combine_surface_at(ocean, fields, {}, p[0], p[1], Interpolation::bicubic);
        const double slope = w.ux * f.raw[1] + w.uz * f.raw[2];
        sum += slope * slope;
        sum2 += slope * slope * slope * slope;
      }
      const double mean = sum / static_cast<double>(points.size());
      const double error = std::sqrt((sum2 / static_cast<double>(points.size()) - mean * mean) /
                                     static_cast<double>(points.size()));
      CHECK(std::fabs(mean - b.resolved.upwind) < 5.0 * error);
    }
  }
}

TEST_CASE("default scene: the shading normal is the gradient of the rasterized surface") {
  // The rasterized surface: p(x0) = (x0 + uD(x0), η(x0)) with η, D as the vertices read them.
  // Its normal by central differences (step 1e−4 m; the bicubic surface is C¹, so the
  // difference quotient converges) against the shading normal, at 3000 points of the view.
  const Scene scene = default_scene();
  const Ocean ocean = realize_ocean(scene.waves, 2);
  const std::vector<CascadeFields> fields = synthesize_ocean(ocean, scene.time, 2);
  for (const ShadingNormals normals : {ShadingNormals::surface, ShadingNormals::high_resolution}) {
    const auto at = [&](double x, double z) {
      return combine_shading_at(ocean, fields, {}, x, z, Interpolation::bicubic, normals);
    };
    const auto position = [&](double x, double z) {
      const PointFields p = at(x, z);
      return std::array<double, 3>{x + p.raw[3], p.height, z + p.raw[4]};
    };
    std::vector<double> shade_x, shade_z, surface_x, surface_z;
    const double d = 1e-4;
    for (const auto& q : r2_points(3000, -60.0, 5.0, 120.0, 150.0)) {
      const auto xp = position(q[0] + d, q[1]), xm = position(q[0] - d, q[1]);
      const auto zp = position(q[0], q[1] + d), zm = position(q[0], q[1] - d);
      std::array<double, 3> tx{}, tz{};
      for (std::size_t i = 0; i < 3; ++i) {
        tx[i] = xp[i] - xm[i];
        tz[i] = zp[i] - zm[i];
      }
      std::array<double, 3> c{tz[1] * tx[2] - tz[2] * tx[1], tz[2] * tx[0] - tz[0] * tx[2],
                              tz[0] * tx[1] - tz[1] * tx[0]};
      const double len =
          (c[1] < 0.0 ? -1.0 : 1.0) * std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
      const PointFields p = at(q[0], q[1]);
      shade_x.push_back(p.normal[0]);
      shade_z.push_back(p.normal[2]);
      surface_x.push_back(c[0] / len);
      surface_z.push_back(c[2] / len);
    }
    const double rx = correlation(shade_x, surface_x);
    const double rz = correlation(shade_z, surface_z);
    MESSAGE("normals " << std::string(normals == ShadingNormals::surface ? "surface"
                                                                         : "high_resolution")
                       << ": correlation of the shading normal with the rasterized surface's "
                          "normal, x "
                       << rx << " (1 - r = " << 1.0 - rx << "), z " << rz
                       << " (1 - r = " << 1.0 - rz << ")");
    if (normals == ShadingNormals::surface) {
      CHECK(rx > 1.0 - 1e-8);  // measured 1 − r = 3e−14 (the difference quotient's error)
      CHECK(rz > 1.0 - 1e-8);
    } else {
      CHECK(rx < 0.9);  // the N_h slopes are not the gradient of the N_l surface
    }
  }
}

namespace {
// m0 of a field over its samples: the mean of (y − ȳ)².
double sample_variance(const std::vector<double>& v) {
  double mean = 0.0;
  for (const double x : v) mean += x;
  mean /= static_cast<double>(v.size());
  double sum = 0.0;
  for (const double x : v) sum += (x - mean) * (x - mean);
  return sum / static_cast<double>(v.size());
}
// The discrete spectrum's m0 at time t: Σ_i Σ_k |h_i(k, t)|² over the N_l patterns (η's bands).
double discrete_m0(const Ocean& ocean, double time) {
  double m0 = 0.0;
  for (const CascadeSpectra& c : ocean.cascades) {
    for (const Complex& h : spectrum_at_time(c.low, time)) m0 += h.re * h.re + h.im * h.im;
  }
  return m0;
}
std::vector<double> heights(const std::vector<PointFields>& p) {
  std::vector<double> v;
  for (const PointFields& f : p) v.push_back(f.height);
  return v;
}
}  // namespace

TEST_CASE("Hs of the combined footprint height (sum.height) agrees with the discrete spectrum") {
  // One cascade: the footprint is its own tile at N_h ≥ N_l points, so Parseval makes the
  // sample m0 equal Σ|h|² up to rounding (1e−12). The bilinear upsampling of the N_l grid that
  // `oceanref fields` used before lost variance (checked below to fail this tolerance).
  json j = json::parse(R"({"seed": 5, "time": 4.0, "waves": {"resolution": 64,
      "low_resolution": 16, "cascades": {"sizes": [300]}, "choppiness": -0.8}})");
  Scene one = parse_scene(j);
  const Ocean single = realize_ocean(one.waves, 2);
  const double m0_single = discrete_m0(single, one.time);
  const std::vector<PointFields> exact =
      combine_on_footprint(single, evolve_ocean(single, one.time), ShadingNormals::surface, 2);
  CHECK(sample_variance(heights(exact)) == doctest::Approx(m0_single).epsilon(1e-12));
  // Bit-identical for any thread count (each point summed alone, in a fixed order).
  for (const int threads : {1, 3}) {
    const std::vector<PointFields> again = combine_on_footprint(
        single, evolve_ocean(single, one.time), ShadingNormals::surface, threads);
    for (std::size_t i = 0; i < exact.size(); ++i) {
      CHECK(again[i].height == exact[i].height);
      CHECK(again[i].normal == exact[i].normal);
      CHECK(again[i].jacobian == exact[i].jacobian);
    }
  }
  const auto grids = synthesize_ocean(single, one.time, 2);
  std::vector<double> bilinear;
  for (int n = 0; n < 64; ++n) {
    for (int m = 0; m < 64; ++m) {
      bilinear.push_back(combine_from_grids(single, grids, m * 300.0 / 64, n * 300.0 / 64).height);
    }
  }
  CHECK(sample_variance(bilinear) < 0.98 * m0_single);
  // The default scene: four cascades on cascade 0's 800 m footprint. Cascades 1–3 do not tile
  // it (golden-ratio sizes), and the cross terms between cascades do not vanish on a finite
  // footprint; both are small because cascade 0 holds most of the energy (measured: 0.011%).
  // Tolerance 0.2% on Hs; the bilinear footprint of before was 6.4% low.
  const Scene scene = default_scene();
  const Ocean ocean = realize_ocean(scene.waves, 2);
  const double m0 = discrete_m0(ocean, scene.time);
  const double hs = 4.0 * std::sqrt(m0);
  for (const ShadingNormals normals : {ShadingNormals::surface, ShadingNormals::high_resolution}) {
    const std::vector<PointFields> sum =
        combine_on_footprint(ocean, evolve_ocean(ocean, scene.time), normals, 2);
    const double hs_fields = 4.0 * std::sqrt(sample_variance(heights(sum)));
    MESSAGE("Hs of sum.height "
            << hs_fields << " m, discrete spectrum " << hs << " m, "
            << "continuous spectrum "
            << spectral_moments(ocean.spectrum, kDefaultMaxWavenumber).significant_wave_height
            << " m");
    CHECK(hs_fields == doctest::Approx(hs).epsilon(2e-3));
  }
  const auto fields = synthesize_ocean(ocean, scene.time, 2);
  const int n = scene.waves.resolution;
  const double spacing = scene.waves.sizes[0] / n;
  std::vector<double> before;
  for (int row = 0; row < n; ++row) {
    for (int m = 0; m < n; ++m) {
      before.push_back(combine_from_grids(ocean, fields, m * spacing, row * spacing).height);
    }
  }
  const double hs_before = 4.0 * std::sqrt(sample_variance(before));
  MESSAGE("Hs of the bilinear footprint (before): " << hs_before << " m");
  CHECK(std::fabs(hs_before / hs - 1.0) > 5e-3);
}

TEST_CASE("shading.normals: scene key, validation, and it changes the image") {
  const json base = json::parse(R"({"seed": 4, "time": 2.0,
      "waves": {"cascades": {"sizes": [120, 35]}, "resolution": 32, "low_resolution": 16,
                "choppiness": -0.7},
      "camera": {"position": [0, 6, 0], "look_at": [0, 1, 50]},
      "grid": {"columns": 96, "rows": 96},
      "atmosphere": {"sun_zenith_deg": 60, "sun_azimuth_deg": 80, "turbidity": 3},
      "shading": {"accuracy": "fast", "sky_order": 3, "sun_order": 1},
      "render": {"width": 48, "height": 27, "samples_per_pixel": 1}})");
  CHECK(parse_scene(base).shading.normals == ShadingNormals::surface);  // the default
  json j = base;
  j["shading"]["normals"] = "high_resolution";
  CHECK(parse_scene(j).shading.normals == ShadingNormals::high_resolution);
  j["shading"]["normals"] = "per_pixel";
  CHECK_THROWS_WITH_AS(parse_scene(j), doctest::Contains("shading.normals: expected surface"),
                       SceneError);
  j["shading"]["normals"] = 1;
  CHECK_THROWS_AS(parse_scene(j), SceneError);
  std::vector<Vec3> images[2];
  SlopeVariance sigma2[2];
  for (int k = 0; k < 2; ++k) {
    json scene_json = base;
    scene_json["shading"]["normals"] = k == 0 ? "surface" : "high_resolution";
    const Scene scene = parse_scene(scene_json);
    const Ocean ocean = realize_ocean(scene.waves, 1);
    const RenderJob job = scene_render_job(scene, ocean, 2);
    sigma2[k] = unresolved_slope_variance(job, scene.waves);
    images[k] = render(job, sigma2[k]).radiance;
  }
  CHECK(images[0] != images[1]);
  CHECK(sigma2[0].upwind > sigma2[1].upwind);  // fewer bands shaded: more left to the BRDF
}

namespace {
// Bitwise equality of doubles (test_support.h's same_bits compares floats).
bool same_double_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}
}  // namespace

TEST_CASE("deformation_at: the deformation and det J of combine_shading_at, bit for bit") {
  // A sample's foam history reads only the deformation of earlier frames, with the grids'
  // stencils kept from the first frame and η not read (and released from the history). Every
  // synthesis (one exemplar point, a tiling's several, the noise blend), both normals, both grid
  // interpolations (60 points) and the direct sum (6), each point's 3 frames read with one
  // FrameStencils.
  const Scene scene = default_scene();
  for (const char* synthesis : {"periodic", "tiling_and_blending", "noise_blended"}) {
    WaveSettings waves = scene.waves;
    if (std::string(synthesis) == "tiling_and_blending") {
      waves = load_scene(std::string(OCEANREF_SOURCE_DIR) +
                         "/reference/scenes/golden/lutz_tiling_and_blending.json")
                  .waves;
    } else if (std::string(synthesis) == "noise_blended") {
      waves = load_scene(std::string(OCEANREF_SOURCE_DIR) +
                         "/reference/scenes/golden/lutz_noise_blended.json")
                  .waves;
    }
    const Ocean ocean = realize_ocean(waves, 2);
    std::vector<std::vector<CascadeFields>> frames;
    std::vector<std::vector<EvolvedCascade>> evolved;
    for (const double t : {0.0, -0.25, -0.5}) {
      frames.push_back(synthesize_ocean(ocean, t, 2));
      evolved.push_back(evolve_ocean(ocean, t));
    }
    for (const ShadingNormals normals :
         {ShadingNormals::surface, ShadingNormals::high_resolution}) {
      // The history as the renderer keeps it: only the deformation's fields.
      std::vector<std::vector<CascadeFields>> kept = frames;
      const std::array<bool, kFieldCount> read = deformation_fields(normals);
      for (auto& frame : kept) {
        for (CascadeFields& c : frame) {
          for (std::size_t q = 0; q < read.size(); ++q) {
            if (!read[q]) c.values[q].clear();
          }
        }
      }
      for (const Interpolation mode :
           {Interpolation::bilinear, Interpolation::bicubic, Interpolation::direct}) {
        CAPTURE(synthesis);
        CAPTURE(static_cast<int>(normals));
        CAPTURE(static_cast<int>(mode));
        std::size_t points_read = 0;
        // The direct sum (no grids: combine_shading_at itself) at fewer points: it is slow.
        const int count = mode == Interpolation::direct ? 6 : 60;
        for (const auto& q : r2_points(count, -60.0, 5.0, 120.0, 150.0)) {
          FrameStencils stencils;
          for (std::size_t f = 0; f < frames.size(); ++f) {
            const PointFields p =
                combine_shading_at(ocean, frames[f], evolved[f], q[0], q[1], mode, normals);
            const SurfaceDeformation d =
                deformation_at(ocean, kept[f], evolved[f], q[0], q[1], mode, normals, stencils);
            CHECK(same_double_bits(d.ddx_dx, p.raw[static_cast<std::size_t>(Field::ddx_dx)]));
            CHECK(same_double_bits(d.ddx_dz, p.raw[static_cast<std::size_t>(Field::ddx_dz)]));
            CHECK(same_double_bits(d.ddz_dz, p.raw[static_cast<std::size_t>(Field::ddz_dz)]));
            CHECK(same_double_bits(d.ddz_dx, p.ddz_dx));
            CHECK(same_double_bits(d.jacobian, p.jacobian));
          }
          points_read = std::max(points_read, stencils.points.size());
          if (mode != Interpolation::direct) {
            // One set of stencils per exemplar point, whatever the number of frames.
            CHECK(stencils.low.size() == stencils.points.size() * ocean.cascades.size());
            CHECK(stencils.high.size() ==
                  (normals == ShadingNormals::high_resolution ? stencils.low.size() : 0));
          }
        }
        if (mode == Interpolation::direct) {
          CHECK(points_read == 0);
        } else if (std::string(synthesis) == "tiling_and_blending") {
          CHECK(points_read >= 2);  // a point between tiles reads several exemplar points
        } else {
          CHECK(points_read == 1);
        }
      }
    }
  }
}
