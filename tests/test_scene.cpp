// Scene files: strict validation with JSON paths; EXR round trip; the whole ocean's FFT grids
// against direct summation.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "io/exr.h"
#include "scene/scene.h"

using namespace oceanref;
using nlohmann::json;

namespace {
json minimal() {
  return json::parse(R"({"seed": 3, "time": 1.5, "waves": {"resolution": 16,
      "cascades": {"sizes": [200, 60]}, "choppiness": -0.8}})");
}

std::string error_path(const json& scene) {
  try {
    parse_scene(scene);
  } catch (const SceneError& e) {
    return e.path();
  }
  return "";
}
}  // namespace

TEST_CASE("scene: defaults and values are read") {
  const Scene s = parse_scene(minimal());
  CHECK(s.seed == 3);
  CHECK(s.time == 1.5);
  CHECK(s.waves.sizes == std::vector<double>{200.0, 60.0});
  CHECK(s.waves.resolution == 16);
  CHECK(s.waves.low_resolution == 16);
  CHECK(s.waves.choppiness == std::vector<double>{-0.8, -0.8});
  CHECK(s.waves.minimum_wavelength == kMinimumWavelength);
  json golden = minimal();
  golden["waves"]["cascades"] =
      json::parse(R"({"largest": 100, "count": 3, "factor": "golden-large"})");
  golden["waves"]["choppiness"] = json::array({-1, -0.5, 0});
  const Scene g = parse_scene(golden);
  CHECK(g.waves.sizes.size() == 3);
  CHECK(g.waves.sizes[1] == doctest::Approx(61.803398874989485));
  // Arrays land component by component (the settings-reach test changes both at once).
  json flow = minimal();
  flow["waves"]["synthesis"] = "tiling_and_blending";
  flow["waves"]["tiling"] = json::parse(R"({"flow": "circular", "flow_center": [10, -30]})");
  const Scene f = parse_scene(flow);
  CHECK(f.waves.tiling.flow.center_x == 10.0);
  CHECK(f.waves.tiling.flow.center_z == -30.0);
  flow["camera"] = json::parse(R"({"position": [1, 20, -3], "look_at": [4, -5, 60]})");
  const Scene c = parse_scene(flow);
  CHECK(c.camera.position == glm::dvec3{1.0, 20.0, -3.0});
  CHECK(c.camera.look_at == glm::dvec3{4.0, -5.0, 60.0});
}

TEST_CASE("scene: every bad value is rejected with its JSON path") {
  json s = minimal();
  s["colour"] = 1;
  CHECK(error_path(s) == "colour");
  s = minimal();
  s["waves"]["resolution"] = 48;  // not a power of two
  CHECK(error_path(s) == "waves.resolution");
  s = minimal();
  s["waves"]["resolution"] = 16.5;
  CHECK(error_path(s) == "waves.resolution");
  s = minimal();
  s["waves"]["low_resolution"] = 32;  // above resolution
  CHECK(error_path(s) == "waves.low_resolution");
  s = minimal();
  s["waves"]["choppiness"] = 0.5;  // u > 0
  CHECK(error_path(s) == "waves.choppiness");
  s["waves"]["allow_positive_choppiness"] = true;
  CHECK(error_path(s).empty());
  s = minimal();
  s["waves"]["choppiness"] = json::array({-1});  // one per cascade
  CHECK(error_path(s) == "waves.choppiness");
  s = minimal();
  s["waves"]["cascades"]["sizes"] = json::array({60, 200});  // increasing with partitioning
  CHECK(error_path(s) == "waves.cascades");
  // Strictly decreasing: two equal sizes would own the same band (the end of the range).
  s["waves"]["cascades"]["sizes"] = json::array({200, 60, 60});
  CHECK(error_path(s) == "waves.cascades");
  s["waves"]["cascades"]["sizes"] = json::array({200, 60, 59.999});
  CHECK(error_path(s).empty());
  s["waves"]["band_partitioning"] = false;  // without partitioning, any order
  s["waves"]["cascades"]["sizes"] = json::array({60, 60, 200});
  CHECK(error_path(s).empty());
  s = minimal();
  s["waves"]["cascades"]["sizes"][1] = "big";
  CHECK(error_path(s) == "waves.cascades.sizes[1]");
  s = minimal();
  s["waves"]["spectrum"]["wind_speed"] = 75;
  CHECK(error_path(s) == "waves.spectrum.wind_speed");
  // A number too large for a double is a parse error of the file, named by its path.
  const std::string file = (std::filesystem::temp_directory_path() / "oceanref_huge.json").string();
  {
    std::ofstream out(file);
    out << R"({"waves": {"spectrum": {"wind_speed": 1e999}}})";
  }
  CHECK_THROWS_WITH_AS(load_scene(file),
                       "waves.spectrum.wind_speed: the number 1e999 is out of the range of a "
                       "double (accepted: finite numbers, magnitude at most "
                       "1.7976931348623157e+308)",
                       SceneError);
  std::filesystem::remove(file);
  s = minimal();
  s["waves"]["spreading"] = json::parse(R"({"model": "cos3"})");
  CHECK(error_path(s) == "waves.spreading.model");
  s = minimal();
  s["waves"]["spreading"] = json::parse(R"({"model": "donelan", "swell": 0.5})");
  CHECK(error_path(s) == "waves.spreading.swell");
  s = minimal();
  s["objects"] = json::array({json::object()});  // an object without its OBJ file
  CHECK(error_path(s) == "objects[0].obj");
  s = minimal();
  s["camera"] = json::parse(R"({"position": [0, 5, 0], "look_at": [0, 5, 0]})");
  CHECK(error_path(s) == "camera");
  s = minimal();
  s["render"] = json::parse(R"({"samples_per_pixel": 3})");
  CHECK(error_path(s) == "render.samples_per_pixel");
  s = minimal();
  s["render"] = json::parse(R"({"pixel_tolerance": 0})");
  CHECK(error_path(s) == "render.pixel_tolerance");
  s = minimal();
  s["render"] = json::parse(R"({"max_samples_per_pixel": 36})");  // without pixel_tolerance
  CHECK(error_path(s) == "render.max_samples_per_pixel");
  s = minimal();
  s["render"] = json::parse(R"({"pixel_tolerance": 0.01, "max_samples_per_pixel": 81})");
  CHECK(error_path(s) == "render.max_samples_per_pixel");  // 4 spp: 36, 324, 2916, 26244
  s = minimal();
  s["shading"] = json::parse(R"({"interpolation": "cubic"})");
  CHECK(error_path(s) == "shading.interpolation");
  s = minimal();
  s["atmosphere"] = json::parse(R"({"turbidity": 12})");
  CHECK(error_path(s) == "atmosphere.turbidity");
  s = minimal();
  s["seed"] = -1;
  CHECK(error_path(s) == "seed");
  s = minimal();
  s.erase("waves");
  CHECK(error_path(s) == "waves");
  CHECK_THROWS_AS(load_scene("/nonexistent/scene.json"), SceneError);
}

TEST_CASE("EXR: float channels with subsampling round-trip exactly; no file left on failure") {
  ExrImage image;
  image.width = 8;
  image.height = 8;
  std::vector<float> full(64);
  std::vector<float> coarse(16);
  for (std::size_t i = 0; i < full.size(); ++i) full[i] = 0.25f * static_cast<float>(i) - 3.0f;
  for (std::size_t i = 0; i < coarse.size(); ++i) coarse[i] = -static_cast<float>(i);
  image.channels = {{"c0.slope_x", 1, full}, {"c0.height", 2, coarse}};
  image.attributes["oceanref.seed"] = "7";
  const std::string path = (std::filesystem::temp_directory_path() / "oceanref_test.exr").string();
  write_exr(path, image);
  const ExrImage back = read_exr(path);
  CHECK(back.width == 8);
  CHECK(back.attributes.at("oceanref.seed") == "7");
  REQUIRE(back.channels.size() == 2);
  for (const ExrChannel& c : back.channels) {
    CHECK(c.values == (c.name == "c0.height" ? coarse : full));
  }
  std::filesystem::remove(path);
  CHECK_THROWS(write_exr("/nonexistent/dir/out.exr", image));
  CHECK_THROWS(read_exr("/nonexistent/in.exr"));
}

TEST_CASE("ocean: combined FFT fields equal direct summation at common grid nodes") {
  // Sizes 120 and 40 m share the nodes of a 40/16 = 2.5 m lattice... every node of cascade 1
  // that is also a node of cascade 0 (spacing 7.5 m vs 2.5 m: every third node).
  json s = minimal();
  s["waves"]["cascades"]["sizes"] = json::array({120, 40});
  s["waves"]["low_resolution"] = 8;
  const Scene scene = parse_scene(s);
  const Ocean ocean = realize_ocean(scene.waves, 2);
  const auto fields = synthesize_ocean(ocean, scene.time, 2);
  for (int m = 0; m < 16; m += 2) {
    for (int n = 0; n < 16; n += 2) {
      const double x = m * 7.5;
      const double z = n * 7.5;
      const PointFields g = combine_from_grids(ocean, fields, x, z);
      const PointFields d = combine_direct(ocean, x, z, scene.time);
      // Field magnitudes are O(1); both paths agree to rounding (see test_waves for the bound).
      CHECK(std::fabs(g.height - d.height) < 1e-12);
      CHECK(std::fabs(g.slope_x - d.slope_x) < 1e-12);
      CHECK(std::fabs(g.slope_z - d.slope_z) < 1e-12);
      CHECK(std::fabs(g.jacobian - d.jacobian) < 1e-12);
    }
  }
}

TEST_CASE("foam of a sequence: steps = 0 is the indicator; accumulation never drops below it") {
  json s = minimal();
  s["waves"]["cascades"]["sizes"] = json::array({40});
  s["waves"]["resolution"] = 32;
  s["waves"]["spectrum"]["wind_speed"] = 20;
  s["waves"]["choppiness"] = -10.0;  // strong enough to fold the surface somewhere
  const Scene scene = parse_scene(s);
  const Ocean ocean = realize_ocean(scene.waves, 1);
  const auto fields = synthesize_ocean(ocean, scene.time, 1);
  const std::vector<double> j = cascade_jacobian(fields[0], ocean.cascades[0].choppiness);
  FoamSequence none;
  const AccumulatedFoam now = accumulate_foam(ocean, scene.time, none, ShadingNormals::surface, 1);
  int folded = 0;
  for (std::size_t c = 0; c < j.size(); ++c) {
    CHECK(now.cascades[0][c] == (j[c] < 0.0 ? 1.0 : 0.0));
    folded += j[c] < 0.0 ? 1 : 0;
  }
  CHECK(folded > 0);
  FoamSequence sequence{0.5, 0.1, 5};
  const AccumulatedFoam acc =
      accumulate_foam(ocean, scene.time, sequence, ShadingNormals::surface, 2);
  int lingering = 0;
  for (std::size_t c = 0; c < j.size(); ++c) {
    CHECK(acc.cascades[0][c] >= now.cascades[0][c]);
    CHECK(acc.cascades[0][c] <= 1.0);
    lingering += acc.cascades[0][c] > now.cascades[0][c] ? 1 : 0;
  }
  CHECK(lingering > 0);  // foam from earlier frames decays instead of vanishing
}

TEST_CASE("scene: the lighting accuracy settings belong to their mode") {
  json s = minimal();
  CHECK(parse_scene(s).shading.accuracy == LightingAccuracy::reference);  // the default
  CHECK(parse_scene(s).shading.tolerance == 1e-6);
  s["shading"]["accuracy"] = "exact";
  CHECK(error_path(s) == "shading.accuracy");
  s = minimal();
  s["shading"]["sky_order"] = 8;  // a fast-mode order in a reference scene
  CHECK(error_path(s) == "shading.sky_order");
  s["shading"]["accuracy"] = "fast";
  CHECK(error_path(s).empty());
  CHECK(parse_scene(s).shading.sky_order == 8);
  s["shading"]["tolerance"] = 1e-6;  // a reference tolerance in a fast scene
  CHECK(error_path(s) == "shading.tolerance");
  s = minimal();
  s["shading"]["sun_order"] = 2;
  CHECK(error_path(s) == "shading.sun_order");
  s = minimal();
  for (const double bad : {0.0, 1e-11, 0.1}) {
    s["shading"]["tolerance"] = bad;
    CHECK(error_path(s) == "shading.tolerance");
  }
  s["shading"]["tolerance"] = 1e-8;
  CHECK(parse_scene(s).shading.tolerance == 1e-8);
}
