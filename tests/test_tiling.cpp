// Tiling and blending (Lutz, Schoentgen & Gilet 2024; waves/tiling.h) and the autocorrelation of
// the displacement (waves/autocorrelation.h): the triangle grid and its weights against their
// definitions and finite differences; the offsets' statistics; the blended surface continuous,
// its slopes and Jacobian the derivatives of its height and displacement (with and without a
// flow map); its variance that of the exemplar (Lutz eq. 4); the flow map turning the waves; the
// proven bounds of the ray tracer holding; and Lutz's claim (Fig. 8): the periodic ocean's ACF
// is 1 at every multiple of its period, tiling and blending's decays below 0.1 and stays there.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/scene.h"
#include "waves/autocorrelation.h"
#include "waves/noise.h"
#include "waves/ocean.h"
#include "waves/random.h"
#include "waves/surface.h"
#include "waves/tiling.h"

using namespace oceanref;

namespace {
// A 40 m exemplar on 32² (JONSWAP peak near 12 m), choppy, read by bicubic interpolation.
nlohmann::json tiling_scene(const std::string& synthesis, const nlohmann::json& tiling = {}) {
  nlohmann::json s = {{"seed", 7u},
                      {"waves",
                       {{"spectrum", {{"model", "jonswap"}, {"wind_speed", 5}, {"fetch", 20000}}},
                        {"spreading", {{"model", "hasselmann"}, {"swell", 0.9}}},
                        {"cascades", {{"sizes", {40}}}},
                        {"resolution", 32},
                        {"choppiness", -1.0},
                        {"synthesis", synthesis}}}};
  if (!tiling.is_null()) s["waves"]["tiling"] = tiling;
  return s;
}

struct TiledOcean {
  Scene scene;
  Ocean ocean;
  std::vector<CascadeFields> fields;
  DisplacedPoint at(double x, double z) const {
    return displaced_point(ocean, fields, {}, x, z, Interpolation::bicubic,
                           ShadingNormals::surface);
  }
  PointFields fields_at(double x, double z) const {
    return combine_surface_at(ocean, fields, {}, x, z, Interpolation::bicubic);
  }
};

TiledOcean tiled_ocean(const nlohmann::json& document) {
  TiledOcean t{parse_scene(document), {}, {}};
  t.ocean = realize_ocean(t.scene.waves, 2);
  t.fields = synthesize_ocean(t.ocean, 0.0, 2);
  return t;
}

// Uniform points of a square [−side/2, side/2)² (a pure function of i).
std::array<double, 2> point_in(double side, std::uint64_t i) {
  const std::uint64_t key = mix64(0x7465737400ULL + i);
  return {side * (uniform_open(random_word(key, 0)) - 0.5),
          side * (uniform_open(random_word(key, 1)) - 0.5)};
}

double raw(const PointFields& p, Field f) {
  return p.raw[static_cast<std::size_t>(f)];
}
}  // namespace

TEST_CASE("tiling: the triangle grid's barycentrics rebuild the point; gradients exact") {
  for (const double edge : {1.0, 40.0, 1000.0}) {
    for (std::uint64_t i = 0; i < 2000; ++i) {
      const auto [x, z] = point_in(1e4 * edge, i);
      const GridTriangle t = grid_triangle(edge, x, z);
      double sum = 0.0, px = 0.0, pz = 0.0;
      for (std::size_t v = 0; v < 3; ++v) {
        REQUIRE(t.barycentric[v] >= -1e-9);
        REQUIRE(t.barycentric[v] <= 1.0 + 1e-9);
        const std::array<double, 2> c = tile_centre(edge, t.vertices[v]);
        sum += t.barycentric[v];
        px += t.barycentric[v] * c[0];
        pz += t.barycentric[v] * c[1];
      }
      CHECK(sum == doctest::Approx(1.0).epsilon(1e-12));
      // The point from its vertices: to the rounding of coordinates of 1e4 edges.
      CHECK(std::fabs(px - x) < 1e-8 * edge);
      CHECK(std::fabs(pz - z) < 1e-8 * edge);
      // The three vertices are the corners of one equilateral triangle of edge a.
      for (std::size_t v = 0; v < 3; ++v) {
        const std::array<double, 2> a = tile_centre(edge, t.vertices[v]);
        const std::array<double, 2> b = tile_centre(edge, t.vertices[(v + 1) % 3]);
        CHECK(std::hypot(a[0] - b[0], a[1] - b[1]) == doctest::Approx(edge).epsilon(1e-9));
      }
      // ∇b against central differences, inside the triangle.
      const double h = 1e-6 * edge;
      const GridTriangle xp = grid_triangle(edge, x + h, z), xm = grid_triangle(edge, x - h, z);
      const GridTriangle zp = grid_triangle(edge, x, z + h), zm = grid_triangle(edge, x, z - h);
      if (xp.vertices != t.vertices || xm.vertices != t.vertices || zp.vertices != t.vertices ||
          zm.vertices != t.vertices) {
        continue;
      }
      for (std::size_t v = 0; v < 3; ++v) {
        CHECK(std::fabs((xp.barycentric[v] - xm.barycentric[v]) / (2 * h) - t.gradient[v][0]) <
              1e-4 / edge);
        CHECK(std::fabs((zp.barycentric[v] - zm.barycentric[v]) / (2 * h) - t.gradient[v][1]) <
              1e-4 / edge);
      }
    }
  }
}

TEST_CASE("tiling: the weights keep sum w^2 = 1, their gradients are exact and bounded") {
  const double edge = 40.0;
  const Tiling tiling{edge, 40.0, 1, 0.0, {}};
  double largest = 0.0;
  for (std::uint64_t i = 0; i < 20000; ++i) {
    const auto [x, z] = point_in(100.0 * edge, i);
    const GridTriangle t = grid_triangle(edge, x, z);
    const BlendWeights w = variance_preserving_weights(t);
    double squares = 0.0, gradients = 0.0;
    for (std::size_t v = 0; v < 3; ++v) {
      squares += w.weight[v] * w.weight[v];
      gradients += std::hypot(w.gradient[v][0], w.gradient[v][1]);
    }
    CHECK(squares == doctest::Approx(1.0).epsilon(1e-14));
    CHECK(gradients <= blend_weight_gradient_bound(tiling));
    largest = std::max(largest, gradients);
    const double h = 1e-6 * edge;
    const auto weights_at = [&](double px, double pz) {
      const GridTriangle s = grid_triangle(edge, px, pz);
      return s.vertices == t.vertices ? variance_preserving_weights(s).weight
                                      : std::array<double, 3>{NAN, NAN, NAN};
    };
    const auto xp = weights_at(x + h, z), xm = weights_at(x - h, z);
    const auto zp = weights_at(x, z + h), zm = weights_at(x, z - h);
    if (std::isnan(xp[0] + xm[0] + zp[0] + zm[0])) continue;
    for (std::size_t v = 0; v < 3; ++v) {
      CHECK(std::fabs((xp[v] - xm[v]) / (2 * h) - w.gradient[v][0]) < 1e-5 / edge);
      CHECK(std::fabs((zp[v] - zm[v]) / (2 * h) - w.gradient[v][1]) < 1e-5 / edge);
    }
  }
  // The bound 12/a is twice the largest sampled (6/a): not vacuous.
  MESSAGE("largest sum |grad w| = " << largest * edge << "/a; bound 12/a");
  CHECK(largest > 0.45 * blend_weight_gradient_bound(tiling));
}

TEST_CASE("tiling: the offsets are uniform over one period and independent") {
  const double period = 40.0;
  const int n = 40000;
  double sx = 0.0, sz = 0.0, sxx = 0.0, szz = 0.0, sxz = 0.0;
  for (int i = 0; i < n; ++i) {
    const std::array<std::int64_t, 2> vertex{i % 200 - 100, i / 200 - 100};
    const std::array<double, 2> h = tile_offset(11, vertex, period);
    REQUIRE(h[0] > 0.0);
    REQUIRE(h[0] < period);
    REQUIRE(h[1] > 0.0);
    REQUIRE(h[1] < period);
    CHECK(tile_offset(11, vertex, period) == h);  // a pure function
    const double u = h[0] / period - 0.5, v = h[1] / period - 0.5;
    sx += u;
    sz += v;
    sxx += u * u;
    szz += v * v;
    sxz += u * v;
  }
  // Uniform on (−½, ½): mean 0 (σ/√n = 0.0014), variance 1/12 (σ 0.0007), no correlation.
  CHECK(std::fabs(sx / n) < 0.006);
  CHECK(std::fabs(sz / n) < 0.006);
  CHECK(std::fabs(sxx / n - 1.0 / 12.0) < 0.003);
  CHECK(std::fabs(szz / n - 1.0 / 12.0) < 0.003);
  CHECK(std::fabs(sxz / n) < 0.003);
  CHECK(tile_offset(12, {0, 0}, period) != tile_offset(11, {0, 0}, period));
}

TEST_CASE("flow map: the angle between the flow and the wind (Lutz eq. 7)") {
  const double pi = 3.141592653589793;
  FlowMap f;
  CHECK(flow_angle(f, 0.3, 5.0, 6.0) == 0.0);
  f.kind = FlowKind::uniform;
  f.direction = 1.0;
  CHECK(flow_angle(f, 0.25, 5.0, 6.0) == 0.75);
  f.kind = FlowKind::circular;
  f.center_x = 10.0;
  f.center_z = -4.0;
  CHECK(flow_angle(f, 0.0, 11.0, -4.0) == doctest::Approx(pi / 2));  // +x of the centre: +z
  CHECK(flow_angle(f, 0.0, 10.0, -3.0) == doctest::Approx(pi));      // +z of it: −x
  CHECK(flow_angle(f, 0.0, 10.0, -4.0) == 0.0);                      // the centre: the wind
  f.kind = FlowKind::converging;
  CHECK(flow_angle(f, 0.5, 11.0, -4.0) == doctest::Approx(pi - 0.5));
  CHECK(flow_angle(f, 0.0, 10.0, -6.0) == doctest::Approx(pi / 2));
}

TEST_CASE(
    "tiling and blending, noise blend: the exemplar has mean 0; the surface is continuous and its "
    "slopes and Jacobian are the derivatives of its height and displacement") {
  for (const nlohmann::json& document :
       {tiling_scene("tiling_and_blending", {{"tile_size", 2}}),
        tiling_scene("tiling_and_blending",
                     {{"tile_size", 1}, {"flow", "circular"}, {"flow_center", {30, -20}}}),
        tiling_scene("noise_blended")}) {
    CAPTURE(document["waves"].dump());
    const TiledOcean t = tiled_ocean(document);
    const bool tiled = t.ocean.synthesis == Synthesis::tiling_and_blending;
    // Lutz eq. 6 needs the exemplar's mean μ: 0, the spectrum has no k = 0 term.
    for (const CascadeFields& f : t.fields) {
      double sum = 0.0, squares = 0.0;
      for (const double v : f.values[static_cast<std::size_t>(Field::height)]) {
        sum += v;
        squares += v * v;
      }
      CHECK(std::fabs(sum) < 1e-12 * std::sqrt(squares) * f.low_resolution);
    }
    const double edge = tiled ? t.ocean.tiling.edge : 40.0;
    int checked = 0;
    for (std::uint64_t i = 0; i < 400; ++i) {
      const auto [x, z] = point_in(20.0 * edge, i);
      const double h = 1e-5;
      // Skip points within h of a triangle edge (the derivatives jump there).
      if (tiled) {
        const GridTriangle tri = grid_triangle(edge, x, z);
        if (*std::min_element(tri.barycentric.begin(), tri.barycentric.end()) < 1e-3) continue;
      }
      const PointFields p = t.fields_at(x, z);
      const DisplacedPoint c = t.at(x, z);
      // displaced_point: the same bits as the fields' height and displacement.
      CHECK(c.height == p.height);
      CHECK(c.x == x + raw(p, Field::displacement_x));
      CHECK(c.z == z + raw(p, Field::displacement_z));
      const DisplacedPoint xp = t.at(x + h, z), xm = t.at(x - h, z);
      const DisplacedPoint zp = t.at(x, z + h), zm = t.at(x, z - h);
      // Central differences: error ~h²·|f'''| < 1e-8 for these waves (k ≤ 2.5 rad/m).
      const double tolerance = 1e-6;
      CHECK(std::fabs((xp.height - xm.height) / (2 * h) - raw(p, Field::slope_x)) < tolerance);
      CHECK(std::fabs((zp.height - zm.height) / (2 * h) - raw(p, Field::slope_z)) < tolerance);
      CHECK(std::fabs((xp.x - xm.x) / (2 * h) - (1.0 + raw(p, Field::ddx_dx))) < tolerance);
      CHECK(std::fabs((zp.x - zm.x) / (2 * h) - raw(p, Field::ddx_dz)) < tolerance);
      CHECK(std::fabs((xp.z - xm.z) / (2 * h) - p.ddz_dx) < tolerance);
      CHECK(std::fabs((zp.z - zm.z) / (2 * h) - (1.0 + raw(p, Field::ddz_dz))) < tolerance);
      // displaced_point_derivatives (Newton's Jacobian in the surface tracer): the same columns.
      const DisplacedPointDerivatives d =
          displaced_point_derivatives(t.ocean, t.fields, {}, x, z, Interpolation::bicubic);
      const std::array<double, 3> dx{(xp.x - xm.x) / (2 * h), (xp.height - xm.height) / (2 * h),
                                     (xp.z - xm.z) / (2 * h)};
      const std::array<double, 3> dz{(zp.x - zm.x) / (2 * h), (zp.height - zm.height) / (2 * h),
                                     (zp.z - zm.z) / (2 * h)};
      for (std::size_t k = 0; k < 3; ++k) {
        CHECK(std::fabs(d.d_dx0[k] - dx[k]) < tolerance);
        CHECK(std::fabs(d.d_dz0[k] - dz[k]) < tolerance);
      }
      CHECK(d.point.height == c.height);
      ++checked;
    }
    CHECK(checked > 300);
    // Continuity across the triangles' edges: either side of the edge s + t = 1 of a rhombus.
    for (int i = 0; i < (tiled ? 200 : 0); ++i) {
      const double s = 3.0 + 0.004 * i, tt = 1.0 - (s - 3.0) - 7.0;  // s + t integer
      const double sqrt3 = std::sqrt(3.0);
      const double x = edge * (s + 0.5 * tt), z = edge * 0.5 * sqrt3 * tt;
      const DisplacedPoint a = t.at(x - 1e-9, z), b = t.at(x + 1e-9, z);
      CHECK(std::fabs(a.height - b.height) < 1e-7);
      CHECK(std::fabs(a.x - b.x) < 1e-7);
    }
  }
}

TEST_CASE("tiling and blending keeps the exemplar's variance within 1% over a large area") {
  const TiledOcean periodic = tiled_ocean(tiling_scene("periodic"));
  const TiledOcean tiled = tiled_ocean(tiling_scene("tiling_and_blending"));
  const double period = 40.0;
  // The exemplar as the surface reads it (bicubic between the nodes): the mean square over one
  // period, on a lattice 8 times the grid's (the interpolant is a cubic per cell: the lattice
  // mean is within 1e-4 of the integral).
  std::array<double, 3> exemplar{};
  const int lattice = 256;
  for (int j = 0; j < lattice; ++j) {
    for (int i = 0; i < lattice; ++i) {
      const double x = period * (i + 0.5) / lattice, z = period * (j + 0.5) / lattice;
      const DisplacedPoint q = periodic.at(x, z);
      exemplar[0] += (q.x - x) * (q.x - x);
      exemplar[1] += q.height * q.height;
      exemplar[2] += (q.z - z) * (q.z - z);
    }
  }
  for (double& v : exemplar) v /= lattice * lattice;
  // The blend at 400 000 random points of a square of 4000 periods (about 10⁷ tiles): the
  // estimate's relative standard deviation is √(2/n) = 0.22% for Gaussian content.
  std::array<double, 3> blended{}, means{};
  const int n = 400000;
  for (int i = 0; i < n; ++i) {
    const auto [x, z] = point_in(4000.0 * period, static_cast<std::uint64_t>(i));
    const DisplacedPoint q = tiled.at(x, z);
    const std::array<double, 3> v{q.x - x, q.height, q.z - z};
    for (std::size_t c = 0; c < 3; ++c) {
      blended[c] += v[c] * v[c];
      means[c] += v[c];
    }
  }
  for (std::size_t c = 0; c < 3; ++c) {
    blended[c] /= n;
    means[c] /= n;
    CAPTURE(c);
    MESSAGE("component " << c << ": exemplar " << exemplar[c] << " m^2, blended " << blended[c]
                         << " m^2, ratio " << blended[c] / exemplar[c]);
    CHECK(std::fabs(blended[c] / exemplar[c] - 1.0) < 0.01);
    CHECK(std::fabs(means[c]) < 0.01 * std::sqrt(exemplar[c]));
  }
}

TEST_CASE("flow map: a uniform flow at 90 degrees to the wind turns the waves") {
  // Wind along x with swell 0.9: the waves' slopes are mostly along x. A uniform flow along z
  // turns them: the slopes are then mostly along z.
  const auto slope_ratio = [](const nlohmann::json& tiling) {
    const TiledOcean t = tiled_ocean(tiling_scene("tiling_and_blending", tiling));
    double xx = 0.0, zz = 0.0;
    for (std::uint64_t i = 0; i < 20000; ++i) {
      const auto [x, z] = point_in(2000.0, i);
      const PointFields p = t.fields_at(x, z);
      xx += raw(p, Field::slope_x) * raw(p, Field::slope_x);
      zz += raw(p, Field::slope_z) * raw(p, Field::slope_z);
    }
    return xx / zz;
  };
  const double wind = slope_ratio({{"flow", "none"}});
  const double turned = slope_ratio({{"flow", "uniform"}, {"flow_direction_deg", 90}});
  MESSAGE("<slope_x^2>/<slope_z^2>: flow none " << wind << ", flow along z " << turned);
  CHECK(wind > 2.0);
  CHECK(turned < 0.5);
  CHECK(turned * wind == doctest::Approx(1.0).epsilon(0.2));
}

TEST_CASE("tiling and blending, noise blend: the surface stays within its proven bounds") {
  const TiledOcean periodic = tiled_ocean(tiling_scene("periodic"));
  const DisplacedSurfaceBounds e =
      displaced_surface_bounds(periodic.ocean, periodic.fields, {}, Interpolation::bicubic);
  for (const nlohmann::json& document :
       {tiling_scene("tiling_and_blending", {{"tile_size", 2}}),
        tiling_scene("tiling_and_blending",
                     {{"tile_size", 0.5}, {"flow", "converging"}, {"flow_center", {0, 0}}}),
        tiling_scene("noise_blended")}) {
    CAPTURE(document["waves"].dump());
    const TiledOcean t = tiled_ocean(document);
    const DisplacedSurfaceBounds b =
        displaced_surface_bounds(t.ocean, t.fields, {}, Interpolation::bicubic);
    if (t.ocean.synthesis == Synthesis::tiling_and_blending) {
      // The header's bounds from the periodic ocean's (M, L) written out: a tile turned by the
      // flow mixes D_x and D_z (M = √(M_x² + M_z²), L = L_x + L_z); the blend of three tiles
      // gives √3 M and √3 L + (12/a) M, a the tiles' edge.
      const double root3 = std::sqrt(3.0), g = 12.0 / t.ocean.tiling.edge;
      const bool turned = t.ocean.tiling.flow.kind != FlowKind::none;
      const double m = turned ? std::hypot(e.offset[0], e.offset[2]) : e.offset[0];
      const double l = turned ? e.lipschitz[0] + e.lipschitz[2] : e.lipschitz[0];
      CHECK(b.offset[0] == doctest::Approx(root3 * m).epsilon(1e-14));
      CHECK(b.lipschitz[0] == doctest::Approx(root3 * l + g * m).epsilon(1e-14));
      CHECK(b.offset[1] == doctest::Approx(root3 * e.offset[1]).epsilon(1e-14));
      CHECK(b.lipschitz[1] == doctest::Approx(root3 * e.lipschitz[1] + g * e.offset[1]));
      if (turned) CHECK((b.offset[2] == b.offset[0] && b.lipschitz[2] == b.lipschitz[0]));
    }
    std::array<double, 3> largest_slope{}, largest_offset{};
    for (std::uint64_t i = 0; i < 20000; ++i) {
      const auto [x, z] = point_in(400.0, i);
      const auto [dx, dz] = point_in(2.0, i + 1000000);
      const DisplacedPoint p = t.at(x, z), q = t.at(x + dx, z + dz);
      const std::array<double, 3> a{p.x - x, p.height, p.z - z};
      const std::array<double, 3> c{q.x - x - dx, q.height, q.z - z - dz};
      const double distance = std::hypot(dx, dz);
      for (std::size_t k = 0; k < 3; ++k) {
        largest_offset[k] = std::max(largest_offset[k], std::fabs(a[k]));
        largest_slope[k] = std::max(largest_slope[k], std::fabs(a[k] - c[k]) / distance);
      }
    }
    for (std::size_t k = 0; k < 3; ++k) {
      CAPTURE(k);
      MESSAGE("component " << k << ": sampled slope " << largest_slope[k]
                           << " <= " << b.lipschitz[k] << ", offset " << largest_offset[k]
                           << " <= " << b.offset[k]);
      CHECK(largest_slope[k] <= b.lipschitz[k]);
      CHECK(largest_offset[k] <= b.offset[k]);
      CHECK(largest_slope[k] > 0.03 * b.lipschitz[k]);  // not vacuous
    }
  }
}

TEST_CASE(
    "acf: the periodic ocean is 1 at every multiple of its period; tiling and blending "
    "decays below 0.1 and stays there") {
  AutocorrelationSettings s;
  s.lines = 4000;
  s.length = 8.0;
  s.samples_per_period = 8;
  const auto acf = [&](const nlohmann::json& document, int threads) {
    const TiledOcean t = tiled_ocean(document);
    return displacement_autocorrelation(t.ocean, t.fields, {}, Interpolation::bicubic,
                                        ShadingNormals::surface, s, threads);
  };
  const Autocorrelation periodic = acf(tiling_scene("periodic"), 2);
  REQUIRE(periodic.lags.size() == 65);
  CHECK(periodic.period == 40.0);
  for (std::size_t j = 0; j < periodic.lags.size(); j += 8) {
    CHECK(std::fabs(periodic.vector[j] - 1.0) < 1e-9);
    for (const std::vector<double>& c : periodic.components) {
      REQUIRE(c.size() == periodic.lags.size());
      CHECK(std::fabs(c[j] - 1.0) < 1e-9);
    }
  }
  CHECK(periodic.vector[4] < 0.5);  // half a period: not periodic there
  // Tiles of two periods (a = L): beyond the tile's diameter 2a no two points share a tile.
  const Autocorrelation tiled = acf(tiling_scene("tiling_and_blending", {{"tile_size", 2}}), 2);
  double beyond = 0.0;
  for (std::size_t j = 0; j < tiled.lags.size(); ++j) {
    if (tiled.lags[j] >= 2.0 * tiled.period) beyond = std::max(beyond, std::fabs(tiled.vector[j]));
  }
  MESSAGE("tiling and blending: ACF at 1 period " << tiled.vector[8]
                                                  << ", largest |ACF| from 2 "
                                                     "to 8 periods "
                                                  << beyond);
  CHECK(beyond < 0.1);
  CHECK(tiled.vector[8] < 0.5);
  // The estimate is the same for any thread count.
  const Autocorrelation one = acf(tiling_scene("tiling_and_blending", {{"tile_size", 2}}), 1);
  CHECK(one.vector == tiled.vector);
  CHECK(one.components[1] == tiled.components[1]);
}

TEST_CASE("gradient noise: 0 at the lattice, exact gradient, mean square 96835/2081079, bounds") {
  double sum = 0.0, squares = 0.0, largest = 0.0, steepest = 0.0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const auto [x, z] = point_in(400.0, static_cast<std::uint64_t>(i));
    const NoiseSample s = gradient_noise(static_cast<std::uint64_t>(i % 64), x, z);
    sum += s.value;
    squares += s.value * s.value;
    largest = std::max(largest, std::fabs(s.value));
    steepest = std::max(steepest, std::hypot(s.d_dx, s.d_dz));
    if (i % 50 == 0) {
      const double h = 1e-6;
      const std::uint64_t key = static_cast<std::uint64_t>(i % 64);
      CHECK(std::fabs((gradient_noise(key, x + h, z).value - gradient_noise(key, x - h, z).value) /
                          (2 * h) -
                      s.d_dx) < 1e-6);
      CHECK(std::fabs((gradient_noise(key, x, z + h).value - gradient_noise(key, x, z - h).value) /
                          (2 * h) -
                      s.d_dz) < 1e-6);
      CHECK(gradient_noise(key, std::floor(x), std::floor(z)).value == 0.0);
    }
  }
  // 64 keys over 1.6·10⁵ cells: the estimate's relative error ~√(2/n) (0.3%) and the cells'.
  MESSAGE("E[n^2] sampled " << squares / n << ", derived " << kGradientNoiseMeanSquare
                            << "; largest |n| " << largest << ", |grad n| " << steepest);
  CHECK(squares / n == doctest::Approx(kGradientNoiseMeanSquare).epsilon(0.02));
  CHECK(std::fabs(sum / n) < 0.01);
  CHECK(largest <= kGradientNoiseValueBound);
  CHECK(steepest <= kGradientNoiseSlopeBound);
}

TEST_CASE("noise blend (Lutz eq. 2): variance (1-w)^2 + w^2 of the exemplar's, periodic ACF") {
  const TiledOcean periodic = tiled_ocean(tiling_scene("periodic"));
  nlohmann::json document = tiling_scene("noise_blended");
  document["waves"]["noise"] = {{"weight", 0.33}};
  const TiledOcean mixed = tiled_ocean(document);
  // The noise's amplitude: its mean square is the exemplar's time-mean mean square, here at t = 0
  // against the node mean of the exemplar (its spatial mean square at this instant: a few % away).
  std::array<double, 3> exemplar{}, noise{};
  const CascadeFields& f = periodic.fields[0];
  const std::array<Field, 3> kinds{Field::displacement_x, Field::height, Field::displacement_z};
  for (std::size_t c = 0; c < 3; ++c) {
    // Choppiness −1: u² = 1 for D.
    for (const double v : f.values[static_cast<std::size_t>(kinds[c])]) exemplar[c] += v * v;
    exemplar[c] /= static_cast<double>(f.values[0].size());
    noise[c] =
        mixed.ocean.noise.amplitude[c] * mixed.ocean.noise.amplitude[c] * kGradientNoiseMeanSquare;
    MESSAGE("component " << c << ": exemplar mean square " << exemplar[c] << ", noise's "
                         << noise[c]);
    CHECK(noise[c] == doctest::Approx(exemplar[c]).epsilon(0.15));
  }
  AutocorrelationSettings s;
  s.lines = 4000;
  s.length = 4.0;
  s.samples_per_period = 4;
  const Autocorrelation acf = displacement_autocorrelation(
      mixed.ocean, mixed.fields, {}, Interpolation::bicubic, ShadingNormals::surface, s, 2);
  // Cyclostationary: at every period the exemplar part repeats, the noise does not (nearly: its
  // lattice of one period shares a vertex one cell over): ACF ≈ (1−w)²/((1−w)² + w²) = 0.805.
  const double expected = 0.67 * 0.67 / (0.67 * 0.67 + 0.33 * 0.33);
  for (std::size_t j = 4; j < acf.lags.size(); j += 4) {
    CAPTURE(j);
    CHECK(std::fabs(acf.vector[j] - expected) < 0.06);
  }
  MESSAGE("noise blend ACF at 1, 2, 3, 4 periods: " << acf.vector[4] << ", " << acf.vector[8]
                                                    << ", " << acf.vector[12] << ", "
                                                    << acf.vector[16] << "; expected " << expected);
  // The weight reaches the surface: w = 0 is the periodic ocean, bit for bit.
  document["waves"]["noise"] = {{"weight", 0.0}};
  const TiledOcean none = tiled_ocean(document);
  for (std::uint64_t i = 0; i < 100; ++i) {
    const auto [x, z] = point_in(500.0, i);
    CHECK(none.at(x, z).height == periodic.at(x, z).height);
  }
}
