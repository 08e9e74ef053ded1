// Parameter extremes (issue 15, point 5): every numeric range that reference/scene.schema.json
// documents — read from the schema itself, so a new range is swept without editing this file —
// at its corners (minimum, maximum; an exclusive minimum is approached by the next double up)
// and at three points drawn with a fixed seed, one key at a time on a tiny scene (16 × 10 pixels,
// 1 sample, two 8² cascades), then eight scenes with every swept key drawn at once. Each case
// runs spectrum → fields → render and must end in one of two ways:
//   - a clean validation error: SceneError whose message names the swept key (any swept key for
//     the combined scenes), or
//   - every value finite: S(ω) and Θ(k) at fixed samples and the spectral moments, every field
//     of every cascade, every pixel of every term of the render (require_finite).
// Anything else — a non-finite value, NonFiniteOutputError, another exception — is a failure,
// listed with the scene that caused it.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "conformance/render_output.h"
#include "core/quadrature.h"
#include "scene/scene.h"
#include "spectrum/model.h"
#include "spectrum/moments.h"
#include "waves/ocean.h"

using namespace oceanref;
using json = nlohmann::json;

namespace {

// A documented numeric range: `path` the JSON path, `index` the element of an array key
// (-1: a scalar key; arrays of numbers are swept one element at a time).
struct Range {
  std::string path;
  int index = -1;
  int array_size = 0;  // the array's fixed size (0: variable, swept as a one-element array)
  bool integer = false;
  double minimum = 0.0;
  double maximum = 0.0;
  bool exclusive_minimum = false;
};

void collect_ranges(const json& node, const std::string& path, std::vector<Range>& out) {
  const std::string type = node.contains("type") ? node["type"].get<std::string>() : "";
  if (type == "object") {
    if (!node.contains("properties")) return;
    for (const auto& [key, child] : node["properties"].items()) {
      collect_ranges(child, path.empty() ? key : path + "." + key, out);
    }
    return;
  }
  const json* numeric = &node;
  Range r;
  r.path = path;
  if (type == "array") {
    numeric = &node["items"];
    const int min_items = node.value("minItems", 1);
    const int max_items = node.value("maxItems", 1);
    r.array_size = min_items == max_items ? min_items : 0;
  } else if (type != "number" && type != "integer") {
    return;
  }
  const std::string item_type = numeric->value("type", "");
  if (item_type != "number" && item_type != "integer") return;
  r.integer = item_type == "integer";
  if (numeric->contains("minimum")) {
    r.minimum = (*numeric)["minimum"].get<double>();
  } else if (numeric->contains("exclusiveMinimum")) {
    r.minimum = (*numeric)["exclusiveMinimum"].get<double>();
    r.exclusive_minimum = true;
  } else {
    return;  // no documented range (e.g. waves.resolution: powers of two, checked by the parser)
  }
  // A range without a maximum (waves.spectrum.depth) is swept up to 1e6 × its minimum.
  r.maximum = numeric->contains("maximum") ? (*numeric)["maximum"].get<double>() : r.minimum * 1e6;
  if (r.array_size > 0) {
    for (int i = 0; i < r.array_size; ++i) {
      Range element = r;
      element.index = i;
      out.push_back(element);
    }
  } else {
    out.push_back(r);
  }
}

// splitmix64: a fixed sequence on every platform (no std distribution).
struct Draw {
  std::uint64_t state;
  double unit() {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1p-53;
  }
};

double lowest(const Range& r) {
  return r.exclusive_minimum ? std::nextafter(r.minimum, std::numeric_limits<double>::infinity())
                             : r.minimum;
}

// A point inside the range: log-uniform over ranges spanning more than three decades of
// positive values, uniform otherwise; integers rounded.
double point_in(const Range& r, Draw& draw) {
  const double lo = lowest(r);
  const double u = draw.unit();
  double v = 0.0;
  if (lo > 0.0 && r.maximum / lo > 1e3) {
    v = lo * std::pow(r.maximum / lo, u);
  } else {
    v = lo + (r.maximum - lo) * u;
  }
  if (r.integer) v = std::round(v);
  return std::fmin(std::fmax(v, lo), r.maximum);
}

json tiny_scene() {
  return json::parse(R"({
    "seed": 7,
    "waves": {"spectrum": {"model": "jonswap"}, "cascades": {"sizes": [60, 6]},
              "resolution": 8, "choppiness": [-0.5, -0.5]},
    "grid": {"columns": 24, "rows": 24},
    "shading": {"accuracy": "fast", "sky_order": 2, "sun_order": 1},
    "render": {"width": 16, "height": 10, "samples_per_pixel": 1}
  })");
}

json& at_path(json& document, const std::string& path) {
  json* node = &document;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = path.find('.', start);
    node = &(*node)[path.substr(start, dot - start)];
    if (dot == std::string::npos) return *node;
    start = dot + 1;
  }
}

// The settings a key needs to have an effect (a key of another model or mode is an error or a
// no-op, which would test nothing).
void enable_key(json& scene, const std::string& path) {
  json& waves = scene["waves"];
  if (path == "waves.spectrum.phillips_suppression") waves["spectrum"]["model"] = "phillips";
  if (path == "waves.spectrum.depth") waves["spectrum"]["model"] = "tma";
  if (path == "waves.spectrum.fetch" || path == "waves.spectrum.wind_speed" ||
      path == "waves.spectrum.gravity") {
    waves["spectrum"]["allow_extrapolation"] = true;  // the whole documented range, not the fit
  }
  if (path == "waves.cascades.largest" || path == "waves.cascades.count") {
    waves["cascades"].erase("sizes");
    waves.erase("choppiness");
  }
  if (path == "waves.cascades.sizes") waves.erase("choppiness");
  if (path.rfind("waves.foam.", 0) == 0 || path == "shading.foam_albedo" ||
      path == "shading.whitecap_threshold") {
    scene["shading"]["whitecaps"] = true;
  }
  if (path == "shading.tolerance") {
    scene["shading"] = {{"accuracy", "reference"}};
  }
  if (path == "render.max_samples_per_pixel") {  // the grid's caps include the range's least, 9
    scene["render"]["pixel_tolerance"] = 0.5;
    scene["render"]["pixel_pattern"] = "grid";
  }
  if (path.rfind("waves.tiling.", 0) == 0) {
    waves["synthesis"] = "tiling_and_blending";
    if (path == "waves.tiling.flow_direction_deg") waves["tiling"]["flow"] = "uniform";
    if (path == "waves.tiling.flow_center") waves["tiling"]["flow"] = "circular";
  }
}

void set_value(json& scene, const Range& r, double v) {
  json& node = at_path(scene, r.path);
  const json value = r.integer ? json(v < 0 ? json(static_cast<std::int64_t>(v))
                                            : json(static_cast<std::uint64_t>(v)))
                               : json(v);
  if (r.index >= 0) {
    if (!node.is_array()) {
      // Start from the documented default, so only this element differs.
      node = json::array();
      const json defaults = r.path == "camera.position"            ? json{0, 4, 0}
                            : r.path == "camera.look_at"           ? json{0, 0, 200}
                            : r.path == "camera.up"                ? json{0, 1, 0}
                            : r.path == "waves.tiling.flow_center" ? json{0, 0}
                                                                   : json{0.5, 0.5, 0.5};
      node = defaults;
    }
    node[static_cast<std::size_t>(r.index)] = value;
  } else if (r.array_size == 0 &&
             (r.path == "waves.cascades.sizes" || r.path == "waves.cascades.band_edges")) {
    node = json::array({value});
  } else {
    node = value;
  }
}

bool all_finite(const std::vector<double>& values) {
  for (const double v : values) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

// Runs one scene; "" when it passed, otherwise what went wrong.
std::string run_case(const json& document, const std::vector<std::string>& keys) {
  Scene scene;
  try {
    scene = parse_scene(document);
  } catch (const SceneError& e) {
    const std::string what = e.what();
    for (const std::string& key : keys) {
      if (what.find(key.substr(key.rfind('.') + 1)) != std::string::npos) return "";
    }
    return "validation error that names no swept key: " + what;
  } catch (const std::exception& e) {
    return std::string("parse threw ") + typeid(e).name() + ": " + e.what();
  }
  try {
    // Spectrum: S(ω), Θ(k) at fixed samples and the moments up to k = 1e4 rad/m.
    const Spectrum s = make_spectrum(scene.waves.spectrum);
    std::vector<double> spectrum_values;
    for (const double omega : {0.05, 0.3, 1.0, 3.0, 30.0}) {
      spectrum_values.push_back(frequency_spectrum(s, omega));
    }
    for (const double k : {0.001, 0.1, 1.0, 100.0}) {
      spectrum_values.push_back(wavevector_spectrum(s, k, 0.3 * k));
      spectrum_values.push_back(wavevector_spectrum(s, -k, 0.1 * k));
    }
    if (!all_finite(spectrum_values)) return "non-finite spectrum value";
    QuadratureTolerance loose;  // finite or not is the question here, not the last digits
    loose.relative = 1e-6;
    const SpectralMoments m = spectral_moments(s, 1e4, loose);
    if (!all_finite({m.m0, m.mss_x, m.mss_z})) return "non-finite spectral moment";
    // Fields of every cascade.
    const Ocean ocean = realize_ocean(scene.waves, 1);
    for (const CascadeFields& f : synthesize_ocean(ocean, scene.time, 1)) {
      for (const auto& field : f.values) {
        if (!all_finite(field))
          return "non-finite wave field (cascade size " + std::to_string(f.size) + ")";
      }
    }
    // The render (render_scene checks every pixel of every term: NonFiniteOutputError).
    RenderOutputOptions options;
    options.threads = 1;
    const RenderedScene rendered = render_scene(scene, options);
    require_finite(rendered.image);
  } catch (const NonFiniteOutputError& e) {
    return std::string("non-finite render: ") + e.what();
  } catch (const SceneError& e) {
    return std::string("SceneError after validation: ") + e.what();
  } catch (const std::exception& e) {
    return std::string("threw ") + typeid(e).name() + ": " + e.what();
  }
  return "";
}

std::vector<Range> documented_ranges() {
  std::ifstream in(OCEANREF_SOURCE_DIR "/reference/scene.schema.json");
  REQUIRE(in);
  std::vector<Range> ranges;
  collect_ranges(json::parse(in), "", ranges);
  return ranges;
}

}  // namespace

TEST_CASE("parameter sweep: every documented range's corners and random points, one at a time") {
  const std::vector<Range> ranges = documented_ranges();
  // The schema documents these ranges (a check that the sweep reads it): scalars and array
  // elements, including camera.position[0..2] and sea_colour[0..2].
  REQUIRE(ranges.size() >= 50);
  Draw draw{20261202};
  int cases = 0, rendered = 0;
  std::vector<std::string> failures;
  for (const Range& r : ranges) {
    std::vector<double> values{lowest(r), r.maximum};
    for (int i = 0; i < 3; ++i) values.push_back(point_in(r, draw));
    int passed_render = 0;
    for (const double v : values) {
      json scene = tiny_scene();
      enable_key(scene, r.path);
      set_value(scene, r, v);
      const std::string failure = run_case(scene, {r.path});
      ++cases;
      const std::string label = r.path + (r.index >= 0 ? "[" + std::to_string(r.index) + "]" : "") +
                                " = " + json(v).dump();
      if (!failure.empty()) {
        failures.push_back(label + ": " + failure);
      }
      // Count what reached the render (a clean error is also a pass).
      try {
        (void)parse_scene(scene);
        ++passed_render;
      } catch (const std::exception&) {
      }
    }
    rendered += passed_render;
    // Every key's default-like middle is valid: at least one of its five values renders, so the
    // sweep never tests only the error path of a key.
    CHECK_MESSAGE(passed_render > 0, r.path, " never got past validation");
  }
  MESSAGE(cases, " cases, ", rendered, " rendered");
  for (const std::string& f : failures) FAIL_CHECK(f);
}

TEST_CASE("parameter sweep: every documented range drawn at once, eight scenes") {
  const std::vector<Range> ranges = documented_ranges();
  Draw draw{915};
  std::vector<std::string> failures;
  int valid = 0;
  for (int n = 0; n < 8; ++n) {
    json scene = tiny_scene();
    std::vector<std::string> keys;
    for (const Range& r : ranges) {
      // Keys that change the model, the cascade layout or the mode are left to the one-at-a-time
      // sweep; the cost keys stay small (the render stays tiny).
      if (r.path == "waves.spectrum.phillips_suppression" || r.path == "waves.spectrum.depth" ||
          r.path == "waves.cascades.largest" || r.path == "waves.cascades.count" ||
          r.path == "waves.cascades.sizes" || r.path == "waves.cascades.band_edges" ||
          r.path == "shading.tolerance" || r.path.rfind("render.", 0) == 0 ||
          r.path.rfind("grid.", 0) == 0 || r.path == "waves.foam.steps" ||
          r.path == "waves.gerstner.direction_bins") {
        continue;
      }
      set_value(scene, r, point_in(r, draw));
      keys.push_back(r.path);
    }
    scene["waves"]["spectrum"]["allow_extrapolation"] = true;
    scene["shading"]["whitecaps"] = true;
    // Keys whose range depends on another's value, made consistent: one direction bin divides
    // any count, and the wavelength band is put in order.
    json& gerstner = scene["waves"]["gerstner"];
    gerstner["direction_bins"] = 1;
    if (gerstner.contains("min_wavelength") && gerstner.contains("max_wavelength") &&
        gerstner["min_wavelength"] >= gerstner["max_wavelength"]) {
      std::swap(gerstner["min_wavelength"], gerstner["max_wavelength"]);
    }
    // Every key is inside its documented range and the dependent ones agree, so each scene must
    // get past validation to the render (a validation error that names a key would also pass
    // run_case, and then the sweep would test nothing).
    try {
      (void)parse_scene(scene);
      ++valid;
    } catch (const SceneError& e) {
      FAIL_CHECK("drawn scene " << n << " refused: " << e.what());
    }
    const std::string failure = run_case(scene, keys);
    if (!failure.empty()) failures.push_back(failure + "\n  scene: " + scene.dump());
  }
  CHECK(valid == 8);
  for (const std::string& f : failures) FAIL_CHECK(f);
}
