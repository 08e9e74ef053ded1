#include "cli/compare_command.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <ostream>
#include <set>
#include <string>

#include "cli/fields_command.h"
#include "cli/render_command.h"
#include "cli/text.h"
#include "conformance/compare.h"
#include "conformance/report.h"
#include "io/sha256.h"

namespace oceanref::cli {

namespace {
void write_metrics(std::ostream& out, const Comparison& c) {
  out << "channel,max_abs,max_rel,rmse,psnr_db,max_ulp,failing_share,worst_x,worst_y\n";
  for (const ChannelMetrics& m : c.channels) {
    out << m.name << ',' << format_number(m.max_absolute) << ',' << format_number(m.max_relative)
        << ',' << format_number(m.rmse) << ',' << format_number(m.psnr) << ',' << m.max_ulp << ','
        << format_number(m.failing_share) << ',' << m.worst_x << ',' << m.worst_y << '\n';
  }
  out << "result," << (c.pass ? "pass" : "fail") << ",failing_pixels_share,"
      << format_number(c.failing_share) << '\n';
}

}  // namespace

std::function<void(std::ostream&)> add_compare_command(CLI::App& app) {
  struct Flags {
    std::string a, b, report;
    double absolute = 0.0, relative = 0.0, share = 0.0;
    long long ulp = 0;
  };
  auto f = std::make_shared<Flags>();
  CLI::App* cmd = app.add_subcommand(
      "compare",
      "Compare a candidate EXR with a golden one channel by channel: max absolute and relative "
      "error, RMSE, PSNR, max float32 ULP distance, failing share, worst pixel. Exit 0 pass, "
      "1 fail, 2 bad input. A value fails if |a-b| > abs + rel*|a| and its ULP distance > ulp.");
  cmd->add_option("GOLDEN", f->a, "golden EXR")->required();
  cmd->add_option("CANDIDATE", f->b, "candidate EXR")->required();
  cmd->add_option("--abs", f->absolute, "absolute tolerance (0)")->check(CLI::Range(0.0, 1e30));
  cmd->add_option("--rel", f->relative, "relative tolerance (0)")->check(CLI::Range(0.0, 1e30));
  cmd->add_option("--ulp", f->ulp, "allowed float32 ULP distance (0)")
      ->check(CLI::Range(0LL, 4294967296LL));
  cmd->add_option("--max-fail-share", f->share, "allowed share of failing pixels in [0, 1] (0)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--report", f->report, "DIR: diff.exr, golden/candidate/diff PNGs, index.html");
  return [f](std::ostream& out) {
    ExrImage golden;
    ExrImage candidate;
    try {
      golden = read_exr(f->a);
      candidate = read_exr(f->b);
    } catch (const std::exception& e) {
      throw UsageError("compare", e.what());
    }
    Comparison c;
    try {
      c = compare_images(golden, candidate, {f->absolute, f->relative, f->ulp, f->share});
    } catch (const std::invalid_argument& e) {
      throw UsageError("compare", e.what());
    }
    write_metrics(out, c);
    if (!f->report.empty()) write_report(f->report, f->a, f->b, golden, candidate, c);
    if (!c.pass) throw CheckFailed{};
  };
}

std::function<void(std::ostream&)> add_golden_command(CLI::App& app) {
  struct Flags {
    std::string root = "reference";
    std::string only;
    int threads = 0;
    bool yes = false;
  };
  auto f = std::make_shared<Flags>();
  CLI::App* cmd = app.add_subcommand(
      "golden",
      "The golden suite in ROOT/golden (manifest.json): verify re-renders every scene "
      "and checks the SHA-256 of the decoded pixels and fields; update rewrites them.");
  cmd->require_subcommand(1);
  CLI::App* verify = cmd->add_subcommand("verify",
                                         "re-render and check bit identity (exit 1 on "
                                         "any mismatch, with its metrics)");
  CLI::App* update = cmd->add_subcommand("update", "re-render and rewrite the golden files");
  for (CLI::App* sub : {verify, update}) {
    sub->add_option("--root", f->root, "the reference folder")->capture_default_str();
    sub->add_option("--threads", f->threads, "worker threads (default: all cores)");
    sub->add_option("--only", f->only, "NAME,NAME,…: just these scenes of the manifest");
  }
  update->add_flag("--yes", f->yes, "required: really rewrite reference/golden");
  return [f, verify, update](std::ostream& out) {
    if (update->parsed() && !f->yes) {
      throw UsageError("--yes", "golden update rewrites the references; pass --yes to do it");
    }
    const std::filesystem::path root(f->root);
    const std::filesystem::path manifest_path = root / "golden" / "manifest.json";
    std::ifstream in(manifest_path);
    if (!in) throw UsageError("--root", "no manifest at " + manifest_path.string());
    nlohmann::json manifest;
    try {
      manifest = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
      throw UsageError("--root", manifest_path.string() + ": not valid JSON: " + e.what());
    }
    const int threads = resolve_threads(f->threads);
    std::set<std::string> only;
    for (std::size_t start = 0; !f->only.empty() && start <= f->only.size();) {
      const std::size_t comma = std::min(f->only.find(',', start), f->only.size());
      only.insert(f->only.substr(start, comma - start));
      start = comma + 1;
    }
    for (const std::string& name : only) {
      const auto& entries = manifest.at("entries");
      if (std::none_of(entries.begin(), entries.end(),
                       [&](const auto& e) { return e.at("name") == name; })) {
        throw UsageError("--only", "no scene named '" + name + "' in " + manifest_path.string());
      }
    }
    int mismatches = 0;
    out << "name,status,pixel_sha256\n";
    for (auto& entry : manifest.at("entries")) {
      const std::string name = entry.at("name").get<std::string>();
      if (!only.empty() && !only.contains(name)) continue;
      const std::filesystem::path scene_path = root / entry.at("scene").get<std::string>();
      const RenderedScene r = render_scene(scene_path.string(), threads, 0, false, false);
      const Scene scene = load_scene(scene_path.string());
      const Ocean ocean = realize_ocean(scene.waves, threads);
      const FieldsImage fields_output = fields_image(scene, ocean, threads);
      const std::string& fields_hash = fields_output.sha256;
      const std::filesystem::path image_path = root / "golden" / (name + ".exr");
      const std::filesystem::path fields_path = root / "golden" / (name + ".fields.exr");
      // Identity on the float32 outputs and on the double buffers behind them.
      const bool same = entry.value("pixel_sha256", "") == r.pixel_sha256 &&
                        entry.value("radiance_f64_sha256", "") == r.radiance_f64_sha256 &&
                        entry.value("fields_sha256", "") == fields_hash &&
                        entry.value("fields_f64_sha256", "") == fields_output.f64_sha256;
      if (update->parsed()) {
        write_exr(image_path.string(), r.exr);
        write_exr_parts(fields_path.string(), fields_output.parts);
        entry["pixel_sha256"] = r.pixel_sha256;
        entry["fields_sha256"] = fields_hash;
        entry["radiance_f64_sha256"] = r.radiance_f64_sha256;
        entry["fields_f64_sha256"] = fields_output.f64_sha256;
        entry["scene_sha256"] = sha256_hex(scene.canonical);
        entry["width"] = r.exr.width;
        entry["height"] = r.exr.height;
        entry["version"] = r.exr.attributes.at("oceanref.version");
        entry["lighting_accuracy"] = r.exr.attributes.at("oceanref.lighting_accuracy");
        const LightingErrorSummary e = summarize_lighting_error(r.image);
        if (e.estimated) entry["lighting_error_max_relative"] = e.max_relative;
        entry["unconverged_samples"] = r.image.unconverged_samples;
        out << name << ',' << (same ? "unchanged" : "updated") << ',' << r.pixel_sha256 << '\n';
        continue;
      }
      out << name << ',' << (same ? "identical" : "MISMATCH") << ',' << r.pixel_sha256 << '\n';
      if (!same) {
        ++mismatches;
        out << "# differs:";
        for (const auto& [key, value] :
             {std::pair{"pixel_sha256", r.pixel_sha256},
              std::pair{"radiance_f64_sha256", r.radiance_f64_sha256},
              std::pair{"fields_sha256", fields_hash},
              std::pair{"fields_f64_sha256", fields_output.f64_sha256}}) {
          if (entry.value(key, "") != value) out << ' ' << key;
        }
        out << '\n';
        try {
          write_metrics(out, compare_images(read_exr(image_path.string()), r.exr, {}));
        } catch (const std::exception& e) {
          out << "# cannot compare with " << image_path.string() << ": " << e.what() << '\n';
        }
      }
    }
    if (update->parsed()) {
      const std::filesystem::path temporary = manifest_path.string() + ".tmp";
      {
        std::ofstream file(temporary);
        file << manifest.dump(2) << '\n';
        if (!file) throw std::runtime_error(manifest_path.string() + ": cannot write");
      }
      std::filesystem::rename(temporary, manifest_path);
    }
    (void)verify;
    if (mismatches > 0) throw CheckFailed{};
  };
}

}  // namespace oceanref::cli
