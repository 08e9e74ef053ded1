// The renderer: a flat mirror sea against the analytic answer, depth against ray–plane
// intersection, the horizon, viewing cases, and thread-count determinism.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <utility>

#include <nlohmann/json.hpp>

#include "core/check.h"
#include "raster/renderer.h"
#include "scene/scene.h"

using namespace oceanref;

namespace {

Scene small_scene(const std::string& camera) {
  const auto j = nlohmann::json::parse(R"({"seed": 4, "time": 2.0,
      "waves": {"cascades": {"sizes": [120, 35]}, "resolution": 32, "choppiness": -0.7},
      "grid": {"columns": 96, "rows": 96},
      "atmosphere": {"sun_zenith_deg": 60, "sun_azimuth_deg": 80, "turbidity": 3},
      "shading": {"whitecaps": true, "accuracy": "fast", "sky_order": 3, "sun_order": 1},
      "render": {"width": 48, "height": 27, "samples_per_pixel": 1}})");
  auto s = j;
  s["camera"] = nlohmann::json::parse(camera);
  return parse_scene(s);
}

struct Setup {
  Scene scene;
  Ocean ocean;
  RenderJob job;
};

std::unique_ptr<Setup> prepare(const Scene& scene, int threads) {
  auto s = std::make_unique<Setup>();
  s->scene = scene;
  s->ocean = realize_ocean(scene.waves, 1);
  s->job = scene_render_job(s->scene, s->ocean, threads);
  s->job.layers = true;  // the tests read the terms, depth and normals
  return s;
}
}  // namespace

TEST_CASE("a flat mirror sea reflects the Preetham sky exactly; depth and horizon are analytic") {
  auto s = prepare(small_scene(R"({"position": [0, 5, 0], "look_at": [0, 1, 60]})"), 2);
  for (CascadeSpectra& c : s->ocean.cascades) {  // a flat sea: no waves
    for (Complex& h : c.high.h0) h = 0.0;
    for (Complex& h : c.low.h0) h = 0.0;
  }
  s->job.shading.sun = false;
  s->job.shading.whitecaps = false;
  const SlopeVariance smooth{1e-10, 1e-10};
  const RenderedImage image = render(s->job, smooth);
  const Camera& cam = s->job.camera;
  const Vec3 e_sky = sky_irradiance(s->job.sky).rgb;
  int sea = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y * image.width + x);
      const glm::dvec3 d = ray_direction(cam, x + 0.5, y + 0.5);
      CAPTURE(x);
      CAPTURE(y);
      if (d.y > 0.0) {
        CHECK(image.coverage[i] == 0.0);  // above the horizon: sky
        continue;
      }
      if (d.y > -1e-3) continue;  // within the far end of the grid: either
      REQUIRE(image.coverage[i] == 1.0);
      ++sea;
      // Depth: the ray meets y = 0 at t = 5/|d_y|; view depth t·(d·forward).
      const double t = cam.position.y / -d.y;
      CHECK(image.depth[i] == doctest::Approx(t * glm::dot(d, cam.forward)).epsilon(1e-9));
      // Radiance: F(cos) L_sky(mirror) + (1 − F) sea E_sky/π, F exact Fresnel at V·N = −d_y.
      const double cos_v = -d.y;
      const double f = fresnel_reflectance(cos_v);
      const Vec3 sky = sky_radiance_rgb(s->job.sky, {d.x, -d.y, d.z});
      for (std::size_t c = 0; c < 3; ++c) {
        const double expected =
            f * sky[c] + (1.0 - f) * s->job.shading.sea_colour[c] * e_sky[c] / std::numbers::pi;
        CHECK(image.radiance[i][c] == doctest::Approx(expected).epsilon(1e-6));
      }
    }
  }
  CHECK(sea > 200);
}

TEST_CASE("every viewing case renders an image within its energy bounds") {
  // Per pixel (1 sample): the sky exactly where no sea is seen; where it is, each lighting term
  // within what energy allows — sun ≤ L_sun (a reflectance ≤ 1), sky ≤ the brightest sky
  // radiance (albedo ≤ 1; 2 % for the order-3 Gauss–Hermite normalization, largest ratio
  // measured 0.32), sea ≤ (1 − F(0°))·colour·E_sky/π (F̄ ≥ F(0°)), foam ≤ albedo·(L_sun Ω_sun +
  // E_sky)/π — and the pixel ≤ their sum (the whitecap mix is a convex combination).
  for (const char* camera :
       {R"({"position": [0, 40, 0], "look_at": [10, 0, 60]})",      // high, looking down
        R"({"position": [0, 3, 0], "look_at": [0, 3, 100]})",       // at the horizon
        R"({"position": [0, 0.3, 0], "look_at": [0, 0.1, 20]})",    // close to the surface
        R"({"position": [0, 0.05, 0], "look_at": [0, 0.05, 30]})",  // inside the volume
        R"({"position": [0, 5, 0], "look_at": [0, 40, 30]})"}) {    // looking up
    CAPTURE(camera);
    auto s = prepare(small_scene(camera), 2);
    const RenderedImage image = render(s->job, unresolved_slope_variance(s->job, s->scene.waves));
    const FrameLighting light = frame_lighting(s->job.sky, s->job.shading);
    Vec3 brightest = sky_radiance_rgb(s->job.sky, s->job.sky.sun_direction);
    for (int z = 0; z <= 180; ++z) {  // 0.5° × 1°, and the sun's own direction
      for (int a = 0; a < 360; ++a) {
        const Vec3 l = sky_radiance_rgb(
            s->job.sky,
            direction_from_angles(z * std::numbers::pi / 360.0, a * std::numbers::pi / 180.0));
        for (std::size_t c = 0; c < 3; ++c) brightest[c] = std::fmax(brightest[c], l[c]);
      }
    }
    const double f0 = fresnel_reflectance(1.0);
    const ShadingSettings& sh = s->job.shading;
    int sea = 0, sky = 0;
    for (int y = 0; y < image.height; ++y) {
      for (int x = 0; x < image.width; ++x) {
        const std::size_t i = static_cast<std::size_t>(y * image.width + x);
        CAPTURE(x);
        CAPTURE(y);
        REQUIRE((image.coverage[i] == 0.0 || image.coverage[i] == 1.0));
        if (image.coverage[i] == 0.0) {
          ++sky;
          const glm::dvec3 d = ray_direction(s->job.camera, x + 0.5, y + 0.5);
          Vec3 expected = sky_radiance_rgb(s->job.sky, {d.x, d.y, d.z});
          if (d.x * light.sun_direction[0] + d.y * light.sun_direction[1] +
                  d.z * light.sun_direction[2] >=
              light.cos_sun_radius) {
            for (std::size_t c = 0; c < 3; ++c) expected[c] += light.sun_radiance[c];
          }
          CHECK(image.radiance[i] == expected);
          continue;
        }
        ++sea;
        for (std::size_t c = 0; c < 3; ++c) {
          const double sea_bound =
              (1.0 - f0) * sh.sea_colour[c] * light.sky_irradiance[c] / std::numbers::pi;
          const double foam_bound =
              sh.foam_albedo *
              (light.sun_radiance[c] * light.sun_solid_angle + light.sky_irradiance[c]) /
              std::numbers::pi;
          CHECK((image.sun[i][c] >= 0.0 && image.sun[i][c] <= light.sun_radiance[c]));
          CHECK((image.sky[i][c] >= 0.0 && image.sky[i][c] <= 1.02 * brightest[c]));
          CHECK((image.sea[i][c] >= 0.0 && image.sea[i][c] <= sea_bound * (1.0 + 1e-12)));
          CHECK((image.foam[i][c] >= 0.0 && image.foam[i][c] <= foam_bound * (1.0 + 1e-12)));
          CHECK(image.radiance[i][c] >= 0.0);
          CHECK(image.radiance[i][c] <=
                (image.sun[i][c] + image.sky[i][c] + image.sea[i][c] + image.foam[i][c]) *
                    (1.0 + 1e-12));
        }
      }
    }
    CHECK(sea + sky == image.width * image.height);
  }
}

TEST_CASE("render determinism: identical pixels for 1, 2, 3 and 8 threads and across runs") {
  const Scene scene = small_scene(R"({"position": [0, 6, 0], "look_at": [0, 1, 50]})");
  auto reference = prepare(scene, 1);
  const SlopeVariance u = unresolved_slope_variance(reference->job, scene.waves);
  const RenderedImage a = render(reference->job, u);
  for (const int threads : {1, 2, 3, 8}) {
    auto s = prepare(scene, threads);
    const RenderedImage b = render(s->job, u);
    CHECK(b.radiance == a.radiance);
    CHECK(b.depth == a.depth);
  }
}

TEST_CASE("the layers are filled only when asked, and never change the radiance") {
  const Scene scene = small_scene(R"({"position": [0, 6, 0], "look_at": [0, 1, 50]})");
  auto s = prepare(scene, 2);
  const SlopeVariance u = unresolved_slope_variance(s->job, scene.waves);
  const RenderedImage with = render(s->job, u);
  s->job.layers = false;
  const RenderedImage without = render(s->job, u);
  const std::size_t pixels = with.radiance.size();
  for (const auto* layer : {&with.sun, &with.sky, &with.sea, &with.foam, &with.normal, &with.x0}) {
    CHECK(layer->size() == pixels);
  }
  CHECK(with.depth.size() == pixels);
  for (const auto* layer :
       {&without.sun, &without.sky, &without.sea, &without.foam, &without.normal, &without.x0}) {
    CHECK(layer->empty());
  }
  CHECK(without.depth.empty());
  CHECK(without.radiance == with.radiance);
  CHECK(without.coverage == with.coverage);
  CHECK(without.lighting_error == with.lighting_error);
}

TEST_CASE("a band of rows renders the same bits as those rows of the whole image") {
  const Scene scene = small_scene(R"({"position": [0, 6, 0], "look_at": [0, 1, 50]})");
  auto s = prepare(scene, 2);
  const SlopeVariance u = unresolved_slope_variance(s->job, scene.waves);
  const RenderedImage whole = render(s->job, u);
  const int h = whole.height;
  REQUIRE(h >= 8);
  int covered = 0;
  for (const std::pair<int, int>& range : {std::pair{0, 1}, std::pair{1, 4}, std::pair{4, h - 1},
                                           std::pair{h - 1, h}, std::pair{2, h}}) {
    const int first = range.first;  // (clang 14 cannot capture a structured binding)
    const int last = range.second;
    CAPTURE(first);
    CAPTURE(last);
    s->job.first_row = first;
    s->job.last_row = last;
    const RenderedImage band = render(s->job, u);
    REQUIRE(band.height == last - first);
    REQUIRE(band.first_row == first);
    REQUIRE(band.width == whole.width);
    const auto offset = static_cast<std::size_t>(first) * static_cast<std::size_t>(whole.width);
    for (std::size_t i = 0; i < band.radiance.size(); ++i) {
      const std::size_t j = offset + i;
      CHECK(band.radiance[i] == whole.radiance[j]);
      CHECK(band.lighting_error[i] == whole.lighting_error[j]);
      CHECK(band.coverage[i] == whole.coverage[j]);
      CHECK(band.sky[i] == whole.sky[j]);
      CHECK(band.depth[i] == whole.depth[j]);
      CHECK(band.normal[i] == whole.normal[j]);
      covered += band.coverage[i] > 0.0 ? 1 : 0;
    }
  }
  CHECK(covered > 0);  // the bands see the sea
  s->job.first_row = 3;
  s->job.last_row = 3;
  CHECK_THROWS_AS(render(s->job, u), PreconditionError);
  s->job.last_row = h + 1;
  CHECK_THROWS_AS(render(s->job, u), PreconditionError);
}

TEST_CASE(
    "reference lighting: the error layer is within the tolerance; accuracy and tolerance "
    "change the image") {
  auto s = prepare(small_scene(R"({"position": [0, 4, 0], "look_at": [0, 1, 60]})"), 2);
  s->job.shading.accuracy = LightingAccuracy::reference;
  s->job.shading.tolerance = 1e-6;
  s->job.camera.width = 20;  // the reference costs ~1 ms per sample: keep the image small
  s->job.camera.height = 11;
  const SlopeVariance unresolved = unresolved_slope_variance(s->job, s->scene.waves);
  const RenderedImage reference = render(s->job, unresolved);
  CHECK(reference.unconverged_samples == 0);
  CHECK(reference.integrand_evaluations > 0);
  int sea = 0;
  for (std::size_t i = 0; i < reference.radiance.size(); ++i) {
    if (!(reference.coverage[i] > 0.0)) continue;
    ++sea;
    for (std::size_t c = 0; c < 3; ++c) {
      // Every term within max(tol·|term|, tol·1e-3·E/π): the sum within ~1.1·tol of the pixel.
      CHECK(reference.lighting_error[i][c] > 0.0);
      CHECK(reference.lighting_error[i][c] <= 1.1e-6 * reference.radiance[i][c]);
    }
  }
  CHECK(sea > 100);
  // A tighter tolerance changes the bits but not beyond the estimates.
  s->job.shading.tolerance = 1e-7;
  const RenderedImage tighter = render(s->job, unresolved);
  bool differs = false;
  for (std::size_t i = 0; i < reference.radiance.size(); ++i) {
    for (std::size_t c = 0; c < 3; ++c) {
      const double d = std::fabs(reference.radiance[i][c] - tighter.radiance[i][c]);
      differs = differs || d > 0.0;
      CHECK(d <= reference.lighting_error[i][c] + tighter.lighting_error[i][c]);
    }
  }
  CHECK(differs);
  // Fast accuracy: its error layer is |fast − reference| + the reference's estimate.
  s->job.shading.accuracy = LightingAccuracy::fast;
  s->job.shading.tolerance = 1e-6;
  s->job.estimate_fast_error = true;
  const RenderedImage fast = render(s->job, unresolved);
  double largest = 0.0;
  for (std::size_t i = 0; i < fast.radiance.size(); ++i) {
    for (std::size_t c = 0; c < 3; ++c) {
      const double d = std::fabs(fast.radiance[i][c] - reference.radiance[i][c]);
      CHECK(fast.lighting_error[i][c] >= d - 1e-12 * reference.radiance[i][c]);
      largest = std::fmax(largest, d / std::fmax(reference.radiance[i][c], 1e-300));
    }
  }
  CHECK(largest > 1e-3);  // order 3/1 is far from converged: the setting matters
  s->job.estimate_fast_error = false;
  const RenderedImage plain = render(s->job, unresolved);
  CHECK(plain.radiance == fast.radiance);  // estimating the error does not change the image
  CHECK(plain.lighting_error[0] == Vec3{0.0, 0.0, 0.0});
}
