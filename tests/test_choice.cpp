// The enum name tables (core/choice.h): each name parses to its value and back, names are unique,
// and every boundary reports a wrong name with its key and the valid names, from the one helper.
#include <doctest/doctest.h>

#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <string_view>

#include "core/choice.h"
#include "core/errors.h"
#include "scene/scene.h"
#include "shading/lighting_terms.h"
#include "shading/ocean_brdf.h"
#include "spectrum/model.h"
#include "waves/interpolation.h"
#include "waves/ocean.h"
#include "waves/surface.h"

using namespace oceanref;

namespace {
// Every name maps to its value and back; names and values are unique.
template <class Table>
void check_table(const Table& table) {
  std::set<std::string_view> names;
  std::set<int> values;
  for (const auto& c : table) {
    CAPTURE(c.name);
    CHECK(names.insert(c.name).second);
    CHECK(values.insert(static_cast<int>(c.value)).second);
    const auto parsed = find_choice(table, c.name);
    REQUIRE(parsed.has_value());
    CHECK(*parsed == c.value);
    CHECK(choice_name(table, c.value) == c.name);
  }
}

std::string section_error(const std::string& section_json) {
  try {
    parse_scene(nlohmann::json::parse(section_json));
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST_CASE("choice tables: every name round-trips, names and values are unique") {
  check_table(kSpectrumModels);
  check_table(kSpreadingModels);
  check_table(kDispersionKinds);
  check_table(kPiersonMoskowitzWinds);
  check_table(kDepthAttenuations);
  check_table(kFresnelForms);
  check_table(kShadingFresnelForms);
  check_table(kErfcForms);
  check_table(kLightingAccuracies);
  check_table(kInterpolations);
  check_table(kShadingNormals);
  check_table(kRealizations);
  // to_string prints the same names the parser reads.
  CHECK(to_string(SpectrumModel::pierson_moskowitz) == "pierson-moskowitz");
  CHECK(to_string(SpreadingModel::donelan_banner) == "donelan-banner");
  CHECK(to_string(DispersionKind::finite_depth) == "finite-depth");
  // The scene and the command line offer exact and schlick; unity is for energy checks only.
  CHECK(kShadingFresnelForms.size() == 2);
  CHECK(!find_choice(kShadingFresnelForms, "unity").has_value());
  CHECK(find_choice(kFresnelForms, "unity") == FresnelForm::unity);
}

TEST_CASE("choice names: one, two or more") {
  constexpr std::array<Choice<int>, 1> one{{{0, "a"}}};
  constexpr std::array<Choice<int>, 2> two{{{0, "a"}, {1, "b"}}};
  constexpr std::array<Choice<int>, 3> three{{{0, "a"}, {1, "b"}, {2, "c"}}};
  CHECK(choice_names(one) == "a");
  CHECK(choice_names(two) == "a or b");
  CHECK(choice_names(three) == "one of a, b, c");
  CHECK(choice_name(two, 5) == "?");
  CHECK(!find_choice(three, "A").has_value());  // names are case-sensitive
  CHECK(!find_choice(three, "").has_value());
}

TEST_CASE("parse_choice: the value, or the caller's error naming the key and the valid names") {
  CHECK(parse_choice<SettingError>(kErfcForms, "erfc", "rational") == ErfcForm::rational);
  try {
    (void)parse_choice<SettingError>(kErfcForms, "erfc", "Rational");
    FAIL("no error");
  } catch (const SettingError& e) {
    CHECK(e.key() == "erfc");
    CHECK(std::string(e.what()) == "expected exact or rational; got 'Rational'");
  }
  CHECK_THROWS_WITH_AS(
      (void)parse_choice<SceneError>(kSpectrumModels, "waves.spectrum.model", "pm"),
      "waves.spectrum.model: expected one of phillips, pierson-moskowitz, jonswap, tma, donelan, "
      "unified; got 'pm'",
      SceneError);
}

TEST_CASE("scene files: a wrong name is reported with its JSON path and the valid names") {
  CHECK(section_error(R"({"waves": {"realization": "white"}})") ==
        "waves.realization: expected gaussian or mastin; got 'white'");
  CHECK(section_error(R"({"waves": {"spectrum": {"pm_wind": "u20"}}})") ==
        "waves.spectrum.pm_wind: expected u10 or u19.5; got 'u20'");
  CHECK(section_error(R"({"waves": {"dispersion": "shallow"}})") ==
        "waves.dispersion: expected one of deep, finite-depth, capillary; got 'shallow'");
  CHECK(section_error(R"({"waves": {}, "shading": {"fresnel": "unity"}})") ==
        "shading.fresnel: expected exact or schlick; got 'unity'");
  CHECK(section_error(R"({"waves": {}, "shading": {"interpolation": "nearest"}})") ==
        "shading.interpolation: expected one of bilinear, bicubic, direct; got 'nearest'");
  // And each name reaches the settings.
  const Scene s = parse_scene(nlohmann::json::parse(
      R"({"waves": {"realization": "mastin", "spectrum": {"model": "tma",
          "tma_attenuation": "thompson-vincent", "depth": 20}},
          "shading": {"accuracy": "fast", "erfc": "rational", "normals": "high_resolution",
                      "interpolation": "direct"}})"));
  CHECK(s.waves.realization == Realization::mastin);
  CHECK(s.waves.spectrum.model == SpectrumModel::tma);
  CHECK(s.waves.spectrum.depth_attenuation == DepthAttenuation::thompson_vincent);
  CHECK(s.shading.accuracy == LightingAccuracy::fast);
  CHECK(s.shading.brdf.erfc == ErfcForm::rational);
  CHECK(s.shading.normals == ShadingNormals::high_resolution);
  CHECK(s.shading.interpolation == Interpolation::direct);
}
