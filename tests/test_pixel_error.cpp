// The pixel as an integral (issue 20, point 1): each pixel's estimated error is three standard
// errors of its samples' mean (pixel_standard_error), written as the pixel_error layer and
// summarised (p50, p99, max relative) in the report and the EXR header. Checked against the
// formula by hand, against a converged render of the same scene (the estimate must cover the
// distance to it for most pixels without being uselessly large), and in its summary's
// quantiles against the sorted values. And the "same samples" export (point 4, `render
// --samples`): every sample of the fixed grid, each pixel their mean.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "conformance/render_output.h"
#include "io/exr.h"
#include "raster/renderer.h"
#include "scene/scene.h"

#include "glitter_scene.h"
#include "temp_dir.h"

using namespace oceanref;

namespace {
Scene glitter_scene(int samples_per_pixel) {
  return parse_scene(testing::glitter_scene_json(samples_per_pixel));
}

RenderedScene render_at(int samples_per_pixel) {
  RenderOutputOptions options;
  options.threads = 2;
  return render_scene(glitter_scene(samples_per_pixel), options);
}
}  // namespace

TEST_CASE("pixel_standard_error is the standard error of the samples' mean") {
  // R: 1, 2, 3, 4 (mean 2.5, Σ(x − mean)² = 5): √(5 / (4·3)); G constant: 0; B: −1, 1, −1, 1
  // (mean 0, Σ = 4): √(4/12).
  const std::vector<Vec3> x{{1.0, 7.0, -1.0}, {2.0, 7.0, 1.0}, {3.0, 7.0, -1.0}, {4.0, 7.0, 1.0}};
  const Vec3 e = pixel_standard_error(x, {2.5, 7.0, 0.0});
  CHECK(e[0] == doctest::Approx(std::sqrt(5.0 / 12.0)).epsilon(1e-15));
  CHECK(e[1] == 0.0);
  CHECK(e[2] == doctest::Approx(std::sqrt(1.0 / 3.0)).epsilon(1e-15));
  // One sample: nothing to estimate from.
  const Vec3 one = pixel_standard_error(std::span(x.data(), 1), x[0]);
  CHECK(one[0] == 0.0);
  CHECK(one[2] == 0.0);
}

TEST_CASE("the pixel error covers the distance to the converged pixel") {
  const RenderedScene coarse = render_at(4);
  const RenderedScene fine = render_at(256);  // the pixel integral, ±fine's own estimate
  REQUIRE(coarse.image.radiance.size() == fine.image.radiance.size());
  int covered = 0;
  int channels = 0;
  std::vector<double> estimate_over_distance;
  for (std::size_t i = 0; i < coarse.image.radiance.size(); ++i) {
    for (std::size_t c = 0; c < 3; ++c) {
      const double d = std::fabs(coarse.image.radiance[i][c] - fine.image.radiance[i][c]);
      const double e = coarse.image.pixel_error[i][c];
      const double e_fine = fine.image.pixel_error[i][c];
      ++channels;
      if (d <= e + e_fine + 1e-12 * std::fabs(fine.image.radiance[i][c])) ++covered;
      if (d > 0.0) estimate_over_distance.push_back(e / d);
    }
  }
  const double share = static_cast<double>(covered) / channels;
  std::sort(estimate_over_distance.begin(), estimate_over_distance.end());
  const double typical = estimate_over_distance[estimate_over_distance.size() / 2];
  MESSAGE("share of pixel channels within the estimates of the 256-spp pixel: "
          << share << "; median estimate / distance: " << typical);
  // Three standard errors cover ~99.7% of a normal error; the 4 samples are few and not normal
  // (a glint all four miss has an estimate of 0), so the check asks for 90%.
  CHECK(share >= 0.90);
  // Not covering by being huge: the typical estimate is within a factor 100 of the distance
  // (measured ~30: where the radiance is smooth across the pixel the stratified mean's error
  // falls faster than the standard error of independent samples, which it is taken as).
  CHECK(typical < 100.0);
  CHECK(typical > 0.1);
}

TEST_CASE("the pixel error's summary: quantiles of the relative estimates, shrinking with spp") {
  const RenderedScene r4 = render_at(4);
  const RenderedScene r16 = render_at(16);
  std::vector<double> relative;
  for (std::size_t i = 0; i < r4.image.radiance.size(); ++i) {
    for (std::size_t c = 0; c < 3; ++c) {
      relative.push_back(r4.image.pixel_error[i][c] / std::fabs(r4.image.radiance[i][c]));
    }
  }
  std::sort(relative.begin(), relative.end());
  const PixelErrorSummary s4 = report_of(r4).pixel_error;
  const PixelErrorSummary s16 = report_of(r16).pixel_error;
  REQUIRE(s4.estimated);
  CHECK(s4.samples_per_pixel == 4);
  CHECK(s4.max_relative == relative.back());
  const double bin = 1.0 - std::ldexp(1.0, -8);
  for (const double q : {0.5, 0.99}) {
    CAPTURE(q);
    const double exact =
        relative[static_cast<std::size_t>(q * static_cast<double>(relative.size()))];
    const double summary = q == 0.5 ? s4.p50_relative : s4.p99_relative;
    CHECK(summary <= exact);
    CHECK(summary > exact * bin);
  }
  CHECK(s4.p50_relative > 0.0);
  CHECK(s4.p50_relative <= s4.p99_relative);
  CHECK(s4.p99_relative <= s4.max_relative);
  // 4× the samples: the standard error falls by ~2 (or faster where the radiance is smooth).
  MESSAGE("p50 at 4 spp " << s4.p50_relative << ", at 16 spp " << s16.p50_relative);
  CHECK(s16.p50_relative < 0.75 * s4.p50_relative);
  CHECK(s16.p50_relative > 0.0);
}

TEST_CASE("one sample per pixel: no estimate, said so") {
  const RenderedScene r = render_at(1);
  const PixelErrorSummary s = report_of(r).pixel_error;
  CHECK_FALSE(s.estimated);
  for (const Vec3& e : r.image.pixel_error) CHECK(e == Vec3{});
  const std::string attribute = r.exr.attributes.at("oceanref.pixel_error");
  CHECK(attribute.size() == kPixelErrorAttributeLength);
  CHECK(attribute.starts_with("not estimated: 1 sample per pixel"));
}

TEST_CASE("the pixel error reaches the EXR: its layer and its header's summary") {
  testing::TempDir dir("oceanref_pixel_error_");
  RenderOutputOptions options;
  options.threads = 2;
  options.aov = true;
  options.streamed = true;
  options.band_rows = 5;
  const std::string path = dir.file("r.exr");
  const RenderReport report = render_scene_to_files(glitter_scene(4), options, path, "");
  options.streamed = false;
  const RenderedScene whole = render_scene(glitter_scene(4), options);
  const ExrImage exr = read_exr(path);
  const std::string attribute = exr.attributes.at("oceanref.pixel_error");
  CHECK(attribute == pixel_error_attribute(report.pixel_error));
  CHECK(attribute.starts_with("3 standard errors of the pixel mean, over 4 samples"));
  CHECK(report.pixel_error.p99_relative == report_of(whole).pixel_error.p99_relative);
  for (std::size_t c = 0; c < 3; ++c) {
    const std::string name = std::string("pixel_error.") + "RGB"[c];
    const auto channel = std::find_if(exr.channels.begin(), exr.channels.end(),
                                      [&](const ExrChannel& ch) { return ch.name == name; });
    REQUIRE(channel != exr.channels.end());
    for (std::size_t i = 0; i < whole.image.pixel_error.size(); ++i) {
      REQUIRE(channel->values[i] == static_cast<float>(whole.image.pixel_error[i][c]));
    }
  }
}

TEST_CASE("same samples: every sample kept, each pixel their mean, each sample probe's value") {
  // `render --samples` (RenderJob::keep_samples): the band's S×S grid row-major; a pixel's
  // radiance is its samples' mean in row-major order (the same bits), and a sample is the one
  // `probe` shades at that position (an independent path: its own raster pass of the pixel).
  const Scene scene = glitter_scene(9);
  const Ocean ocean = realize_ocean(scene.waves, 2);
  RenderJob job = scene_render_job(scene, ocean, 2);
  const SlopeVariance unresolved = unresolved_slope_variance(job, scene.waves);
  job.keep_samples = true;
  const RenderedImage image = render(job, unresolved);
  const int s = 3, columns = 24 * s;
  REQUIRE(image.sample_radiance.size() == static_cast<std::size_t>(12 * s * columns));
  for (int y = 0; y < 12; ++y) {
    for (int x = 0; x < 24; ++x) {
      Vec3 mean{};
      for (int b = 0; b < s; ++b) {
        for (int a = 0; a < s; ++a) {
          const Vec3& v =
              image.sample_radiance[static_cast<std::size_t>((y * s + b) * columns + x * s + a)];
          for (std::size_t c = 0; c < 3; ++c) mean[c] += (1.0 / 9.0) * v[c];
        }
      }
      CHECK(mean == image.radiance[static_cast<std::size_t>(y * 24 + x)]);
    }
  }
  const std::vector<SampleProbe> probe = probe_pixel(job, unresolved, 17, 8);
  for (int b = 0; b < s; ++b) {
    for (int a = 0; a < s; ++a) {
      CHECK(probe[static_cast<std::size_t>(b * s + a)].radiance ==
            image.sample_radiance[static_cast<std::size_t>((8 * s + b) * columns + 17 * s + a)]);
    }
  }
  // Without keep_samples nothing is kept.
  job.keep_samples = false;
  CHECK(render(job, unresolved).sample_radiance.empty());
}
