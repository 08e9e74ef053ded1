// A render streamed band by band to its files (render_scene_to_files, `oceanref render`) is the
// render held whole (render_scene, then write_exr and write_preview_png, as `merge` writes it):
// the same EXR and PNG bytes and the same report for any band height, with and without the
// layers, in fast and reference accuracy; and the report's median lighting error, kept as a
// histogram for the bands, is within its stated bin of the exact median.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "conformance/render_output.h"
#include "io/exr.h"
#include "scene/scene.h"

#include "temp_dir.h"

using namespace oceanref;

namespace {
using testing::TempDir;

std::vector<char> bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A small scene with waves, sun, sky and whitecaps, in the given accuracy.
Scene streaming_scene(const std::string& accuracy) {
  nlohmann::json s = nlohmann::json::parse(R"({
    "seed": 5,
    "waves": {"spectrum": {"model": "jonswap", "wind_speed": 9, "fetch": 60000},
              "cascades": {"largest": 200, "count": 2, "factor": "golden-small"},
              "resolution": 32, "choppiness": -1.0},
    "camera": {"position": [0, 4, 0], "look_at": [0, 1, 40]},
    "grid": {"columns": 64, "rows": 64},
    "atmosphere": {"sun_zenith_deg": 70, "sun_azimuth_deg": 80},
    "shading": {"whitecaps": true, "whitecap_threshold": 0.7},
    "render": {"width": 23, "height": 19, "samples_per_pixel": 4}})");
  s["shading"]["accuracy"] = accuracy;
  if (accuracy == "reference") s["shading"]["tolerance"] = 1e-3;
  return parse_scene(s);
}
}  // namespace

TEST_CASE("a render streamed in bands writes the bytes of the whole render") {
  TempDir dir;
  // Fast with and without the layers, reference (costlier: the sanitizer builds run this too)
  // with them, so that its error estimates reach the files.
  for (const auto& mode :
       {std::pair{"fast", false}, std::pair{"fast", true}, std::pair{"reference", true}}) {
    const std::string accuracy = mode.first;  // (no structured binding: CAPTURE is a lambda)
    const bool aov = mode.second;
    const Scene scene = streaming_scene(accuracy);
    CAPTURE(accuracy);
    CAPTURE(aov);
    RenderOutputOptions options;
    options.threads = 2;
    options.aov = aov;
    const RenderedScene whole = render_scene(scene, options);
    const std::string whole_exr = dir.file("whole.exr");
    const std::string whole_png = dir.file("whole.png");
    write_exr(whole_exr, whole.exr);
    write_preview_png(whole_png, whole.image, whole.settings);
    const RenderReport expected = report_of(whole);
    for (const int band : {1, 4, 7, 19, 0}) {
      if (accuracy == "reference" && band != 4) continue;
      CAPTURE(band);
      options.streamed = true;
      options.band_rows = band;
      const std::string exr = dir.file("band.exr");
      const std::string png = dir.file("band.png");
      const RenderReport r = render_scene_to_files(scene, options, exr, png);
      CHECK(r.pixel_sha256 == expected.pixel_sha256);
      CHECK(r.radiance_f64_sha256 == expected.radiance_f64_sha256);
      CHECK(r.lighting_error.estimated == expected.lighting_error.estimated);
      CHECK(r.lighting_error.max_relative == expected.lighting_error.max_relative);
      CHECK(r.lighting_error.median_relative == expected.lighting_error.median_relative);
      CHECK(r.pixel_error.estimated == expected.pixel_error.estimated);
      CHECK(r.pixel_error.p50_relative == expected.pixel_error.p50_relative);
      CHECK(r.pixel_error.p99_relative == expected.pixel_error.p99_relative);
      CHECK(r.pixel_error.max_relative == expected.pixel_error.max_relative);
      CHECK(r.unconverged_samples == expected.unconverged_samples);
      CHECK(r.integrand_evaluations == expected.integrand_evaluations);
      CHECK(bytes_of(exr) == bytes_of(whole_exr));
      CHECK(bytes_of(png) == bytes_of(whole_png));
      options.streamed = false;
    }
  }
}

TEST_CASE("a streamed render's progress rises through its bands to 1") {
  TempDir dir;
  const Scene scene = streaming_scene("fast");  // 19 rows: bands of 7, 7 and 5
  RenderOutputOptions options;
  options.threads = 1;  // the callbacks in order
  options.streamed = true;
  options.band_rows = 7;
  std::vector<double> shares;
  options.progress = [&](double share) { shares.push_back(share); };
  (void)render_scene_to_files(scene, options, dir.file("p.exr"), "");
  // Each band reports its start (when its rows start: the rows before it done), then every row.
  std::vector<double> expected;
  for (const auto& [first, last] : {std::pair{0, 7}, std::pair{7, 14}, std::pair{14, 19}}) {
    expected.push_back(first / 19.0);
    for (int row = first + 1; row <= last; ++row) expected.push_back(row / 19.0);
  }
  REQUIRE(shares.size() == expected.size());
  for (std::size_t k = 0; k < shares.size(); ++k) {
    CHECK(shares[k] == doctest::Approx(expected[k]).epsilon(1e-15));
  }
  CHECK(shares.front() == 0.0);
  CHECK(std::is_sorted(shares.begin(), shares.end()));
  CHECK(shares.back() == 1.0);
}

TEST_CASE("the memory estimate of a streamed render counts one band") {
  Scene scene = streaming_scene("fast");
  scene.image.width = 4096;
  scene.image.height = 4096;
  RenderOutputOptions options;
  const double whole = render_memory_estimate(scene, options).total();
  options.streamed = true;
  const int band = stream_band_rows(scene, options);
  CHECK(band >= 1);
  CHECK(band < 4096);
  const double streamed = render_memory_estimate(scene, options).total();
  CHECK(streamed < whole);
  CHECK(streamed < 320.0 * 1024 * 1024);  // the 256 MiB band and the frame's grids
  scene.image.height = 16384;
  CHECK(render_memory_estimate(scene, options).total() == streamed);  // independent of height
  options.band_rows = 3;
  CHECK(stream_band_rows(scene, options) == 3);
}

TEST_CASE("the median lighting error is the lower edge of its 2^-8 bin") {
  const Scene scene = streaming_scene("reference");
  RenderOutputOptions options;
  options.threads = 2;
  const RenderedScene r = render_scene(scene, options);
  std::vector<double> relative;
  for (std::size_t i = 0; i < r.image.radiance.size(); ++i) {
    if (!(r.image.coverage[i] > 0.0)) continue;
    for (std::size_t c = 0; c < 3; ++c) {
      relative.push_back(r.image.lighting_error[i][c] / std::fabs(r.image.radiance[i][c]));
    }
  }
  REQUIRE(relative.size() > 10);
  std::sort(relative.begin(), relative.end());
  const double exact = relative[relative.size() / 2];
  const LightingErrorSummary s = summarize_lighting_error(r.image);
  REQUIRE(s.estimated);
  CHECK(s.max_relative == relative.back());
  CHECK(s.median_relative <= exact);
  CHECK(s.median_relative > exact * (1.0 - std::ldexp(1.0, -8)));
}

TEST_CASE("a streamed render refuses what its files cannot hold, under the scene key") {
  // --samples exports the fixed S×S grid: not Mastin's extra samples, not adaptive refinement;
  // a tile is rasterized. Each checked beside the accepted case, before any file is written.
  TempDir dir;
  const auto key_of_refusal = [&](const Scene& scene, const RenderOutputOptions& options,
                                  const std::string& samples) -> std::string {
    try {
      if (options.tiles > 1) {
        (void)render_scene_piece(scene, options);
      } else {
        (void)render_scene_to_files(scene, options, dir.file("r.exr"), "", samples);
      }
    } catch (const SceneError& e) {
      CHECK_FALSE(std::filesystem::exists(dir.file("r.exr")));
      return e.path();
    }
    return "accepted";
  };
  RenderOutputOptions options;
  options.threads = 1;
  options.streamed = true;
  options.keep_samples = true;
  const Scene plain = streaming_scene("fast");
  Scene mastin = plain;
  mastin.image.mastin_antialiasing = 0.05;
  Scene adaptive = plain;
  adaptive.image.pixel_tolerance = 0.05;
  CHECK(key_of_refusal(mastin, options, dir.file("s.exr")) == "render.mastin_antialiasing");
  CHECK(key_of_refusal(adaptive, options, dir.file("s.exr")) == "render.pixel_tolerance");
  options.keep_samples = false;
  CHECK(key_of_refusal(mastin, options, "") == "accepted");
  CHECK(key_of_refusal(adaptive, options, "") == "accepted");
  std::filesystem::remove(dir.file("r.exr"));
  RenderOutputOptions tile;
  tile.threads = 1;
  tile.tiles = 2;
  tile.renderer = Renderer::raytrace;
  CHECK(key_of_refusal(plain, tile, "") == "render.renderer");
  tile.renderer = Renderer::raster;
  CHECK(key_of_refusal(plain, tile, "") == "accepted");
}
