// waves.model gerstner: the wave set read through the ocean's every path (the same numbers as
// the set's own sum), its slope budget, its render (the same bits for any thread count) and the
// settings that do not go with it.
#include <doctest/doctest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "conformance/fields_output.h"
#include "raster/renderer.h"
#include "scene/scene.h"
#include "spectrum/moments.h"

using namespace oceanref;

namespace {
nlohmann::json gerstner_scene_json() {
  return nlohmann::json::parse(R"({"seed": 4, "time": 3.0,
      "waves": {"model": "gerstner", "spectrum": {"wind_speed": 9, "fetch": 50000},
                "choppiness": -1.0, "gerstner": {"count": 48, "direction_bins": 6}},
      "camera": {"position": [0, 5, 0], "look_at": [0, 1, 60]},
      "grid": {"columns": 64, "rows": 64},
      "shading": {"accuracy": "fast", "whitecaps": true},
      "render": {"width": 32, "height": 18, "samples_per_pixel": 1}})");
}
}  // namespace

TEST_CASE("gerstner ocean: every reading is the wave set's own sum") {
  const Scene scene = parse_scene(gerstner_scene_json());
  CHECK(scene.unused.empty());
  const Ocean ocean = realize_ocean(scene.waves, 1);
  REQUIRE(ocean.gerstner.has_value());
  CHECK(ocean.cascades.empty());
  CHECK(ocean.gerstner->waves.size() == 48);
  CHECK(ocean.gerstner->choppiness == -1.0);
  const std::vector<EvolvedCascade> evolved = evolve_ocean(ocean, 3.0);
  REQUIRE(evolved.size() == 1);
  for (const auto& [x, z] :
       {std::pair{0.3, 7.0}, std::pair{-12.5, 40.25}, std::pair{100.0, -3.0}}) {
    // The surface reading: add_cascade then finish_surface_combination, as gerstner_point.
    const PointFields expected = gerstner_point(*ocean.gerstner, x, z, 3.0);
    const PointFields surface = combine_shading_at(ocean, {}, evolved, x, z, Interpolation::direct,
                                                   ShadingNormals::surface);
    CHECK(surface.raw == expected.raw);
    CHECK(surface.normal == expected.normal);
    CHECK(surface.jacobian == expected.jacobian);
    // The Gamper reading (eq. 4.25, 4.26) of the same raw sums.
    PointFields gamper;
    add_cascade(gamper, gerstner_raw_fields(*ocean.gerstner, x, z, 3.0), -1.0);
    finish_combination(gamper);
    const PointFields direct = combine_direct(ocean, evolved, x, z);
    CHECK(direct.raw == gamper.raw);
    CHECK(direct.jacobian == gamper.jacobian);
    // The displaced point: x0 + uD, η.
    const DisplacedPoint p =
        displaced_point(ocean, {}, evolved, x, z, Interpolation::direct, ShadingNormals::surface);
    CHECK(p.x == x + expected.raw[static_cast<std::size_t>(Field::displacement_x)]);
    CHECK(p.height == expected.height);
  }
  // |η| and |D| are bounded by ΣA.
  double sum = 0.0;
  for (const GerstnerWave& w : ocean.gerstner->waves) sum += w.amplitude;
  CHECK(height_bound(ocean) == sum);
}

TEST_CASE("gerstner ocean: the slope budget counts the set and what it leaves to the BRDF") {
  const Scene scene = parse_scene(gerstner_scene_json());
  const Ocean ocean = realize_ocean(scene.waves, 1);
  const SlopeVarianceBudget b = slope_variance_budget(
      ocean, scene.waves.minimum_wavelength, 3.0, Interpolation::direct, ShadingNormals::surface);
  const GerstnerWaves& g = *ocean.gerstner;
  const SlopeVariance set = gerstner_slope_variance(g, ocean.spectrum.wind_direction);
  CHECK(b.resolved.upwind == set.upwind);
  // The set's own: the mean square of each wave's slope k A sin ψ along and across the wind,
  // ½ A² k² cos²(θ − φ) and ½ A² k² sin²(θ − φ), summed.
  double upwind = 0.0, crosswind = 0.0;
  for (const GerstnerWave& w : g.waves) {
    const double power = 0.5 * w.amplitude * w.amplitude * w.wavenumber * w.wavenumber;
    upwind += power * std::pow(std::cos(w.direction - ocean.spectrum.wind_direction), 2);
    crosswind += power * std::pow(std::sin(w.direction - ocean.spectrum.wind_direction), 2);
  }
  CHECK(set.upwind == doctest::Approx(upwind).epsilon(1e-12));
  CHECK(set.crosswind == doctest::Approx(crosswind).epsilon(1e-12));
  CHECK(set.crosswind > 0.1 * set.upwind);  // the set spreads across the wind too
  // unresolved = the spectrum above k_max + the draw's deficit in its band [k_min, k_max]:
  // (above + band − set); the band's own quadrature to 1e-8 relative.
  const SlopeVariance band =
      band_slope_variance(ocean.spectrum, g.min_wavenumber, g.max_wavenumber);
  CHECK(b.unresolved.upwind ==
        doctest::Approx(b.above_cutoff.upwind + band.upwind - set.upwind).epsilon(1e-9));
  CHECK(b.cutoff_wavenumber == g.max_wavenumber);
  // The set's slopes are of the order of the band's (one wave per cell, A = √(2V)): within 50%.
  CHECK(set.upwind == doctest::Approx(band.upwind).epsilon(0.5));
}

TEST_CASE("gerstner ocean: renders the same bits for any thread count; the set's settings count") {
  const auto render_of = [](const nlohmann::json& j, int threads) {
    const Scene scene = parse_scene(j);
    const Ocean ocean = realize_ocean(scene.waves, threads);
    const RenderJob job = scene_render_job(scene, ocean, threads);
    CHECK(job.shading.interpolation == Interpolation::direct);
    return render(job, unresolved_slope_variance(job, scene.waves)).radiance;
  };
  const std::vector<Vec3> one = render_of(gerstner_scene_json(), 1);
  CHECK(render_of(gerstner_scene_json(), 2) == one);
  nlohmann::json fewer = gerstner_scene_json();
  fewer["waves"]["gerstner"]["count"] = 24;
  CHECK(render_of(fewer, 2) != one);
}

TEST_CASE("gerstner ocean: settings that do not go with it name their key") {
  const auto refused = [](const char* patch, const char* key) {
    nlohmann::json j = gerstner_scene_json();
    j.merge_patch(nlohmann::json::parse(patch));
    CHECK_THROWS_WITH_AS(parse_scene(j), doctest::Contains(key), SceneError);
  };
  refused(R"({"waves": {"synthesis": "tiling_and_blending"}})", "waves.synthesis");
  refused(R"({"waves": {"choppiness": [-1, -0.5]}})", "waves.choppiness");
  // With two cascades an array of two passes the cascades' own check; a Gerstner set has one.
  refused(R"({"waves": {"cascades": {"count": 2}, "choppiness": [-1, -0.5]}})",
          "waves.choppiness: must be one number (waves.model is gerstner");
  refused(R"({"waves": {"realization": "mastin"}})", "waves.realization: must be gaussian");
  refused(R"({"waves": {"gerstner": {"direction_bins": 5}}})", "waves.gerstner.direction_bins");
  refused(R"({"waves": {"gerstner": {"min_wavelength": 50, "max_wavelength": 20}}})",
          "waves.gerstner.min_wavelength");
  refused(R"({"render": {"footprint_filtering": true}})", "render.footprint_filtering");
  refused(R"({"render": {"renderer": "raytrace_surface"}})", "render.renderer");
  // The cascades' keys do nothing and are reported.
  nlohmann::json j = gerstner_scene_json();
  j["waves"]["resolution"] = 64;
  const Scene s = parse_scene(j);
  REQUIRE(s.unused.size() == 1);
  CHECK(s.unused[0].path == "waves.resolution");
  // `fields` writes grids a Gerstner ocean does not have.
  const Ocean ocean = realize_ocean(s.waves, 1);
  CHECK_THROWS_WITH_AS(fields_image(s, ocean, 1), doctest::Contains("waves.model"), SceneError);
}

TEST_CASE("gerstner ocean: the default band runs from 2 peak wavelengths to a twentieth of one") {
  // README (waves.gerstner): by default the band drawn is [λ_p/20, 2λ_p], λ_p = 2π/k_p the
  // peak wavelength — k_p here from JONSWAP's peak (Gamper eq. 3.43, 3.52, 3.53) and deep water
  // (k = ω²/g), written out independently of the spectrum code.
  const Scene scene = parse_scene(gerstner_scene_json());
  const double g = 9.81, u = 9.0, fetch = 50000.0;
  const double chi = g * fetch / (u * u);
  const double omega_p = 2.0 * std::numbers::pi * g * 3.5 * std::pow(chi, -0.33) / u;
  const double peak = 2.0 * std::numbers::pi / (omega_p * omega_p / g);
  const GerstnerDraw& d = scene.waves.gerstner;
  CHECK(d.min_wavenumber == doctest::Approx(2.0 * std::numbers::pi / (2.0 * peak)).epsilon(1e-12));
  CHECK(d.max_wavenumber == doctest::Approx(2.0 * std::numbers::pi / (peak / 20.0)).epsilon(1e-12));
  // Given explicitly, the band is what the keys say.
  nlohmann::json s = gerstner_scene_json();
  s["waves"]["gerstner"]["max_wavelength"] = 30.0;
  s["waves"]["gerstner"]["min_wavelength"] = 0.25;
  const GerstnerDraw e = parse_scene(s).waves.gerstner;
  CHECK(e.min_wavenumber == doctest::Approx(2.0 * std::numbers::pi / 30.0).epsilon(1e-15));
  CHECK(e.max_wavenumber == doctest::Approx(2.0 * std::numbers::pi / 0.25).epsilon(1e-15));
}
