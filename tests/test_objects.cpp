// Objects in the scene (issue 17, point 4): the `objects` section parsed strictly, OBJ meshes
// placed in the world, both renderers showing them depth-tested against the sea, and the ray
// tracer's reflections of them.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "conformance/scene_objects.h"
#include "raster/renderer.h"
#include "scene/scene.h"
#include "shading/ocean_lighting.h"
#include "temp_dir.h"
#include "test_support.h"

using namespace oceanref;
using nlohmann::json;

namespace {

const std::string kObjectsBuoy = OCEANREF_SOURCE_DIR "/reference/objects/buoy.obj";

// A small scene looking at the buoy from 12 m; fast lighting.
json objects_scene() {
  return json::parse(R"({
    "seed": 1,
    "waves": {"spectrum": {"model": "jonswap", "wind_speed": 8, "fetch": 50000,
                           "wind_direction_deg": 80},
              "cascades": {"sizes": [200, 37]}, "resolution": 32, "choppiness": -0.8},
    "camera": {"position": [0, 2.5, 0], "look_at": [0, 0.6, 14], "vertical_fov_deg": 40},
    "grid": {"columns": 96, "rows": 96},
    "atmosphere": {"sun_zenith_deg": 70, "sun_azimuth_deg": 60},
    "shading": {"accuracy": "fast"},
    "render": {"width": 60, "height": 40, "samples_per_pixel": 4},
    "objects": [{"obj": "", "position": [0, 0, 12], "rotation_deg": [0, 20, 5], "scale": 1.5,
                 "material": {"albedo": [0.8, 0.15, 0.1]}}]})");
}

json objects_scene_with(const std::string& obj) {
  json s = objects_scene();
  s["objects"][0]["obj"] = obj;
  return s;
}

// Renders the scene with the given renderer (and reflections); `objects` false: without them.
RenderedImage objects_render(const json& document, Renderer renderer, bool reflections = true,
                             bool objects = true, int threads = 2) {
  const Scene scene = parse_scene(document);
  const Ocean ocean = realize_ocean(scene.waves, threads);
  const SceneObjects loaded = load_scene_objects(scene);
  RenderJob job = scene_render_job(scene, ocean, threads);
  job.renderer = renderer;
  job.object_reflections = reflections;
  job.layers = true;
  if (objects) job.objects = &loaded;
  return render(job, unresolved_slope_variance(job, scene.waves));
}

double objects_max_difference(const RenderedImage& a, const RenderedImage& b) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.radiance.size(); ++i) {
    for (std::size_t c = 0; c < 3; ++c) {
      const double scale = std::fmax(std::fabs(b.radiance[i][c]), 1e-300);
      worst = std::fmax(worst, std::fabs(a.radiance[i][c] - b.radiance[i][c]) / scale);
    }
  }
  return worst;
}

}  // namespace

TEST_CASE("objects: placement is scale, then rotations about x, y, z, then translation") {
  ObjectSettings o;
  o.scale = 2.0;
  o.position = {1.0, 2.0, 3.0};
  CHECK(object_to_world(o, {1.0, 0.0, 0.0}) == glm::dvec3(3.0, 2.0, 3.0));
  // 90° about y (right-handed): +x goes to -z.
  o.rotation_deg = {0.0, 90.0, 0.0};
  glm::dvec3 p = object_to_world(o, {1.0, 0.0, 0.0});
  CHECK(p.x == doctest::Approx(1.0).epsilon(1e-15));
  CHECK(p.z == doctest::Approx(1.0).epsilon(1e-15));  // 3 - 2
  // x first, then z: 90° about x takes +y to +z, then 90° about z leaves z alone; +x goes to +y.
  o = ObjectSettings{};
  o.rotation_deg = {90.0, 0.0, 90.0};
  p = object_to_world(o, {0.0, 1.0, 0.0});
  CHECK(std::fabs(p.x) < 1e-15);
  CHECK(std::fabs(p.y) < 1e-15);
  CHECK(p.z == doctest::Approx(1.0).epsilon(1e-15));
  p = object_to_world(o, {1.0, 0.0, 0.0});
  CHECK(p.y == doctest::Approx(1.0).epsilon(1e-15));
  // Rotations keep lengths.
  o.rotation_deg = {17.0, -123.0, 301.0};
  CHECK(glm::length(object_to_world(o, {0.3, -0.4, 1.2})) ==
        doctest::Approx(std::sqrt(0.09 + 0.16 + 1.44)).epsilon(1e-14));
}

TEST_CASE("objects: the section is validated key by key") {
  const auto error_of = [](const json& document) -> std::string {
    try {
      (void)parse_scene(document);
    } catch (const SceneError& e) {
      return e.path();
    }
    return "";
  };
  json s = objects_scene_with("a.obj");
  CHECK(error_of(s) == "");
  CHECK(parse_scene(s).objects.size() == 1);
  CHECK(parse_scene(s).objects[0].scale == 1.5);
  s["objects"][0].erase("obj");
  CHECK(error_of(s) == "objects[0].obj");
  s = objects_scene_with("a.obj");
  s["objects"][0]["colour"] = 1;
  CHECK(error_of(s) == "objects[0].colour");
  s = objects_scene_with("a.obj");
  s["objects"][0]["material"]["albedo"] = json::array({0.5, -0.1, 0.5});
  CHECK(error_of(s) == "objects[0].material.albedo[1]");
  s = objects_scene_with("a.obj");
  s["objects"][0]["scale"] = 0;
  CHECK(error_of(s) == "objects[0].scale");
  s = objects_scene_with("a.obj");
  s["objects"] = json::object();
  CHECK(error_of(s) == "objects");
  // At most kMaxSceneObjects (64) objects: 64 are read, the 65th is refused with the limit.
  s = objects_scene_with("a.obj");
  s["objects"] = json::array();
  for (std::size_t i = 0; i < kMaxSceneObjects; ++i) s["objects"].push_back({{"obj", "a.obj"}});
  CHECK(error_of(s) == "");
  CHECK(parse_scene(s).objects.size() == 64);
  s["objects"].push_back({{"obj", "a.obj"}});
  CHECK(error_of(s) == "objects");
  CHECK_THROWS_WITH_AS(parse_scene(s), doctest::Contains("at most 64 objects"), SceneError);
}

TEST_CASE("objects: OBJ files are read relative to the scene, and their errors name the key") {
  testing::TempDir dir;
  std::filesystem::copy_file(kObjectsBuoy, dir.file("buoy.obj"));
  json s = objects_scene_with("buoy.obj");
  {
    std::ofstream(dir.file("scene.json")) << s.dump();
    const Scene scene = load_scene(dir.file("scene.json"), nullptr);
    const SceneObjects o = load_scene_objects(scene);
    CHECK(o.triangles.size() > 100);
    CHECK(o.material.size() == o.triangles.size());
    REQUIRE(o.materials.size() == 1);
    CHECK(o.materials[0].albedo == std::array<double, 3>{0.8, 0.15, 0.1});
  }
  std::ofstream(dir.file("broken.obj")) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n";
  s = objects_scene_with("broken.obj");
  std::ofstream(dir.file("scene.json")) << s.dump();
  const Scene scene = load_scene(dir.file("scene.json"), nullptr);
  try {
    (void)load_scene_objects(scene);
    FAIL("a face index beyond the vertices was accepted");
  } catch (const SceneError& e) {
    CHECK(e.path() == "objects[0].obj");
    CHECK(std::string(e.what()).find("broken.obj:4:") != std::string::npos);
  }
}

TEST_CASE("objects: the two renderers agree on objects; the ray tracer adds their reflections") {
  const json s = objects_scene_with(kObjectsBuoy);
  const RenderedImage raster = objects_render(s, Renderer::raster);
  const RenderedImage plain = objects_render(s, Renderer::raytrace, false);
  const RenderedImage reflecting = objects_render(s, Renderer::raytrace, true);
  const RenderedImage sea = objects_render(s, Renderer::raster, true, false);
  // Where both see the same surfaces: the rasterizer and the ray tracer without reflections
  // agree as on the sea alone (tests/test_tracer.cpp: within 1e-9, rounding of the weights).
  CHECK(objects_max_difference(plain, raster) < 1e-9);
  // The object is seen: pixels differ from the sea alone, and the object's pixels hold no sea.
  int object_pixels = 0, reflection_pixels = 0;
  for (std::size_t i = 0; i < raster.radiance.size(); ++i) {
    if (raster.radiance[i] != sea.radiance[i]) ++object_pixels;
    if (reflecting.radiance[i] != plain.radiance[i]) {
      ++reflection_pixels;
      // A reflection is in the sea's sky term, below the object: a pixel the sea covers.
      CHECK(reflecting.coverage[i] > 0.0);
      CHECK(reflecting.sky[i] != plain.sky[i]);
      CHECK(reflecting.sun[i] == plain.sun[i]);
    }
  }
  MESSAGE("object pixels " << object_pixels << ", reflecting pixels " << reflection_pixels);
  CHECK(object_pixels > 40);
  CHECK(reflection_pixels > 10);
  // The same bits for any thread count, reflections included.
  const RenderedImage one = objects_render(s, Renderer::raytrace, true, true, 1);
  CHECK(testing::same_bits(one.radiance, reflecting.radiance));
}

TEST_CASE("objects: an object under the surface is hidden by it; its radiance is the model's") {
  json s = objects_scene_with(kObjectsBuoy);
  // 6 m under the rest level, far more than the waves' amplitude: the sea is in front.
  s["objects"][0]["position"] = json::array({0, -6, 12});
  const RenderedImage sea = objects_render(s, Renderer::raster, true, false);
  CHECK(testing::same_bits(objects_render(s, Renderer::raster).radiance, sea.radiance));
  CHECK(testing::same_bits(objects_render(s, Renderer::raytrace, false).radiance,
                           objects_render(s, Renderer::raytrace, false, false).radiance));
  // Above the sea, a pixel the buoy covers fully: every sample is the Lambertian model,
  // ρ/π(E_sun max(0, n·s) + E_sky (1 + n_y)/2), evaluated here from the probe's normal.
  s = objects_scene_with(kObjectsBuoy);
  const Scene scene = parse_scene(s);
  const Ocean ocean = realize_ocean(scene.waves, 2);
  const SceneObjects loaded = load_scene_objects(scene);
  RenderJob job = scene_render_job(scene, ocean, 2);
  job.objects = &loaded;
  const SlopeVariance u = unresolved_slope_variance(job, scene.waves);
  const FrameLighting light = frame_lighting(job.sky, job.shading);
  int checked = 0;
  for (int y = 0; y < scene.image.height && checked == 0; ++y) {
    const std::vector<SampleProbe> probe = probe_pixel(job, u, scene.image.width / 2, y);
    bool all = true;
    for (const SampleProbe& p : probe) all = all && p.object;
    if (!all) continue;
    for (const SampleProbe& p : probe) {
      CHECK(std::fabs(length(p.normal) - 1.0) < 1e-15);
      const double cos_sun = std::fmax(0.0, dot(p.normal, light.sun_direction));
      for (std::size_t c = 0; c < 3; ++c) {
        const double expected = loaded.materials[0].albedo[c] / testing::kPi *
                                (light.sun_radiance[c] * light.sun_solid_angle * cos_sun +
                                 light.sky_irradiance[c] * 0.5 * (1.0 + p.normal[1]));
        CHECK(p.radiance[c] == doctest::Approx(expected).epsilon(1e-14));
      }
      ++checked;
    }
  }
  CHECK(checked == 4);
}

TEST_CASE("objects: every setting of an object changes the image") {
  const json base = objects_scene_with(kObjectsBuoy);
  const RenderedImage before = objects_render(base, Renderer::raster);
  const auto changed = [&](const char* key, const json& value) {
    json s = base;
    if (std::string(key) == "albedo") {
      s["objects"][0]["material"]["albedo"] = value;
    } else {
      s["objects"][0][key] = value;
    }
    return !testing::same_bits(objects_render(s, Renderer::raster).radiance, before.radiance);
  };
  CHECK(changed("position", json::array({0.5, 0, 12})));
  CHECK(changed("rotation_deg", json::array({0, 60, 5})));
  CHECK(changed("scale", 1.2));
  CHECK(changed("albedo", json::array({0.2, 0.5, 0.1})));
  json other = base;
  other["render"]["renderer"] = "raytrace";  // render.renderer: the ray tracer's reflections
  const Scene scene = parse_scene(other);
  CHECK(scene.image.renderer == Renderer::raytrace);
  CHECK(scene_render_job(scene, realize_ocean(scene.waves, 1), 1).renderer == Renderer::raytrace);
}
