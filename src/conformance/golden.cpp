#include "conformance/golden.h"

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <utility>

#include "conformance/compare.h"
#include "conformance/fields_output.h"
#include "conformance/render_output.h"
#include "io/exr.h"
#include "io/output_file.h"
#include "io/sha256.h"
#include "scene/scene.h"

namespace oceanref {

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
    // A converged golden (render.pixel_tolerance) carries its error layers, pixel_error and
    // lighting_error, for `compare --converged`, and the samples per pixel (the pixel hashes
    // cover R, G, B only, so the layers change no hash).
    const bool converged = scene.image.pixel_tolerance > 0.0;
    render_options.aov = converged;
    const RenderedScene r = render_scene(scene, render_options);
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
        const int cap =
            refined_samples_per_axis(scene.image.samples_per_axis, scene.image.max_refinements);
        entry["max_samples_per_pixel"] = cap * cap;
        entry["pixel_samples_mean"] = p.mean_samples;
        entry["capped_pixels"] = p.capped_pixels;
        entry["pixel_error_p50_relative"] = p.p50_relative;
        entry["pixel_error_p99_relative"] = p.p99_relative;
        entry["pixel_error_max_relative"] = p.max_relative;
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
    if (s.differs.empty() || s.status != "MISMATCH") continue;
    out << "# differs:";
    for (const std::string& key : s.differs) out << ' ' << key;
    out << '\n' << s.comparison;
  }
  return out.str();
}

}  // namespace oceanref
