#include "scene/scene.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>

#include "core/choice.h"
#include "core/format.h"
#include "core/fp_environment.h"
#include "shading/reference_lighting.h"

namespace oceanref {

const std::vector<std::string>& scene_key_paths() {
  static const std::vector<std::string> paths{
      "seed",
      "time",
      "waves.spectrum.model",
      "waves.spectrum.wind_speed",
      "waves.spectrum.wind_direction_deg",
      "waves.spectrum.fetch",
      "waves.spectrum.depth",
      "waves.spectrum.gravity",
      "waves.spectrum.gamma",
      "waves.spectrum.alpha",
      "waves.spectrum.peak_omega",
      "waves.spectrum.sigma_low",
      "waves.spectrum.sigma_high",
      "waves.spectrum.pm_wind",
      "waves.spectrum.tma_attenuation",
      "waves.spectrum.phillips_suppression",
      "waves.spectrum.capillary_wavenumber",
      "waves.spectrum.allow_extrapolation",
      "waves.spreading.model",
      "waves.spreading.swell",
      "waves.spreading.swell_model",
      "waves.spreading.spread_blend",
      "waves.spreading.printed",
      "waves.dispersion",
      "waves.model",
      "waves.gerstner.count",
      "waves.gerstner.direction_bins",
      "waves.gerstner.min_wavelength",
      "waves.gerstner.max_wavelength",
      "waves.cascades.sizes",
      "waves.cascades.largest",
      "waves.cascades.count",
      "waves.cascades.factor",
      "waves.cascades.band_edges",
      "waves.resolution",
      "waves.low_resolution",
      "waves.choppiness",
      "waves.allow_positive_choppiness",
      "waves.band_partitioning",
      "waves.minimum_wavelength",
      "waves.foam.decay",
      "waves.foam.time_step",
      "waves.foam.steps",
      "waves.realization",
      "waves.synthesis",
      "waves.tiling.tile_size",
      "waves.tiling.flow",
      "waves.tiling.flow_direction_deg",
      "waves.tiling.flow_center",
      "waves.noise.weight",
      "waves.noise.cell_size",
      "waves.mastin.filter",
      "waves.mastin.fractal_dimension",
      "waves.mastin.animation",
      "waves.mastin.dominant_phase_rate",
      "waves.mastin.background_phase_rate",
      "camera.position",
      "camera.look_at",
      "camera.up",
      "camera.vertical_fov_deg",
      "grid.columns",
      "grid.rows",
      "grid.margin",
      "atmosphere.sun_zenith_deg",
      "atmosphere.sun_azimuth_deg",
      "atmosphere.turbidity",
      "shading.model",
      "shading.four_term.ambient_intensity",
      "shading.four_term.ambient_colour",
      "shading.four_term.air_bubble_density",
      "shading.four_term.air_bubble_colour",
      "shading.four_term.subsurface_height_intensity",
      "shading.four_term.subsurface_view_intensity",
      "shading.four_term.water_scattering_colour",
      "shading.four_term.specular_colour",
      "shading.four_term.shininess",
      "shading.four_term.reflection_intensity",
      "shading.sun",
      "shading.sky",
      "shading.sea",
      "shading.whitecaps",
      "shading.fresnel",
      "shading.erfc",
      "shading.accuracy",
      "shading.tolerance",
      "shading.sky_order",
      "shading.sun_order",
      "shading.sea_colour",
      "shading.foam_albedo",
      "shading.whitecap_threshold",
      "shading.interpolation",
      "shading.normals",
      "render.width",
      "render.height",
      "render.samples_per_pixel",
      "render.pixel_tolerance",
      "render.max_samples_per_pixel",
      "render.pixel_pattern",
      "render.footprint_filtering",
      "render.mastin_antialiasing",
      "render.renderer",
      "render.surface_tolerance",
      "render.tone_key",
      "render.tone_white",
  };
  return paths;
}

namespace {
using json = nlohmann::json;

// Builds the document with nlohmann's DOM builder while keeping the JSON path of the value being
// read, so that a duplicate key or a number that overflows a double is reported at its path.
class StrictSceneSax {
 public:
  explicit StrictSceneSax(json& root) : dom_(root, true) {}

  bool null() { return value(dom_.null()); }
  bool boolean(bool v) { return value(dom_.boolean(v)); }
  bool number_integer(json::number_integer_t v) { return value(dom_.number_integer(v)); }
  bool number_unsigned(json::number_unsigned_t v) { return value(dom_.number_unsigned(v)); }
  bool number_float(json::number_float_t v, const json::string_t& s) {
    return value(dom_.number_float(v, s));
  }
  bool string(json::string_t& v) { return value(dom_.string(v)); }
  bool binary(json::binary_t& v) { return value(dom_.binary(v)); }
  bool start_object(std::size_t n) {
    check_depth();
    frames_.push_back({true, {}, {}, 0});
    return dom_.start_object(n);
  }
  bool key(json::string_t& k) {
    Frame& f = frames_.back();
    if (!f.keys.insert(k).second) {
      f.key = k;
      throw SceneError(path(),
                       "duplicate key (given more than once in the same object; give each "
                       "key once)");
    }
    f.key = k;
    return dom_.key(k);
  }
  bool end_object() {
    frames_.pop_back();
    return value(dom_.end_object());
  }
  bool start_array(std::size_t n) {
    check_depth();
    frames_.push_back({false, {}, {}, 0});
    return dom_.start_array(n);
  }
  bool end_array() {
    frames_.pop_back();
    return value(dom_.end_array());
  }
  bool parse_error(std::size_t /*position*/, const std::string& last_token,
                   const json::exception& e) {
    if (e.id == 406) {  // out_of_range.406: a number that overflows a double
      throw SceneError(path(), "the number " + escape_value(last_token) +
                                   " is out of the range of a double (accepted: finite numbers, "
                                   "magnitude at most 1.7976931348623157e+308)");
    }
    std::string what = e.what();
    const std::size_t bracket = what.find("] ");
    if (what.rfind("[json.exception.", 0) == 0 && bracket != std::string::npos) {
      what = what.substr(bracket + 2);
    }
    // nlohmann's message gives the line and column (1-based) of the offending byte.
    throw SceneError(source_, "not valid JSON: " + escape_value(what, 200));
  }

  std::string source_;

 private:
  struct Frame {
    bool object;
    std::set<std::string> keys;
    std::string key;
    std::size_t index;
  };
  // The path of the value being read: keys joined by '.', array indices as [i].
  std::string path() const {
    std::string p;
    for (const Frame& f : frames_) {
      if (f.object) {
        p += (p.empty() ? "" : ".") + escape_value(f.key);
      } else {
        p += "[" + std::to_string(f.index) + "]";
      }
    }
    return p.empty() ? "(top level)" : p;
  }
  // A scene nests four levels deep; far deeper input is refused before anything recurses over it
  // (printing a value in a message, writing the canonical scene).
  static constexpr std::size_t kMaxDepth = 64;
  void check_depth() const {
    if (frames_.size() >= kMaxDepth) {
      throw SceneError(path().substr(0, 200),
                       "nested more than " + std::to_string(kMaxDepth) +
                           " objects or arrays deep (a scene nests at most four levels)");
    }
  }
  bool value(bool ok) {
    if (!frames_.empty() && !frames_.back().object) ++frames_.back().index;
    return ok;
  }
  nlohmann::detail::json_sax_dom_parser<json> dom_;
  std::vector<Frame> frames_;
};

// A JSON value quoted in a message: its type and its text (escaped, cut when long).
std::string describe(const json& v) {
  const std::string text = escape_value(v.dump(-1, ' ', false, json::error_handler_t::replace));
  switch (v.type()) {
    case json::value_t::string:
      return "the string " + text;
    case json::value_t::boolean:
      return "the boolean " + text;
    case json::value_t::null:
      return "null";
    case json::value_t::array:
      return "an array " + text;
    case json::value_t::object:
      return "an object " + text;
    default:
      return "the number " + text;
  }
}

std::string join(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

// The keys of the object at `path` ("" for the top level): the next component of every key path
// under it, in the order of scene_key_paths(); the top level also holds `objects` (rejected as
// not supported yet).
std::vector<std::string> section_keys(const std::string& path) {
  // An element of the objects array, and its material.
  if (path.rfind("objects[", 0) == 0) {
    if (path.ends_with(".material")) return {"albedo"};
    return {"obj", "position", "rotation_deg", "scale", "material"};
  }
  std::vector<std::string> keys;
  const std::string prefix = path.empty() ? "" : path + ".";
  for (const std::string& k : scene_key_paths()) {
    if (k.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string rest = k.substr(prefix.size());
    const std::string child = rest.substr(0, rest.find('.'));
    if (std::find(keys.begin(), keys.end(), child) == keys.end()) keys.push_back(child);
  }
  if (path.empty()) keys.push_back("objects");
  return keys;
}

// A finite number in [lo, hi]; `lo`/`hi` of +-kTypeOnly mean that the range is checked later (by
// make_spectrum, which knows the model), so the message states only the type.
constexpr double kTypeOnly = 1e300;
double checked_number(const json& v, const std::string& path, double lo, double hi,
                      const std::string& unit) {
  const bool ranged = lo > -kTypeOnly || hi < kTypeOnly;
  const std::string range =
      ranged ? " in [" + shortest_number(lo) + ", " + shortest_number(hi) + "]" + unit
             : std::string();
  if (!v.is_number()) throw SceneError(path, "expected a number" + range + ", got " + describe(v));
  const double x = v.get<double>();
  if (!std::isfinite(x)) {
    throw SceneError(path, "expected a finite number" + range + ", got " + shortest_number(x));
  }
  if (x < lo || x > hi) {
    throw SceneError(path, "must be in [" + shortest_number(lo) + ", " + shortest_number(hi) + "]" +
                               unit + ", got " + shortest_number(x));
  }
  return x;
}

// A JSON object whose keys are checked against the accepted set (section_keys of its path).
struct Section {
  const json& value;
  std::string path;

  Section(const json& v, std::string p) : value(v), path(std::move(p)) {
    if (!value.is_object()) {
      throw SceneError(path.empty() ? "(top level)" : path,
                       "expected an object, got " + describe(value));
    }
    const std::vector<std::string> keys = section_keys(path);
    for (const auto& item : value.items()) {
      if (std::find(keys.begin(), keys.end(), item.key()) == keys.end()) {
        std::string list;
        for (const std::string& k : keys) list += (list.empty() ? "" : ", ") + k;
        throw SceneError(join(path, escape_value(item.key())),
                         "unknown key (accepted: " + list + ")");
      }
    }
  }
  bool has(const char* key) const { return value.contains(key); }
  const json& at(const char* key) const { return value.at(key); }
  std::string where(const char* key) const { return join(path, key); }

  double number(const char* key, double fallback, double lo, double hi,
                const char* unit = "") const {
    if (!has(key)) return fallback;
    return checked_number(at(key), where(key), lo, hi, unit);
  }
  std::optional<double> optional_number(const char* key, double lo, double hi) const {
    if (!has(key)) return std::nullopt;
    return number(key, 0.0, lo, hi);
  }
  int integer(const char* key, int fallback, int lo, int hi) const {
    if (!has(key)) return fallback;
    const json& v = at(key);
    const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    if (!v.is_number_integer()) {
      throw SceneError(where(key), "expected an integer in " + range + ", got " + describe(v));
    }
    // An unsigned value over INT64_MAX must not wrap (18446744073709551615 is not -1).
    const bool in_range =
        v.is_number_unsigned()
            ? v.get<std::uint64_t>() <= static_cast<std::uint64_t>(hi) &&
                  (lo <= 0 || v.get<std::uint64_t>() >= static_cast<std::uint64_t>(lo))
            : v.get<std::int64_t>() >= lo && v.get<std::int64_t>() <= hi;
    if (!in_range) {
      throw SceneError(where(key), "must be in " + range + ", got " + escape_value(v.dump()));
    }
    return static_cast<int>(v.get<std::int64_t>());
  }
  bool boolean(const char* key, bool fallback) const {
    if (!has(key)) return fallback;
    if (!at(key).is_boolean()) {
      throw SceneError(where(key), "expected true or false, got " + describe(at(key)));
    }
    return at(key).get<bool>();
  }
  std::string text(const char* key, const std::string& fallback) const {
    if (!has(key)) return fallback;
    if (!at(key).is_string()) {
      throw SceneError(where(key), "expected a string, got " + describe(at(key)));
    }
    return at(key).get<std::string>();
  }
};

// The choice of a table (core/choice.h) that the key names, `fallback` when it is absent.
template <class Table>
auto choice(const Section& s, const char* key, const Table& table, const std::string& fallback) {
  return parse_choice<SceneError>(table, s.where(key), s.text(key, fallback));
}

int resolution(const Section& s, const char* key, int fallback, int hi) {
  const int n = s.integer(key, fallback, 4, hi);
  if (!std::has_single_bit(static_cast<unsigned>(n))) {
    throw SceneError(s.where(key), "must be a power of two in [4, " + std::to_string(hi) +
                                       "], got " + std::to_string(n));
  }
  return n;
}

// The JSON path of each library setting key.
std::string spectrum_path(const std::string& key) {
  static const std::map<std::string, std::string> paths{
      {"wind_direction", "waves.spectrum.wind_direction_deg"},
      {"peak_frequency", "waves.spectrum.peak_omega"},
      {"swell", "waves.spreading.swell"},
      {"spread_blend", "waves.spreading.spread_blend"}};
  const auto it = paths.find(key);
  return it == paths.end() ? "waves.spectrum." + key : it->second;
}

SpectrumSettings parse_spectrum(const Section& spectrum, const Section* spreading,
                                const Section& waves) {
  SpectrumSettings s;
  s.model = choice(spectrum, "model", kSpectrumModels, "jonswap");
  // Ranges are checked by make_spectrum (one place); here only types and finiteness.
  const double big = kTypeOnly;
  s.wind_speed = spectrum.number("wind_speed", s.wind_speed, -big, big);
  s.wind_direction = spectrum.number("wind_direction_deg", 0.0, -720.0, 720.0, " degrees") *
                     std::numbers::pi / 180.0;
  s.fetch = spectrum.number("fetch", s.fetch, -big, big);
  if (spectrum.has("depth")) s.depth = spectrum.number("depth", 0.0, -big, big);
  s.gravity = spectrum.number("gravity", s.gravity, -big, big);
  s.gamma = spectrum.optional_number("gamma", -big, big);
  s.alpha = spectrum.optional_number("alpha", -big, big);
  s.peak_frequency = spectrum.optional_number("peak_omega", -big, big);
  s.sigma_low = spectrum.optional_number("sigma_low", -big, big);
  s.sigma_high = spectrum.optional_number("sigma_high", -big, big);
  s.pm_wind = choice(spectrum, "pm_wind", kPiersonMoskowitzWinds, "u10");
  s.depth_attenuation = choice(spectrum, "tma_attenuation", kDepthAttenuations, "exact");
  s.phillips_suppression =
      spectrum.number("phillips_suppression", s.phillips_suppression, -big, big);
  s.capillary_wavenumber =
      spectrum.number("capillary_wavenumber", s.capillary_wavenumber, -big, big);
  s.allow_extrapolation = spectrum.boolean("allow_extrapolation", false);
  if (spreading != nullptr) {
    if (spreading->has("model")) {
      s.spreading = choice(*spreading, "model", kSpreadingModels, "");
    }
    s.swell = spreading->number("swell", s.swell, -big, big);
    s.swell_model = choice(*spreading, "swell_model", kSwellModels, "lutz");
    s.spread_blend = spreading->number("spread_blend", s.spread_blend, -big, big);
    s.printed_spreading = spreading->boolean("printed", false);
  }
  if (waves.has("dispersion")) {
    s.dispersion = choice(waves, "dispersion", kDispersionKinds, "");
  }
  return s;
}

std::vector<double> parse_sizes(const Section& waves) {
  if (!waves.has("cascades")) return {1000.0};
  const Section c(waves.at("cascades"), waves.where("cascades"));
  if (c.has("sizes")) {
    if (c.has("largest") || c.has("count") || c.has("factor")) {
      throw SceneError(c.path, "give either sizes or largest/count/factor, not both");
    }
    const json& list = c.at("sizes");
    if (!list.is_array() || list.empty() || list.size() > 16) {
      throw SceneError(
          c.where("sizes"),
          "expected an array of 1 to 16 sizes in [0.01, 1000000] m, got " + describe(list));
    }
    std::vector<double> sizes;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string p = c.where("sizes") + "[" + std::to_string(i) + "]";
      sizes.push_back(checked_number(list[i], p, 0.01, 1e6, " m"));
    }
    return sizes;
  }
  const double largest = c.number("largest", 1000.0, 0.01, 1e6, " m");
  const int count = c.integer("count", 4, 1, 16);
  const std::string factor = c.text("factor", "golden-large");
  if (factor != "golden-large" && factor != "golden-small") {
    throw SceneError(c.where("factor"),
                     "expected golden-large (f = 1/phi) or golden-small "
                     "(f = 1 - 1/phi); got '" +
                         escape_value(factor) + "'");
  }
  return golden_ratio_sizes(largest, count,
                            factor == "golden-large" ? GoldenFactor::large : GoldenFactor::small);
}

// waves.cascades.band_edges: count − 1 increasing wavenumbers, each at most its cascade's Nyquist
// wavenumber on the N_l grid (the one holding η and D), the last below the last cascade's.
std::vector<double> parse_band_edges(const Section& waves, const WaveSettings& w) {
  if (!waves.has("cascades")) return {};
  const Section c(waves.at("cascades"), waves.where("cascades"));
  if (!c.has("band_edges")) return {};
  const std::string key = c.where("band_edges");
  if (!w.band_partitioning) throw SceneError(key, "needs waves.band_partitioning true");
  const json& list = c.at("band_edges");
  const std::size_t count = w.sizes.size() - 1;
  if (!list.is_array() || list.size() != count) {
    throw SceneError(key, "expected an array of " + std::to_string(count) +
                              " wavenumbers (one fewer than the cascades) in rad/m, got " +
                              describe(list));
  }
  std::vector<double> edges;
  for (std::size_t i = 0; i < count; ++i) {
    const std::string p = key + "[" + std::to_string(i) + "]";
    const double lower = i == 0 ? 0.0 : edges.back();
    // The band [e_{i−1}, e_i) must fit under cascade i's Nyquist wavenumber, and the last band
    // [e_{count−1}, Nyquist of the last) must not be empty.
    const double upper = std::fmin(nyquist_wavenumber(w.sizes[i], w.low_resolution),
                                   nyquist_wavenumber(w.sizes[i + 1], w.low_resolution));
    const double e = checked_number(list[i], p, 0.0, 1e6, " rad/m");
    if (!(e > lower && e <= upper)) {
      throw SceneError(p, "must be in (" + shortest_number(lower) + ", " + shortest_number(upper) +
                              "] rad/m (above the previous edge, at most the Nyquist wavenumber "
                              "pi*N_l/L of the cascades on either side), got " +
                              shortest_number(e));
    }
    edges.push_back(e);
  }
  return edges;
}

std::vector<double> parse_choppiness(const Section& waves, std::size_t count, bool allow_positive) {
  const double hi = allow_positive ? 10.0 : 0.0;
  const auto check = [&](const json& value, const std::string& p) {
    const double u = checked_number(value, p, -10.0, 10.0, "");
    if (u > hi) {
      throw SceneError(p,
                       "must be in [-10, " + shortest_number(hi) + "], got " + shortest_number(u) +
                           (allow_positive ? ""
                                           : " (u > 0 flattens crests instead of sharpening them, "
                                             "Gamper eq. 4.20; set waves.allow_positive_choppiness "
                                             "to use it)"));
    }
    return u;
  };
  if (!waves.has("choppiness")) return std::vector<double>(count, 0.0);
  const json& v = waves.at("choppiness");
  if (v.is_number()) {
    return std::vector<double>(count, check(v, waves.where("choppiness")));
  }
  if (!v.is_array() || v.size() != count) {
    throw SceneError(waves.where("choppiness"),
                     "expected a number or an array with one number per cascade (" +
                         std::to_string(count) + ") in [-10, " + shortest_number(hi) + "], got " +
                         describe(v));
  }
  std::vector<double> u;
  for (std::size_t i = 0; i < count; ++i) {
    const std::string p = waves.where("choppiness") + "[" + std::to_string(i) + "]";
    u.push_back(check(v[i], p));
  }
  return u;
}

// A fixed-length array of numbers, each in [−limit, limit]; `form` names its elements ("x, y, z").
template <std::size_t N>
std::array<double, N> number_array(const Section& s, const char* key, const char* form,
                                   double limit) {
  const json& v = s.at(key);
  if (!v.is_array() || v.size() != N) {
    throw SceneError(s.where(key), std::string("expected [") + form + "], each in [-" +
                                       shortest_number(limit) + ", " + shortest_number(limit) +
                                       "], got " + describe(v));
  }
  std::array<double, N> out{};
  for (std::size_t i = 0; i < N; ++i) {
    const std::string p = s.where(key) + "[" + std::to_string(i) + "]";
    out[i] = checked_number(v[i], p, -limit, limit, "");
  }
  return out;
}

glm::dvec3 vector3(const Section& s, const char* key, glm::dvec3 fallback, double limit) {
  if (!s.has(key)) return fallback;
  const std::array<double, 3> v = number_array<3>(s, key, "x, y, z", limit);
  return {v[0], v[1], v[2]};
}

// A linear RGB colour: three numbers in [0, 1] (an error names the channel's index).
Vec3 colour(const Section& s, const char* key, const Vec3& fallback) {
  const glm::dvec3 v = vector3(s, key, {fallback[0], fallback[1], fallback[2]}, 1.0);
  for (glm::length_t i = 0; i < 3; ++i) {
    if (v[i] < 0.0) {
      throw SceneError(s.where(key) + "[" + std::to_string(i) + "]",
                       "must be in [0, 1], got " + shortest_number(v[i]));
    }
  }
  return {v.x, v.y, v.z};
}

// waves.synthesis and the waves.tiling section (waves/tiling.h).
void parse_synthesis(const Section& waves, WaveSettings& w) {
  w.synthesis = choice(waves, "synthesis", kSyntheses, "periodic");
  if (waves.has("noise")) {
    const Section noise(waves.at("noise"), "waves.noise");
    w.noise_weight = noise.number("weight", w.noise_weight, 0.0, 1.0);
    w.noise_cell_size =
        noise.number("cell_size", w.noise_cell_size, 0.01, 64.0, " exemplar periods");
  }
  if (!waves.has("tiling")) return;
  const Section tiling(waves.at("tiling"), "waves.tiling");
  TilingSettings& t = w.tiling;
  // Lutz §7 studies 1/2 to 4 exemplar periods; below 1/4 the tiles change faster than the waves.
  t.tile_size = tiling.number("tile_size", t.tile_size, 0.25, 16.0, " exemplar periods");
  t.flow.kind = choice(tiling, "flow", kFlowKinds, "none");
  t.flow.direction = tiling.number("flow_direction_deg", 0.0, -720.0, 720.0, " degrees") *
                     std::numbers::pi / 180.0;
  if (tiling.has("flow_center")) {
    const std::array<double, 2> c = number_array<2>(tiling, "flow_center", "x, z", 1e6);
    t.flow.center_x = c[0];
    t.flow.center_z = c[1];
  }
}

// The objects array: each element an OBJ file and its placement and material.
std::vector<ObjectSettings> parse_objects(const Section& top) {
  std::vector<ObjectSettings> objects;
  if (!top.has("objects")) return objects;
  const json& list = top.at("objects");
  if (!list.is_array() || list.size() > kMaxSceneObjects) {
    throw SceneError("objects", "expected an array of at most " + std::to_string(kMaxSceneObjects) +
                                    " objects, got " + describe(list));
  }
  for (std::size_t i = 0; i < list.size(); ++i) {
    const Section o(list[i], "objects[" + std::to_string(i) + "]");
    ObjectSettings object;
    if (!o.has("obj")) throw SceneError(o.path + ".obj", "missing: the object's OBJ file");
    object.obj = o.text("obj", "");
    if (object.obj.empty() || object.obj.find('\0') != std::string::npos) {
      throw SceneError(o.where("obj"), "expected the path of an OBJ file, got \"\"");
    }
    object.position = vector3(o, "position", object.position, 1e6);
    object.rotation_deg = vector3(o, "rotation_deg", object.rotation_deg, 360.0);
    object.scale = o.number("scale", object.scale, 1e-6, 1e4);
    if (o.has("material")) {
      const Section m(o.at("material"), o.where("material"));
      object.material.albedo = colour(m, "albedo", {0.5, 0.5, 0.5});
    }
    objects.push_back(std::move(object));
  }
  return objects;
}

// render.pixel_tolerance, its pattern render.pixel_pattern and its cap
// render.max_samples_per_pixel, adaptive_samples(pattern, S, r) for r ≥ 1 refinements (renderer.h).
void parse_adaptive_sampling(const Section& render, ImageSettings& im) {
  const int s = im.samples_per_axis;
  if (!render.has("pixel_tolerance")) {
    for (const char* key : {"max_samples_per_pixel", "pixel_pattern"}) {
      if (render.has(key)) {
        throw SceneError(std::string("render.") + key,
                         "applies with render.pixel_tolerance only (adaptive sampling)");
      }
    }
    return;
  }
  im.pixel_tolerance = render.number("pixel_tolerance", 0.0, kMinPixelTolerance, 1.0);
  im.pixel_pattern = choice(render, "pixel_pattern", kPixelPatterns, "sobol");
  std::vector<int> caps;  // the valid caps, r ≥ 1, up to the grid's finest
  constexpr int kMostSamples = kMaxAdaptiveSamplesPerAxis * kMaxAdaptiveSamplesPerAxis;
  for (int r = 1; adaptive_samples(im.pixel_pattern, s, r) <= kMostSamples; ++r) {
    caps.push_back(adaptive_samples(im.pixel_pattern, s, r));
  }
  // The default cap: the grid's largest up to the fixed grid's most samples (1024; its first
  // when none is that small: there is always one, 3S ≤ 3·kMaxSamplesPerAxis ≤ 243), and the
  // Sobol' pattern's largest up to the grid's default (the same cost at most; its first when none
  // is that small).
  const auto largest_cap = [&](PixelPattern pattern, int most) {
    int fallback = adaptive_samples(pattern, s, 1);
    for (int r = 1; adaptive_samples(pattern, s, r) <= most; ++r) {
      fallback = adaptive_samples(pattern, s, r);
    }
    return fallback;
  };
  const int grid_fallback =
      largest_cap(PixelPattern::grid, kMaxSamplesPerAxis * kMaxSamplesPerAxis);
  const int fallback = im.pixel_pattern == PixelPattern::grid
                           ? grid_fallback
                           : largest_cap(PixelPattern::sobol, grid_fallback);
  const int cap = render.integer("max_samples_per_pixel", fallback, 0, kMostSamples);
  const auto found = std::find(caps.begin(), caps.end(), cap);
  if (found == caps.end()) {
    std::string valid;
    for (const int c : caps) valid += (valid.empty() ? "" : ", ") + std::to_string(c);
    const std::string form =
        im.pixel_pattern == PixelPattern::grid
            ? "(S*3^r)^2 for r >= 1 refinements of the S x S grid"
            : std::to_string(kPixelReplicates) + " replicates x N*2^r points for r >= 1 " +
                  "doublings of the first N = " + std::to_string(sobol_first_points(s));
    throw SceneError("render.max_samples_per_pixel",
                     "must be " + form + " of render.samples_per_pixel " + std::to_string(s * s) +
                         " (render.pixel_pattern " +
                         std::string(choice_name(kPixelPatterns, im.pixel_pattern)) +
                         ") and at most " + std::to_string(kMostSamples) + ": one of " + valid +
                         "; got " + std::to_string(cap));
  }
  im.max_refinements = static_cast<int>(found - caps.begin()) + 1;
}

void parse_rendering(const Section& top, Scene& scene) {
  const json empty = json::object();
  const Section camera(top.has("camera") ? top.at("camera") : empty, "camera");
  CameraSettings& c = scene.camera;
  c.position = vector3(camera, "position", c.position, 1e6);
  c.look_at = vector3(camera, "look_at", c.look_at, 1e7);
  c.up = vector3(camera, "up", c.up, 1e3);
  c.vertical_fov_deg =
      camera.number("vertical_fov_deg", c.vertical_fov_deg, 1.0, 170.0, " degrees");
  const Section grid(top.has("grid") ? top.at("grid") : empty, "grid");
  scene.grid.columns = grid.integer("columns", 512, 2, 8192);
  scene.grid.rows = grid.integer("rows", 512, 2, 8192);
  scene.grid.margin = grid.number("margin", 0.1, 0.0, 1.0);
  const Section atmosphere(top.has("atmosphere") ? top.at("atmosphere") : empty, "atmosphere");
  AtmosphereSettings& a = scene.atmosphere;
  a.sun_zenith_deg = atmosphere.number("sun_zenith_deg", a.sun_zenith_deg, 0.0, 180.0, " degrees");
  a.sun_azimuth_deg =
      atmosphere.number("sun_azimuth_deg", a.sun_azimuth_deg, -720.0, 720.0, " degrees");
  a.turbidity = atmosphere.number("turbidity", a.turbidity, kMinTurbidity, kMaxTurbidity);
  const Section shading(top.has("shading") ? top.at("shading") : empty, "shading");
  ShadingSettings& h = scene.shading;
  h.model = choice(shading, "model", kShadingModels, "bruneton");
  if (shading.has("four_term")) {
    const Section f(shading.at("four_term"), "shading.four_term");
    FourTermParameters& p = h.four_term;
    p.ambient_intensity = f.number("ambient_intensity", p.ambient_intensity, 0.0, 1e3);
    p.ambient_colour = colour(f, "ambient_colour", p.ambient_colour);
    p.air_bubble_density = f.number("air_bubble_density", p.air_bubble_density, 0.0, 1e3);
    p.air_bubble_colour = colour(f, "air_bubble_colour", p.air_bubble_colour);
    p.subsurface_height_intensity =
        f.number("subsurface_height_intensity", p.subsurface_height_intensity, 0.0, 1e3, " per m");
    p.subsurface_view_intensity =
        f.number("subsurface_view_intensity", p.subsurface_view_intensity, 0.0, 1e3);
    p.water_scattering_colour = colour(f, "water_scattering_colour", p.water_scattering_colour);
    p.specular_colour = colour(f, "specular_colour", p.specular_colour);
    p.shininess = f.number("shininess", p.shininess, 1.0, 1e4);
    p.reflection_intensity = f.number("reflection_intensity", p.reflection_intensity, 0.0, 1e3);
    validate(p);
  }
  h.sun = shading.boolean("sun", true);
  h.sky = shading.boolean("sky", true);
  h.sea = shading.boolean("sea", true);
  h.whitecaps = shading.boolean("whitecaps", false);
  h.brdf.fresnel = choice(shading, "fresnel", kShadingFresnelForms, "exact");
  h.brdf.erfc = choice(shading, "erfc", kErfcForms, "exact");
  h.accuracy = choice(shading, "accuracy", kLightingAccuracies, "reference");
  // Each setting belongs to one mode: a key of the other is a mistake, not something to ignore
  // (sky_order and sun_order also serve the reference under adaptive sampling: checked below).
  const bool fast = h.accuracy == LightingAccuracy::fast;
  if (fast && shading.has("tolerance")) {
    throw SceneError("shading.tolerance",
                     "applies to shading.accuracy \"reference\" only (fast uses sky_order and "
                     "sun_order)");
  }
  h.tolerance =
      shading.number("tolerance", h.tolerance, kMinLightingTolerance, kMaxLightingTolerance);
  h.sky_order = shading.integer("sky_order", h.sky_order, 1, 128);
  h.sun_order = shading.integer("sun_order", h.sun_order, 0, 64);
  h.sea_colour = colour(shading, "sea_colour", h.sea_colour);
  h.foam_albedo = shading.number("foam_albedo", h.foam_albedo, 0.0, 1.0);
  h.whitecap_threshold = shading.number("whitecap_threshold", h.whitecap_threshold, -10.0, 10.0);
  h.interpolation = choice(shading, "interpolation", kInterpolations, "bicubic");
  h.normals = choice(shading, "normals", kShadingNormals, "surface");
  const Section render(top.has("render") ? top.at("render") : empty, "render");
  ImageSettings& im = scene.image;
  im.width = render.integer("width", im.width, 1, 16384);
  im.height = render.integer("height", im.height, 1, 16384);
  const int spp =
      render.integer("samples_per_pixel", 4, 1, kMaxSamplesPerAxis * kMaxSamplesPerAxis);
  const int axis = static_cast<int>(std::lround(std::sqrt(static_cast<double>(spp))));
  if (axis * axis != spp) {
    throw SceneError(
        "render.samples_per_pixel",
        "must be a square number S*S (S x S stratified samples), got " + std::to_string(spp));
  }
  im.samples_per_axis = axis;
  parse_adaptive_sampling(render, im);
  if (two_level_lighting(scene)) {
    // The samples' reference lighting takes a tenth of the pixel's budget unless the scene says
    // (README, "One error budget per pixel").
    if (!shading.has("tolerance")) {
      h.tolerance = std::clamp(kTwoLevelLightingShare * im.pixel_tolerance, kMinLightingTolerance,
                               kMaxLightingTolerance);
    }
    if (!shading.has("sky_order")) h.sky_order = kTwoLevelSkyOrder;
  } else if (!fast) {
    for (const char* key : {"sky_order", "sun_order"}) {
      if (shading.has(key)) {
        throw SceneError(std::string("shading.") + key,
                         "applies to shading.accuracy \"fast\", or to \"reference\" with "
                         "render.pixel_tolerance (the rules the pixels' samples are lit by "
                         "before the reference corrects them); the reference mode is converged "
                         "to shading.tolerance");
      }
    }
  }
  im.footprint_filtering = render.boolean("footprint_filtering", false);
  im.renderer = choice(render, "renderer", kRenderers, "raster");
  im.surface_tolerance = render.number("surface_tolerance", kDefaultSurfaceTolerance,
                                       kMinSurfaceTolerance, kMaxSurfaceTolerance);
  im.mastin_antialiasing = render.number("mastin_antialiasing", 0.0, 1e-3, 1.0);
  if (im.mastin_antialiasing > 0.0 && im.pixel_tolerance > 0.0) {
    throw SceneError("render.mastin_antialiasing",
                     "not with render.pixel_tolerance (choose one way to add samples)");
  }
  im.tone_key = render.number("tone_key", im.tone_key, 1e-3, 1.0);
  im.tone_white = render.number("tone_white", im.tone_white, 0.0, 1e30);
  try {
    (void)scene_camera(scene);
  } catch (const std::invalid_argument& e) {
    throw SceneError("camera", e.what());
  }
}

// Whether the key at a dotted path is present in the document.
bool present(const json& document, const std::string& path) {
  const json* node = &document;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = path.find('.', start);
    const std::string key = path.substr(start, dot == std::string::npos ? dot : dot - start);
    if (!node->is_object() || !node->contains(key)) return false;
    node = &node->at(key);
    if (dot == std::string::npos) return true;
    start = dot + 1;
  }
}

bool any_choppiness(const WaveSettings& w, bool positive_only) {
  for (const double u : w.choppiness) {
    if (positive_only ? u > 0.0 : u != 0.0) return true;
  }
  return false;
}

// A key that a scene may hold without it changing anything: `inert` gives the reason for this
// scene, or "" when the scene consumes it. Keys without a rule are consumed whenever present.
// tests/test_settings_reach.cpp checks every reason: with it, changing the key changes nothing.
struct KeyUse {
  const char* path;
  std::string (*inert)(const Scene&);
};

std::string foam_inert(const Scene& s) {
  if (!any_choppiness(s.waves, false)) {
    return "no cascade has choppiness: the Jacobian is 1 everywhere and there is no foam";
  }
  return "";
}
// Keys of one shading model in a scene of the other.
std::string four_term_inert(const Scene& s) {
  return s.shading.model == ShadingModel::four_term ? "" : "shading.model is not four_term";
}
std::string bruneton_inert(const Scene& s) {
  return s.shading.model == ShadingModel::bruneton
             ? ""
             : "shading.model is four_term (closed forms, its own colours: shading.four_term)";
}

std::string foam_sequence_inert(const Scene& s) {
  const std::string none = foam_inert(s);
  if (!none.empty()) return none;
  return s.foam.steps == 0 ? "waves.foam.steps is 0 (the instantaneous foam indicator)" : "";
}

// Keys of one wave model in a scene of the other.
std::string gerstner_inert(const Scene& s) {
  return s.waves.model == WaveModel::gerstner ? "" : "waves.model is not gerstner";
}
std::string cascades_inert(const Scene& s) {
  return s.waves.model == WaveModel::gerstner
             ? "waves.model is gerstner (a wave set summed directly: no cascades or grids)"
             : "";
}

std::string tiling_inert(const Scene& s) {
  return s.waves.synthesis == Synthesis::tiling_and_blending
             ? ""
             : "waves.synthesis is not tiling_and_blending";
}
std::string noise_inert(const Scene& s) {
  return s.waves.synthesis == Synthesis::noise_blended ? ""
                                                       : "waves.synthesis is not noise_blended";
}
std::string mastin_inert(const Scene& s) {
  return s.waves.realization == Realization::mastin ? "" : "waves.realization is not mastin";
}
std::string mastin_shift_inert(const Scene& s) {
  if (const std::string r = mastin_inert(s); !r.empty()) return r;
  return s.waves.mastin.animation == MastinAnimation::constant_shift
             ? ""
             : "waves.mastin.animation is not constant_shift";
}

// D = (1 − b) D_cos² + b D_cos2s (Alimardanov Algorithm 2): with b = 0 nothing of s is used.
std::string spread_blend_zero_inert(const Scene& s) {
  return s.waves.spectrum.spread_blend == 0.0
             ? "waves.spreading.spread_blend is 0 (the cos-2s part has no weight)"
             : "";
}

const std::vector<KeyUse>& key_uses() {
  static const std::vector<KeyUse> uses{
      {"waves.spectrum.fetch",
       [](const Scene& s) -> std::string {
         const SpectrumSettings& w = s.waves.spectrum;
         if (w.model == SpectrumModel::pierson_moskowitz || w.model == SpectrumModel::phillips) {
           return "the " + std::string(to_string(w.model)) + " spectrum has no fetch";
         }
         if ((w.model == SpectrumModel::jonswap || w.model == SpectrumModel::tma) && w.alpha &&
             w.peak_frequency) {
           return "alpha and peak_omega are both given, so the fetch laws are not used";
         }
         return "";
       }},
      {"waves.spectrum.depth",
       [](const Scene& s) -> std::string {
         const SpectrumSettings& w = s.waves.spectrum;
         const DispersionKind d = w.dispersion.value_or(default_dispersion(w.model));
         if (w.model != SpectrumModel::tma && d == DispersionKind::deep) {
           return "the spectrum is not tma and the dispersion is deep";
         }
         return "";
       }},
      {"waves.spectrum.pm_wind",
       [](const Scene& s) -> std::string {
         const SpectrumSettings& w = s.waves.spectrum;
         if (w.model != SpectrumModel::pierson_moskowitz) {
           return "applies to the pierson-moskowitz spectrum only";
         }
         return w.peak_frequency ? "peak_omega is given, so the wind law of the peak is not used"
                                 : "";
       }},
      {"waves.spectrum.tma_attenuation",
       [](const Scene& s) -> std::string {
         return s.waves.spectrum.model == SpectrumModel::tma ? ""
                                                             : "applies to the tma spectrum only";
       }},
      {"waves.spectrum.phillips_suppression",
       [](const Scene& s) -> std::string {
         return s.waves.spectrum.model == SpectrumModel::phillips
                    ? ""
                    : "applies to the phillips spectrum only";
       }},
      {"waves.spectrum.capillary_wavenumber",
       [](const Scene& s) -> std::string {
         const SpectrumSettings& w = s.waves.spectrum;
         if (capillary_wavenumber_used(w)) return "";
         return "applies to the capillary dispersion and the unified spectrum and spreading only "
                "(here the dispersion is " +
                std::string(to_string(w.dispersion.value_or(default_dispersion(w.model)))) +
                ", the spreading " +
                std::string(to_string(w.spreading.value_or(default_spreading(w.model)))) + ")";
       }},
      {"waves.spectrum.allow_extrapolation",
       [](const Scene& s) -> std::string {
         SpectrumSettings w = s.waves.spectrum;
         if (!w.allow_extrapolation) return "";
         w.allow_extrapolation = false;
         try {
           (void)make_spectrum(w);
         } catch (const SettingError&) {
           return "";
         }
         return "no parameter is outside its fitted range";
       }},
      {"waves.spreading.swell", spread_blend_zero_inert},
      {"waves.spreading.swell_model",
       [](const Scene& s) -> std::string {
         if (s.waves.spectrum.swell == 0.0) return "waves.spreading.swell is 0";
         return spread_blend_zero_inert(s);
       }},
      {"waves.spreading.printed",
       [](const Scene& s) -> std::string {
         const SpectrumSettings& w = s.waves.spectrum;
         const SpreadingModel m = w.spreading.value_or(default_spreading(w.model));
         if (m == SpreadingModel::cos2 || m == SpreadingModel::cos4 ||
             m == SpreadingModel::donelan) {
           return "";
         }
         return "applies to the cos2, cos4 and donelan spreading only, not " +
                std::string(to_string(m));
       }},
      {"waves.gerstner.count", gerstner_inert},
      {"waves.gerstner.direction_bins", gerstner_inert},
      {"waves.gerstner.min_wavelength", gerstner_inert},
      {"waves.gerstner.max_wavelength", gerstner_inert},
      {"waves.cascades.sizes", cascades_inert},
      {"waves.cascades.largest", cascades_inert},
      {"waves.cascades.count", cascades_inert},
      {"waves.resolution", cascades_inert},
      {"waves.low_resolution", cascades_inert},
      {"waves.band_partitioning", cascades_inert},
      {"shading.interpolation", cascades_inert},
      {"waves.cascades.factor",
       [](const Scene& s) -> std::string {
         if (const std::string r = cascades_inert(s); !r.empty()) return r;
         return s.waves.sizes.size() == 1 ? "there is one cascade (count 1)" : "";
       }},
      {"waves.cascades.band_edges",
       [](const Scene& s) -> std::string {
         if (const std::string r = cascades_inert(s); !r.empty()) return r;
         return s.waves.sizes.size() == 1 ? "there is one cascade (no hand-over)" : "";
       }},
      {"waves.allow_positive_choppiness",
       [](const Scene& s) -> std::string {
         return any_choppiness(s.waves, true) ? "" : "no cascade has positive choppiness";
       }},
      {"waves.mastin.filter", mastin_inert},
      {"waves.mastin.animation", mastin_inert},
      {"waves.mastin.fractal_dimension",
       [](const Scene& s) -> std::string {
         if (const std::string r = mastin_inert(s); !r.empty()) return r;
         return s.waves.mastin.filter == MastinFilter::spectrum
                    ? "waves.mastin.filter is spectrum, not a power law"
                    : "";
       }},
      {"waves.mastin.dominant_phase_rate", mastin_shift_inert},
      {"waves.mastin.background_phase_rate", mastin_shift_inert},
      {"waves.tiling.tile_size", tiling_inert},
      {"waves.tiling.flow", tiling_inert},
      {"waves.tiling.flow_direction_deg",
       [](const Scene& s) -> std::string {
         if (const std::string r = tiling_inert(s); !r.empty()) return r;
         return s.waves.tiling.flow.kind == FlowKind::uniform ? ""
                                                              : "waves.tiling.flow is not uniform";
       }},
      {"waves.tiling.flow_center",
       [](const Scene& s) -> std::string {
         if (const std::string r = tiling_inert(s); !r.empty()) return r;
         const FlowKind k = s.waves.tiling.flow.kind;
         return k == FlowKind::circular || k == FlowKind::converging
                    ? ""
                    : "waves.tiling.flow is neither circular nor converging";
       }},
      {"waves.noise.weight", noise_inert},
      {"waves.noise.cell_size",
       [](const Scene& s) -> std::string {
         if (const std::string r = noise_inert(s); !r.empty()) return r;
         return s.waves.noise_weight == 0.0 ? "waves.noise.weight is 0" : "";
       }},
      {"waves.foam.steps", foam_inert},
      {"waves.foam.decay", foam_sequence_inert},
      {"waves.foam.time_step", foam_sequence_inert},
      {"shading.four_term.ambient_intensity", four_term_inert},
      {"shading.four_term.ambient_colour", four_term_inert},
      {"shading.four_term.air_bubble_density", four_term_inert},
      {"shading.four_term.air_bubble_colour", four_term_inert},
      {"shading.four_term.subsurface_height_intensity", four_term_inert},
      {"shading.four_term.subsurface_view_intensity", four_term_inert},
      {"shading.four_term.water_scattering_colour", four_term_inert},
      {"shading.four_term.specular_colour", four_term_inert},
      {"shading.four_term.shininess", four_term_inert},
      {"shading.four_term.reflection_intensity", four_term_inert},
      {"shading.fresnel", bruneton_inert},
      {"shading.erfc", bruneton_inert},
      {"shading.accuracy", bruneton_inert},
      {"shading.tolerance", bruneton_inert},
      {"shading.sea_colour",
       [](const Scene& s) -> std::string {
         if (const std::string r = bruneton_inert(s); !r.empty()) return r;
         return s.shading.sea ? "" : "shading.sea is false";
       }},
      {"shading.foam_albedo",
       [](const Scene& s) -> std::string {
         return s.shading.whitecaps ? "" : "shading.whitecaps is false";
       }},
      {"shading.whitecap_threshold",
       [](const Scene& s) -> std::string {
         return s.shading.whitecaps ? "" : "shading.whitecaps is false";
       }},
      {"shading.sun_order",
       [](const Scene& s) -> std::string {
         if (const std::string r = bruneton_inert(s); !r.empty()) return r;
         return s.shading.sun ? "" : "shading.sun is false";
       }},
      {"shading.sky_order",
       [](const Scene& s) -> std::string {
         if (const std::string r = bruneton_inert(s); !r.empty()) return r;
         // The rule also averages the Fresnel factor F̄ of the sea term.
         return s.shading.sky || s.shading.sea ? "" : "shading.sky and shading.sea are false";
       }},
      {"render.surface_tolerance",
       [](const Scene& s) -> std::string {
         return s.image.renderer == Renderer::raytrace_surface
                    ? ""
                    : "render.renderer is not raytrace_surface (`render --renderer "
                      "raytrace_surface` uses it)";
       }},
  };
  return uses;
}

std::vector<UnusedKey> unused_keys(const json& document, const Scene& scene) {
  std::vector<UnusedKey> unused;
  for (const KeyUse& use : key_uses()) {
    if (!present(document, use.path)) continue;
    std::string reason = use.inert(scene);
    if (!reason.empty()) unused.push_back({use.path, std::move(reason)});
  }
  return unused;
}
}  // namespace

json parse_scene_json(std::string_view text, const std::string& source) {
  // nlohmann's lexer takes a NUL byte for the end of the input, so "{} \0 garbage" would parse.
  const std::size_t nul = text.find('\0');
  if (nul != std::string_view::npos) {
    const std::size_t line_start = text.rfind('\n', nul);
    const std::size_t line =
        1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + nul, '\n'));
    const std::size_t column = line_start == std::string_view::npos ? nul + 1 : nul - line_start;
    throw SceneError(source, "not valid JSON: a NUL byte at line " + std::to_string(line) +
                                 ", column " + std::to_string(column) +
                                 " (a scene file is UTF-8 JSON text)");
  }
  json document;
  StrictSceneSax sax(document);
  sax.source_ = source;
  // Strict: anything after the value but whitespace is a syntax error; no comments.
  json::sax_parse(text, &sax, json::input_format_t::json, true, false);
  return document;
}

// waves.model and waves.gerstner (after the rendering settings: some do not go with it).
void parse_gerstner(const Section& waves, Scene& scene) {
  WaveSettings& w = scene.waves;
  w.model = choice(waves, "model", kWaveModels, "fft");
  // waves.gerstner is validated in any scene (and reported unused without the model).
  // The band drawn: by default from 2 peak wavelengths down to a twentieth of one.
  const Spectrum spectrum = make_spectrum(w.spectrum);
  const double peak = 2.0 * std::numbers::pi / spectrum.peak_wavenumber;
  const json empty = json::object();
  const Section g(waves.has("gerstner") ? waves.at("gerstner") : empty, "waves.gerstner");
  GerstnerDraw& d = w.gerstner;
  d.count = g.integer("count", d.count, 1, kMaxGerstnerWaves);
  d.direction_bins = g.integer("direction_bins", d.direction_bins, 1, d.count);
  if (d.count % d.direction_bins != 0) {
    throw SceneError("waves.gerstner.direction_bins",
                     "must divide waves.gerstner.count = " + std::to_string(d.count) + ", got " +
                         std::to_string(d.direction_bins));
  }
  const double longest = g.number("max_wavelength", std::fmin(2.0 * peak, 1e5), 1e-3, 1e5, " m");
  const double shortest =
      g.number("min_wavelength", std::fmin(peak / 20.0, 0.5 * longest), 1e-5, 1e4, " m");
  if (!(shortest < longest)) {
    throw SceneError("waves.gerstner.min_wavelength",
                     "must be below waves.gerstner.max_wavelength = " + shortest_number(longest) +
                         " m, got " + shortest_number(shortest));
  }
  d.min_wavenumber = 2.0 * std::numbers::pi / longest;
  d.max_wavenumber = 2.0 * std::numbers::pi / shortest;
  d.choppiness = w.choppiness.front();
  if (w.model != WaveModel::gerstner) return;
  const auto refuse = [](const std::string& key, const std::string& why) {
    throw SceneError(key, why +
                              " (waves.model is gerstner: one wave set summed anywhere, "
                              "directly)");
  };
  if (w.synthesis != Synthesis::periodic) refuse("waves.synthesis", "must be periodic");
  if (w.realization != Realization::gaussian) refuse("waves.realization", "must be gaussian");
  if (scene.image.footprint_filtering) refuse("render.footprint_filtering", "must be false");
  if (scene.image.renderer == Renderer::raytrace_surface) {
    refuse("render.renderer",
           "raytrace_surface needs the cascades' bounds; use raster or raytrace");
  }
  if (waves.has("choppiness") && waves.at("choppiness").is_array() &&
      waves.at("choppiness").size() != 1) {
    refuse("waves.choppiness", "must be one number");
  }
}

Scene parse_scene(const json& document) {
  const ReferenceFpEnvironment fp;
  const Section top(document, "");
  Scene scene;
  scene.objects = parse_objects(top);
  if (top.has("seed")) {
    const json& s = top.at("seed");
    if (!s.is_number_unsigned()) {
      throw SceneError("seed", "expected an integer in [0, 18446744073709551615] (2^64 - 1), got " +
                                   describe(s));
    }
    scene.seed = s.get<std::uint64_t>();
  }
  scene.time = top.number("time", 0.0, -1e7, 1e7, " s");
  if (!top.has("waves")) throw SceneError("waves", "missing: the scene needs a waves section");
  const Section waves(top.at("waves"), "waves");
  const json empty = json::object();
  const Section spectrum(waves.has("spectrum") ? waves.at("spectrum") : empty, "waves.spectrum");
  std::optional<Section> spreading;
  if (waves.has("spreading")) {
    spreading.emplace(waves.at("spreading"), "waves.spreading");
  }
  WaveSettings& w = scene.waves;
  w.seed = scene.seed;
  w.spectrum = parse_spectrum(spectrum, spreading ? &*spreading : nullptr, waves);
  w.sizes = parse_sizes(waves);
  w.resolution = resolution(waves, "resolution", 256, 8192);
  w.low_resolution = resolution(waves, "low_resolution", w.resolution, w.resolution);
  w.choppiness =
      parse_choppiness(waves, w.sizes.size(), waves.boolean("allow_positive_choppiness", false));
  w.band_partitioning = waves.boolean("band_partitioning", true);
  w.realization = choice(waves, "realization", kRealizations, "gaussian");
  if (waves.has("mastin")) {
    const Section mastin(waves.at("mastin"), "waves.mastin");
    MastinSettings& m = w.mastin;
    m.filter = choice(mastin, "filter", kMastinFilters, "spectrum");
    // D in (2, 3): a surface's fractal dimension; the ends make H = 1 or 0.
    m.fractal_dimension = mastin.number("fractal_dimension", m.fractal_dimension, 2.01, 2.99);
    m.animation = choice(mastin, "animation", kMastinAnimations, "dispersion");
    m.dominant_phase_rate =
        mastin.number("dominant_phase_rate", m.dominant_phase_rate, 0.0, 1e3, " rad/s");
    m.background_phase_rate =
        mastin.number("background_phase_rate", m.background_phase_rate, 0.0, 1e3, " rad/s");
  }
  if (w.band_partitioning) {
    for (std::size_t i = 1; i < w.sizes.size(); ++i) {
      if (!(w.sizes[i] < w.sizes[i - 1])) {
        throw SceneError("waves.cascades",
                         "band partitioning needs strictly decreasing sizes, "
                         "largest first");
      }
    }
  }
  w.band_edges = parse_band_edges(waves, w);
  parse_synthesis(waves, w);
  w.minimum_wavelength = waves.number(
      "minimum_wavelength", default_minimum_wavelength(w.spectrum.model), 0.0, 100.0, " m");
  if (waves.has("foam")) {
    const Section foam(waves.at("foam"), "waves.foam");
    scene.foam.decay = foam.number("decay", scene.foam.decay, 0.0, 1e3, " per second");
    scene.foam.time_step = foam.number("time_step", scene.foam.time_step, 1e-4, 10.0, " s");
    if (foam.has("steps") && foam.at("steps").is_string()) {
      // "steady": as many steps as make the foam independent of where it started.
      if (foam.at("steps") != "steady") {
        throw SceneError("waves.foam.steps",
                         "expected an integer in [0, " + std::to_string(kMaxFoamSteps) +
                             "] or \"steady\", got " + escape_value(foam.at("steps").dump()));
      }
      if (!(scene.foam.decay > 0.0)) {
        throw SceneError("waves.foam.steps",
                         "\"steady\" needs waves.foam.decay > 0 (foam that never decays has no "
                         "steady state)");
      }
      const double steps = std::floor(1.0 / (scene.foam.decay * scene.foam.time_step)) + 2.0;
      if (steps > kMaxFoamSteps) {
        throw SceneError("waves.foam.steps",
                         "\"steady\" would take " + format_number(steps) + " steps (more than " +
                             std::to_string(kMaxFoamSteps) +
                             "): raise waves.foam.decay or waves.foam.time_step");
      }
      scene.foam.steps = steady_foam_steps(scene.foam.decay, scene.foam.time_step);
    } else {
      scene.foam.steps = foam.integer("steps", 0, 0, kMaxFoamSteps);
    }
  }
  try {
    (void)make_spectrum(w.spectrum);
  } catch (const SettingError& e) {
    throw SceneError(spectrum_path(e.key()), e.what());
  }
  parse_rendering(top, scene);
  parse_gerstner(waves, scene);
  if (scene.foam.steps > 0 && scene.shading.whitecaps && scene.image.footprint_filtering) {
    throw SceneError("waves.foam.steps",
                     "accumulated whitecaps are read at each sample's point, not filtered to its "
                     "footprint: not with render.footprint_filtering (set steps to 0 or turn the "
                     "filter off)");
  }
  scene.unused = unused_keys(document, scene);
  scene.canonical = document.dump();
  return scene;
}

Camera scene_camera(const Scene& s) {
  return make_camera(s.camera.position, s.camera.look_at, s.camera.up,
                     s.camera.vertical_fov_deg * std::numbers::pi / 180.0, s.image.width,
                     s.image.height);
}

bool two_level_lighting(const Scene& scene) {
  return scene.image.pixel_tolerance > 0.0 && scene.shading.model == ShadingModel::bruneton &&
         scene.shading.accuracy == LightingAccuracy::reference;
}

RenderJob scene_render_job(const Scene& scene, const Ocean& ocean, int threads) {
  const ReferenceFpEnvironment fp;
  RenderJob job;
  job.ocean = &ocean;
  job.time = scene.time;
  job.camera = scene_camera(scene);
  job.grid = scene.grid;
  job.sky = scene_sky(scene);
  job.shading = scene.shading;
  // A Gerstner set has no grids: it is summed at every point.
  if (scene.waves.model == WaveModel::gerstner) job.shading.interpolation = Interpolation::direct;
  if (scene.shading.whitecaps) {
    job.unresolved_jacobian = unresolved_jacobian_moments(
        ocean, slope_variance_budget(ocean, scene.waves.minimum_wavelength, scene.time,
                                     scene.shading.interpolation, scene.shading.normals, threads));
  }
  job.foam = scene.foam;
  job.samples_per_axis = scene.image.samples_per_axis;
  job.pixel_tolerance = scene.image.pixel_tolerance;
  job.max_refinements = scene.image.max_refinements;
  job.pixel_pattern = scene.image.pixel_pattern;
  job.lighting_correction = two_level_lighting(scene);
  job.footprint_filtering = scene.image.footprint_filtering;
  job.renderer = scene.image.renderer;
  job.surface_tolerance = scene.image.surface_tolerance;
  job.antialiasing_contrast = scene.image.mastin_antialiasing;
  job.threads = threads;
  return job;
}

Sky scene_sky(const Scene& s) {
  const double deg = std::numbers::pi / 180.0;
  return make_sky(s.atmosphere.turbidity, s.atmosphere.sun_zenith_deg * deg,
                  s.atmosphere.sun_azimuth_deg * deg);
}

void apply_scene_override(json& document, const std::string& assignment) {
  const std::size_t equals = assignment.find('=');
  const std::string key = assignment.substr(0, equals);
  if (equals == std::string::npos || key.empty()) {
    throw SceneError("--set",
                     "expected KEY=VALUE with KEY a scene key's JSON path (e.g. "
                     "shading.accuracy=fast), got '" +
                         escape_value(assignment) + "'");
  }
  const std::string text = assignment.substr(equals + 1);
  // A JSON value as written, else the bare word as a string (strict: one value, finite).
  json value;
  try {
    value = parse_scene_json(text, key);
  } catch (const SceneError&) {
    value = text;
  }
  json* object = &document;
  std::string path;
  for (std::size_t start = 0;;) {
    const std::size_t dot = key.find('.', start);
    const std::string part = key.substr(start, dot == std::string::npos ? dot : dot - start);
    if (part.empty()) {
      throw SceneError(key, "--set: an empty part in the key's path");
    }
    if (!object->is_object()) {
      throw SceneError(path, "--set " + key + ": " + path + " is not an object");
    }
    path += (path.empty() ? "" : ".") + part;
    if (dot == std::string::npos) {
      if (value.is_null()) {
        object->erase(part);
      } else {
        (*object)[part] = value;
      }
      return;
    }
    if (!object->contains(part)) (*object)[part] = json::object();
    object = &(*object)[part];
    start = dot + 1;
  }
}

Scene load_scene(const std::string& path, std::ostream* warnings) {
  return load_scene(path, {}, warnings);
}

Scene load_scene(const std::string& path, const std::vector<std::string>& overrides,
                 std::ostream* warnings) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path, "cannot open the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw SceneError(path, "cannot read the scene file");
  json document = parse_scene_json(text.str(), path);
  for (const std::string& o : overrides) apply_scene_override(document, o);
  Scene scene = parse_scene(document);
  scene.directory = std::filesystem::path(path).parent_path().string();
  if (warnings != nullptr) {
    for (const UnusedKey& u : scene.unused) {
      *warnings << "oceanref: warning: " << path << ": " << u.path
                << " has no effect in this scene (" << u.reason << ")\n";
    }
  }
  return scene;
}

Scene load_scene(const std::string& path) {
  return load_scene(path, &std::cerr);
}

}  // namespace oceanref
