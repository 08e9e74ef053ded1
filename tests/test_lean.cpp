// LEAN mapping (shading/lean.h) against independent computations, and the filtered-shading study
// (conformance/lean_study.h): the moments of one normal by hand; the turned moments (Lutz eq.
// 19–21) against the moments of turned normals; the blended covariance (eq. 13) in its limits;
// the Beckmann lobe a density with the given mean and covariance (quadrature); and the study's
// claims — on a periodic ocean every LEAN form is the footprint's own, with a flow map the
// rotation correction matters (Lutz Fig. 7), normal mapping loses the lobe's width.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "conformance/lean_study.h"
#include "scene/scene.h"
#include "shading/lean.h"
#include "waves/ocean.h"
#include "waves/surface.h"

using namespace oceanref;

namespace {
std::array<double, 3> normal_of_slopes(double sx, double sz) {
  const double l = std::sqrt(sx * sx + 1.0 + sz * sz);
  return {-sx / l, 1.0 / l, -sz / l};
}

LeanMoments mean_moments(const std::vector<std::array<double, 3>>& normals) {
  LeanMoments sum;
  const auto count = static_cast<double>(normals.size());
  for (const auto& n : normals) {
    const LeanMoments m = lean_moments(n);
    for (std::size_t c = 0; c < 2; ++c) sum.b[c] += m.b[c] / count;
    for (std::size_t c = 0; c < 3; ++c) sum.m[c] += m.m[c] / count;
  }
  return sum;
}

const LeanStudyRow& study_row(const std::vector<LeanStudyRow>& rows, const std::string& method,
                              double footprint) {
  for (const LeanStudyRow& r : rows) {
    if (r.method == method && r.footprint == footprint) return r;
  }
  FAIL("no row " << method << " at " << footprint);
  return rows.front();
}

nlohmann::json lean_scene(const nlohmann::json& waves_patch) {
  nlohmann::json s = {{"seed", 3u},
                      {"waves",
                       {{"spectrum", {{"model", "jonswap"}, {"wind_speed", 5}, {"fetch", 20000}}},
                        {"spreading", {{"model", "hasselmann"}, {"swell", 0.9}}},
                        {"cascades", {{"sizes", {40}}}},
                        {"resolution", 32}}},
                      {"shading", {{"accuracy", "fast"}}}};
  s["waves"].merge_patch(waves_patch);
  return s;
}
}  // namespace

TEST_CASE("LEAN moments of one normal (Lutz eq. 9-10) and its covariance (eq. 11-12)") {
  const LeanMoments m = lean_moments(normal_of_slopes(0.3, -0.2));
  CHECK(m.b[0] == doctest::Approx(-0.3).epsilon(1e-15));
  CHECK(m.b[1] == doctest::Approx(0.2).epsilon(1e-15));
  CHECK(m.m[0] == doctest::Approx(0.09).epsilon(1e-15));
  CHECK(m.m[1] == doctest::Approx(0.04).epsilon(1e-15));
  CHECK(m.m[2] == doctest::Approx(-0.06).epsilon(1e-15));
  // One normal has no spread: σ(b, m) = 0; Σ = (1/s)·I.
  const SlopeCovariance c = lean_covariance(m.b, m.m, 0.01);
  CHECK(std::fabs(c.xx - 0.01) < 1e-16);
  CHECK(std::fabs(c.zz - 0.01) < 1e-16);
  CHECK(std::fabs(c.xz) < 1e-16);
}

TEST_CASE("LEAN: turned moments (Lutz eq. 16, 19-21) are the moments of the turned normals") {
  std::vector<std::array<double, 3>> normals;
  for (int i = 0; i < 50; ++i) {
    normals.push_back(normal_of_slopes(0.3 * std::sin(1.7 * i), 0.2 * std::cos(2.3 * i) + 0.05));
  }
  for (const double theta : {0.3, -1.2, 2.5}) {
    const double c = std::cos(theta), s = std::sin(theta);
    std::vector<std::array<double, 3>> turned;
    for (const auto& n : normals)
      turned.push_back({c * n[0] - s * n[2], n[1], s * n[0] + c * n[2]});
    const LeanMoments direct = mean_moments(turned);
    const LeanMoments formula = turned_lean_moments(mean_moments(normals), c, s);
    for (std::size_t k = 0; k < 2; ++k) CHECK(formula.b[k] == doctest::Approx(direct.b[k]));
    for (std::size_t k = 0; k < 3; ++k) {
      CHECK(std::fabs(formula.m[k] - direct.m[k]) < 1e-15);
    }
  }
}

TEST_CASE("LEAN: the blended covariance (Lutz eq. 13) in its limits") {
  const LeanMoments a{{0.1, -0.05}, {0.03, 0.02, 0.004}};
  const LeanMoments b{{-0.02, 0.07}, {0.05, 0.01, -0.002}};
  const LeanMoments mean{{0.0, 0.0}, {0.04, 0.015, 0.001}};
  // One tile of weight 1: its own covariance.
  const SlopeCovariance one = blended_lean_covariance({a, b, b}, {1.0, 0.0, 0.0}, mean, 0.005);
  const SlopeCovariance own = lean_covariance(a.b, a.m, 0.005);
  CHECK(one.xx == doctest::Approx(own.xx));
  CHECK(one.zz == doctest::Approx(own.zz));
  CHECK(one.xz == doctest::Approx(own.xz));
  // Σ w² = 1: the exemplar's mean term cancels.
  const double w = 1.0 / std::sqrt(3.0);
  const SlopeCovariance with = blended_lean_covariance({a, b, a}, {w, w, w}, mean, 0.0);
  const SlopeCovariance without = blended_lean_covariance({a, b, a}, {w, w, w}, LeanMoments{}, 0.0);
  CHECK(with.xx == doctest::Approx(without.xx).epsilon(1e-12));
  CHECK(with.xz == doctest::Approx(without.xz).epsilon(1e-12));
}

TEST_CASE("LEAN: the Beckmann lobe is a density with its mean and covariance") {
  const std::array<double, 2> b{0.05, -0.03};
  const SlopeCovariance s{0.02, 0.008, 0.004};
  double mass = 0.0, mx = 0.0, mz = 0.0, xx = 0.0, zz = 0.0, xz = 0.0;
  const int n = 600;
  const double half = 1.2, d = 2.0 * half / n;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const std::array<double, 2> h{b[0] - half + (i + 0.5) * d, b[1] - half + (j + 0.5) * d};
      const double p = beckmann_slope_density(h, b, s) * d * d;
      mass += p;
      mx += p * h[0];
      mz += p * h[1];
      xx += p * (h[0] - b[0]) * (h[0] - b[0]);
      zz += p * (h[1] - b[1]) * (h[1] - b[1]);
      xz += p * (h[0] - b[0]) * (h[1] - b[1]);
    }
  }
  // The midpoint rule on a Gaussian over ±8σ: accurate far beyond these tolerances.
  CHECK(mass == doctest::Approx(1.0).epsilon(1e-9));
  CHECK(mx == doctest::Approx(b[0]).epsilon(1e-9));
  CHECK(mz == doctest::Approx(b[1]).epsilon(1e-9));
  CHECK(xx == doctest::Approx(s.xx).epsilon(1e-6));
  CHECK(zz == doctest::Approx(s.zz).epsilon(1e-6));
  CHECK(xz == doctest::Approx(s.xz).epsilon(1e-6));
}

TEST_CASE("LEAN study: the exemplar's mean moments (Lutz eq. 13) are the period's averages") {
  // Without choppiness the LEAN moments of the direct sums are the slopes and their products:
  // trigonometric polynomials of degree below 32 (the low band's 32 modes per axis) whose
  // averages over the period any midpoint rule of more than 32 points per axis gives exactly. So
  // μ from its 128 × 128 grid equals the mean over another grid (96 × 96, shifted by a third of
  // a cell) to rounding, and μ_B (a mean slope) is zero to rounding.
  const Scene scene = parse_scene(lean_scene({{"choppiness", 0}}));
  const Ocean ocean = realize_ocean(scene.waves, 2);
  const std::vector<EvolvedCascade> evolved = evolve_ocean(ocean, 3.5);
  const double period = 40.0;
  const LeanMoments mu = exemplar_mean_moments(ocean, {}, evolved, Interpolation::direct, period);
  std::vector<std::array<double, 3>> normals;
  for (int j = 0; j < 96; ++j) {
    for (int i = 0; i < 96; ++i) {
      normals.push_back(combine_surface_at(ocean, {}, evolved, period * (i + 1.0 / 3.0) / 96,
                                           period * (j + 1.0 / 3.0) / 96, Interpolation::direct)
                            .normal);
    }
  }
  const LeanMoments other = mean_moments(normals);
  const double mss = mu.m[0] + mu.m[1];
  MESSAGE("exemplar: mu_B " << mu.b[0] << ", " << mu.b[1] << "; mean square slope " << mss);
  CHECK(mss > 1e-3);
  for (std::size_t c = 0; c < 2; ++c) CHECK(std::fabs(mu.b[c]) < 1e-12 * std::sqrt(mss));
  for (std::size_t c = 0; c < 3; ++c) CHECK(mu.m[c] == doctest::Approx(other.m[c]).epsilon(1e-11));
}

TEST_CASE(
    "LEAN study: the lobe errors are summed over the box centre ± half width, 24 x 24 cells") {
  const std::array<double, 2> centre{0.03, -0.02}, half{0.4, 0.1};
  const std::vector<std::array<double, 2>> grid = lobe_grid(centre, half);
  REQUIRE(grid.size() == 24 * 24);
  // Cell k = 24 j + i has its centre at c + w ((2i + 1)/24 - 1): the cells tile [c - w, c + w].
  double mean_x = 0.0, mean_z = 0.0;
  for (std::size_t k = 0; k < grid.size(); ++k) {
    const double i = static_cast<double>(k % 24), j = static_cast<double>(k / 24);
    CHECK(grid[k][0] == doctest::Approx(centre[0] + half[0] * ((2.0 * i + 1.0) / 24.0 - 1.0)));
    CHECK(grid[k][1] == doctest::Approx(centre[1] + half[1] * ((2.0 * j + 1.0) / 24.0 - 1.0)));
    mean_x += grid[k][0] / 576.0;
    mean_z += grid[k][1] / 576.0;
  }
  // Symmetric about the centre, the outer cells half a cell inside the box.
  CHECK(mean_x == doctest::Approx(centre[0]));
  CHECK(mean_z == doctest::Approx(centre[1]));
  CHECK(grid.front()[0] == doctest::Approx(centre[0] - half[0] * 23.0 / 24.0));
  CHECK(grid.back()[1] == doctest::Approx(centre[1] + half[1] * 23.0 / 24.0));
}

TEST_CASE(
    "LEAN study: periodic, every LEAN form is the footprint's; with a flow map the "
    "rotation correction matters (Lutz Fig. 7)") {
  LeanStudySettings settings;
  settings.footprints = 4;
  settings.samples_per_axis = 24;
  settings.footprint_sizes = {10.0};
  const std::vector<LeanStudyRow> periodic =
      lean_study(parse_scene(lean_scene(nlohmann::json::object())), settings);
  REQUIRE(periodic.size() == 4);
  const double exact = study_row(periodic, "lean_exact", 10.0).lobe_error_mean;
  CHECK(study_row(periodic, "lean", 10.0).lobe_error_mean == doctest::Approx(exact));
  CHECK(study_row(periodic, "lean_corrected", 10.0).lobe_error_mean == doctest::Approx(exact));
  CHECK(study_row(periodic, "normal_mapping", 10.0).lobe_error_mean > 3.0 * exact);
  // Tiled with the waves turned by 60°: uncorrected LEAN keeps the unturned second moments.
  const std::vector<LeanStudyRow> flow = lean_study(
      parse_scene(lean_scene({{"synthesis", "tiling_and_blending"},
                              {"tiling", {{"flow", "uniform"}, {"flow_direction_deg", 60}}}})),
      settings);
  const double corrected = study_row(flow, "lean_corrected", 10.0).lobe_error_mean;
  const double uncorrected = study_row(flow, "lean", 10.0).lobe_error_mean;
  const double normal = study_row(flow, "normal_mapping", 10.0).lobe_error_mean;
  MESSAGE("lobe error with a 60 degree flow: normal mapping " << normal << ", LEAN " << uncorrected
                                                              << ", corrected LEAN " << corrected);
  CHECK(corrected < 0.5 * uncorrected);
  CHECK(uncorrected < normal);
  CHECK(corrected < 0.15);
}
