#include "conformance/golden.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>
#include <sstream>
#include <utility>

#include "conformance/compare.h"
#include "conformance/fields_output.h"
#include "conformance/render_output.h"
#include "core/format.h"
#include "core/math.h"
#include "io/exr.h"
#include "io/output_file.h"
#include "io/sha256.h"
#include "raster/camera.h"
#include "scene/scene.h"
#include "shading/tone_mapping.h"
#include "sky/preetham.h"

namespace oceanref {

namespace {
// The mean Preetham sky over the S × S sample rays of pixel (x, y), in sample order; false when
// a ray's cosine to the sun exceeds cos_near_sun (its disk is added there).
bool open_sky_mean(const Camera& camera, const Sky& sky, double cos_near_sun, int x, int y, int s,
                   Vec3& mean) {
  const double per_sample = 1.0 / (s * s);
  mean = {};
  for (int r = y * s; r < (y + 1) * s; ++r) {
    for (int c = x * s; c < (x + 1) * s; ++c) {
      const glm::dvec3 ray = ray_direction(camera, (c + 0.5) / s, (r + 0.5) / s);
      const Vec3 d{ray.x, ray.y, ray.z};
      if (dot(d, sky.sun_direction) > cos_near_sun) return false;
      const Vec3 l = sky_radiance_rgb(sky, d);
      for (std::size_t k = 0; k < 3; ++k) mean[k] += per_sample * l[k];
    }
  }
  return true;
}
}  // namespace

std::vector<std::string> golden_physics_failures(const Scene& scene, const RenderedImage& image) {
  std::vector<std::string> failures;
  for (const UnusedKey& u : scene.unused) {
    failures.push_back(u.path + " has no effect (" + u.reason + ")");
  }
  const auto pixel = [&](std::size_t p) {
    return "pixel (" + std::to_string(p % static_cast<std::size_t>(image.width)) + ", " +
           std::to_string(p / static_cast<std::size_t>(image.width)) + ")";
  };
  // Linear sRGB channels may be negative for a colour outside its gamut (a grazing sun is
  // redder than sRGB holds), so the energy bound is on luminance; an error is >= 0 per channel.
  const std::pair<const char*, const std::vector<Vec3>*> terms[] = {{"radiance", &image.radiance},
                                                                    {"sun", &image.sun},
                                                                    {"sky", &image.sky},
                                                                    {"sea", &image.sea},
                                                                    {"foam", &image.foam}};
  // A two-level pixel (and its terms) is an estimate of a luminance ≥ 0 corrected by a sampled
  // mean (reference − fast at some of its samples): it may fall below 0 within its lighting
  // bound, as a faint term where the fast rules see a little more than the reference does.
  const bool two_level = two_level_lighting(scene);
  for (const auto& [name, values] : terms) {
    for (std::size_t p = 0; p < values->size(); ++p) {
      const Vec3& v = (*values)[p];
      const double y = relative_luminance(v);
      const double floor = two_level ? -relative_luminance(image.lighting_error[p]) : 0.0;
      if (std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]) && y >= floor) continue;
      failures.push_back(std::string(name) + " at " + pixel(p) + " has luminance " +
                         format_number(y));
    }
  }
  for (std::size_t p = 0; p < image.lighting_error.size(); ++p) {
    for (const double v : image.lighting_error[p]) {
      if (v >= 0.0 && std::isfinite(v)) continue;
      failures.push_back("lighting_error at " + pixel(p) + " is " + format_number(v));
      break;
    }
  }
  double foam = 0.0;
  for (std::size_t p = 0; p < image.coverage.size(); ++p) {
    if (!(image.coverage[p] >= 0.0 && image.coverage[p] <= 1.0)) {
      failures.push_back("coverage at " + pixel(p) + " is " + format_number(image.coverage[p]));
    }
    if (p < image.foam.size()) foam = std::max(foam, image.foam[p][1]);
  }
  if (scene.shading.whitecaps && !(foam > 0.0)) {
    failures.push_back("shading.whitecaps is on and no pixel shows foam");
  }
  // Open sky: fixed-grid renders (adaptive sampling and Mastin's extra samples take other rays)
  // without objects (the coverage counts the sea only).
  if (scene.image.pixel_tolerance > 0.0 || scene.image.mastin_antialiasing > 0.0 ||
      !scene.objects.empty()) {
    return failures;
  }
  const Camera camera = scene_camera(scene);
  const Sky sky = scene_sky(scene);
  const double cos_near_sun = math::cos(2.0 * std::numbers::pi / 180.0);  // 2° from the sun
  // A pixel is the box-filtered mean of its own samples: one whose samples all miss the sea is
  // the sky over its rays.
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const auto p = static_cast<std::size_t>(y * image.width + x);
      Vec3 mean;
      if (image.coverage[p] != 0.0 ||
          !open_sky_mean(camera, sky, cos_near_sun, x, y, image.samples_per_axis, mean)) {
        continue;
      }
      const Vec3& got = image.radiance[p];
      for (std::size_t k = 0; k < 3; ++k) {
        if (std::fabs(got[k] - mean[k]) <= 1e-12 * mean[k]) continue;
        failures.push_back("the open sky at " + pixel(p) + " is " + format_number(got[k]) +
                           ", the Preetham sky over its rays " + format_number(mean[k]));
        break;
      }
    }
  }
  return failures;
}

namespace {
GoldenReport run(const std::filesystem::path& root, const GoldenOptions& options, bool update) {
  const std::filesystem::path manifest_path = root / "golden" / "manifest.json";
  std::ifstream in(manifest_path);
  if (!in) throw GoldenInputError("root", "no manifest at " + manifest_path.string());
  nlohmann::json manifest;
  try {
    manifest = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw GoldenInputError("root", manifest_path.string() + ": not valid JSON: " + e.what());
  }
  const std::set<std::string> only(options.only.begin(), options.only.end());
  for (const std::string& name : only) {
    const auto& entries = manifest.at("entries");
    if (std::none_of(entries.begin(), entries.end(),
                     [&](const auto& e) { return e.at("name") == name; })) {
      throw GoldenInputError("only", "no scene named '" + name + "' in " + manifest_path.string());
    }
  }
  GoldenReport report;
  for (auto& entry : manifest.at("entries")) {
    const std::string name = entry.at("name").get<std::string>();
    if (!only.empty() && !only.contains(name)) continue;
    const std::filesystem::path scene_path = root / entry.at("scene").get<std::string>();
    const Scene scene = load_scene(scene_path.string());
    RenderOutputOptions render_options;
    render_options.threads = options.threads;
    render_options.log = options.log;
    // The layers are rendered for golden_physics_failures. The stored image keeps them only for a
    // converged golden (render.pixel_tolerance): its error layers, pixel_error and
    // lighting_error, for `compare --converged`, and the samples per pixel (the pixel hashes
    // cover R, G, B only, so the layers change no hash).
    const bool converged = scene.image.pixel_tolerance > 0.0;
    render_options.aov = true;
    RenderedScene r = render_scene(scene, render_options);
    // A Gerstner ocean has no wave grids: its golden is the image alone.
    const bool has_fields = scene.waves.model != WaveModel::gerstner;
    FieldsImage fields;
    if (has_fields) {
      fields = fields_image(scene, realize_ocean(scene.waves, options.threads), options.threads,
                            options.log);
    }
    const std::filesystem::path image_path = root / "golden" / (name + ".exr");
    const std::filesystem::path fields_path = root / "golden" / (name + ".fields.exr");
    // Identity on the float32 outputs and on the double buffers behind them.
    std::vector<std::pair<const char*, std::string>> hashes{
        {kGoldenHashKeys[0], r.pixel_sha256}, {kGoldenHashKeys[1], r.radiance_f64_sha256}};
    if (has_fields) {
      hashes.emplace_back(kGoldenHashKeys[2], fields.sha256);
      hashes.emplace_back(kGoldenHashKeys[3], fields.f64_sha256);
    }
    GoldenSceneResult result;
    result.name = name;
    result.pixel_sha256 = r.pixel_sha256;
    for (const auto& [key, value] : hashes) {
      if (entry.value(key, "") != value) result.differs.push_back(key);
    }
    result.same = result.differs.empty();
    result.physics = golden_physics_failures(scene, r.image);
    if (!result.physics.empty()) {
      ++report.invalid;
      result.status = "INVALID";
      report.scenes.push_back(std::move(result));
      continue;
    }
    // The stored image (and the one a mismatch is compared with) has no layers unless converged.
    if (!converged) r = scene_output(scene, std::move(r.image), false);
    if (update) {
      write_exr(image_path.string(), r.exr);
      if (has_fields) write_exr_parts(fields_path.string(), fields.parts);
      for (const auto& [key, value] : hashes) entry[key] = value;
      entry["scene_sha256"] = sha256_hex(scene.canonical);
      entry["width"] = r.exr.width;
      entry["height"] = r.exr.height;
      entry["version"] = r.exr.attributes.at("oceanref.version");
      entry["lighting_accuracy"] = r.exr.attributes.at("oceanref.lighting_accuracy");
      const LightingErrorSummary e = summarize_lighting_error(r.image);
      if (e.estimated) entry["lighting_error_max_relative"] = e.max_relative;
      entry["unconverged_samples"] = r.image.unconverged_samples;
      if (converged) {
        const PixelErrorSummary p = summarize_pixel_error(r.image);
        entry["pixel_tolerance"] = scene.image.pixel_tolerance;
        entry["max_samples_per_pixel"] = adaptive_samples(
            scene.image.pixel_pattern, scene.image.samples_per_axis, scene.image.max_refinements);
        entry["pixel_samples_mean"] = p.mean_samples;
        entry["capped_pixels"] = p.capped_pixels;
        entry["pixel_error_p50_relative"] = p.p50_relative;
        entry["pixel_error_p99_relative"] = p.p99_relative;
        entry["pixel_error_max_relative"] = p.max_relative;
        if (two_level_lighting(scene)) {  // the lighting part of the bound, and its cost
          entry["lighting_error_median_relative"] = e.median_relative;
          entry["corrected_samples"] = r.image.corrected_samples;
        }
      }
      result.status = result.same ? "unchanged" : "updated";
    } else {
      result.status = result.same ? "identical" : "MISMATCH";
      if (!result.same) {
        ++report.mismatches;
        try {
          result.comparison =
              comparison_text(compare_parts({ExrPart{"", 0, 0, read_exr(image_path.string())}},
                                            {ExrPart{"", 0, 0, r.exr}}, {}, uniform_profile({})));
        } catch (const std::exception& e) {
          result.comparison =
              "# cannot compare with " + image_path.string() + ": " + e.what() + "\n";
        }
      }
    }
    report.scenes.push_back(std::move(result));
  }
  if (update) {
    write_output_file(manifest_path.string(), manifest.dump(2) + '\n');
  }
  return report;
}
}  // namespace

GoldenReport verify_golden(const std::filesystem::path& root, const GoldenOptions& options) {
  return run(root, options, false);
}

GoldenReport update_golden(const std::filesystem::path& root, const GoldenOptions& options) {
  return run(root, options, true);
}

std::string golden_text(const GoldenReport& report) {
  std::ostringstream out;
  out << "name,status,pixel_sha256\n";
  for (const GoldenSceneResult& s : report.scenes) {
    out << s.name << ',' << s.status << ',' << s.pixel_sha256 << '\n';
    for (const std::string& failure : s.physics) out << "# invalid: " << failure << '\n';
    if (s.differs.empty() || s.status != "MISMATCH") continue;
    out << "# differs:";
    for (const std::string& key : s.differs) out << ' ' << key;
    out << '\n' << s.comparison;
  }
  return out.str();
}

}  // namespace oceanref
