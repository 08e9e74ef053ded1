// shading.model four_term in the renderer: every sea sample's terms are Vincevičius's closed
// forms (shading/four_term.h) at that sample's view, normal and height, lit by the frame's sun
// and sky; the shading toggles remove their term; the model's keys are unused in the other model.
#include <doctest/doctest.h>

#include <numbers>

#include <nlohmann/json.hpp>

#include "raster/renderer.h"
#include "scene/scene.h"

using namespace oceanref;

namespace {
nlohmann::json four_term_scene_json() {
  return nlohmann::json::parse(R"({"seed": 2, "time": 1.0,
      "waves": {"cascades": {"sizes": [150, 40]}, "resolution": 32, "choppiness": -0.8},
      "camera": {"position": [0, 5, 0], "look_at": [0, 1, 50]},
      "grid": {"columns": 64, "rows": 64},
      "shading": {"model": "four_term",
                  "four_term": {"shininess": 80, "subsurface_height_intensity": 2}},
      "render": {"width": 32, "height": 18, "samples_per_pixel": 4}})");
}
}  // namespace

TEST_CASE("four-term shading: each sample's terms are the closed forms at its point") {
  const Scene scene = parse_scene(four_term_scene_json());
  CHECK(scene.unused.empty());
  const Ocean ocean = realize_ocean(scene.waves, 1);
  const RenderJob job = scene_render_job(scene, ocean, 1);
  const FrameLighting light = frame_lighting(job.sky, job.shading);
  const Vec3 light_colour = scaled(light.sun_radiance, light.sun_solid_angle / std::numbers::pi);
  int sea = 0;
  for (const auto& [px, py] : {std::pair{16, 12}, std::pair{5, 15}, std::pair{27, 17},
                               std::pair{20, 14}, std::pair{9, 16}, std::pair{30, 13}}) {
    for (const SampleProbe& p : probe_pixel(job, {1e-4, 1e-4}, px, py)) {
      if (!p.hit) continue;
      ++sea;
      // Independently: the mirror of V about N, the sky there, the four terms.
      const Vec3 r = combine(2.0 * dot(p.view, p.normal), p.normal, -1.0, p.view);
      const Vec3 sky = r[1] > 0.0 ? sky_radiance_rgb(job.sky, r) : Vec3{};
      const FourTermRadiance t =
          four_term_shading(scene.shading.four_term, p.view, p.normal, light.sun_direction,
                            p.position.y, light_colour, sky);
      for (std::size_t c = 0; c < 3; ++c) {
        CHECK(p.lighting.sun[c] == doctest::Approx(t.specular[c]).epsilon(1e-12));
        CHECK(p.lighting.sky[c] == doctest::Approx(t.reflection[c]).epsilon(1e-12));
        CHECK(p.lighting.sea[c] == doctest::Approx(t.ambient[c] + t.subsurface[c]).epsilon(1e-12));
        CHECK(p.radiance[c] == doctest::Approx(four_term_total(t)[c]).epsilon(1e-12));
        CHECK(p.lighting_error[c] == 0.0);  // closed forms
      }
    }
  }
  CHECK(sea > 20);
}

TEST_CASE("four-term shading: the toggles and the model change the image as they should") {
  const auto render_of = [](const nlohmann::json& j) {
    const Scene scene = parse_scene(j);
    const Ocean ocean = realize_ocean(scene.waves, 1);
    RenderJob job = scene_render_job(scene, ocean, 2);
    job.layers = true;
    return render(job, {1e-4, 1e-4});
  };
  const nlohmann::json base = four_term_scene_json();
  const RenderedImage all = render_of(base);
  for (const char* toggle : {"sun", "sky", "sea"}) {
    CAPTURE(toggle);
    nlohmann::json j = base;
    j["shading"][toggle] = false;
    const RenderedImage off = render_of(j);
    const std::vector<Vec3>& layer = std::string(toggle) == "sun"   ? off.sun
                                     : std::string(toggle) == "sky" ? off.sky
                                                                    : off.sea;
    double left = 0.0, before = 0.0;
    for (std::size_t i = 0; i < layer.size(); ++i) {
      left += layer[i][1];
      before += (std::string(toggle) == "sun"   ? all.sun
                 : std::string(toggle) == "sky" ? all.sky
                                                : all.sea)[i][1];
    }
    CHECK(left == 0.0);
    CHECK(before > 0.0);
  }
  nlohmann::json bruneton = base;
  bruneton["shading"].erase("four_term");
  bruneton["shading"]["model"] = "bruneton";
  CHECK(render_of(bruneton).radiance != all.radiance);
  // The other model's keys do nothing and are reported.
  nlohmann::json mixed = base;
  mixed["shading"]["sea_colour"] = {0.1, 0.2, 0.3};
  const Scene s = parse_scene(mixed);
  REQUIRE(s.unused.size() == 1);
  CHECK(s.unused[0].path == "shading.sea_colour");
  // Out-of-range parameters name their key.
  nlohmann::json bad = base;
  bad["shading"]["four_term"]["shininess"] = 0.5;
  CHECK_THROWS_WITH_AS(parse_scene(bad), doctest::Contains("shading.four_term.shininess"),
                       SceneError);
  bad = base;
  bad["shading"]["four_term"]["specular_colour"] = {0.5, -0.1, 0.2};
  CHECK_THROWS_WITH_AS(parse_scene(bad), doctest::Contains("specular_colour[1]"), SceneError);
}
