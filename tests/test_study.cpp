// The measurements in library code (conformance/study.h, conformance/lighting_map.h): checked for
// their numbers, not their timings (timings are never tested).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "conformance/lighting_map.h"
#include "conformance/study.h"
#include "scene/scene.h"

using namespace oceanref;

namespace {
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

TEST_CASE("study: FFT grids equal direct summation at the nodes; interpolation errors ordered") {
  const Scene scene = study_scene();
  const FftVsDirect r = study_fft_vs_direct(scene, 2);
  CHECK(r.points == 8);
  // Fields of O(1) m from a 16² inverse DFT: both sides are sums of the same 256 terms, so they
  // agree to rounding (~1e-15); an index, sign or normalisation error would show as O(0.1).
  CHECK(r.max_abs_difference < 1e-12);
  CHECK(r.fft_seconds_per_frame > 0.0);

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
