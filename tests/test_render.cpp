// The renderer: a flat mirror sea against the analytic answer, depth against ray–plane
// intersection, the horizon, viewing cases, and thread-count determinism.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include <nlohmann/json.hpp>

#include "raster/renderer.h"
#include "scene/scene.h"

using namespace oceanref;

namespace {

Scene small_scene(const std::string& camera) {
  const auto j = nlohmann::json::parse(R"({"seed": 4, "time": 2.0,
      "waves": {"cascades": {"sizes": [120, 35]}, "resolution": 32, "choppiness": -0.7},
      "grid": {"columns": 96, "rows": 96},
      "atmosphere": {"sun_zenith_deg": 60, "sun_azimuth_deg": 80, "turbidity": 3},
      "shading": {"whitecaps": true, "sky_order": 3, "sun_order": 1},
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
  const WindSlopeVariance smooth{1e-10, 1e-10};
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

TEST_CASE("every viewing case renders a valid image (no NaN, nothing negative)") {
  for (const char* camera :
       {R"({"position": [0, 40, 0], "look_at": [10, 0, 60]})",      // high, looking down
        R"({"position": [0, 3, 0], "look_at": [0, 3, 100]})",       // at the horizon
        R"({"position": [0, 0.3, 0], "look_at": [0, 0.1, 20]})",    // close to the surface
        R"({"position": [0, 0.05, 0], "look_at": [0, 0.05, 30]})",  // inside the volume
        R"({"position": [0, 5, 0], "look_at": [0, 40, 30]})"}) {    // looking up
    CAPTURE(camera);
    auto s = prepare(small_scene(camera), 2);
    const RenderedImage image = render(s->job, unresolved_slope_variance(s->job, s->scene.waves));
    for (const Vec3& c : image.radiance) {
      for (const double v : c) CHECK((std::isfinite(v) && v >= 0.0));
    }
  }
}

TEST_CASE("render determinism: identical pixels for 1, 2, 3 and 8 threads and across runs") {
  const Scene scene = small_scene(R"({"position": [0, 6, 0], "look_at": [0, 1, 50]})");
  auto reference = prepare(scene, 1);
  const WindSlopeVariance u = unresolved_slope_variance(reference->job, scene.waves);
  const RenderedImage a = render(reference->job, u);
  for (const int threads : {1, 2, 3, 8}) {
    auto s = prepare(scene, threads);
    const RenderedImage b = render(s->job, u);
    CHECK(b.radiance == a.radiance);
    CHECK(b.depth == a.depth);
  }
}
