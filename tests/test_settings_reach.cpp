// Every scene setting reaches the pipeline (issue 14 point 5, issue 21): for a tiny scene, each key
// the parser accepts (scene_key_paths(), so a new key without a row fails) is changed alone to
// another valid value, and the output it should affect must change — the wave fields, the
// rendered radiance, the accumulated foam — or the change must turn an invalid scene into a
// valid one (the allow_* flags), or the key only affects the PNG preview (checked by
// tests/cli_test.sh). Every reason the parser gives for a key without effect (Scene::unused) is
// checked the other way: in such a scene, changing the key changes nothing.
//
// Outputs are compared by SHA-256 of their double values, so any change, even of one ulp,
// counts; the test cannot pass on a setting that is read but not applied.
#include <doctest/doctest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "io/sha256.h"
#include "raster/renderer.h"
#include "scene/scene.h"

using namespace oceanref;
using nlohmann::json;

namespace {

// The tiny scene every change starts from: two cascades of 16², a 12×8 image at one sample per
// pixel, fast lighting, whitecaps on (with a threshold that gives foam), t ≠ 0 (so ω matters).
json base_scene() {
  return json::parse(R"({
    "seed": 1, "time": 3.0,
    "waves": {"resolution": 16, "cascades": {"sizes": [60, 20]}, "choppiness": -1.5},
    "camera": {"position": [0, 6, 0], "look_at": [0, 0, 60]},
    "grid": {"columns": 24, "rows": 24},
    "shading": {"accuracy": "fast", "whitecaps": true, "whitecap_threshold": 0.8},
    "render": {"width": 12, "height": 8, "samples_per_pixel": 1}})");
}

enum Output : unsigned { kFields = 1, kPixels = 2, kFoam = 4 };

enum class Effect {
  outputs,   // the outputs in `mask` change
  accepted,  // the scene is rejected without the change and accepted with it
  preview,   // only the PNG preview changes (tests/cli_test.sh); fields and pixels do not
};

struct Row {
  const char* path;
  json value;
  json context;  // a JSON merge patch applied to the base scene before and after the change
  Effect effect;
  unsigned mask = 0;
};

Row changes(const char* path, json value, unsigned mask, json context = json::object()) {
  return {path, std::move(value), std::move(context), Effect::outputs, mask};
}

const json kCascadesByCount =
    json::parse(R"({"waves": {"cascades": {"sizes": null, "largest": 60, "count": 2}}})");

std::vector<Row> reach_rows() {
  const unsigned waves = kFields | kPixels;
  const auto ctx = [](const char* text) { return json::parse(text); };
  return {
      changes("seed", std::uint64_t{2}, waves),
      changes("time", 4.0, waves),
      changes("waves.spectrum.model", "pierson-moskowitz", waves),
      changes("waves.spectrum.wind_speed", 12, waves),
      changes("waves.spectrum.wind_direction_deg", 30, waves),
      changes("waves.spectrum.fetch", 50000, waves),
      changes("waves.spectrum.depth", 6, waves,
              ctx(R"({"waves": {"dispersion": "finite-depth"}})")),
      changes("waves.spectrum.gravity", 9.7, waves),
      changes("waves.spectrum.gamma", 5, waves),
      changes("waves.spectrum.alpha", 0.01, waves),
      changes("waves.spectrum.peak_omega", 1.2, waves),
      changes("waves.spectrum.sigma_low", 0.1, waves),
      changes("waves.spectrum.sigma_high", 0.12, waves),
      changes("waves.spectrum.pm_wind", "u19.5", waves,
              ctx(R"({"waves": {"spectrum": {"model": "pierson-moskowitz"}}})")),
      changes("waves.spectrum.tma_attenuation", "thompson-vincent", waves,
              ctx(R"({"waves": {"spectrum": {"model": "tma", "depth": 8}}})")),
      changes("waves.spectrum.phillips_suppression", 0.05, waves,
              ctx(R"({"waves": {"spectrum": {"model": "phillips"}}})")),
      // k ≤ 2.5 rad/m here: (k/k_m)² changes ω(k) by ~1e-4 relative at t = 3 s.
      changes("waves.spectrum.capillary_wavenumber", 200, waves,
              ctx(R"({"waves": {"dispersion": "capillary"}})")),
      {"waves.spectrum.allow_extrapolation", true,
       ctx(R"({"waves": {"spectrum": {"fetch": 1000000}}})"), Effect::accepted},
      changes("waves.spreading.model", "cos2", waves),
      changes("waves.spreading.swell", 0.5, waves),
      changes("waves.spreading.swell_model", "alimardanov", waves,
              ctx(R"({"waves": {"spreading": {"swell": 0.5}}})")),
      changes("waves.spreading.spread_blend", 0.5, waves),
      changes("waves.spreading.printed", true, waves,
              ctx(R"({"waves": {"spreading": {"model": "cos2"}}})")),
      changes("waves.dispersion", "capillary", waves),
      changes("waves.cascades.sizes", json::array({50, 20}), waves),
      changes("waves.cascades.largest", 80, waves, kCascadesByCount),
      changes("waves.cascades.count", 3, waves, kCascadesByCount),
      changes("waves.cascades.factor", "golden-small", waves, kCascadesByCount),
      changes("waves.cascades.band_edges", json::array({0.5}), waves),
      changes("waves.resolution", 32, waves),
      changes("waves.low_resolution", 8, waves),
      changes("waves.choppiness", -4, kPixels | kFoam,
              ctx(R"({"waves": {"choppiness": -6}})")),  // raw fields are before u
      {"waves.allow_positive_choppiness", true, ctx(R"({"waves": {"choppiness": 0.5}})"),
       Effect::accepted},
      changes("waves.band_partitioning", false, waves),
      changes("waves.minimum_wavelength", 5, waves),
      // Foam needs det J < 0 somewhere: stronger choppiness than the base scene's.
      changes("waves.foam.decay", 3, kFoam,
              ctx(R"({"waves": {"choppiness": -6, "foam": {"steps": 3}}})")),
      changes("waves.foam.time_step", 0.1, kFoam,
              ctx(R"({"waves": {"choppiness": -6, "foam": {"steps": 3}}})")),
      changes("waves.foam.steps", 3, kFoam, ctx(R"({"waves": {"choppiness": -6}})")),
      changes("waves.realization", "mastin", waves),
      changes("waves.mastin.filter", "power_law", waves,
              ctx(R"({"waves": {"realization": "mastin"}})")),
      changes("waves.mastin.fractal_dimension", 2.5, waves,
              ctx(R"({"waves": {"realization": "mastin", "mastin": {"filter": "power_law"}}})")),
      changes("waves.mastin.animation", "constant_shift", waves,
              ctx(R"({"waves": {"realization": "mastin"}})")),
      // A largest cascade of 400 m samples the peak (k_p ≈ 0.05 rad/m), so some components are
      // dominant.
      changes("waves.mastin.dominant_phase_rate", 0.7, waves,
              ctx(R"({"waves": {"realization": "mastin", "cascades": {"sizes": [400, 20]},
                                "mastin": {"animation": "constant_shift"}}})")),
      changes("waves.mastin.background_phase_rate", 0.2, waves,
              ctx(R"({"waves": {"realization": "mastin",
                                "mastin": {"animation": "constant_shift"}}})")),
      // Tiling and blending reads the exemplar's fields elsewhere: the pixels change, the
      // cascades' fields do not.
      changes("waves.synthesis", "tiling_and_blending", kPixels),
      changes("waves.tiling.tile_size", 1, kPixels,
              ctx(R"({"waves": {"synthesis": "tiling_and_blending"}})")),
      changes("waves.tiling.flow", "circular", kPixels,
              ctx(R"({"waves": {"synthesis": "tiling_and_blending"}})")),
      changes("waves.tiling.flow_direction_deg", 45, kPixels,
              ctx(R"({"waves": {"synthesis": "tiling_and_blending",
                                "tiling": {"flow": "uniform"}}})")),
      changes("waves.tiling.flow_center", json::array({10, 30}), kPixels,
              ctx(R"({"waves": {"synthesis": "tiling_and_blending",
                                "tiling": {"flow": "converging"}}})")),
      changes("waves.noise.weight", 0.5, kPixels,
              ctx(R"({"waves": {"synthesis": "noise_blended"}})")),
      changes("waves.noise.cell_size", 0.5, kPixels,
              ctx(R"({"waves": {"synthesis": "noise_blended"}})")),
      changes("camera.position", json::array({0, 8, 0}), kPixels),
      changes("camera.look_at", json::array({10, 0, 60}), kPixels),
      changes("camera.up", json::array({0.2, 1, 0}), kPixels),
      changes("camera.vertical_fov_deg", 40, kPixels),
      changes("grid.columns", 32, kPixels),
      changes("grid.rows", 32, kPixels),
      changes("grid.margin", 0.3, kPixels),
      changes("atmosphere.sun_zenith_deg", 60, kPixels),
      changes("atmosphere.sun_azimuth_deg", 120, kPixels),
      changes("atmosphere.turbidity", 4, kPixels),
      changes("shading.model", "four_term", kPixels),
      changes("waves.model", "gerstner", kPixels | kFields),
      changes("waves.gerstner.count", 32, kPixels, ctx(R"({"waves": {"model": "gerstner"}})")),
      changes("waves.gerstner.direction_bins", 4, kPixels,
              ctx(R"({"waves": {"model": "gerstner"}})")),
      changes("waves.gerstner.min_wavelength", 2.0, kPixels,
              ctx(R"({"waves": {"model": "gerstner"}})")),
      changes("waves.gerstner.max_wavelength", 40.0, kPixels,
              ctx(R"({"waves": {"model": "gerstner"}})")),
      changes("shading.four_term.ambient_intensity", 0.9, kPixels,
              ctx(R"({"shading": {"model": "four_term"}})")),
      changes("shading.four_term.ambient_colour", json::array({0.3, 0.1, 0.1}), kPixels,
              ctx(R"({"shading": {"model": "four_term"}})")),
      changes("shading.four_term.air_bubble_density", 0.2, kPixels,
              ctx(R"({"shading": {"model": "four_term"}})")),
      changes("shading.four_term.air_bubble_colour", json::array({0.3, 0.3, 0.1}), kPixels,
              ctx(R"({"shading": {"model": "four_term"}})")),
      changes("shading.four_term.subsurface_height_intensity", 4, kPixels,
              ctx(R"({"shading": {"model": "four_term"}})")),
      changes("shading.four_term.subsurface_view_intensity", 3, kPixels,
              ctx(R"({"shading": {"model": "four_term"}})")),
      changes("shading.four_term.water_scattering_colour", json::array({0.1, 0.5, 0.2}), kPixels,
              ctx(R"({"shading": {"model": "four_term"}})")),
      changes("shading.four_term.specular_colour", json::array({0.5, 0.5, 1}), kPixels,
              ctx(R"({"shading": {"model": "four_term"}})")),
      changes("shading.four_term.shininess", 500, kPixels,
              ctx(R"({"shading": {"model": "four_term"}})")),
      changes("shading.four_term.reflection_intensity", 0.3, kPixels,
              ctx(R"({"shading": {"model": "four_term"}})")),
      changes("shading.sun", false, kPixels),
      changes("shading.sky", false, kPixels),
      changes("shading.sea", false, kPixels),
      changes("shading.whitecaps", false, kPixels),
      changes("shading.fresnel", "schlick", kPixels),
      changes("shading.erfc", "rational", kPixels),
      changes("shading.accuracy", "reference", kPixels),
      changes("shading.tolerance", 1e-3, kPixels, ctx(R"({"shading": {"accuracy": "reference"}})")),
      changes("shading.sky_order", 8, kPixels),
      changes("shading.sun_order", 4, kPixels),
      changes("shading.sea_colour", json::array({0.1, 0.3, 0.2}), kPixels),
      changes("shading.foam_albedo", 0.3, kPixels),
      changes("shading.whitecap_threshold", 0.6, kPixels),
      changes("shading.interpolation", "bilinear", kPixels),
      changes("shading.normals", "high_resolution", kPixels),
      changes("render.width", 10, kPixels),
      changes("render.height", 6, kPixels),
      changes("render.samples_per_pixel", 4, kPixels),
      changes("render.pixel_tolerance", 0.05, kPixels),
      changes("render.max_samples_per_pixel", 9, kPixels,
              ctx(R"({"render": {"pixel_tolerance": 1e-3, "pixel_pattern": "grid"}})")),
      changes("render.pixel_pattern", "grid", kPixels,
              ctx(R"({"render": {"pixel_tolerance": 0.05}})")),
      changes("render.footprint_filtering", true, kPixels),
      // The ray tracer on the continuous surface: other visibility at the horizon's crests,
      // other hit points. (raytrace, on the same grid, differs only in the rounding of the
      // weights: tests/test_tracer.cpp.)
      changes("render.renderer", "raytrace_surface", kPixels),
      // Other patches to start Newton's method from: other rounding of the hits, at least.
      changes("render.surface_tolerance", 1.0, kPixels,
              json::parse(R"({"render": {"renderer": "raytrace_surface"}})")),
      changes("render.mastin_antialiasing", 0.02, kPixels),
      {"render.tone_key", 0.3, json::object(), Effect::preview},
      {"render.tone_white", 2.0, json::object(), Effect::preview},
  };
}

// Scenes in which a key does nothing, with the parser's reason (a substring).
struct InertRow {
  const char* path;
  json value;
  json context;
  const char* reason;
};

std::vector<InertRow> inert_rows() {
  const auto ctx = [](const char* text) { return json::parse(text); };
  return {
      {"waves.spectrum.fetch", 50000, ctx(R"({"waves": {"spectrum": {"model": "phillips"}}})"),
       "phillips spectrum has no fetch"},
      {"waves.spectrum.fetch", 50000,
       ctx(R"({"waves": {"spectrum": {"model": "pierson-moskowitz"}}})"),
       "pierson-moskowitz spectrum has no fetch"},
      {"waves.spectrum.fetch", 50000,
       ctx(R"({"waves": {"spectrum": {"alpha": 0.01, "peak_omega": 1.2}}})"), "both given"},
      {"waves.spectrum.depth", 6, json::object(), "dispersion is deep"},
      {"waves.spectrum.pm_wind", "u19.5", json::object(), "pierson-moskowitz spectrum only"},
      {"waves.spectrum.pm_wind", "u19.5",
       ctx(R"({"waves": {"spectrum": {"model": "pierson-moskowitz", "peak_omega": 1.2}}})"),
       "peak_omega is given"},
      {"waves.spectrum.tma_attenuation", "thompson-vincent", json::object(), "tma spectrum only"},
      {"waves.spectrum.phillips_suppression", 0.05, json::object(), "phillips spectrum only"},
      {"waves.spectrum.allow_extrapolation", true, json::object(), "fitted range"},
      {"waves.spectrum.capillary_wavenumber", 200, json::object(),
       "capillary dispersion and the unified spectrum and spreading only"},
      {"waves.spreading.swell", 0.5, ctx(R"({"waves": {"spreading": {"spread_blend": 0}}})"),
       "spread_blend is 0"},
      {"waves.spreading.swell_model", "alimardanov", json::object(), "swell is 0"},
      {"waves.spreading.swell_model", "alimardanov",
       ctx(R"({"waves": {"spreading": {"swell": 0.5, "spread_blend": 0}}})"), "spread_blend is 0"},
      {"waves.spreading.printed", true, json::object(), "not hasselmann"},
      {"waves.cascades.factor", "golden-small",
       ctx(R"({"waves": {"cascades": {"sizes": null, "largest": 60, "count": 1}}})"),
       "one cascade"},
      {"waves.allow_positive_choppiness", true, json::object(), "no cascade has positive"},
      {"waves.allow_positive_choppiness", true, ctx(R"({"waves": {"choppiness": 0}})"),
       "no cascade has positive"},
      {"waves.allow_positive_choppiness", true, ctx(R"({"waves": {"choppiness": [-0.5, 0]}})"),
       "no cascade has positive"},
      {"waves.mastin.filter", "power_law", json::object(), "realization is not mastin"},
      {"waves.mastin.animation", "constant_shift", json::object(), "realization is not mastin"},
      {"waves.mastin.background_phase_rate", 0.2, json::object(), "realization is not mastin"},
      {"waves.mastin.fractal_dimension", 2.5, ctx(R"({"waves": {"realization": "mastin"}})"),
       "filter is spectrum"},
      {"waves.mastin.dominant_phase_rate", 0.7,
       ctx(R"({"waves": {"realization": "mastin", "cascades": {"sizes": [400, 20]}}})"),
       "not constant_shift"},
      {"waves.tiling.tile_size", 1, json::object(), "synthesis is not tiling_and_blending"},
      {"waves.tiling.flow", "circular", json::object(), "synthesis is not tiling_and_blending"},
      {"waves.tiling.flow_direction_deg", 45,
       ctx(R"({"waves": {"synthesis": "tiling_and_blending"}})"), "flow is not uniform"},
      {"waves.tiling.flow_center", json::array({10, 30}),
       ctx(R"({"waves": {"synthesis": "tiling_and_blending", "tiling": {"flow": "uniform"}}})"),
       "neither circular nor converging"},
      {"waves.noise.weight", 0.5, json::object(), "synthesis is not noise_blended"},
      {"waves.noise.cell_size", 0.5, ctx(R"({"waves": {"synthesis": "noise_blended",
                                                       "noise": {"weight": 0}}})"),
       "weight is 0"},
      {"waves.cascades.band_edges", json::array(),
       ctx(R"({"waves": {"cascades": {"sizes": [60]}, "choppiness": 0}})"), "one cascade"},
      {"waves.foam.steps", 3, ctx(R"({"waves": {"choppiness": 0}})"), "no foam"},
      {"render.surface_tolerance", 1.0, json::object(), "not raytrace_surface"},
      {"waves.foam.decay", 3, ctx(R"({"waves": {"choppiness": -6}})"), "steps is 0"},
      {"waves.foam.time_step", 0.1, ctx(R"({"waves": {"choppiness": -6}})"), "steps is 0"},
      {"waves.foam.decay", 3, ctx(R"({"waves": {"choppiness": 0, "foam": {"steps": 3}}})"),
       "no foam"},
      {"shading.sea_colour", json::array({0.1, 0.3, 0.2}), ctx(R"({"shading": {"sea": false}})"),
       "shading.sea is false"},
      {"shading.foam_albedo", 0.3, ctx(R"({"shading": {"whitecaps": false}})"),
       "whitecaps is false"},
      {"shading.whitecap_threshold", 0.6, ctx(R"({"shading": {"whitecaps": false}})"),
       "whitecaps is false"},
      {"shading.sun_order", 4, ctx(R"({"shading": {"sun": false}})"), "shading.sun is false"},
      {"shading.four_term.shininess", 500, json::object(), "shading.model is not four_term"},
      {"waves.gerstner.count", 32, json::object(), "waves.model is not gerstner"},
      {"waves.resolution", 32, ctx(R"({"waves": {"model": "gerstner"}})"),
       "waves.model is gerstner"},
      {"shading.interpolation", "bilinear", ctx(R"({"waves": {"model": "gerstner"}})"),
       "waves.model is gerstner"},
      {"shading.four_term.ambient_colour", json::array({0.3, 0.1, 0.1}), json::object(),
       "shading.model is not four_term"},
      {"shading.sea_colour", json::array({0.1, 0.3, 0.2}),
       ctx(R"({"shading": {"model": "four_term"}})"), "shading.model is four_term"},
      {"shading.fresnel", "schlick", ctx(R"({"shading": {"model": "four_term"}})"),
       "shading.model is four_term"},
      {"shading.sun_order", 4, ctx(R"({"shading": {"model": "four_term"}})"),
       "shading.model is four_term"},
      {"shading.sky_order", 8, ctx(R"({"shading": {"sky": false, "sea": false}})"),
       "shading.sky and shading.sea are false"},
  };
}

void set_path(json& document, const std::string& path, const json& value) {
  json* node = &document;
  std::size_t start = 0;
  for (std::size_t dot; (dot = path.find('.', start)) != std::string::npos; start = dot + 1) {
    node = &(*node)[path.substr(start, dot - start)];
  }
  (*node)[path.substr(start)] = value;
}

template <class T>
void append(std::vector<std::uint8_t>& bytes, const T& v) {
  std::uint8_t b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  bytes.insert(bytes.end(), b, b + sizeof(T));
}

struct Outputs {
  std::string fields, pixels, foam;
  std::vector<UnusedKey> unused;
  double foam_coverage = 0.0;  // the share of the image's sea pixels with foam (see run)
};

// The outputs of a scene; realizations and results are cached (many rows share them).
class Pipeline {
 public:
  // `foam`: also accumulate the foam sequence (the costly part; only its rows need it).
  Outputs run(const json& document, bool foam = false) {
    const std::string key = document.dump() + (foam ? "+foam" : "");
    if (const auto it = results_.find(key); it != results_.end()) return it->second;
    const Scene scene = parse_scene(document);
    json waves_key = document["waves"];
    waves_key["seed"] = scene.seed;
    const std::string wk = waves_key.dump();
    if (!oceans_.count(wk)) oceans_.emplace(wk, realize_ocean(scene.waves, 2));
    const Ocean& ocean = oceans_.at(wk);
    Outputs out;
    out.unused = scene.unused;
    std::vector<std::uint8_t> bytes;
    for (const CascadeFields& f : synthesize_ocean(ocean, scene.time, 2)) {
      for (const auto& grid : f.values) {
        for (const double v : grid) append(bytes, v);
      }
    }
    out.fields = sha256_hex(bytes);
    RenderJob job = scene_render_job(scene, ocean, 2);
    job.layers = true;  // the foam layer
    // The BRDF roughness depends on the waves, the time and how the fields are read
    // (slope_variance_budget): cached by those, since it costs most of a tiny render.
    const std::string uk = wk + "|" + std::to_string(scene.time) + "|" +
                           std::to_string(static_cast<int>(scene.shading.interpolation)) + "|" +
                           std::to_string(static_cast<int>(scene.shading.normals));
    if (!unresolved_.count(uk)) {
      unresolved_.emplace(uk, unresolved_slope_variance(job, scene.waves));
    }
    const RenderedImage image = render(job, unresolved_.at(uk));
    bytes.clear();
    append(bytes, image.width);
    append(bytes, image.height);
    for (const Vec3& c : image.radiance) {
      for (const double v : c) append(bytes, v);
    }
    out.pixels = sha256_hex(bytes);
    // W > 0 wherever the unresolved waves could fold (a tail of the normal): "foamy" is a pixel
    // with at least a tenth of the foamiest one's foam.
    double foamy = 0.0, sea = 0.0, most = 0.0;
    REQUIRE(image.foam.size() == image.coverage.size());
    for (const Vec3& f : image.foam) most = std::max(most, f[0]);
    for (std::size_t i = 0; i < image.foam.size(); ++i) {
      foamy += image.foam[i][0] > 0.1 * most ? 1.0 : 0.0;
      sea += image.coverage[i] > 0.0 ? 1.0 : 0.0;
    }
    out.foam_coverage = sea > 0.0 ? foamy / sea : 0.0;
    if (foam) {
      bytes.clear();
      const AccumulatedFoam acc =
          accumulate_foam(ocean, scene.time, scene.foam, scene.shading.normals, 2);
      for (const auto& c : acc.cascades) {
        for (const double v : c) append(bytes, v);
      }
      for (const double v : acc.combined) append(bytes, v);
      out.foam = sha256_hex(bytes);
    }
    return results_.emplace(key, out).first->second;
  }

 private:
  std::map<std::string, Ocean> oceans_;
  std::map<std::string, SlopeVariance> unresolved_;
  std::map<std::string, Outputs> results_;
};

bool lists(const std::vector<UnusedKey>& unused, const std::string& path) {
  for (const UnusedKey& u : unused) {
    if (u.path == path) return true;
  }
  return false;
}

Pipeline& pipeline() {
  static Pipeline p;
  return p;
}

}  // namespace

TEST_CASE("settings reach: every scene key has exactly one row") {
  std::multiset<std::string> rows;
  for (const Row& r : reach_rows()) rows.insert(r.path);
  for (const std::string& key : scene_key_paths()) {
    CAPTURE(key);
    CHECK(rows.count(key) == 1);
  }
  const std::vector<std::string>& keys = scene_key_paths();
  for (const std::string& row : rows) {
    CAPTURE(row);
    CHECK(std::find(keys.begin(), keys.end(), row) != keys.end());
  }
}

TEST_CASE("settings reach: each key changed alone changes what it should") {
  Pipeline& p = pipeline();
  const Outputs base = p.run(base_scene());
  // The base scene exercises what the rows rely on: whitecaps on part of the sea.
  CHECK(base.foam_coverage > 0.0);
  CHECK(base.foam_coverage < 1.0);
  CHECK(base.unused.empty());
  for (const Row& r : reach_rows()) {
    const std::string path = r.path;
    CAPTURE(path);
    CAPTURE(r.value.dump());
    json before = base_scene();
    before.merge_patch(r.context);
    json after = before;
    set_path(after, r.path, r.value);
    REQUIRE(before != after);
    if (r.effect == Effect::accepted) {
      CHECK_THROWS_AS(parse_scene(before), SceneError);
      const Outputs a = p.run(after);
      CHECK_FALSE(lists(a.unused, r.path));
      continue;
    }
    const bool foam = (r.mask & kFoam) != 0;
    const Outputs b = p.run(before, foam);
    const Outputs a = p.run(after, foam);
    CHECK_FALSE(lists(a.unused, r.path));
    if (r.effect == Effect::preview) {
      CHECK(a.fields == b.fields);
      CHECK(a.pixels == b.pixels);
      continue;
    }
    if (r.mask & kFields) CHECK(a.fields != b.fields);
    if (r.mask & kPixels) CHECK(a.pixels != b.pixels);
    if (r.mask & kFoam) CHECK(a.foam != b.foam);
    // A key that only shades leaves the waves alone (its row would otherwise claim too little).
    if (!(r.mask & (kFields | kFoam))) CHECK(a.fields == b.fields);
  }
}

TEST_CASE("unused keys: each reason holds (the key changes nothing) and is reported") {
  Pipeline& p = pipeline();
  for (const InertRow& r : inert_rows()) {
    const std::string path = r.path;
    CAPTURE(path);
    CAPTURE(r.context.dump());
    json before = base_scene();
    before.merge_patch(r.context);
    json after = before;
    set_path(after, r.path, r.value);
    const bool foam = std::string(r.path).rfind("waves.foam.", 0) == 0;
    const Outputs b = p.run(before, foam);
    const Outputs a = p.run(after, foam);
    CHECK(a.fields == b.fields);
    CHECK(a.pixels == b.pixels);
    CHECK(a.foam == b.foam);
    bool found = false;
    for (const UnusedKey& u : a.unused) {
      if (u.path != r.path) continue;
      found = true;
      CAPTURE(u.reason);
      CHECK(u.reason.find(r.reason) != std::string::npos);
    }
    CHECK(found);
  }
}

TEST_CASE("unused keys: load_scene warns on the stream, naming the file and the JSON path") {
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / "oceanref_unused_key_test.json";
  {
    std::ofstream out(file);
    out << R"({"waves": {"spectrum": {"model": "phillips", "fetch": 5000},
                         "resolution": 8, "cascades": {"sizes": [50]}},
               "shading": {"sea": false, "sea_colour": [0.1, 0.2, 0.3]}})";
  }
  std::ostringstream warnings;
  const Scene scene = load_scene(file.string(), &warnings);
  std::filesystem::remove(file);
  REQUIRE(scene.unused.size() == 2);
  CHECK(scene.unused[0].path == "waves.spectrum.fetch");
  CHECK(scene.unused[1].path == "shading.sea_colour");
  const std::string text = warnings.str();
  CHECK(text ==
        "oceanref: warning: " + file.string() +
            ": waves.spectrum.fetch has no effect in this scene (the phillips spectrum has no "
            "fetch)\n"
            "oceanref: warning: " +
            file.string() +
            ": shading.sea_colour has no effect in this scene (shading.sea is false)\n");
  // A scene that uses everything it holds warns about nothing.
  std::ostringstream none;
  {
    std::ofstream out(file);
    out << R"({"waves": {"spectrum": {"fetch": 5000}, "resolution": 8}})";
  }
  CHECK(load_scene(file.string(), &none).unused.empty());
  std::filesystem::remove(file);
  CHECK(none.str().empty());
}

TEST_CASE("scene keys: scene_key_paths equals the leaves of reference/scene.schema.json") {
  std::ifstream in(std::string(OCEANREF_SOURCE_DIR) + "/reference/scene.schema.json");
  REQUIRE(in);
  const json schema = json::parse(in);
  std::vector<std::string> leaves;
  const auto walk = [&](const auto& self, const json& node, const std::string& path) -> void {
    for (const auto& [key, sub] : node.at("properties").items()) {
      const std::string p = path.empty() ? key : path + "." + key;
      if (sub.contains("properties")) {
        self(self, sub, p);
      } else if (p != "objects") {  // rejected as not supported yet (scene.h)
        leaves.push_back(p);
      }
    }
  };
  walk(walk, schema, "");
  CHECK(std::set<std::string>(leaves.begin(), leaves.end()) ==
        std::set<std::string>(scene_key_paths().begin(), scene_key_paths().end()));
  CHECK(leaves.size() == scene_key_paths().size());
}
