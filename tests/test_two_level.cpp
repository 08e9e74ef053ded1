// One error budget per pixel (issue 50, point 1): adaptive sampling with reference lighting is a
// two-level estimate. Every sample is lit by the fast rules; each pixel is corrected by the mean
// of (reference − fast) over one level of its nested grid; pixel_error bounds the fast level's
// pixel integral, lighting_error the correction (3 standard errors of its mean + the reference's
// own estimates), and their sum meets render.pixel_tolerance or the pixel is capped. Checked: a
// pixel corrected at all its samples is the reference render of those samples (the identity the
// estimate rests on); the correction's actual error against that render is within lighting_error;
// the stopping rule on the sum; the same bits for any thread count; the scene keys (the
// reference's tolerance derived from the pixel's, the fast rules' orders accepted and read).
// The two-level estimate's costs and the designs it was measured against: tools/two_level_study.sh.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "conformance/render_output.h"
#include "raster/renderer.h"
#include "scene/scene.h"

#include "glitter_scene.h"
#include "test_support.h"

using namespace oceanref;
using nlohmann::json;

namespace {
// The glitter scene's left 13 columns (13×12: waves, sun glitter, sky, horizon) lit by the
// reference at 1e-2 (its cheapest tolerance: the reference samples are the tests' cost).
json two_level_glitter(int samples_per_pixel) {
  json s = testing::glitter_scene_json(samples_per_pixel);
  s["shading"] = {{"accuracy", "reference"}, {"tolerance", 1e-2}};
  s["render"]["width"] = 13;  // uneven, not square
  return s;
}

// The cases below are the nested grid's (its levels are the fixed grid's samples) unless the scene
// names a pattern.
RenderedImage two_level_render(json s, int threads) {
  if (s["render"].contains("pixel_tolerance") && !s["render"].contains("pixel_pattern")) {
    s["render"]["pixel_pattern"] = "grid";
  }
  RenderOutputOptions options;
  options.threads = threads;
  options.aov = true;
  return render_scene(parse_scene(s), options).image;
}

double largest_channel(const Vec3& v) {
  return std::max({v[0], v[1], v[2]});
}
}  // namespace

TEST_CASE("two-level: a pixel corrected at all its samples is the reference render of them") {
  // One sample per pixel, capped at 9: the one sample's correction estimates nothing, so every
  // pixel that sees the sea is refined to 3×3 and corrected at all 9. The mean of the fast
  // samples plus the mean of reference − fast over the same samples is the mean of the reference
  // samples, which the fixed 3×3 grid of a reference render shades at the same positions.
  json s = two_level_glitter(1);
  s["render"]["pixel_tolerance"] = 0.05;
  s["render"]["max_samples_per_pixel"] = 9;
  const RenderedImage two = two_level_render(s, 2);
  json fixed = two_level_glitter(9);
  const RenderedImage reference = two_level_render(fixed, 2);
  REQUIRE(two.radiance.size() == reference.radiance.size());
  int sea = 0;
  for (std::size_t i = 0; i < two.radiance.size(); ++i) {
    REQUIRE(two.pixel_samples[i] == 9.0);
    if (two.coverage[i] > 0.0) ++sea;
    for (std::size_t c = 0; c < 3; ++c) {
      // Rounding only: the two sums (fast, then the differences) against one.
      CHECK(std::fabs(two.radiance[i][c] - reference.radiance[i][c]) <=
            1e-13 * std::fabs(reference.radiance[i][c]) + 1e-15);
      CHECK(std::fabs(two.sun[i][c] + two.sky[i][c] + two.sea[i][c] -
                      (reference.sun[i][c] + reference.sky[i][c] + reference.sea[i][c])) <=
            1e-12 * std::fabs(reference.radiance[i][c]) + 1e-12);
    }
  }
  MESSAGE(sea << " of " << two.radiance.size() << " pixels see the sea");
  CHECK(sea > 25);
  CHECK(sea < static_cast<int>(two.radiance.size()));
}

TEST_CASE(
    "two-level: the correction's error is within lighting_error, the sum meets the tolerance") {
  // 4 spp capped at 36: pixels corrected at their 2×2 samples or, where that bound is too wide,
  // at all 36. Against the reference render of the 6×6 grid (the pixel's samples when refined),
  // the two-level pixel differs only by its correction's sampling error.
  constexpr double kTolerance = 0.05;
  json s = two_level_glitter(4);
  s["render"]["pixel_tolerance"] = kTolerance;
  s["render"]["max_samples_per_pixel"] = 36;
  const RenderedImage two = two_level_render(s, 2);
  const RenderedImage reference = two_level_render(two_level_glitter(36), 2);
  int refined_sea = 0, within = 0, corrected_partly = 0;
  long capped = 0;
  for (std::size_t i = 0; i < two.radiance.size(); ++i) {
    const double allowed = kTolerance * largest_channel(two.radiance[i]);
    bool meets = true;
    for (std::size_t c = 0; c < 3; ++c) {
      CHECK(two.lighting_error[i][c] >= 0.0);
      meets = meets && two.pixel_error[i][c] + two.lighting_error[i][c] <= allowed;
    }
    if (!meets) ++capped;
    // The stopping rule: below the cap, a pixel stops only within the tolerance.
    if (two.pixel_samples[i] < 36.0) CHECK(meets);
    if (two.pixel_samples[i] != 36.0 || !(two.coverage[i] > 0.0)) continue;
    ++refined_sea;
    bool in = true;
    bool exact = true;
    for (std::size_t c = 0; c < 3; ++c) {
      const double actual = std::fabs(two.radiance[i][c] - reference.radiance[i][c]);
      in = in && actual <= two.lighting_error[i][c] + 1e-12 * std::fabs(reference.radiance[i][c]);
      exact = exact && actual <= 1e-12 * std::fabs(reference.radiance[i][c]);
    }
    if (in) ++within;
    if (!exact) ++corrected_partly;
  }
  MESSAGE("refined sea pixels " << refined_sea << ", corrected at 4 of 36 samples "
                                << corrected_partly << ", within lighting_error " << within
                                << "; capped " << capped);
  CHECK(two.capped_pixels == capped);
  REQUIRE(refined_sea > 20);
  CHECK(corrected_partly > 5);  // the correction is sampled, not complete, in most of them
  // 3 standard errors of four samples: a pixel outside is rare (the t-distribution of 3 degrees
  // of freedom leaves 6% beyond 3), and the reference's own estimate adds to it.
  CHECK(within >= static_cast<int>(0.9 * refined_sea));
  CHECK(two.corrected_samples > 4L * refined_sea);
}

TEST_CASE("two-level: the same bits for any thread count") {
  json s = two_level_glitter(4);
  s["render"]["pixel_tolerance"] = 0.02;
  s["render"]["max_samples_per_pixel"] = 36;
  s["render"]["width"] = 6;
  const RenderedImage one = two_level_render(s, 1);
  const RenderedImage three = two_level_render(s, 3);
  CHECK(one.radiance == three.radiance);
  CHECK(one.lighting_error == three.lighting_error);
  CHECK(one.pixel_error == three.pixel_error);
  CHECK(one.sky == three.sky);
  CHECK(one.corrected_samples == three.corrected_samples);
  CHECK(one.corrected_samples > 0);
}

TEST_CASE("two-level: the scene's keys") {
  json s = two_level_glitter(4);
  s["shading"].erase("tolerance");
  // Without adaptive sampling the fast rules' orders are the other mode's keys.
  json fixed = s;
  fixed["shading"]["sky_order"] = 8;
  CHECK_THROWS_WITH_AS(parse_scene(fixed), doctest::Contains("shading.sky_order"), SceneError);
  s["render"]["pixel_tolerance"] = 0.02;
  const Scene derived = parse_scene(s);
  CHECK(two_level_lighting(derived));
  // The reference's tolerance: a tenth of the pixel's, unless given.
  CHECK(derived.shading.tolerance == kTwoLevelLightingShare * 0.02);
  CHECK(derived.shading.sky_order == kTwoLevelSkyOrder);  // the fast samples' rule, unless given
  s["shading"]["tolerance"] = 1e-2;
  CHECK(parse_scene(s).shading.tolerance == 1e-2);
  json fast = s;
  fast["shading"] = {{"accuracy", "fast"}};
  CHECK_FALSE(two_level_lighting(parse_scene(fast)));
  // The cheap level's order is read: it changes the samples (and so the bits), not what the pixel
  // estimates.
  s["render"]["width"] = 8;
  s["render"]["max_samples_per_pixel"] = 36;
  json finer = s;
  finer["shading"]["sky_order"] = 4;
  const RenderedImage a = two_level_render(s, 2);
  const RenderedImage b = two_level_render(finer, 2);
  CHECK(a.radiance != b.radiance);
  // Two estimates of the same pixels: apart by at most their two bounds (nearly always).
  int agree = 0;
  for (std::size_t i = 0; i < a.radiance.size(); ++i) {
    bool in = true;
    for (std::size_t c = 0; c < 3; ++c) {
      const double bound = a.pixel_error[i][c] + a.lighting_error[i][c] + b.pixel_error[i][c] +
                           b.lighting_error[i][c];
      in = in && std::fabs(a.radiance[i][c] - b.radiance[i][c]) <= bound + 1e-12;
    }
    if (in) ++agree;
  }
  CHECK(agree >= static_cast<int>(0.9 * static_cast<double>(a.radiance.size())));
}

TEST_CASE("two-level: the correction stops at the 3S x 3S grid (kMaxCorrectionRefinements)") {
  // With the cap at 18×18 samples a correction could go on to all 324; it stops at 6×6 (36
  // reference samples a pixel at most), except where none of the 6×6 sees the sea.
  // A coarse cheap level (one node) leaves wide corrections, which would refine further.
  json s = two_level_glitter(4);
  s["shading"]["sky_order"] = 1;
  s["render"]["pixel_tolerance"] = 0.05;
  s["render"]["max_samples_per_pixel"] = 324;
  const RenderedImage image = two_level_render(s, 2);
  long sea = 0;
  for (const double c : image.coverage) sea += c > 0.0 ? 1 : 0;
  MESSAGE("corrected samples " << image.corrected_samples << " over " << sea << " sea pixels");
  CHECK(image.corrected_samples > 4 * sea);  // some corrections refined to 6×6
  CHECK(image.corrected_samples <= 40 * sea);
}

TEST_CASE(
    "two-level (Sobol'): each level's samples lead the next's, each lit by the reference once") {
  // A coarse cheap level (one node) leaves wide corrections, so many pixels refine theirs to
  // level 3, the first 32 samples. Kept from level to level, a pixel lights at most 32 of its sea
  // samples by the reference (lit again at each level it would be 4 + 8 + 16 + 32).
  json s = two_level_glitter(4);
  s["shading"]["sky_order"] = 1;
  s["render"]["pixel_tolerance"] = 0.05;
  s["render"]["pixel_pattern"] = "sobol";
  s["render"]["max_samples_per_pixel"] = 256;
  const RenderedImage image = two_level_render(s, 2);
  double most = 0.0;  // Σ min(32, the pixel's sea samples)
  long sea = 0;
  long capped = 0;
  for (std::size_t i = 0; i < image.radiance.size(); ++i) {
    most += std::min(32.0, std::round(image.coverage[i] * image.pixel_samples[i]));
    sea += image.coverage[i] > 0.0 ? 1 : 0;
    bool meets = true;
    for (std::size_t c = 0; c < 3; ++c) {
      meets = meets && image.pixel_error[i][c] + image.lighting_error[i][c] <=
                           0.05 * largest_channel(image.radiance[i]);
    }
    if (!meets) ++capped;
    if (image.pixel_samples[i] < 256.0) CHECK(meets);
  }
  MESSAGE("corrected samples " << image.corrected_samples << " over " << sea
                               << " sea pixels; at most " << most);
  CHECK(image.capped_pixels == capped);
  CHECK(image.corrected_samples > 8 * sea);  // corrections refined past the first 4 samples
  CHECK(static_cast<double>(image.corrected_samples) <= most);
  const RenderedImage one = two_level_render(s, 1);
  CHECK(one.radiance == image.radiance);
  CHECK(one.lighting_error == image.lighting_error);
}
