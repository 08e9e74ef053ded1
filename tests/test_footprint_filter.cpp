// Footprint filtering (issue 20, point 3; waves/footprint_filter.h, raster/footprint.h): each
// filtered level is the Gaussian-filtered spectrum summed exactly (direct summation at the
// level's nodes), the blend's rule, the footprint slope variance table against the sum over
// every mode, V's limits (0 for a point, the whole discrete slope variance for an unbounded
// footprint), the screen-space derivatives of x0 against finite differences, and in a render:
// the setting changes the pixels, any thread count gives the same bits, and at 1 spp the sea is
// closer to the converged integral than the unfiltered 1-spp render.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <nlohmann/json.hpp>

#include "conformance/render_output.h"
#include "raster/footprint.h"
#include "raster/renderer.h"
#include "scene/scene.h"
#include "waves/footprint_filter.h"
#include "waves/ocean.h"
#include "waves/slope_budget.h"

#include "glitter_scene.h"

using namespace oceanref;
using nlohmann::json;

namespace {
// Two cascades, multi-resolution (N_l = 16 < N_h = 32), choppy.
WaveSettings small_waves() {
  WaveSettings w;
  w.seed = 7;
  w.sizes = {100.0, 23.0};
  w.resolution = 32;
  w.low_resolution = 16;
  w.choppiness = {-0.6, -0.6};
  return w;
}

// Σ_k h(k, t)·G(k)·e^{ik·x} of one pattern at (x, z): the height of the filtered pattern, summed
// over the full pattern (not the level's reduced grid).
double filtered_height(const PatternSpectrum& p, double time, double radius, double x, double z) {
  const std::vector<Complex> h = spectrum_at_time(p, time);
  const int n = p.pattern.resolution;
  const double dk = wavenumber_spacing(p.pattern.size);
  double sum = 0.0;
  for (int b = 0; b < n; ++b) {
    for (int a = 0; a < n; ++a) {
      const double kx = wave_index(a, n) * dk, kz = wave_index(b, n) * dk;
      const double g = std::exp(-0.5 * radius * radius * (kx * kx + kz * kz));
      const double phase = kx * x + kz * z;
      const Complex v = h[grid_offset(a, b, n)];
      sum += g * (v.re * std::cos(phase) - v.im * std::sin(phase));
    }
  }
  return sum;
}

json default_scene_reduced(int spp, bool filtering) {
  json s = testing::default_scene_reduced_json(spp);
  if (filtering) s["render"]["footprint_filtering"] = true;
  return s;
}

RenderedScene render_with(const json& s, int threads) {
  RenderOutputOptions options;
  options.threads = threads;
  options.aov = true;
  return render_scene(parse_scene(s), options);
}
}  // namespace

TEST_CASE("footprint filter: the level blend") {
  const std::vector<double> radii{0.0, 0.5, 1.0, 2.0, 4.0};
  CHECK(level_blend(radii, 0.0).level == 0);
  CHECK(level_blend(radii, 0.0).weight == 0.0);
  // Below r_1: linear in r² towards level 1.
  CHECK(level_blend(radii, 0.0625).level == 0);
  CHECK(level_blend(radii, 0.0625).weight == doctest::Approx(0.25).epsilon(1e-15));
  // At a level's radius: that level alone; between two: log2(r/r_l).
  CHECK(level_blend(radii, 1.0).level == 2);
  CHECK(level_blend(radii, 1.0).weight == doctest::Approx(0.0).epsilon(1e-15));
  CHECK(level_blend(radii, 2.0).level == 2);
  CHECK(level_blend(radii, 2.0).weight == doctest::Approx(0.5).epsilon(1e-12));
  // Beyond the last: the last alone.
  CHECK(level_blend(radii, 100.0).level == 4);
  CHECK(level_blend(radii, 100.0).weight == 0.0);
  // The blend's transfer: G at the levels, between them the weighted mean.
  CHECK(blend_transfer(radii, {2, 0.0}, 3.0) == doctest::Approx(std::exp(-4.5)));
  CHECK(blend_transfer(radii, {2, 0.5}, 1.0) ==
        doctest::Approx(0.5 * std::exp(-0.5) + 0.5 * std::exp(-2.0)));
}

TEST_CASE("footprint filter: a mode folds to the half-plane of directions [0, π), k and −k alike") {
  // Every direction in steps of π/4, the wind axis and the axis across it included (a wind
  // direction of 0 puts whole rows of modes on them, exactly).
  for (int i = 0; i < 8; ++i) {
    const double angle = std::numbers::pi / 4.0 * i;
    const double along = i % 2 == 0 ? std::round(2.0 * std::cos(angle)) : 2.0 * std::cos(angle);
    const double across = i % 2 == 0 ? std::round(2.0 * std::sin(angle)) : 2.0 * std::sin(angle);
    const WindFrameWavevector k = folded_wavevector({along, across});
    const WindFrameWavevector opposite = folded_wavevector({-along, -across});
    INFO("direction " << i << "·π/4");
    const double folded_angle = std::atan2(k.across, k.along);
    CHECK(folded_angle >= 0.0);
    CHECK(folded_angle < std::numbers::pi);
    CHECK(k.along == opposite.along);
    CHECK(k.across == opposite.across);
    // The fold keeps k or takes −k: |k| and the line of k unchanged.
    CHECK(std::fabs(k.along) == std::fabs(along));
    CHECK(std::fabs(k.across) == std::fabs(across));
    CHECK(k.along * across == k.across * along);
  }
}

TEST_CASE("footprint filter: the radii double from a quarter of the finest spacing to the size") {
  // One cascade of 100 m on 32²: r_1 = 100/32/4 = 0.78125 m, r_l = r_1·2^{l−1}; the last level
  // is the first with r_L ≥ 100 m, here exactly 100 m (r_8).
  WaveSettings w;
  w.seed = 3;
  w.sizes = {100.0};
  w.resolution = 32;
  w.low_resolution = 32;
  w.choppiness = {-0.5};
  const Ocean ocean = realize_ocean(w, 1);
  const FootprintFilter f =
      make_footprint_filter(ocean, 0.0, Interpolation::bicubic, ShadingNormals::surface, false, 2);
  REQUIRE(f.radii.size() == 9);
  CHECK(f.radii[0] == 0.0);
  for (std::size_t l = 1; l < f.radii.size(); ++l)
    CHECK(f.radii[l] == std::ldexp(0.78125, int(l) - 1));
  CHECK(f.radii.back() == 100.0);
}

TEST_CASE("footprint filter: a footprint on the table's nodes reads that node, in the wind frame") {
  // The documented layout (footprint_filter.h): node (r, q, j) holds λ₁ = r_1²·2^{r−6} (√λ₁ from
  // r_1/8 in ½ octaves), λ₂ = λ₁·4^{q−8} (log2 √(λ₂/λ₁) = q − 8) and the major axis at πj/16 from
  // the wind, at values[(r·9 + q)·16 + j]. A world footprint with those axes, turned by the wind
  // φ, reads that node alone (trilinear weights 0 or 1, to rounding).
  WaveSettings waves = small_waves();
  waves.spectrum.wind_direction = 0.7;
  const Ocean ocean = realize_ocean(waves, 1);
  const FootprintFilter f =
      make_footprint_filter(ocean, 0.4, Interpolation::bicubic, ShadingNormals::surface, false, 1);
  const double r1_squared = f.radii[1] * f.radii[1];
  for (const std::array<int, 3>& node_index :
       {std::array{8, 4, 0}, std::array{8, 4, 3}, std::array{10, 2, 11}, std::array{5, 6, 7}}) {
    // Named copies: clang 14 does not let CAPTURE's lambda see structured bindings.
    const int r = node_index[0], q = node_index[1], j = node_index[2];
    CAPTURE(r);
    CAPTURE(q);
    CAPTURE(j);
    const double major = std::ldexp(r1_squared, r - 6), minor = std::ldexp(major, 2 * (q - 8));
    const double angle = 0.7 + std::numbers::pi * j / 16.0;
    const double c = std::cos(angle), s = std::sin(angle);
    const Footprint fp{major * c * c + minor * s * s, (major - minor) * c * s,
                       major * s * s + minor * c * c};
    const SlopeVariance node = f.variance.values[static_cast<std::size_t>((r * 9 + q) * 16 + j)];
    const SlopeVariance read = footprint_slope_variance(f, fp);
    CHECK(read.upwind == doctest::Approx(node.upwind).epsilon(1e-6));
    CHECK(read.crosswind == doctest::Approx(node.crosswind).epsilon(1e-6));
  }
  // Past the last direction node (j = 15) the half-turn wraps to node 0: halfway between them
  // (j = 15.5) the reading is their mean.
  const auto at = [&](int r, int q, int j) {
    return f.variance.values[static_cast<std::size_t>((r * 9 + q) * 16 + j)];
  };
  const double major = std::ldexp(r1_squared, 2), minor = std::ldexp(major, -8);
  for (const double j : {15.0, 15.5}) {
    CAPTURE(j);
    const double angle = 0.7 + std::numbers::pi * j / 16.0;
    const double c = std::cos(angle), s = std::sin(angle);
    const Footprint fp{major * c * c + minor * s * s, (major - minor) * c * s,
                       major * s * s + minor * c * c};
    const double w = j - 15.0;
    const SlopeVariance read = footprint_slope_variance(f, fp);
    CHECK(read.upwind ==
          doctest::Approx((1.0 - w) * at(8, 4, 15).upwind + w * at(8, 4, 0).upwind).epsilon(1e-6));
    CHECK(read.crosswind ==
          doctest::Approx((1.0 - w) * at(8, 4, 15).crosswind + w * at(8, 4, 0).crosswind)
              .epsilon(1e-6));
  }
}

TEST_CASE("footprint filter: every level is the Gaussian-filtered spectrum, summed exactly") {
  const Ocean ocean = realize_ocean(small_waves(), 1);
  const double time = 1.7;
  const FootprintFilter f =
      make_footprint_filter(ocean, time, Interpolation::bicubic, ShadingNormals::surface, false, 2);
  REQUIRE(f.radii.size() >= 4);
  CHECK(f.radii[0] == 0.0);
  CHECK(f.radii[1] == doctest::Approx(0.25 * 23.0 / 32.0));
  CHECK(f.radii.back() >= 100.0);
  const double bound = height_bound(ocean);
  bool reduced = false;
  for (std::size_t l = 1; l < f.radii.size(); ++l) {
    const FilterLevel& level = f.levels[l - 1];
    for (std::size_t c = 0; c < ocean.cascades.size(); ++c) {
      const CascadeFields& grids = level.grids[c];
      const int n = grids.low_resolution;
      reduced = reduced || n < ocean.cascades[c].low.pattern.resolution;
      const double spacing = grids.size / n;
      // The level's grid has spacing ≤ r/2 (or the pattern's own).
      CHECK((spacing <= 0.5 * f.radii[l] + 1e-12 || n == ocean.cascades[c].low.pattern.resolution));
      double largest = 0.0, worst = 0.0;
      for (const auto& [m, k] : {std::pair{0, 0}, std::pair{1, n / 2}, std::pair{n - 1, 3 % n}}) {
        const double expected =
            filtered_height(ocean.cascades[c].low, time, f.radii[l], m * spacing, k * spacing);
        const double got = grids.values[0][static_cast<std::size_t>(k * n + m)];
        largest = std::max(largest, std::fabs(expected));
        worst = std::max(worst, std::fabs(got - expected));
      }
      // The dropped modes have G < 3e-9 (of at most Σ|h0| together); the rest is rounding.
      CHECK_MESSAGE(worst <= 1e-9 * largest + 3e-9 * bound,
                    "level " << l << ", cascade " << c << ", N " << n << ", r " << f.radii[l]);
    }
  }
  CHECK(reduced);
}

TEST_CASE("footprint filter: V from the table against the sum over every mode, and its limits") {
  const Ocean ocean = realize_ocean(small_waves(), 1);
  const double time = 0.4;
  for (const ShadingNormals normals : {ShadingNormals::surface, ShadingNormals::high_resolution}) {
    const FootprintFilter f =
        make_footprint_filter(ocean, time, Interpolation::bicubic, normals, true, 1);
    // A point: nothing under it.
    const SlopeVariance none = footprint_slope_variance(f, Footprint{});
    CHECK(none.upwind == 0.0);
    CHECK(none.crosswind == 0.0);
    // An unbounded footprint: every slope of the shaded patterns, Σ|h|²(k·ê)² — the slope
    // budget's discrete variance.
    const SlopeVarianceBudget budget =
        slope_variance_budget(ocean, 0.0173, time, Interpolation::bicubic, normals);
    const Footprint huge{1e8, 0.0, 1e8};
    const FootprintResidual residual_all =
        footprint_residual_exact(ocean, time, normals, f.radii, huge);
    const SlopeVariance all = residual_all.slopes;
    CHECK(all.upwind == doctest::Approx(budget.discrete.upwind).epsilon(1e-9));
    CHECK(all.crosswind == doctest::Approx(budget.discrete.crosswind).epsilon(1e-9));
    const SlopeVariance table_all = footprint_slope_variance(f, huge);
    CHECK(table_all.upwind == doctest::Approx(budget.discrete.upwind).epsilon(1e-6));
    // Footprints of every size, elongation (up to 1:300) and direction: the table's bins and
    // trilinear reading within 15% of the exact sum where V is ≥ 0.1% of the total (measured
    // 12.9% and 11.8% for the two normals, at the most elongated footprints: the table has 16
    // directions over π; the BRDF's response to σ² is smooth, so this is a small share of the
    // filter's error against the converged pixel, ACCURACY.md).
    double worst = 0.0, worst_jacobian = 0.0;
    const double total = budget.discrete.upwind + budget.discrete.crosswind;
    for (int i = 0; i < 60; ++i) {
      const double major = 0.3 * std::pow(2.0, 0.37 * i - 8.0);
      const double ratio = std::pow(10.0, -2.5 * ((i * 7) % 11) / 10.0);
      const double angle = 0.61 * i;
      const double c = std::cos(angle), s = std::sin(angle);
      const double a = major * major, b = a * ratio * ratio;
      const Footprint fp{a * c * c + b * s * s, (a - b) * c * s, a * s * s + b * c * c};
      const FootprintResidual residual =
          footprint_residual_exact(ocean, time, normals, f.radii, fp);
      const SlopeVariance& exact = residual.slopes;
      const SlopeVariance table = footprint_slope_variance(f, fp);
      for (const auto& [e, t] :
           {std::pair{exact.upwind, table.upwind}, std::pair{exact.crosswind, table.crosswind}}) {
        if (e < 1e-3 * total) continue;
        worst = std::max(worst, std::fabs(t - e) / e);
      }
      // The displacement gradient's moments, the same bins and reading: their slope-like sums
      // (aaaa + 2aacc + cccc = u²-weighted slope variance) to the same 15%.
      const JacobianMoments je = residual.jacobian, jt = footprint_jacobian_moments(f, fp);
      const double e_sum = je.aaaa + 2.0 * je.aacc + je.cccc;
      const double all_sum = residual_all.jacobian.aaaa + 2.0 * residual_all.jacobian.aacc +
                             residual_all.jacobian.cccc;
      if (e_sum >= 1e-3 * all_sum) {
        worst_jacobian =
            std::max(worst_jacobian, std::fabs(jt.aaaa + 2.0 * jt.aacc + jt.cccc - e_sum) / e_sum);
      }
    }
    MESSAGE("largest relative error of the footprint variance table: "
            << worst << ", Jacobian moments: " << worst_jacobian);
    CHECK(worst < 0.15);
    CHECK(worst_jacobian < 0.15);
    // Every mode's u²-weighted moments under the unbounded footprint: with one choppiness
    // (small_waves) u² times the slope variances (aaaa + aacc along, aacc + cccc across).
    const double u2 = ocean.cascades.front().choppiness * ocean.cascades.front().choppiness;
    CHECK(residual_all.jacobian.aaaa + residual_all.jacobian.aacc ==
          doctest::Approx(u2 * all.upwind).epsilon(1e-12));
    CHECK(residual_all.jacobian.aacc + residual_all.jacobian.cccc ==
          doctest::Approx(u2 * all.crosswind).epsilon(1e-12));
  }
}

TEST_CASE("footprint: the screen-space derivatives of x0 against finite differences") {
  // A triangle seen in perspective: screen vertices with depths, base positions on the sea.
  const std::array<ScreenVertex, 3> screen{ScreenVertex{10.0, 20.0, 5.0},
                                           ScreenVertex{60.0, 25.0, 40.0},
                                           ScreenVertex{30.0, 70.0, 12.0}};
  const std::array<glm::dvec2, 3> base{glm::dvec2{1.0, 2.0}, glm::dvec2{8.0, 30.0},
                                       glm::dvec2{-3.0, 9.0}};
  // The perspective-correct weights at an image point.
  const auto weights = [&](double x, double y) {
    const ScreenVertex &a = screen[0], &b = screen[1], &c = screen[2];
    const double area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
    const std::array<double, 3> l{((b.x - x) * (c.y - y) - (c.x - x) * (b.y - y)) / area,
                                  ((c.x - x) * (a.y - y) - (a.x - x) * (c.y - y)) / area,
                                  ((a.x - x) * (b.y - y) - (b.x - x) * (a.y - y)) / area};
    const double q = l[0] / a.z + l[1] / b.z + l[2] / c.z;
    return std::array<double, 3>{l[0] / a.z / q, l[1] / b.z / q, l[2] / c.z / q};
  };
  const auto x0 = [&](double x, double y) {
    const std::array<double, 3> w = weights(x, y);
    return w[0] * base[0] + w[1] * base[1] + w[2] * base[2];
  };
  const double x = 33.0, y = 38.0, h = 1e-4;
  const BaseDerivatives d = base_derivatives(screen, base, weights(x, y));
  const glm::dvec2 dx = (x0(x + h, y) - x0(x - h, y)) / (2.0 * h);
  const glm::dvec2 dy = (x0(x, y + h) - x0(x, y - h)) / (2.0 * h);
  for (const auto& [got, expected] : {std::pair{d.along_x, dx}, std::pair{d.along_y, dy}}) {
    CHECK(got.x == doctest::Approx(expected.x).epsilon(1e-6));
    CHECK(got.y == doctest::Approx(expected.y).epsilon(1e-6));
  }
  // A cell of side c as a Gaussian: variance c²/12 per axis.
  const Footprint f = sample_footprint({{2.0, 0.0}, {0.0, 3.0}}, 0.5);
  CHECK(f.xx == doctest::Approx(4.0 * 0.25 / 12.0));
  CHECK(f.zz == doctest::Approx(9.0 * 0.25 / 12.0));
  CHECK(f.xz == 0.0);
  // A degenerate triangle has no footprint.
  const std::array<ScreenVertex, 3> flat{ScreenVertex{0.0, 0.0, 1.0}, ScreenVertex{1.0, 1.0, 1.0},
                                         ScreenVertex{2.0, 2.0, 1.0}};
  CHECK(base_derivatives(flat, base, {1.0 / 3, 1.0 / 3, 1.0 / 3}).along_x == glm::dvec2{0.0});
}

TEST_CASE("footprint: a grid vertex's and a sample's cell as the covariance of its parallelogram") {
  // The covariance of x = a·e_u + b·e_v, a and b uniform on [−½, ½], by the two-point Gauss rule
  // in a and b (exact for this quadratic): nodes ±1/(2√3), weights ½.
  const auto covariance = [](glm::dvec2 eu, glm::dvec2 ev) {
    const double n = 0.5 / std::sqrt(3.0);
    double xx = 0.0, xz = 0.0, zz = 0.0;
    for (const double a : {-n, n}) {
      for (const double b : {-n, n}) {
        const glm::dvec2 x = a * eu + b * ev;
        xx += 0.25 * x.x * x.x;
        xz += 0.25 * x.x * x.y;
        zz += 0.25 * x.y * x.y;
      }
    }
    return Footprint{xx, xz, zz};
  };
  const auto same = [](const Footprint& got, const Footprint& want) {
    CHECK(got.xx == doctest::Approx(want.xx).epsilon(1e-12));
    CHECK(got.xz == doctest::Approx(want.xz).epsilon(1e-12));
    CHECK(got.zz == doctest::Approx(want.zz).epsilon(1e-12));
  };
  // A curved grid of 4 × 3 vertices: base(i, j) = (i² + 0.5 j, 2i + 3j² + 0.25 ij).
  ProjectedGrid grid;
  grid.visible = true;
  grid.columns = 4;
  grid.rows = 3;
  const auto base = [](int i, int j) {
    return glm::dvec2{i * i + 0.5 * j, 2.0 * i + 3.0 * j * j + 0.25 * i * j};
  };
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 4; ++i) grid.base.push_back(base(i, j));
  }
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 4; ++i) {
      CAPTURE(i);
      CAPTURE(j);
      // Central differences inside, one-sided at the border.
      const int l = std::max(i - 1, 0), r = std::min(i + 1, 3);
      const int u = std::max(j - 1, 0), d = std::min(j + 1, 2);
      const glm::dvec2 eu = (base(r, j) - base(l, j)) / double(r - l);
      const glm::dvec2 ev = (base(i, d) - base(i, u)) / double(d - u);
      same(grid_vertex_footprint(grid, i, j), covariance(eu, ev));
    }
  }
  // A sample's cell of side c pixels mapped by the screen derivatives (not axis-aligned).
  const BaseDerivatives derivatives{{2.0, 0.7}, {-0.4, 3.0}};
  same(sample_footprint(derivatives, 0.5),
       covariance(0.5 * derivatives.along_x, 0.5 * derivatives.along_y));
}

TEST_CASE("footprint filtering: the setting changes the pixels, not with the thread count") {
  const RenderedScene plain = render_with(default_scene_reduced(1, false), 2);
  const RenderedScene one = render_with(default_scene_reduced(1, true), 1);
  const RenderedScene two = render_with(default_scene_reduced(1, true), 2);
  CHECK(one.pixel_sha256 != plain.pixel_sha256);
  CHECK(one.pixel_sha256 == two.pixel_sha256);
  CHECK(one.radiance_f64_sha256 == two.radiance_f64_sha256);
}

TEST_CASE("footprint filtering at 1 spp: the sea closer to the converged integral") {
  // The default scene at 48×27 (fast lighting) against 256 spp, over pixels fully covered by the
  // sea: the RMS error of the filtered 1-spp render at most half that of the plain 1-spp render
  // (measured 2.6× lower at 160×90: ACCURACY.md), and its energy within 15% (the filter treats
  // slopes under the footprint as Bruneton's visible, masked microfacets where the supersampled
  // image averages them as normals: 12% less reflected light at 160×90, ACCURACY.md).
  const RenderedScene dense = render_with(default_scene_reduced(256, false), 2);
  const RenderedScene plain = render_with(default_scene_reduced(1, false), 2);
  const RenderedScene filtered = render_with(default_scene_reduced(1, true), 2);
  const auto rms = [&](const RenderedScene& r, double& energy) {
    double squares = 0.0, sum = 0.0, reference = 0.0;
    int count = 0;
    for (std::size_t p = 0; p < dense.image.radiance.size(); ++p) {
      if (dense.image.coverage[p] < 1.0) continue;
      for (std::size_t c = 0; c < 3; ++c) {
        const double d = r.image.radiance[p][c] - dense.image.radiance[p][c];
        squares += d * d;
        sum += r.image.radiance[p][c];
        reference += dense.image.radiance[p][c];
      }
      ++count;
    }
    REQUIRE(count > 300);
    energy = sum / reference;
    return std::sqrt(squares / (3.0 * count)) / (reference / (3.0 * count));
  };
  double plain_energy = 0.0, filtered_energy = 0.0;
  const double plain_rms = rms(plain, plain_energy);
  const double filtered_rms = rms(filtered, filtered_energy);
  MESSAGE("sea RMS relative error at 1 spp: plain " << plain_rms << ", filtered " << filtered_rms
                                                    << "; energy " << plain_energy << ", "
                                                    << filtered_energy);
  CHECK(filtered_rms < 0.5 * plain_rms);
  CHECK(std::fabs(filtered_energy - 1.0) < 0.15);
}

TEST_CASE("footprint filter: direct summation of each level equals its grids at their nodes") {
  // Interpolation::direct sums each filtered level's modes (evolve_ocean of the level); the grid
  // modes interpolate the level's FFT grids, which hold the same sums at their nodes. At the
  // origin, a node of every cascade, both read the same fields at any footprint, to rounding.
  const Ocean ocean = realize_ocean(small_waves(), 1);
  const double time = 0.9;
  const double bound = height_bound(ocean);
  for (const ShadingNormals normals : {ShadingNormals::surface, ShadingNormals::high_resolution}) {
    CAPTURE(choice_name(kShadingNormals, normals));
    const FootprintFilter direct =
        make_footprint_filter(ocean, time, Interpolation::direct, normals, false, 2);
    const FootprintFilter grid =
        make_footprint_filter(ocean, time, Interpolation::bicubic, normals, false, 2);
    REQUIRE(direct.radii == grid.radii);
    REQUIRE(direct.levels.size() == grid.levels.size());
    for (const FilterLevel& level : direct.levels) {
      CHECK(level.grids.empty());
      CHECK(level.evolved.size() >= ocean.cascades.size());
    }
    const std::vector<CascadeFields> fields = synthesize_ocean(ocean, time, 1);
    const std::vector<EvolvedCascade> evolved = evolve_ocean(ocean, time);
    for (const double r : {0.1, 0.7, 3.0, 20.0, 400.0}) {
      CAPTURE(r);
      const Footprint f{r * r, 0.3 * r * r, 0.1 * r * r};
      const PointFields a = filtered_fields_at(ocean, {}, evolved, direct, 0.0, 0.0, f,
                                               Interpolation::direct, normals);
      const PointFields b =
          filtered_fields_at(ocean, fields, {}, grid, 0.0, 0.0, f, Interpolation::bicubic, normals);
      CHECK(std::fabs(a.height - b.height) <= 1e-9 * bound);
      // `surface` normals take the slopes and displacement derivatives of the interpolant (a
      // Catmull-Rom derivative at a node is not the spectral one): only the values compare.
      const bool all = normals == ShadingNormals::high_resolution;
      for (std::size_t i = 0; i < kFieldCount; ++i) {
        CAPTURE(i);
        const auto field = static_cast<Field>(i);
        if (!all && field != Field::height && field != Field::displacement_x &&
            field != Field::displacement_z) {
          continue;
        }
        CHECK(std::fabs(a.raw[i] - b.raw[i]) <= 1e-9 * (1.0 + std::fabs(b.raw[i])));
      }
      if (all) CHECK(std::fabs(a.jacobian - b.jacobian) <= 1e-9);
    }
  }
}

TEST_CASE("footprint filter: a footprint between two levels reads their blend, field by field") {
  // level_blend gives the two levels and the weight w of a footprint; every field read is
  // (1 − w)·(finer level's) + w·(coarser level's), each level read alone, and the normal the
  // blend of the two normals made unit again.
  const Ocean ocean = realize_ocean(small_waves(), 1);
  const double time = 0.4;
  const FootprintFilter filter =
      make_footprint_filter(ocean, time, Interpolation::bicubic, ShadingNormals::surface, false, 1);
  REQUIRE(filter.levels.size() >= 3);
  const std::vector<CascadeFields> fields = synthesize_ocean(ocean, time, 1);
  // √λ₁ = r_1·2^1.3: 1.3 octaves above r_1, so levels 2 and 3 with w = 0.3 (to rounding).
  const double r = filter.radii[1] * std::exp2(1.3);
  const Footprint f{r * r, 0.0, 0.25 * r * r};
  const LevelBlend b = level_blend(filter.radii, footprint_major_variance(f));
  REQUIRE(b.level == 2);
  CHECK(b.weight == doctest::Approx(0.3).epsilon(1e-12));
  const double x = 3.7, z = -11.2;
  const auto level = [&](int l) {
    const FilterLevel& at = filter.levels[static_cast<std::size_t>(l) - 1];
    return combine_shading_at(at.ocean, at.grids, at.evolved, x, z, Interpolation::bicubic,
                              ShadingNormals::surface);
  };
  const PointFields fine = level(2), coarse = level(3);
  const PointFields read = filtered_fields_at(ocean, fields, {}, filter, x, z, f,
                                              Interpolation::bicubic, ShadingNormals::surface);
  const double w = b.weight;
  const auto blend = [&](double a, double c) { return (1.0 - w) * a + w * c; };
  for (std::size_t i = 0; i < kFieldCount; ++i) {
    CAPTURE(i);
    CHECK(read.raw[i] == blend(fine.raw[i], coarse.raw[i]));
  }
  // Each checked field differs between the levels, so a swapped or dropped blend shows.
  CHECK(fine.ddz_dx != coarse.ddz_dx);
  CHECK(read.ddz_dx == blend(fine.ddz_dx, coarse.ddz_dx));
  CHECK(fine.height != coarse.height);
  CHECK(read.height == blend(fine.height, coarse.height));
  CHECK(read.slope_x == blend(fine.slope_x, coarse.slope_x));
  CHECK(read.slope_z == blend(fine.slope_z, coarse.slope_z));
  CHECK(fine.jacobian != coarse.jacobian);
  CHECK(read.jacobian == blend(fine.jacobian, coarse.jacobian));
  CHECK(read.foam == blend(fine.foam, coarse.foam));
  std::array<double, 3> n{};
  for (std::size_t c = 0; c < 3; ++c) n[c] = blend(fine.normal[c], coarse.normal[c]);
  const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (std::size_t c = 0; c < 3; ++c) CHECK(read.normal[c] == n[c] / length);
}
