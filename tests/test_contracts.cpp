// The contracts now in library code: the render file and its two hashes
// (conformance/render_output.h), the fields file and its hashes (conformance/fields_output.h)
// and the golden suite (conformance/golden.h), checked without the command line.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "conformance/channel_name.h"
#include "conformance/fields_output.h"
#include "conformance/golden.h"
#include "conformance/render_output.h"
#include "core/format.h"
#include "io/exr.h"
#include "io/sha256.h"
#include "scene/scene.h"
#include "test_support.h"

using namespace oceanref;
using oceanref::testing::golden_hashes_checked;

namespace {
// A golden scene of the suite: 48x27 pixels, one cascade of 16², direct interpolation.
const std::string kTinyGolden = "mastin_spread_direct_tiny";

std::filesystem::path source(const std::string& relative) {
  return std::filesystem::path(OCEANREF_SOURCE_DIR) / relative;
}

nlohmann::json read_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

void write_json(const std::filesystem::path& path, const nlohmann::json& j) {
  std::ofstream out(path);
  out << j.dump(2) << '\n';
}

// A reference folder holding one scene of the golden suite and its manifest entry.
std::filesystem::path golden_copy(const std::string& folder, const std::string& name) {
  const auto root = std::filesystem::temp_directory_path() / folder;
  std::filesystem::remove_all(root);
  std::filesystem::create_directories(root / "golden");
  std::filesystem::create_directories(root / "scenes" / "golden");
  const nlohmann::json manifest = read_json(source("reference/golden/manifest.json"));
  nlohmann::json copy = manifest;
  copy["entries"] = nlohmann::json::array();
  for (const auto& e : manifest.at("entries")) {
    if (e.at("name") == name) copy["entries"].push_back(e);
  }
  REQUIRE(copy["entries"].size() == 1);
  std::filesystem::copy_file(source("reference/scenes/golden/" + name + ".json"),
                             root / "scenes" / "golden" / (name + ".json"));
  for (const char* suffix : {".exr", ".fields.exr"}) {
    std::filesystem::copy_file(source("reference/golden/" + name + suffix),
                               root / "golden" / (name + suffix));
  }
  write_json(root / "golden" / "manifest.json", copy);
  return root;
}

// The hash definitions of docs/FILES.md, written out independently of the library's.
std::string rgb_float32_hash(const ExrImage& exr) {
  std::vector<std::uint8_t> bytes;
  const std::size_t n = exr.channels[0].values.size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t c = 0; c < 3; ++c) {
      std::uint32_t bits;
      std::memcpy(&bits, &exr.channels[c].values[i], 4);
      for (int b = 0; b < 4; ++b) bytes.push_back(static_cast<std::uint8_t>(bits >> (8 * b)));
    }
  }
  return sha256_hex(bytes);
}
}  // namespace

TEST_CASE("render file: channels, attributes and the two hashes as docs/FILES.md defines them") {
  const Scene scene = load_scene(source("reference/scenes/golden/" + kTinyGolden + ".json"));
  RenderOutputOptions options;
  options.threads = 2;
  const RenderedScene r = render_scene(scene, options);
  REQUIRE(r.exr.channels.size() == 3);
  CHECK(r.exr.channels[0].name == "R");
  CHECK(r.exr.channels[2].name == "B");
  CHECK(r.exr.width == 48);
  CHECK(r.exr.height == 27);
  // The float32 pixel hash, recomputed from the channels here.
  CHECK(r.pixel_sha256 == rgb_float32_hash(r.exr));
  CHECK(pixel_sha256(r.exr.channels) == r.pixel_sha256);  // the library's helper for one image
  CHECK(r.exr.attributes.at("oceanref.pixel_sha256") == r.pixel_sha256);
  CHECK(r.exr.attributes.at("oceanref.radiance_f64_sha256") == r.radiance_f64_sha256);
  CHECK(r.exr.attributes.at("oceanref.scene_sha256") == sha256_hex(scene.canonical));
  CHECK(r.exr.attributes.at("oceanref.pixel_error") ==
        pixel_error_attribute(report_of(r).pixel_error));
  CHECK(r.exr.matrices.count("worldToCamera") == 1);
  CHECK(r.exr.matrices.count("worldToNDC") == 1);
  // The golden suite's stored hashes for this scene.
  const nlohmann::json manifest = read_json(source("reference/golden/manifest.json"));
  for (const auto& e : manifest.at("entries")) {
    if (e.at("name") != kTinyGolden || !golden_hashes_checked()) continue;
    CHECK(e.at("pixel_sha256") == r.pixel_sha256);
    CHECK(e.at("radiance_f64_sha256") == r.radiance_f64_sha256);
  }
  // A one-ulp change of one radiance value changes the f64 hash, not necessarily the float32 one.
  std::vector<Vec3> changed = r.image.radiance;
  changed[7][1] = std::nextafter(changed[7][1], 1e300);
  CHECK(radiance_f64_sha256(changed) != r.radiance_f64_sha256);
  CHECK(radiance_f64_sha256(r.image.radiance) == r.radiance_f64_sha256);

  {  // AOVs add the layers, not the pixels
    options.aov = true;
    const RenderedScene a = render_scene(scene, options);
    CHECK(a.pixel_sha256 == r.pixel_sha256);
    std::set<std::string> names;
    for (const ExrChannel& c : a.exr.channels) names.insert(c.name);
    for (const char* n : {"sun.R", "sky.G", "sea.B", "foam.R", "normal.G", "x0.B", "depth",
                          "coverage", "lighting_error.R", "pixel_error.B"}) {
      CHECK(names.count(n) == 1);
    }
    CHECK(a.exr.channels.size() == 3 + 6 * 3 + 2 + 3 + 3);
  }
}

TEST_CASE("fields file: parts, unique channel names, hashes of the doubles and the floats") {
  const Scene scene = load_scene(source("reference/scenes/golden/" + kTinyGolden + ".json"));
  const Ocean ocean = realize_ocean(scene.waves, 2);
  const FieldsImage f = fields_image(scene, ocean, 2);
  // One cascade on one grid: parts c0 and sum.
  REQUIRE(f.parts.size() == 2);
  CHECK(f.parts[0].name == "c0");
  CHECK(f.parts[1].name == "sum");
  // A cascade's part names its cascade, choppiness and band; sum, the combination of every
  // cascade, has none of them, only the grid it shares with cascade 0 (docs/FILES.md).
  const auto& c0 = f.parts[0].image.attributes;
  const auto& sum = f.parts[1].image.attributes;
  CHECK(c0.at("oceanref.cascade") == "0");
  CHECK(c0.at("oceanref.cascade_choppiness") == format_number(scene.waves.choppiness[0]));
  CHECK(c0.count("oceanref.band_rad_per_m") == 1);
  for (const char* key :
       {"oceanref.cascade", "oceanref.cascade_choppiness", "oceanref.band_rad_per_m"}) {
    CAPTURE(key);
    CHECK(sum.count(key) == 0);
  }
  CHECK(sum.at("oceanref.L_m") == c0.at("oceanref.L_m"));
  CHECK(sum.at("oceanref.N") == std::to_string(scene.waves.resolution));
  std::set<std::string> names;  // field names: the channel names without ".V"
  std::size_t channels = 0;
  for (const ExrPart& p : f.parts) {
    CHECK(p.image.attributes.at("oceanref.scene_sha256") == sha256_hex(scene.canonical));
    for (const ExrChannel& c : p.image.channels) {
      // Blender's layer.pass.channel: every channel ends in the one-letter id ".V".
      REQUIRE(c.name.ends_with(".V"));
      const std::string field = c.name.substr(0, c.name.size() - 2);
      CHECK(field_name_of_channel(c.name) == field);
      CHECK(exr_channel_name(field) == c.name);
      names.insert(field);
      ++channels;
      // Unit attributes are named by the field, not the channel.
      CHECK(p.image.attributes.count("oceanref.units." + field) == 1);
      CHECK(p.image.attributes.count("oceanref.units." + c.name) == 0);
    }
  }
  CHECK(names.size() == channels);
  // 8 fields, Jacobian and foam of c0; 8 channels of sum.
  CHECK(channels == 18);
  for (const char* field : {"c0.height", "c0.ddx_dz", "c0.foam", "sum.normal_x", "sum.foam"}) {
    CHECK(names.count(field) == 1);
  }
  // The float32 hash, written out: every field in field-name order, its field name (without
  // ".V", as before the suffix: the manifest's hashes did not change), a zero byte, its values
  // as binary32 little-endian.
  std::vector<std::uint8_t> bytes;
  for (const std::string& name : names) {
    bytes.insert(bytes.end(), name.begin(), name.end());
    bytes.push_back(0);
    for (const ExrPart& p : f.parts) {
      for (const ExrChannel& c : p.image.channels) {
        if (c.name != exr_channel_name(name)) continue;
        for (const float v : c.values) append_bytes(bytes, v);
      }
    }
  }
  CHECK(sha256_hex(bytes) == f.sha256);
  const nlohmann::json manifest = read_json(source("reference/golden/manifest.json"));
  for (const auto& e : manifest.at("entries")) {
    if (e.at("name") != kTinyGolden || !golden_hashes_checked()) continue;
    CHECK(e.at("fields_sha256") == f.sha256);
    CHECK(e.at("fields_f64_sha256") == f.f64_sha256);
  }
  // At a grid node the FFT and the direct sum agree to rounding (rows of every field).
  const std::vector<PointFieldRow> rows = fields_at_point(scene, ocean, 0.0, 0.0, 2);
  CHECK(rows.size() == kFieldNames.size() + 8);
  for (const PointFieldRow& r : rows) {
    if (r.cascade != "0") continue;
    CHECK(std::fabs(r.fft - r.direct) <= 1e-9 * (1.0 + std::fabs(r.direct)));
  }
}

TEST_CASE("golden suite: verify passes on a copy, fails naming the hash after a change") {
  const auto root = golden_copy("oceanref_test_golden", kTinyGolden);
  const auto manifest_path = root / "golden" / "manifest.json";
  GoldenOptions options;
  options.threads = 2;
  // Bad input names the option, before anything is rendered.
  options.only = {"no_such_scene"};
  CHECK_THROWS_AS(verify_golden(root, options), GoldenInputError);
  options.only = {kTinyGolden};
  try {
    verify_golden(root / "missing", options);
    FAIL("no error");
  } catch (const GoldenInputError& e) {
    CHECK(e.option() == "root");
  }

  // Without the golden hashes the copy's are this build's first (the rest holds either way).
  if (!golden_hashes_checked()) update_golden(root, options);
  const GoldenReport ok = verify_golden(root, options);
  REQUIRE(ok.scenes.size() == 1);
  CHECK(ok.pass());
  CHECK(ok.scenes[0].status == "identical");
  CHECK(ok.scenes[0].differs.empty());
  CHECK(golden_text(ok) == "name,status,pixel_sha256\n" + kTinyGolden + ",identical," +
                               ok.scenes[0].pixel_sha256 + "\n");

  // A stored hash altered: that key, and only it, differs.
  const nlohmann::json stored = read_json(manifest_path);
  nlohmann::json m = stored;
  m["entries"][0]["fields_sha256"] = std::string(64, '0');
  write_json(manifest_path, m);
  const GoldenReport bad_hash = verify_golden(root, options);
  CHECK_FALSE(bad_hash.pass());
  CHECK(bad_hash.mismatches == 1);
  CHECK(bad_hash.scenes[0].status == "MISMATCH");
  CHECK(bad_hash.scenes[0].differs == std::vector<std::string>{"fields_sha256"});
  CHECK(golden_text(bad_hash).find("# differs: fields_sha256\n") != std::string::npos);
  write_json(manifest_path, stored);

  // The scene altered (another seed; fast lighting to keep the test short): every hash differs
  // and the stored image is compared with the new one.
  const auto scene_path = root / "scenes" / "golden" / (kTinyGolden + ".json");
  nlohmann::json s = read_json(scene_path);
  s["seed"] = 20;
  s["shading"]["accuracy"] = "fast";
  write_json(scene_path, s);
  const GoldenReport bad_scene = verify_golden(root, options);
  CHECK_FALSE(bad_scene.pass());
  CHECK(bad_scene.scenes[0].differs.size() == 4);
  CHECK(bad_scene.scenes[0].comparison.find("result: fail") != std::string::npos);
  // Without the stored image the mismatch still reports, saying why nothing was compared.
  const auto image_path = root / "golden" / (kTinyGolden + ".exr");
  std::filesystem::rename(image_path, root / "away.exr");
  const GoldenReport no_image = verify_golden(root, options);
  CHECK(no_image.mismatches == 1);
  CHECK(no_image.scenes[0].comparison.rfind("# cannot compare with " + image_path.string(), 0) ==
        0);
  std::filesystem::rename(root / "away.exr", image_path);

  // A scene whose render fails the physics checks (an inert key) is INVALID, whatever its
  // hashes, and update writes nothing of it.
  nlohmann::json inert = s;
  inert["shading"]["whitecap_threshold"] = 0.5;  // whitecaps are off
  write_json(scene_path, inert);
  const std::string manifest_before = read_json(manifest_path).dump();
  for (const bool update : {false, true}) {
    CAPTURE(update);
    const GoldenReport invalid =
        update ? update_golden(root, options) : verify_golden(root, options);
    CHECK_FALSE(invalid.pass());
    CHECK(invalid.invalid == 1);
    CHECK(invalid.mismatches == 0);
    CHECK(invalid.scenes[0].status == "INVALID");
    REQUIRE(invalid.scenes[0].physics.size() == 1);
    CHECK(invalid.scenes[0].physics[0].find("shading.whitecap_threshold has no effect") !=
          std::string::npos);
    CHECK(read_json(manifest_path).dump() == manifest_before);
  }
  write_json(scene_path, s);

  // A manifest that is not JSON names the file.
  const std::string manifest_text = read_json(manifest_path).dump();
  std::ofstream(manifest_path) << "{\"entries\": [";
  try {
    verify_golden(root, options);
    FAIL("no error");
  } catch (const GoldenInputError& e) {
    CHECK(e.option() == "root");
    CHECK(std::string(e.what()).find(manifest_path.string() + ": not valid JSON") == 0);
  }
  std::ofstream(manifest_path) << manifest_text;

  // Update rewrites the manifest (no temporary left behind) and the files; verify then passes.
  const GoldenReport updated = update_golden(root, options);
  CHECK(updated.pass());
  CHECK(updated.scenes[0].status == "updated");
  CHECK_FALSE(std::filesystem::exists(manifest_path.string() + ".tmp"));
  const nlohmann::json rewritten = read_json(manifest_path);
  CHECK(rewritten["entries"][0]["pixel_sha256"] == updated.scenes[0].pixel_sha256);
  CHECK(rewritten["entries"][0]["pixel_sha256"] != ok.scenes[0].pixel_sha256);
  CHECK(rewritten["entries"][0]["lighting_accuracy"].get<std::string>().rfind("fast", 0) == 0);
  CHECK(verify_golden(root, options).pass());
  std::filesystem::remove_all(root);
}

TEST_CASE(
    "golden update: a converged scene's manifest entry holds its sampling and pixel error, its "
    "file the error layers; a fixed-spp golden's file is R, G, B") {
  // The suite's converged golden, made small (24 × 16) and capped at 6² samples (S = 2, one
  // refinement): the tolerance of 1% leaves pixels at the cap.
  const std::string name = "default_converged_fast";
  const auto root = golden_copy("oceanref_test_golden_converged", name);
  const auto scene_path = root / "scenes" / "golden" / (name + ".json");
  nlohmann::json s = read_json(scene_path);
  s["render"]["width"] = 24;
  s["render"]["height"] = 16;
  s["render"]["max_samples_per_pixel"] = 36;
  s["render"]["pixel_pattern"] = "grid";
  s["grid"] = {{"columns", 128}, {"rows", 128}, {"margin", 0.15}};
  write_json(scene_path, s);
  GoldenOptions options;
  options.threads = 2;
  REQUIRE(update_golden(root, options).pass());
  const nlohmann::json entry = read_json(root / "golden" / "manifest.json")["entries"][0];
  CHECK(entry.at("pixel_tolerance").get<double>() == 0.01);
  CHECK(entry.at("max_samples_per_pixel").get<int>() == 36);
  CHECK(entry.at("width").get<int>() == 24);
  CHECK(entry.at("height").get<int>() == 16);
  CHECK(entry.at("lighting_accuracy").get<std::string>().rfind("fast", 0) == 0);
  CHECK(entry.at("unconverged_samples").get<long>() == 0);
  CHECK_FALSE(entry.contains("lighting_error_max_relative"));  // fast lighting: no estimate

  // The stored file keeps the layers of a converged golden: the samples per pixel and the
  // pixel error, which the entry summarises (recomputed here from the file's float32 values).
  const ExrImage exr = read_exr((root / "golden" / (name + ".exr")).string());
  const auto channel = [&](const std::string& n) -> const std::vector<float>& {
    for (const ExrChannel& c : exr.channels) {
      if (c.name == n) return c.values;
    }
    FAIL("no channel " << n);
    return exr.channels[0].values;
  };
  const std::vector<float>& samples = channel("samples");
  REQUIRE(samples.size() == 24u * 16u);
  double sum = 0.0;
  int at_cap = 0;
  for (const float n : samples) {
    CHECK(n >= 4.0f);
    CHECK(n <= 36.0f);
    sum += static_cast<double>(n);
    at_cap += n == 36.0f ? 1 : 0;
  }
  CHECK(entry.at("pixel_samples_mean").get<double>() ==
        doctest::Approx(sum / 384.0).epsilon(1e-12));
  const long capped = entry.at("capped_pixels").get<long>();
  CHECK(capped > 0);
  CHECK(capped <= at_cap);
  std::vector<double> relative;
  for (const char* c : {"R", "G", "B"}) {
    const std::vector<float>& error = channel(std::string("pixel_error.") + c);
    const std::vector<float>& value = channel(c);
    for (std::size_t i = 0; i < value.size(); ++i) {
      if (value[i] > 0.0f)
        relative.push_back(static_cast<double>(error[i]) / static_cast<double>(value[i]));
    }
  }
  std::sort(relative.begin(), relative.end());
  REQUIRE(relative.size() > 100);
  // The max is exact in double; from float32 values it agrees to ~1e-7. The quantiles are the
  // lower edges of 2⁻⁸-wide relative bins: within 2⁻⁷ below the order statistic.
  CHECK(entry.at("pixel_error_max_relative").get<double>() ==
        doctest::Approx(relative.back()).epsilon(1e-6));
  for (const std::pair<const char*, double>& quantile :
       {std::pair{"pixel_error_p50_relative", 0.5}, std::pair{"pixel_error_p99_relative", 0.99}}) {
    const std::string key = quantile.first;
    const double q = quantile.second;
    CAPTURE(key);
    const double v = entry.at(key).get<double>();
    const auto rank = static_cast<std::size_t>(q * static_cast<double>(relative.size()));
    CHECK(v <= relative[std::min(rank + 1, relative.size() - 1)] * (1.0 + 1e-6));
    CHECK(v >= relative[rank > 0 ? rank - 1 : 0] * (1.0 - 1.0 / 128.0));
  }
  CHECK(entry.at("pixel_error_p99_relative").get<double>() > 0.01);  // the capped pixels
  std::filesystem::remove_all(root);

  // A fixed-sample golden's file has the image alone.
  const auto tiny = golden_copy("oceanref_test_golden_tiny_layers", kTinyGolden);
  REQUIRE(update_golden(tiny, options).pass());
  const ExrImage plain = read_exr((tiny / "golden" / (kTinyGolden + ".exr")).string());
  std::set<std::string> names;
  for (const ExrChannel& c : plain.channels) names.insert(c.name);
  CHECK(names == std::set<std::string>{"R", "G", "B"});
  std::filesystem::remove_all(tiny);
}

TEST_CASE(
    "golden physics checks: a clean render passes; an inert key, a wrong sky, a negative "
    "term or error, a coverage over 1 or foamless whitecaps fail") {
  // A small sea under an open sky: 24 × 16 pixels, fast lighting, whitecaps that show foam.
  nlohmann::json s = nlohmann::json::parse(R"({
    "seed": 3, "waves": {"resolution": 16, "cascades": {"sizes": [40, 12]}, "choppiness": -1.5},
    "camera": {"position": [0, 4, 0], "look_at": [0, 4, 50]},
    "atmosphere": {"sun_zenith_deg": 60, "sun_azimuth_deg": 30},
    "shading": {"accuracy": "fast", "whitecaps": true, "whitecap_threshold": 0.9},
    "render": {"width": 24, "height": 16, "samples_per_pixel": 4}})");
  const Scene scene = parse_scene(s);
  RenderOutputOptions options;
  options.threads = 2;
  options.aov = true;
  const RenderedImage clean = render_scene(scene, options).image;
  CHECK(golden_physics_failures(scene, clean).empty());
  const auto fails_with = [&](const Scene& sc, const RenderedImage& image,
                              const std::string& what) {
    const std::vector<std::string> failures = golden_physics_failures(sc, image);
    REQUIRE(failures.size() >= 1);
    CAPTURE(failures[0]);
    CHECK(failures[0].find(what) != std::string::npos);
  };
  // The open sky: the top rows (the camera looks at the horizon) hold the Preetham sky to
  // rounding; 1e-11 more in one pixel (ten times the tolerance) is a failure.
  RenderedImage sky = clean;
  sky.radiance[static_cast<std::size_t>(2 * 24 + 5)][1] *= 1.0 + 1e-11;
  fails_with(scene, sky, "the open sky at pixel (5, 2)");
  RenderedImage corner = clean;  // the first row and column are checked too
  corner.radiance[0][1] *= 1.0 + 1e-11;
  fails_with(scene, corner, "the open sky at pixel (0, 0)");
  RenderedImage negative = clean;
  negative.sea[static_cast<std::size_t>(15 * 24 + 3)] = {-1.0, -1.0, -1.0};
  fails_with(scene, negative, "sea at pixel (3, 15) has luminance -1");
  RenderedImage wrong_error = clean;
  wrong_error.lighting_error[static_cast<std::size_t>(14 * 24 + 7)][2] = -1e-3;
  fails_with(scene, wrong_error, "lighting_error at pixel (7, 14) is -0.001");
  RenderedImage wrong_coverage = clean;
  wrong_coverage.coverage[static_cast<std::size_t>(13 * 24 + 9)] = 1.25;
  fails_with(scene, wrong_coverage, "coverage at pixel (9, 13) is 1.25");
  RenderedImage foamless = clean;
  for (Vec3& f : foamless.foam) f = {0.0, 0.0, 0.0};
  fails_with(scene, foamless, "shading.whitecaps is on and no pixel shows foam");
  // An inert key: the fetch of a Phillips spectrum.
  s["waves"]["spectrum"] = {{"model", "phillips"}, {"fetch", 30000}};
  const Scene inert = parse_scene(s);
  fails_with(inert, clean, "waves.spectrum.fetch has no effect");
}
