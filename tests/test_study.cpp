// The measurements in library code (conformance/study.h, conformance/lighting_map.h): checked for
// their numbers, not their timings (timings are never tested).
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <numbers>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "conformance/lighting_map.h"
#include "conformance/study.h"
#include "scene/scene.h"
#include "shading/ocean_brdf.h"
#include "sky/preetham.h"
#include "waves/cascades.h"
#include "waves/ocean.h"

using namespace oceanref;

namespace {
// The comma-separated fields of each line of a bench's output that starts with `prefix`.
std::vector<std::vector<std::string>> bench_rows(const std::string& text,
                                                 const std::string& prefix) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind(prefix, 0) != 0) continue;
    std::istringstream fields(line);
    rows.emplace_back();
    for (std::string f; std::getline(fields, f, ',');) rows.back().push_back(f);
  }
  return rows;
}

Scene study_scene() {
  return load_scene(std::string(OCEANREF_SOURCE_DIR) +
                    "/reference/scenes/golden/mastin_spread_direct_tiny.json");
}
}  // namespace

TEST_CASE("lighting map, quick sweep: reference within tolerance and estimates, fast converging") {
  const LightingMap map = measure_lighting_map(lighting_map_sweep(true), 2);
  // 2 views x 1 azimuth x 2 roughness x 1 normal x 2 suns; F̄ takes the first sun's views.
  CHECK(map.lit_cases == 8);
  CHECK(map.fresnel_cases == 4);
  // Per integral: 3 fast orders and 3 tolerances.
  REQUIRE(map.rows.size() == 18);
  for (const int u : map.truth_unconverged) CHECK(u == 0);
  for (const LightingMapRow& r : map.rows) {
    CAPTURE(r.label);
    CHECK(r.cases == (r.integral == LightingIntegral::fresnel ? 4u : 8u));
    CHECK(r.median <= r.p95);
    CHECK(r.p95 <= r.max);
    if (r.fast) continue;
    // The reference's own error estimate bounds its actual error, and the actual error is
    // within the tolerance's bound, in every case.
    CHECK(r.estimate_violations == 0);
    CHECK(r.tolerance_misses == 0);
    CHECK(r.unconverged == 0);
    CHECK(r.worst_ratio <= 1.0);
    CHECK(r.max <= r.setting);
  }
  // Fast: a higher order is more accurate (largest error over the sweep), per integral.
  for (const LightingIntegral i :
       {LightingIntegral::sky, LightingIntegral::fresnel, LightingIntegral::sun}) {
    double previous = HUGE_VAL;
    for (const LightingMapRow& r : map.rows) {
      if (r.integral != i || !r.fast) continue;
      CHECK(r.max < previous);
      previous = r.max;
    }
  }
  // The outputs: one CSV row per map row, the markdown's summary line counts the cases.
  const std::string csv = lighting_map_csv(map);
  CHECK(static_cast<std::size_t>(std::count(csv.begin(), csv.end(), '\n')) == 1 + 18);
  CHECK(lighting_map_markdown(map).find("Reference error estimates below the actual error "
                                        "(against the truth, allowing the truth's own estimate; "
                                        "every tolerance and integral): 0 of 60") !=
        std::string::npos);
  CHECK(lighting_map_svg(map).rfind("<svg", 0) == 0);
}

TEST_CASE("lighting map: an error is within the tolerance exactly when it is within its bound") {
  // The map's error statistics (lighting_relative_error) and its count of tolerance misses
  // (lighting_tolerance_bound) must read the tolerance the same way: for every integral, truth
  // and value, the relative error is the largest |x − t| over the channels' bounds, times τ.
  const LightingSweep sweep = make_lighting_sweep(lighting_map_sweep(true));
  const LightingSun& sun = sweep.suns[0];
  REQUIRE(sun.sun_floor > 0.0);
  // By hand: F̄ = 0.9 is read relative to 1 − F̄ = 0.1; the sun's reflectance relative to itself
  // above its floor and to the floor below; each sky channel relative to its own floor below it.
  const double tau = 1e-6;
  CHECK(lighting_relative_error(LightingIntegral::fresnel, sun, {0.9 + 1e-8, 0, 0}, {0.9, 0, 0}) ==
        doctest::Approx(1e-7).epsilon(1e-6));
  CHECK(lighting_tolerance_bound(LightingIntegral::fresnel, sun, tau, 0.9, 0) ==
        doctest::Approx(1e-7).epsilon(1e-12));
  CHECK(lighting_tolerance_bound(LightingIntegral::sun, sun, tau, 2.0, 0) == 2.0 * tau);
  CHECK(lighting_tolerance_bound(LightingIntegral::sun, sun, tau, -0.1 * sun.sun_floor, 0) ==
        tau * sun.sun_floor);
  for (std::size_t c = 0; c < 3; ++c) {
    CHECK(lighting_tolerance_bound(LightingIntegral::sky, sun, tau, 0.5 * sun.sky_floor[c], c) ==
          tau * sun.sky_floor[c]);
    CHECK(lighting_tolerance_bound(LightingIntegral::sky, sun, tau, -3.0 * sun.sky_floor[c], c) ==
          tau * (3.0 * sun.sky_floor[c]));
  }
  // The identity over truths above, at and below the floors, F̄ from 0 to near 1, and values
  // off by relative and absolute amounts in one or every channel.
  const double scales[] = {0.0, 0.3, 1.0, 7.0, 1e3};
  for (const LightingIntegral integral :
       {LightingIntegral::sky, LightingIntegral::fresnel, LightingIntegral::sun}) {
    for (const double scale : scales) {
      for (int variant = 0; variant < 4; ++variant) {
        Vec3 t{};
        Vec3 x{};
        for (std::size_t c = 0; c < 3; ++c) {
          const double floor = integral == LightingIntegral::sky   ? sun.sky_floor[c]
                               : integral == LightingIntegral::sun ? sun.sun_floor
                                                                   : 0.1;
          t[c] = integral == LightingIntegral::fresnel ? std::fmin(0.999, 0.1 * scale)
                                                       : scale * floor * (1.0 + 0.2 * double(c));
          const double delta = variant < 2 ? 1e-5 * (std::fabs(t[c]) + floor) : 1e-9 * floor;
          x[c] = t[c] + (variant % 2 == 0 || c == 1 ? delta : -0.5 * delta);
        }
        double expected = 0.0;
        const std::size_t channels = integral == LightingIntegral::sky ? 3 : 1;
        for (std::size_t c = 0; c < channels; ++c) {
          expected = std::fmax(expected, std::fabs(x[c] - t[c]) * tau /
                                             lighting_tolerance_bound(integral, sun, tau, t[c], c));
        }
        CAPTURE(static_cast<int>(integral));
        CAPTURE(scale);
        CAPTURE(variant);
        CHECK(lighting_relative_error(integral, sun, x, t) ==
              doctest::Approx(expected).epsilon(1e-12));
      }
    }
  }
}

TEST_CASE("lighting map plot: every point where its time and error put it, labels apart") {
  // A map written by hand (no timing): per integral two fast orders and two tolerances, times
  // and errors over several decades, one error of 0 (drawn at the floor, 1e-17).
  LightingMap map;
  const LightingIntegral integrals[] = {LightingIntegral::sky, LightingIntegral::fresnel,
                                        LightingIntegral::sun};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 4; ++j) {
      LightingMapRow r;
      r.integral = integrals[i];
      r.fast = j < 2;
      r.label = r.fast ? std::to_string(8 << j) : (j == 2 ? "1e-6" : "1e-9");
      r.seconds = 2e-7 * std::pow(10.0, 0.9 * j + 0.3 * i);
      r.p95 = i == 2 && j == 3 ? 0.0 : std::pow(10.0, -2.0 - 2.5 * j - 0.5 * i);
      if (i == 0 && j == 1) {  // a few pixels from the first: their labels compete for a place
        r.seconds = 1.1 * map.rows[0].seconds;
        r.p95 = 1.3 * map.rows[0].p95;
      }
      r.median = r.p95 / 4.0;
      r.max = r.p95 == 0.0 ? 0.0 : r.p95 * 30.0;
      map.rows.push_back(r);
    }
  }
  const std::string svg = lighting_map_svg(map);
  const auto numbers = [](const std::smatch& m) {
    std::vector<double> v;
    for (std::size_t i = 1; i < m.size(); ++i) v.push_back(std::stod(m[i].str()));
    return v;
  };
  const auto all = [&](const std::regex& re) {
    std::vector<std::vector<double>> found;
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), re); it != std::sregex_iterator();
         ++it) {
      found.push_back(numbers(*it));
    }
    return found;
  };
  const auto panels = all(std::regex(
      R"re(<rect x="([-\d.e]+)" y="([-\d.e]+)" width="([-\d.e]+)" height="([-\d.e]+)" fill="none")re"));
  const auto dots = all(std::regex(R"re(<circle cx="([-\d.e]+)" cy="([-\d.e]+)")re"));
  const auto bars = all(std::regex(
      R"re(<line x1="([-\d.e]+)" y1="([-\d.e]+)" x2="([-\d.e]+)" y2="([-\d.e]+)" stroke="#[0-9a-f]+" stroke-opacity)re"));
  const auto lines =
      all(std::regex(R"re(<polyline points="([-\d.e]+),([-\d.e]+) ([-\d.e]+),([-\d.e]+)")re"));
  REQUIRE(panels.size() == 3);
  REQUIRE(dots.size() == 12);  // in the map's order: per integral, fast, then reference
  REQUIRE(bars.size() == 12);
  REQUIRE(lines.size() == 6);  // one per integral and mode, through its dots
  // Three panels of one size side by side, evenly spaced, apart and inside the picture.
  std::smatch picture;
  REQUIRE(std::regex_search(svg, picture, std::regex(R"re(<svg [^>]*width="([\d.]+)")re")));
  const double picture_width = std::stod(picture[1].str());
  for (std::size_t p = 1; p < 3; ++p) {
    CAPTURE(p);
    for (const std::size_t k : {1u, 2u, 3u}) CHECK(panels[p][k] == panels[0][k]);
    CHECK(panels[p][0] - panels[p - 1][0] == doctest::Approx(panels[1][0] - panels[0][0]));
    CHECK(panels[p][0] > panels[p - 1][0] + panels[p - 1][2]);
  }
  CHECK(panels[0][0] > 0.0);
  CHECK(panels[2][0] + panels[2][2] < picture_width);
  // The axes are shared: x = a + b·log10(t) within a panel, y = c − d·log10(e), d > 0, the same
  // in every panel. Fitted on two dots, checked on all.
  const auto log_error = [](double e) { return std::log10(std::max(e, 1e-17)); };
  const double b = (dots[3][0] - dots[0][0]) /
                   (std::log10(map.rows[3].seconds) - std::log10(map.rows[0].seconds));
  const double d =
      -(dots[3][1] - dots[0][1]) / (log_error(map.rows[3].p95) - log_error(map.rows[0].p95));
  CHECK(b > 0.0);
  CHECK(d > 0.0);
  for (std::size_t i = 0; i < 12; ++i) {
    const LightingMapRow& r = map.rows[i];
    const std::vector<double>& panel = panels[i / 4];
    CAPTURE(i);
    const double a = dots[i / 4 * 4][0] - b * std::log10(map.rows[i / 4 * 4].seconds);
    const double c = dots[0][1] + d * log_error(map.rows[0].p95);
    CHECK(dots[i][0] == doctest::Approx(a + b * std::log10(r.seconds)).epsilon(1e-5));
    CHECK(dots[i][1] == doctest::Approx(c - d * log_error(r.p95)).epsilon(1e-5));
    // The bar from the median to the largest error, at the dot's x.
    CHECK(bars[i][0] == dots[i][0]);
    CHECK(bars[i][2] == dots[i][0]);
    CHECK(bars[i][1] == doctest::Approx(c - d * log_error(r.median)).epsilon(1e-5));
    CHECK(bars[i][3] == doctest::Approx(c - d * log_error(r.max)).epsilon(1e-5));
    // Inside its panel, every point and bar end.
    for (const double y : {dots[i][1], bars[i][1], bars[i][3]}) {
      CHECK(y >= panel[1] - 1e-9);
      CHECK(y <= panel[1] + panel[3] + 1e-9);
    }
    CHECK(dots[i][0] >= panel[0] - 1e-9);
    CHECK(dots[i][0] <= panel[0] + panel[2] + 1e-9);
  }
  for (std::size_t l = 0; l < 6; ++l) {
    CHECK(lines[l][0] == dots[2 * l][0]);
    CHECK(lines[l][1] == dots[2 * l][1]);
    CHECK(lines[l][2] == dots[2 * l + 1][0]);
    CHECK(lines[l][3] == dots[2 * l + 1][1]);
  }
  // The x axis in each panel: its tick labels ("1eN", 11 px type) a line below the panel, its
  // title a line below them, inside the picture.
  std::smatch picture_height;
  REQUIRE(std::regex_search(svg, picture_height, std::regex(R"re(<svg [^>]*height="([\d.]+)")re")));
  const auto x_ticks =
      all(std::regex(R"re(<text x="([-\d.e]+)" y="([-\d.e]+)" text-anchor="middle">1e-?\d+<)re"));
  const auto x_titles = all(std::regex(
      R"re(<text x="([-\d.e]+)" y="([-\d.e]+)" text-anchor="middle">time per integral \[s\]<)re"));
  REQUIRE(x_titles.size() == 3);
  REQUIRE(x_ticks.size() >= 6);
  for (const std::vector<double>& tick : x_ticks) {
    CHECK(tick[1] >= panels[0][1] + panels[0][3] + 11.0);
    for (const std::vector<double>& title : x_titles) CHECK(title[1] >= tick[1] + 11.0);
  }
  for (std::size_t p = 0; p < 3; ++p) {
    CHECK(x_titles[p][0] == doctest::Approx(panels[p][0] + panels[p][2] / 2));
    CHECK(x_titles[p][1] <= std::stod(picture_height[1].str()));
  }
  // The labels (9 px type: at most 5.6 px per character, 10 px tall): each beside a dot, no two
  // overlapping.
  struct Label {
    double x, y, width;
  };
  std::vector<Label> labels;
  const std::regex label_re(
      R"re(<text x="([-\d.e]+)" y="([-\d.e]+)" font-size="9"[^>]*>([^<]*)<)re");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), label_re);
       it != std::sregex_iterator(); ++it) {
    labels.push_back({std::stod((*it)[1].str()), std::stod((*it)[2].str()),
                      5.6 * static_cast<double>((*it)[3].length())});
  }
  REQUIRE(labels.size() >= 6);
  for (std::size_t i = 0; i < labels.size(); ++i) {
    const Label& l = labels[i];
    CHECK(std::any_of(dots.begin(), dots.end(), [&](const std::vector<double>& p) {
      return std::fabs(l.y - p[1]) <= 12.0 && l.x >= p[0] - 8.0 - l.width && l.x <= p[0] + 8.0;
    }));
    for (std::size_t j = 0; j < i; ++j) {
      const Label& o = labels[j];
      const bool apart =
          l.x + l.width <= o.x || o.x + o.width <= l.x || l.y <= o.y - 10.0 || o.y <= l.y - 10.0;
      CHECK(apart);
    }
  }
}

TEST_CASE("lighting pixels: an image against itself has zero error; bad input names the image") {
  ExrImage image;
  image.width = 2;
  image.height = 1;
  for (const char* n :
       {"R", "G", "B", "lighting_error.R", "lighting_error.G", "lighting_error.B"}) {
    image.channels.push_back({n, 1, {1.0f, 2.0f}});
  }
  image.channels.push_back({"coverage", 1, {1.0f, 0.0f}});
  const LightingPixelErrors same = lighting_pixel_errors(image, image);
  CHECK(same.pixels == 2);
  CHECK(same.sea_pixels == 1);
  CHECK(same.difference.max == 0.0);
  CHECK(same.layer.max == 1.0);  // the layer says 1 where the radiance is 1
  ExrImage other = image;
  other.channels[0].values[0] = 1.5f;  // R of the sea pixel, 50% off
  CHECK(lighting_pixel_errors(image, other).difference.max == doctest::Approx(1.0 / 3.0));
  other.width = 1;
  CHECK_THROWS_AS(lighting_pixel_errors(image, other), LightingPixelsInputError);
  ExrImage plain = image;
  plain.channels.pop_back();  // no coverage: not an --aov render
  try {
    lighting_pixel_errors(plain, image);
    FAIL("no error");
  } catch (const LightingPixelsInputError& e) {
    CHECK_FALSE(e.reference);
    CHECK(std::string(e.what()).find("no channel 'coverage'") != std::string::npos);
  }
}

TEST_CASE("study sweeps: every knob ascends toward, and stays below, its most exact setting") {
  // The study measures each setting against the finest one in the same run (ACCURACY.md,
  // "Study"): a sweep out of order, or one that reaches its reference, would mislabel its table.
  const auto ascending = [](const std::vector<int>& v) {
    return !v.empty() && v.front() >= 1 && std::is_sorted(v.begin(), v.end()) &&
           std::adjacent_find(v.begin(), v.end()) == v.end();
  };
  const StudySweeps full = study_sweeps(false, 3), quick = study_sweeps(true, 3);
  for (const StudySweeps& s : {full, quick}) {
    CHECK(ascending(s.fft_resolutions));
    CHECK(ascending(s.cascade_counts));
    CHECK(ascending(s.grid_columns));
    CHECK(ascending(s.axes));
    CHECK(s.grid_columns.back() < s.finest_grid);
    CHECK(s.axes.back() < s.finest_axis);
    CHECK(s.synthesis.threads == 3);
  }
  // The published tables (ACCURACY.md): N 32..256 x 1..4 cascades; grids 64..1024 against 2048²
  // at 320x180; 1..16 spp against 64 at 160x90 on a 512² grid; 5 frames; Gauss-Hermite 64.
  CHECK(full.fft_resolutions == std::vector<int>{32, 64, 128, 256});
  CHECK(full.cascade_counts == std::vector<int>{1, 2, 3, 4});
  CHECK(full.grid_columns == std::vector<int>{64, 128, 256, 512, 1024});
  CHECK(full.finest_grid == 2048);
  CHECK(full.grid_width * 9 == full.grid_height * 16);
  CHECK(full.finest_axis == 8);
  CHECK(full.spp_width == 160);
  CHECK(full.synthesis.frames == 5);
  CHECK(full.synthesis.resolution == SynthesisBenchOptions{}.resolution);
  CHECK(full.lighting_order == 64);
  // The quick sweep: smaller in every dimension.
  CHECK(quick.finest_grid < full.finest_grid);
  CHECK(quick.grid_width * quick.grid_height < full.grid_width * full.grid_height);
  CHECK(quick.spp_width * quick.spp_height < full.spp_width * full.spp_height);
  CHECK(quick.synthesis.resolution < full.synthesis.resolution);
}

TEST_CASE("study: FFT grids equal direct summation at the nodes; interpolation errors ordered") {
  const Scene scene = study_scene();
  const FftVsDirect r = study_fft_vs_direct(scene, 2);
  CHECK(r.points == 8);
  // Fields of O(1) m from a 16² inverse DFT: both sides are sums of the same 256 terms, so they
  // agree to rounding (~1e-15); an index, sign or normalisation error would show as O(0.1).
  CHECK(r.max_abs_difference < 1e-12);
  CHECK(r.fft_seconds_per_frame > 0.0);
  // Per node: the frame's time shared among every cascade's N_h² nodes (two cascades here).
  {
    Scene two = scene;
    two.waves.sizes = {60.0, 21.0};
    two.waves.choppiness = {scene.waves.choppiness[0], scene.waves.choppiness[0]};
    const FftVsDirect t = study_fft_vs_direct(two, 2);
    const double nodes = static_cast<double>(two.waves.resolution) * two.waves.resolution;
    CHECK(t.fft_seconds_per_node == t.fft_seconds_per_frame / (nodes * 2.0));
  }

  const std::vector<InterpolationError> e = interpolation_errors(scene, 2);
  REQUIRE(e.size() == 3);
  CHECK(e[0].mode == "bilinear");
  CHECK(e[1].mode == "bicubic");
  CHECK(e[2].mode == "direct");
  // Direct summation against itself: exact.
  CHECK(e[2].height == 0.0);
  CHECK(e[2].slope == 0.0);
  CHECK(e[2].jacobian == 0.0);
  // Between nodes the grids are approximations: non-zero errors, the bicubic's below the
  // bilinear's for the height (the smoothest field).
  CHECK(e[0].height > 0.0);
  CHECK(e[1].height > 0.0);
  CHECK(e[1].height < e[0].height);
  // The points: (300·frac(i/g), 300·frac(i/g²)), i = 1 … 64, g the real root of g³ = g + 1.
  const std::vector<std::array<double, 2>> points = r2_points(64, 300.0);
  REQUIRE(points.size() == 64);
  const double g = 1.32471795724474602596;
  CHECK(g * g * g == doctest::Approx(g + 1.0).epsilon(1e-15));
  for (const int i : {1, 2, 64}) {
    CAPTURE(i);
    CHECK(points[static_cast<std::size_t>(i - 1)][0] == 300.0 * std::fmod(i / g, 1.0));
    CHECK(points[static_cast<std::size_t>(i - 1)][1] == 300.0 * std::fmod(i / (g * g), 1.0));
  }
  // Each error is the largest over those points of |grid − direct summation|, recomputed here.
  const Ocean ocean = realize_ocean(scene.waves, 2);
  const std::vector<CascadeFields> fields = synthesize_ocean(ocean, scene.time, 2);
  const std::vector<EvolvedCascade> evolved = evolve_ocean(ocean, scene.time);
  for (std::size_t m = 0; m < 2; ++m) {
    CAPTURE(e[m].mode);
    double height = 0.0, slope = 0.0, jacobian = 0.0;
    for (const auto& [x, z] : points) {
      const PointFields p = combine_at(ocean, fields, evolved, x, z, e[m].interpolation);
      const PointFields d = combine_direct(ocean, x, z, scene.time);
      height = std::max(height, std::fabs(p.height - d.height));
      slope = std::max({slope, std::fabs(p.slope_x - d.slope_x), std::fabs(p.slope_z - d.slope_z)});
      jacobian = std::max(jacobian, std::fabs(p.jacobian - d.jacobian));
    }
    CHECK(e[m].height == height);
    CHECK(e[m].slope == slope);
    CHECK(e[m].jacobian == jacobian);
  }

  std::ostringstream out;
  bench_slope_budget(
      out,
      std::string(OCEANREF_SOURCE_DIR) + "/reference/scenes/golden/mastin_spread_direct_tiny.json",
      2);
  // 2 normals x 3 interpolations x 2 axes, each line ending in the budget identity's error
  // (resolved + sigma2 = moment), which must vanish to rounding.
  std::istringstream lines(out.str());
  std::string line;
  std::getline(lines, line);
  int rows = 0;
  while (std::getline(lines, line)) {
    ++rows;
    const double identity_error = std::stod(line.substr(line.rfind(',') + 1));
    CHECK(std::fabs(identity_error) < 1e-12);
  }
  CHECK(rows == 12);
}

TEST_CASE("study 5: whitecap footprints against the nodes' J, recomputed block by block") {
  // The study's folding sea (16 m/s, choppiness −2.5) on the tiny study scene, 32² nodes: J at
  // every node of cascade 0's tile, then per 4×4 footprint its mean, its variance (two-pass), the
  // share below ε = 0.5 and the Gaussian model ½ erfc((μ − ε)/√(2σ²)) (Dupuy & Bruneton),
  // written here with std::erfc. The sums run in another order: agreement to 1e-12.
  Scene scene = study_scene();
  scene.waves.resolution = scene.waves.low_resolution = 32;
  scene.shading.whitecap_threshold = 0.5;
  const WhitecapFootprints w = study_whitecap_footprints(scene, 1);
  WaveSettings stormy = scene.waves;
  stormy.spectrum.wind_speed = 16.0;
  stormy.choppiness.assign(stormy.sizes.size(), -2.5);
  const Ocean ocean = realize_ocean(stormy, 1);
  const std::vector<CascadeFields> fields = synthesize_ocean(ocean, scene.time, 1);
  const int n = 32;
  const double size = stormy.sizes[0];
  std::vector<double> jacobian;
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      jacobian.push_back(combine_from_grids(ocean, fields, x * size / n, y * size / n).jacobian);
    }
  }
  const double eps = 0.5;
  const auto below = [eps](double j) { return j < eps ? 1.0 : 0.0; };
  double total_share = 0.0;
  for (const double j : jacobian) total_share += below(j);
  total_share /= static_cast<double>(jacobian.size());
  double difference = 0.0, largest = 0.0;
  for (int by = 0; by < n; by += 4) {
    for (int bx = 0; bx < n; bx += 4) {
      std::vector<double> block;
      for (int y = by; y < by + 4; ++y) {
        for (int x = bx; x < bx + 4; ++x) block.push_back(jacobian[std::size_t(y * n + x)]);
      }
      double mean = 0.0, variance = 0.0, share = 0.0;
      for (const double j : block) mean += j;
      mean /= 16.0;
      for (const double j : block) {
        variance += (j - mean) * (j - mean);
        share += below(j);
      }
      variance /= 16.0;
      share /= 16.0;
      const double gauss = variance > 0.0
                               ? 0.5 * std::erfc((mean - eps) / std::sqrt(2.0 * variance))
                               : (mean < eps ? 1.0 : 0.0);
      difference += std::fabs(gauss - share);
      largest = std::max(largest, std::fabs(gauss - share));
    }
  }
  CHECK(w.footprints == 64);
  // The sea folds in places, not everywhere: the shares and distances are not trivial.
  CHECK(total_share > 0.0);
  CHECK(total_share < 0.5);
  CHECK(w.mean_coverage == doctest::Approx(total_share).epsilon(1e-12));
  CHECK(w.mean_abs_difference == doctest::Approx(difference / 64.0).epsilon(1e-9));
  CHECK(w.max_abs_difference == doctest::Approx(largest).epsilon(1e-9));
  CHECK(largest > 0.0);
}

TEST_CASE("bench synthesis: the bilinear lookup's errors are |grid - direct| at its 64 points") {
  SynthesisBenchOptions options;
  options.cascades = 2;
  options.resolution = 32;
  options.frames = 1;
  options.threads = 1;
  std::ostringstream out;
  bench_synthesis(out, options);
  // The rows "bilinear,<field>,<max |direct|>,<max |bilinear - direct|>", read back.
  std::map<std::string, std::array<double, 2>> printed;
  for (const std::vector<std::string>& f : bench_rows(out.str(), "bilinear,")) {
    REQUIRE(f.size() == 4);
    printed[f[1]] = {std::stod(f[2]), std::stod(f[3])};
  }
  REQUIRE(printed.size() == 3);
  // The bench's ocean (JONSWAP 10 m/s, sizes 1000·(1−1/φ)^i m, seed 1) at t = 10 s, recomputed
  // here point by point: the printed 17 digits read back to the same doubles.
  WaveSettings w;
  w.seed = options.seed;
  w.sizes = golden_ratio_sizes(1000.0, options.cascades, GoldenFactor::small);
  w.resolution = w.low_resolution = options.resolution;
  w.choppiness.assign(w.sizes.size(), -1.0);
  const Ocean ocean = realize_ocean(w, 1);
  const std::vector<CascadeFields> grids = synthesize_ocean(ocean, 10.0, 1);
  const std::vector<EvolvedCascade> evolved = evolve_ocean(ocean, 10.0);
  std::array<double, 3> direct{}, error{};
  for (const auto& [x, z] : r2_points(64, w.sizes[0])) {
    const PointFields a = combine_from_grids(ocean, grids, x, z);
    const PointFields d = combine_direct(ocean, evolved, x, z);
    direct = {std::max(direct[0], std::fabs(d.height)),
              std::max({direct[1], std::fabs(d.slope_x), std::fabs(d.slope_z)}),
              std::max(direct[2], std::fabs(d.jacobian - 1.0))};
    error = {
        std::max(error[0], std::fabs(a.height - d.height)),
        std::max({error[1], std::fabs(a.slope_x - d.slope_x), std::fabs(a.slope_z - d.slope_z)}),
        std::max(error[2], std::fabs(a.jacobian - d.jacobian))};
  }
  const std::array<std::string, 3> names{"height", "slope", "jacobian-1"};
  for (std::size_t i = 0; i < names.size(); ++i) {
    CAPTURE(names[i]);
    CHECK(printed[names[i]][0] == direct[i]);
    CHECK(printed[names[i]][1] == error[i]);
    // Between nodes the lookup is an approximation (32 nodes over 1000 m: cells of 31 m, so
    // errors of the order of the field, but below it).
    CHECK(0.0 < error[i]);
    CHECK(error[i] < direct[i]);
  }
}

TEST_CASE(
    "bench lighting: the shader sun BRDF's error where the exact one is within 1e-6 of its peak") {
  std::ostringstream out;
  bench_lighting(out, 16);
  // "sun_brdf_schlick_rational_vs_exact,<max>,<mean>,<samples>"
  const auto rows = bench_rows(out.str(), "sun_brdf_schlick_rational_vs_exact,");
  REQUIRE(rows.size() == 1);
  REQUIRE(rows[0].size() == 4);
  const std::string& max = rows[0][1];
  const std::string& mean = rows[0][2];
  const std::string& samples = rows[0][3];
  // The sweep again: σ² (crosswind 0.6 σ²) × view zenith 0–85° × 7 azimuths, the sun at 40° and
  // azimuth 0, T = 2.5; a view counts where the exact BRDF·cos exceeds 10⁻⁶ of its value at the
  // mirror direction of the sun about the mean normal, 2(n·s)n − s.
  constexpr double deg = std::numbers::pi / 180.0;
  const Vec3 sun = make_sky(2.5, 40.0 * deg, 0.0).sun_direction;
  const Vec3 n{0.0, 1.0, 0.0};
  const Vec3 mirror{2.0 * sun[1] * n[0] - sun[0], 2.0 * sun[1] * n[1] - sun[1],
                    2.0 * sun[1] * n[2] - sun[2]};
  const SurfaceFrame frame = wind_frame(n, 0.0);
  BrdfOptions shader;
  shader.fresnel = FresnelForm::schlick;
  shader.erfc = ErfcForm::rational;
  double largest = 0.0, sum = 0.0;
  int count = 0;
  for (const double s2 : {1e-3, 5e-3, 0.01, 0.02, 0.05, 0.1}) {
    const SlopeVariance s{s2, 0.6 * s2};
    const double peak = ocean_brdf(sun, mirror, frame, s).brdf_cos;
    for (int vz = 0; vz <= 85; vz += 5) {
      for (int va = 0; va <= 180; va += 30) {
        const Vec3 v = direction_from_angles(vz * deg, (180.0 + va) * deg);
        const double exact = ocean_brdf(sun, v, frame, s).brdf_cos;
        if (!(exact > 1e-6 * peak)) continue;
        const double e = std::fabs(ocean_brdf(sun, v, frame, s, shader).brdf_cos - exact) / exact;
        largest = std::max(largest, e);
        sum += e;
        ++count;
      }
    }
  }
  // 418 of the 756 views (the rest are far from the glitter, where relative errors mean nothing).
  CHECK(std::stoi(samples) == count);
  CHECK(count < 6 * 18 * 7);
  CHECK(std::stod(max) == doctest::Approx(largest).epsilon(1e-12));
  CHECK(std::stod(mean) == doctest::Approx(sum / count).epsilon(1e-12));
}

TEST_CASE(
    "lighting map markdown: the cost table only when every integral's defaults were measured") {
  // The table sets the reference at the default tolerance against the fast mode at the default
  // orders (ShadingSettings), per integral; a map without one of those rows (a sweep of other
  // orders or tolerances) has no such table, and writing it must not fail.
  const ShadingSettings defaults;
  const LightingIntegral integrals[] = {LightingIntegral::sky, LightingIntegral::fresnel,
                                        LightingIntegral::sun};
  // Times at the unit boundaries: 1 ms and 1 s are written in those units.
  const double kScale[] = {1e-3, 1.0, 1e-6};
  const auto markdown_without = [&](int missing, bool missing_fast) {
    LightingMap map;
    for (int i = 0; i < 3; ++i) {
      for (const bool fast : {true, false}) {
        if (i == missing && fast == missing_fast) continue;
        LightingMapRow r;
        r.integral = integrals[i];
        r.fast = fast;
        r.setting = !fast                                 ? defaults.tolerance
                    : r.integral == LightingIntegral::sun ? defaults.sun_order
                                                          : defaults.sky_order;
        r.label = fast ? "order" : "tolerance";
        r.cases = 4;
        r.seconds = (fast ? 1.0 : 3.0) * kScale[i];
        r.median = r.p95 = r.max = fast ? 1e-3 : 1e-7;
        map.rows.push_back(r);
      }
    }
    return lighting_map_markdown(map);
  };
  const std::string title = "**Cost and error: reference at tolerance";
  const std::string whole = markdown_without(-1, false);
  const std::size_t table = whole.find(title);
  REQUIRE(table != std::string::npos);
  // Each integral's row: fast time, reference time (3x), their ratio.
  CHECK(whole.find("| 1 ms | 3 ms | 3 |", table) != std::string::npos);
  CHECK(whole.find("| 1 s | 3 s | 3 |", table) != std::string::npos);
  CHECK(whole.find("| 1 µs | 3 µs | 3 |", table) != std::string::npos);
  for (int i = 0; i < 3; ++i) {
    for (const bool fast : {true, false}) {
      CAPTURE(i);
      CAPTURE(fast);
      std::string without;
      REQUIRE_NOTHROW(without = markdown_without(i, fast));
      CHECK(without.find(title) == std::string::npos);
    }
  }
}

TEST_CASE("lighting map, full sweep: the sweep reference/ACCURACY.md publishes, case for case") {
  // The published map is measured over lighting_map_sweep(false) (tools/lighting_accuracy_map.sh):
  // its sweep line, written from the spec, must be the one in ACCURACY.md, and the case counts
  // the products of the spec's sizes (views × azimuths × roughness × normals × suns; F̄ without
  // the suns).
  LightingMap map;
  map.spec = lighting_map_sweep(false);
  const LightingSweepSpec& s = map.spec;
  map.fresnel_cases =
      s.cos_view.size() * s.azimuths_deg.size() * s.roughness.size() * s.tilted.size();
  map.lit_cases = map.fresnel_cases * s.suns.size();
  const std::string written = lighting_map_markdown(map);
  const std::string sweep = written.substr(0, written.find("}: ") + 3);
  std::ifstream in(std::string(OCEANREF_SOURCE_DIR) + "/reference/ACCURACY.md");
  const std::string accuracy((std::istreambuf_iterator<char>(in)), {});
  const std::size_t at = accuracy.find(sweep);
  REQUIRE_MESSAGE(at != std::string::npos, "ACCURACY.md does not hold the sweep " << sweep);
  const std::string counts = std::to_string(map.lit_cases) +
                             " cases for the reflected sky and the "
                             "sun disk, " +
                             std::to_string(map.fresnel_cases) + " for F̄";
  CHECK(accuracy.compare(at + sweep.size(), counts.size(), counts) == 0);
}

TEST_CASE("lighting map: each case is the view, roughness and sun its sweep names") {
  // The geometry the map's rows are about, checked from the cases themselves: each sun at its
  // zenith angle (cos = its direction's up component) and azimuth 90°; each view at V·N = v_n,
  // with its mirror direction 2(V·N)N − V at azimuth φ about N from the sun's side; every
  // combination once, in the spec's order; F̄ over the first sun's cases.
  const LightingSweepSpec spec = lighting_map_sweep(false);
  const LightingSweep sweep = make_lighting_sweep(spec);
  const double deg = 3.141592653589793 / 180.0;
  REQUIRE(sweep.suns.size() == spec.suns.size());
  for (std::size_t k = 0; k < spec.suns.size(); ++k) {
    const LightingSun& sun = sweep.suns[k];
    CHECK(sun.name == spec.suns[k].first);
    const double zenith = spec.suns[k].second * deg;
    const Vec3& d = sun.sky.sun_direction;
    CHECK(d[1] == doctest::Approx(std::cos(zenith)).epsilon(1e-12));
    CHECK(std::hypot(d[0], d[2]) == doctest::Approx(std::sin(zenith)).epsilon(1e-12));
    const Vec3 east = direction_from_angles(0.5 * 3.141592653589793, 90.0 * deg);
    CHECK(dot(d, east) == doctest::Approx(std::sin(zenith)).epsilon(1e-12));
    CHECK(sun.sun_radiance[1] > 0.0);
  }
  const std::size_t per_sun =
      spec.tilted.size() * spec.cos_view.size() * spec.azimuths_deg.size() * spec.roughness.size();
  REQUIRE(sweep.lit.size() == per_sun * spec.suns.size());
  REQUIRE(sweep.fresnel.size() == per_sun);
  std::size_t i = 0;
  for (const bool tilted : spec.tilted) {
    for (std::size_t k = 0; k < spec.suns.size(); ++k) {
      for (const double vn : spec.cos_view) {
        for (const double phi : spec.azimuths_deg) {
          for (const SlopeVariance& s : spec.roughness) {
            const LightingCase& c = sweep.lit[i++];
            const Vec3& n = c.frame.normal;
            CHECK(c.sun == k);
            CHECK(c.s.upwind == s.upwind);
            CHECK(c.s.crosswind == s.crosswind);
            CHECK((n[1] < 1.0) == tilted);
            CHECK(dot(c.view, n) == doctest::Approx(vn).epsilon(1e-12));
            // The tangential parts of the mirror direction and of the sun, about N.
            const Vec3 mirror = combine(2.0 * vn, n, -1.0, c.view);
            const Vec3 sun = sweep.suns[k].sky.sun_direction;
            const Vec3 m_t = combine(1.0, mirror, -vn, n);
            const Vec3 s_t = combine(1.0, sun, -dot(sun, n), n);
            const double cos_phi = dot(m_t, s_t) / std::sqrt(dot(m_t, m_t) * dot(s_t, s_t));
            CHECK(cos_phi == doctest::Approx(std::cos(phi * deg)).epsilon(1e-12).scale(1.0));
          }
        }
      }
    }
  }
  const std::size_t per_normal = per_sun / spec.tilted.size();  // the cases of one normal, one sun
  for (std::size_t j = 0; j < sweep.fresnel.size(); ++j) {
    const LightingCase& first_sun =
        sweep.lit[j / per_normal * per_normal * spec.suns.size() + j % per_normal];
    CHECK(sweep.fresnel[j].sun == 0);
    CHECK(sweep.fresnel[j].view == first_sun.view);
    CHECK(sweep.fresnel[j].frame.normal == first_sun.frame.normal);
    CHECK(sweep.fresnel[j].s.upwind == first_sun.s.upwind);
  }
}
