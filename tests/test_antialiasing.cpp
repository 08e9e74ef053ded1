// Mastin's adaptive anti-aliasing (issue 17, point 3; render.mastin_antialiasing): 16 extra
// samples in the pixels whose luminance contrast with a neighbour exceeds the threshold.
#include <doctest/doctest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <utility>

#include "conformance/scene_objects.h"
#include "raster/renderer.h"
#include "scene/scene.h"
#include "test_support.h"

using namespace oceanref;
using nlohmann::json;

namespace {

// The buoy on the sea (its outline and the horizon are the discontinuities), 1 spp.
json aa_scene(double threshold) {
  json s = json::parse(R"({
    "seed": 2,
    "waves": {"spectrum": {"model": "jonswap", "wind_speed": 8, "fetch": 50000},
              "cascades": {"sizes": [200, 37]}, "resolution": 32, "choppiness": -0.8},
    "camera": {"position": [0, 2.5, 0], "look_at": [0, 0.6, 14], "vertical_fov_deg": 40},
    "grid": {"columns": 96, "rows": 96},
    "atmosphere": {"sun_zenith_deg": 70, "sun_azimuth_deg": 60},
    "shading": {"accuracy": "fast"},
    "render": {"width": 48, "height": 32, "samples_per_pixel": 1},
    "objects": [{"obj": "", "position": [0, 0, 12], "scale": 1.5}]})");
  s["objects"][0]["obj"] = OCEANREF_SOURCE_DIR "/reference/objects/buoy.obj";
  if (threshold > 0.0) s["render"]["mastin_antialiasing"] = threshold;
  return s;
}

struct AaRender {
  Scene scene;
  Ocean ocean;
  SceneObjects objects;
  RenderJob job;
  SlopeVariance unresolved;
};

std::unique_ptr<AaRender> aa_prepare(const json& document, Renderer renderer, int spp = 1,
                                     int threads = 2) {
  auto r = std::make_unique<AaRender>();
  r->scene = parse_scene(document);
  r->scene.image.samples_per_axis = static_cast<int>(std::lround(std::sqrt(spp)));
  r->ocean = realize_ocean(r->scene.waves, threads);
  r->objects = load_scene_objects(r->scene);
  r->job = scene_render_job(r->scene, r->ocean, threads);
  r->job.objects = &r->objects;
  r->job.renderer = renderer;
  r->unresolved = unresolved_slope_variance(r->job, r->scene.waves);
  return r;
}

}  // namespace

TEST_CASE("Mastin anti-aliasing: the luminance contrast") {
  CHECK(luminance_contrast({1, 1, 1}, {0, 0, 0}) == 1.0);
  CHECK(luminance_contrast({0, 0, 0}, {0, 0, 0}) == 0.0);
  CHECK(luminance_contrast({2, 2, 2}, {1, 1, 1}) == doctest::Approx(1.0 / 3.0).epsilon(1e-15));
  // BT.709 weights: pure green is brighter than pure red.
  CHECK(luminance_contrast({0, 1, 0}, {1, 0, 0}) ==
        doctest::Approx((0.7152 - 0.2126) / (0.7152 + 0.2126)).epsilon(1e-15));
}

TEST_CASE(
    "Mastin anti-aliasing: flagged pixels are the mean of S² + 16 samples, others unchanged") {
  // At 1 and 4 spp: with S = 2 a flagged pixel shades its 2×2 samples again, each from its own
  // fragment, before the 16 extra ones.
  for (const auto& variant : {std::pair{Renderer::raster, 1},
                              {Renderer::raytrace, 1},
                              {Renderer::raster, 4},
                              {Renderer::raytrace, 4}}) {
    const Renderer renderer = variant.first;
    const int spp = variant.second;
    CAPTURE(static_cast<int>(renderer));
    CAPTURE(spp);
    const double threshold = 0.25;
    const auto base = aa_prepare(aa_scene(0.0), renderer, spp);
    const RenderedImage one = render(base->job, base->unresolved);
    const auto dense = aa_prepare(aa_scene(0.0), renderer, 16);
    const RenderedImage sixteen = render(dense->job, dense->unresolved);
    const auto aa = aa_prepare(aa_scene(threshold), renderer, spp);
    const RenderedImage image = render(aa->job, aa->unresolved);
    const int w = image.width, h = image.height;
    const auto at = [&](int x, int y) { return static_cast<std::size_t>(y * w + x); };
    // The largest contrast of a pixel with its 4 neighbours in the plain render.
    const auto contrast_at = [&](int x, int y) {
      double contrast = 0.0;
      const int dx[] = {-1, 1, 0, 0}, dy[] = {0, 0, -1, 1};
      for (int n = 0; n < 4; ++n) {
        const int nx = x + dx[n], ny = y + dy[n];
        if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
        contrast = std::fmax(contrast,
                             luminance_contrast(one.radiance[at(x, y)], one.radiance[at(nx, ny)]));
      }
      return contrast;
    };
    long flagged = 0;
    int first_flagged = -1;  // x + w·y of the first flagged pixel
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const double contrast = contrast_at(x, y);
        if (contrast > threshold && first_flagged < 0) first_flagged = x + w * y;
        const Vec3& got = image.radiance[at(x, y)];
        if (contrast > threshold) {
          ++flagged;
          // (the S² samples, whose mean the plain render holds, + the 16 of the 4×4 grid,
          // which a 16-spp render holds) / (S² + 16).
          for (std::size_t c = 0; c < 3; ++c) {
            const double expected =
                (spp * one.radiance[at(x, y)][c] + 16.0 * sixteen.radiance[at(x, y)][c]) /
                (spp + 16.0);
            CHECK(got[c] == doctest::Approx(expected).epsilon(1e-12));
          }
        } else {
          CHECK(got == one.radiance[at(x, y)]);
        }
      }
    }
    MESSAGE("flagged " << flagged << " of " << w * h);
    CHECK(flagged == image.antialiased_pixels);
    CHECK(flagged > 20);
    CHECK(flagged < w * h / 2);
    // A threshold equal to a pixel's contrast leaves that pixel alone: "above", not "at".
    REQUIRE(first_flagged >= 0);
    const int fx = first_flagged % w, fy = first_flagged / w;
    const double exact = contrast_at(fx, fy);
    const auto at_exact = aa_prepare(aa_scene(exact), renderer, spp);
    const RenderedImage edge = render(at_exact->job, at_exact->unresolved);
    CHECK(edge.radiance[at(fx, fy)] == one.radiance[at(fx, fy)]);
    long above = 0;
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) above += contrast_at(x, y) > exact ? 1 : 0;
    }
    CHECK(edge.antialiased_pixels == above);
    // Bands (each renders its neighbour rows) and threads give the same bits.
    const RenderFrame frame = prepare_frame(aa->job, aa->unresolved);
    const RenderedImage top = render_rows(frame, 0, 13);
    const RenderedImage bottom = render_rows(frame, 13, h);
    std::vector<Vec3> joined = top.radiance;
    joined.insert(joined.end(), bottom.radiance.begin(), bottom.radiance.end());
    CHECK(testing::same_bits(joined, image.radiance));
    CHECK(top.antialiased_pixels + bottom.antialiased_pixels == image.antialiased_pixels);
    const auto single = aa_prepare(aa_scene(threshold), renderer, spp, 1);
    CHECK(testing::same_bits(render(single->job, single->unresolved).radiance, image.radiance));
  }
}

TEST_CASE("Mastin anti-aliasing: a scene setting, not with adaptive sampling") {
  json s = aa_scene(0.1);
  CHECK(parse_scene(s).image.mastin_antialiasing == 0.1);
  s["render"]["pixel_tolerance"] = 0.01;
  try {
    (void)parse_scene(s);
    FAIL("accepted with pixel_tolerance");
  } catch (const SceneError& e) {
    CHECK(e.path() == "render.mastin_antialiasing");
  }
  s = aa_scene(0.0);
  s["render"]["mastin_antialiasing"] = 0;
  CHECK_THROWS_AS((void)parse_scene(s), SceneError);
}

TEST_CASE("Mastin anti-aliasing at the most samples: 32 x 32 and 16 more, each weighted alike") {
  // 1024 + 16 samples: the resolve's fixed-grid estimate holds all of them (it held 1024 once).
  json s = aa_scene(1e-3);
  s["render"]["width"] = 4;
  s["render"]["height"] = 3;
  s["camera"]["look_at"] = {0, 2.5, 14};  // the horizon across the middle row
  const auto r = aa_prepare(s, Renderer::raster, 1024);
  const RenderedImage image = render(r->job, r->unresolved);
  CHECK(image.antialiased_pixels > 0);
  for (const Vec3& e : image.pixel_error) {
    for (const double v : e) CHECK(std::isfinite(v));
  }
}
