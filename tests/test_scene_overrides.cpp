// Scene overrides on the command line (`render --set KEY=VALUE`, apply_scene_override): applied
// to the document before parsing, so an override is validated as in a file, names its key in an
// error, and is part of the scene the outputs record (Scene::canonical).
#include <doctest/doctest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "scene/scene.h"

using namespace oceanref;
using nlohmann::json;

TEST_CASE("scene overrides: values, paths, removal and the recorded scene") {
  json d = json::parse(R"({"waves": {}, "shading": {"accuracy": "reference", "tolerance": 1e-6},
                           "render": {"width": 640}})");
  apply_scene_override(d, "shading.accuracy=fast");         // a bare word: a string
  apply_scene_override(d, "shading.tolerance=null");        // removed: its default applies
  apply_scene_override(d, "render.width=64");               // JSON: a number
  apply_scene_override(d, "render.height=36");              // a new key
  apply_scene_override(d, "atmosphere.sun_zenith_deg=60");  // a new section
  apply_scene_override(d, R"(camera.position=[0, 3, 0])");  // JSON: an array
  apply_scene_override(d, "render.renderer=\"raytrace\"");  // JSON: a quoted string
  CHECK(d["shading"] == json::parse(R"({"accuracy": "fast"})"));
  CHECK(d["render"]["width"] == 64);
  CHECK(d["render"]["height"] == 36);
  CHECK(d["atmosphere"]["sun_zenith_deg"] == 60);
  CHECK(d["camera"]["position"] == json::parse("[0, 3, 0]"));
  CHECK(d["render"]["renderer"] == "raytrace");
  const Scene scene = parse_scene(d);
  CHECK(scene.shading.accuracy == LightingAccuracy::fast);
  CHECK(scene.image.width == 64);
  CHECK(scene.atmosphere.sun_zenith_deg == 60.0);
  CHECK(scene.canonical.find("\"fast\"") != std::string::npos);  // what the EXR header records
  // The last of two overrides of one key wins.
  apply_scene_override(d, "render.width=32");
  CHECK(parse_scene(d).image.width == 32);
}

TEST_CASE("scene overrides: errors name the key") {
  json d = json::parse(R"({"waves": {}, "shading": {"accuracy": "fast"}})");
  CHECK_THROWS_WITH_AS(apply_scene_override(d, "render.width"),
                       doctest::Contains("expected KEY=VALUE"), SceneError);
  CHECK_THROWS_WITH_AS(apply_scene_override(d, "=3"), doctest::Contains("expected KEY=VALUE"),
                       SceneError);
  CHECK_THROWS_WITH_AS(apply_scene_override(d, "render..width=3"),
                       doctest::Contains("an empty part"), SceneError);
  CHECK_THROWS_WITH_AS(apply_scene_override(d, "shading.accuracy.x=1"),
                       doctest::Contains("shading.accuracy is not an object"), SceneError);
  // Validated as in a file: an unknown key, a value out of range, the other mode's key.
  json unknown = d;
  apply_scene_override(unknown, "render.widht=3");
  CHECK_THROWS_WITH_AS(parse_scene(unknown), doctest::Contains("render.widht: unknown key"),
                       SceneError);
  json range = d;
  apply_scene_override(range, "render.width=0");
  CHECK_THROWS_WITH_AS(parse_scene(range), doctest::Contains("render.width: must be in [1, 16384]"),
                       SceneError);
  json other = d;
  apply_scene_override(other, "shading.tolerance=1e-3");
  CHECK_THROWS_WITH_AS(parse_scene(other), doctest::Contains("shading.tolerance"), SceneError);
  json not_number = d;
  apply_scene_override(not_number, "render.width=wide");
  CHECK_THROWS_WITH_AS(parse_scene(not_number), doctest::Contains("render.width"), SceneError);
}
