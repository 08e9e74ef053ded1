#include "cli/compare_command.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <ostream>
#include <sstream>
#include <string>

#include "cli/text.h"
#include "conformance/compare.h"
#include "conformance/golden.h"
#include "conformance/report.h"
#include "io/output_file.h"

namespace oceanref::cli {

namespace {
// Each input may take a quarter of --max-memory: two images as floats, and the comparison's
// per-value errors (doubles) of one.
std::vector<ExrPart> read_parts(const std::string& flag, const std::string& path,
                                double max_memory) {
  try {
    return read_parts_for_compare(path, max_memory / 4.0);
  } catch (const std::exception& e) {
    throw UsageError(flag, e.what());
  }
}

// The list file of --suggest: one run per line, "CANDIDATE" (against GOLDEN) or
// "CANDIDATE GOLDEN"; blank lines and lines starting with '#' are skipped. Relative paths are
// relative to the list file's folder.
std::vector<std::pair<std::string, std::string>> read_run_list(const std::string& path,
                                                               const std::string& golden) {
  std::ifstream in(path);
  if (!in) throw UsageError("--list", path + ": cannot read");
  const std::filesystem::path base = std::filesystem::path(path).parent_path();
  const auto resolve = [&](const std::string& p) {
    return std::filesystem::path(p).is_absolute() ? p : (base / p).string();
  };
  std::vector<std::pair<std::string, std::string>> runs;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string x; words >> x;) w.push_back(x);
    if (w.empty() || w[0][0] == '#') continue;
    if (w.size() == 1) {
      if (golden.empty()) {
        throw UsageError(
            "--list", path + ":" + std::to_string(number) + ": one file, but no GOLDEN was given");
      }
      runs.emplace_back(golden, resolve(w[0]));
    } else if (w.size() == 2) {
      runs.emplace_back(resolve(w[1]), resolve(w[0]));
    } else {
      throw UsageError("--list", path + ":" + std::to_string(number) +
                                     ": expected CANDIDATE or CANDIDATE GOLDEN");
    }
  }
  if (runs.empty()) throw UsageError("--list", path + ": no run listed");
  return runs;
}
}  // namespace

std::function<void(std::ostream&)> add_compare_command(CLI::App& app) {
  struct Flags {
    std::vector<std::string> files;
    std::string report, profile, channels, json, format = "text", list, output, name, max_memory;
    ChannelThreshold threshold;
    bool alpha = false, suggest = false, converged = false;
    double safety = 4.0;
    double min_ssim = 0.0;
  };
  auto f = std::make_shared<Flags>();
  CLI::App* cmd = app.add_subcommand(
      "compare",
      "Compare a candidate EXR with a golden one, every part and level, channel by channel. "
      "Per value: scale s = max(|g|, F*RMS(g)) (RMS of the golden channel), relative error "
      "e = |c-g|/s; the value passes if |c-g| <= A + R*s, or if its float32 ULP distance <= U; "
      "a channel passes if at most S of its values fail. Any non-finite mismatch (NaN or +-Inf "
      "on one side only, +Inf vs -Inf, NaN vs Inf) fails, always. Prints per channel the "
      "percentiles p50/p90/p99/p99.9/max of e, the largest |c-g|, RMS(g), the largest ULP "
      "distance, the failing share and the worst pixel; for a part with R, G, B (or Y) also "
      "its SSIM (see --min-ssim). Exit 0 pass, 1 fail, 2 bad input. "
      "With --suggest: derive per-channel thresholds from several candidate runs.");
  cmd->add_option(
         "FILES", f->files,
         "CANDIDATE.exr GOLDEN.exr, the golden last (with --suggest: CANDIDATE... GOLDEN or GOLDEN "
         "--list FILE or --list FILE)")
      ->expected(0, -1);
  auto* abs = cmd->add_option("--abs", f->threshold.absolute, "A: absolute tolerance (0)")
                  ->check(number_in(0.0, 1e30));
  auto* rel = cmd->add_option("--rel", f->threshold.relative, "R: relative tolerance (0)")
                  ->check(number_in(0.0, 1e30));
  auto* floor = cmd->add_option("--floor", f->threshold.floor,
                                "F: the relative error's floor in units of RMS(g) (0; with "
                                "--suggest: 1)")
                    ->check(number_in(0.0, 1e30));
  auto* ulp = cmd->add_option("--ulp", f->threshold.ulp, "U: values within U float32 ULPs pass (0)")
                  ->check(integer_in(0LL, 4294967296LL));
  auto* share = cmd->add_option("--max-fail-share", f->threshold.allowed_share,
                                "S: allowed share of failing values per channel, in [0, 1] (0)")
                    ->check(number_in(0.0, 1.0));
  auto* min_ssim =
      cmd->add_option("--min-ssim", f->min_ssim,
                      "fail a part with R, G, B (or Y) whose SSIM is below this, in [-1, 1] "
                      "(SSIM: Wang et al. 2004 on the luminance tone-mapped by the golden's "
                      "log-average, 11x11 Gaussian window sigma 1.5, K1 0.01, K2 0.03, L 1; always "
                      "reported for such parts)")
          ->check(number_in(-1.0, 1.0));
  cmd->add_option("--profile", f->profile,
                  "FILE: per-channel thresholds (reference/profiles/*.json) instead of "
                  "--abs/--rel/--floor/--ulp/--max-fail-share")
      ->excludes(abs)
      ->excludes(rel)
      ->excludes(floor)
      ->excludes(ulp)
      ->excludes(share)
      ->excludes(min_ssim);
  cmd->add_option("--channels", f->channels,
                  "NAME,NAME,... or CANDIDATE=GOLDEN,...: compare just these (names or aliases: "
                  "R/r/red/rgba.R, G, B, A, Y/luminance); default: every candidate channel but "
                  "alpha, matched by name or alias");
  cmd->add_flag("--alpha", f->alpha, "also compare alpha channels (ignored by default)");
  cmd->add_flag("--converged", f->converged,
                "converged mode: add the golden's own estimated error of each R, G, B value "
                "(its pixel_error and lighting_error layers, from render --aov) to the "
                "tolerance, so a candidate with other sample positions is judged against the "
                "pixel integral (README, \"Converged pixels\")");
  cmd->add_option("--json", f->json,
                  "FILE: the full result as JSON (percentiles, histogram, worst)");
  cmd->add_option("--format", f->format, "stdout: text (a table) or json")
      ->check(CLI::IsMember({"text", "json"}))
      ->capture_default_str();
  cmd->add_option("--report", f->report,
                  "DIR: index.html (self-contained: heat maps, fail masks, worst-pixel crops, "
                  "golden/candidate flip) and diff.exr");
  cmd->add_flag("--suggest", f->suggest,
                "derive per-channel thresholds from candidate runs: R = safety * the largest e "
                "over the runs, channels grouped by name with digits as '*'; prints the profile "
                "JSON (or writes -o)");
  cmd->add_option("--list", f->list,
                  "FILE (--suggest): one run per line, CANDIDATE or CANDIDATE GOLDEN");
  cmd->add_option("--safety", f->safety, "--suggest: safety factor (4)")
      ->check(number_in(1.0, 1e6));
  cmd->add_option("-o,--output", f->output, "--suggest: write the profile JSON to FILE");
  cmd->add_option("--name", f->name, "--suggest: the profile's name");
  cmd->add_option("--max-memory", f->max_memory,
                  "refuse inputs whose pixels need more than a quarter of SIZE each: bytes or K, "
                  "M, G, T (binary), e.g. 20G; default 8G");
  return [f, floor, min_ssim](std::ostream& out) {
    const double max_memory = max_memory_flag(f->max_memory);
    // The report folder is created if missing; its index.html must not be an input either.
    const std::filesystem::path report_page = std::filesystem::path(f->report) / "index.html";
    std::vector<std::string> inputs = f->files;
    for (const std::string* p : {&f->profile, &f->list}) {
      if (!p->empty()) inputs.push_back(*p);
    }
    check_output_paths({{"--json", f->json},
                        {"--output", f->output},
                        {"--report", std::filesystem::is_directory(f->report) ? report_page.string()
                                                                              : std::string()}},
                       inputs);
    ChannelSelection selection;
    if (!f->channels.empty()) {
      try {
        selection = parse_channel_selection(f->channels);
      } catch (const std::invalid_argument& e) {
        throw UsageError("--channels", e.what());
      }
    }
    selection.include_alpha = f->alpha;
    if (f->suggest) {
      if (!f->report.empty() || !f->profile.empty() || !f->json.empty() || min_ssim->count() > 0 ||
          f->converged) {
        throw UsageError("--suggest",
                         "cannot be combined with --report, --profile, --json, "
                         "--min-ssim or --converged");
      }
      std::vector<std::pair<std::string, std::string>> runs;
      // The golden is the last file, as in compare CANDIDATE GOLDEN.
      const std::string golden = f->files.empty() ? std::string() : f->files.back();
      for (std::size_t i = 0; i + 1 < f->files.size(); ++i) runs.emplace_back(golden, f->files[i]);
      if (!f->list.empty()) {
        const auto listed = read_run_list(f->list, golden);
        runs.insert(runs.end(), listed.begin(), listed.end());
      }
      if (runs.empty()) {
        throw UsageError("--suggest", "needs CANDIDATE... GOLDEN or --list FILE");
      }
      const double floor_value = floor->count() > 0 ? f->threshold.floor : 1.0;
      ChannelThreshold measure;
      measure.floor = floor_value;
      std::vector<Comparison> comparisons;
      std::string derivation =
          "oceanref compare --suggest over " + std::to_string(runs.size()) + " run(s):";
      if (runs.size() > 4) derivation += " listed in " + f->list;
      for (const auto& [g, c] : runs) {
        try {
          comparisons.push_back(compare_parts(read_parts("GOLDEN", g, max_memory),
                                              read_parts("CANDIDATE", c, max_memory), selection,
                                              uniform_profile(measure)));
        } catch (const std::invalid_argument& e) {
          throw UsageError("compare", e.what());
        }
        if (runs.size() <= 4) derivation += " " + std::filesystem::path(c).filename().string();
      }
      std::vector<SuggestedRule> rules;
      try {
        rules = suggest_thresholds(comparisons, f->safety, floor_value);
      } catch (const std::invalid_argument& e) {
        throw UsageError("--suggest", e.what());
      }
      const std::string text = suggested_profile_json(
          rules, f->name.empty() ? "suggested" : f->name, derivation, f->safety, floor_value);
      if (f->output.empty()) {
        out << text;
      } else {
        write_output_file(f->output, text);
        out << "wrote " << f->output << " (" << rules.size() << " channel rules from "
            << runs.size() << " runs)\n";
      }
      return;
    }
    if (f->files.size() != 2) {
      throw UsageError("compare", "expected CANDIDATE.exr GOLDEN.exr, got " +
                                      std::to_string(f->files.size()) + " file(s)");
    }
    if (!f->list.empty() || !f->output.empty()) {
      throw UsageError("--list", "--list and --output belong to --suggest");
    }
    ThresholdProfile profile = uniform_profile(f->threshold);
    if (min_ssim->count() > 0) profile.min_ssim = f->min_ssim;
    if (!f->profile.empty()) {
      try {
        profile = read_profile(f->profile);
      } catch (const std::invalid_argument& e) {
        throw UsageError("--profile", e.what());
      }
    }
    if (f->converged) profile.golden_error = true;
    const std::vector<ExrPart> candidate = read_parts("CANDIDATE", f->files[0], max_memory);
    const std::vector<ExrPart> golden = read_parts("GOLDEN", f->files[1], max_memory);
    Comparison c;
    try {
      c = compare_parts(golden, candidate, selection, profile);
    } catch (const std::invalid_argument& e) {
      throw UsageError("compare", e.what());
    }
    const std::string json = comparison_json(c, f->files[1], f->files[0]);
    if (!f->json.empty()) write_output_file(f->json, json);
    out << (f->format == "json" ? json : comparison_text(c));
    if (!f->report.empty()) {
      write_report(f->report, f->files[1], f->files[0], golden, candidate, c);
    }
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
    sub->add_option("--threads", f->threads, "worker threads (default: all cores)")
        ->check(integer_in(0, 1024, " (0: all cores)"));
    sub->add_option("--only", f->only, "NAME,NAME,…: just these scenes of the manifest");
  }
  update->add_flag("--yes", f->yes, "required: really rewrite reference/golden");
  return [f, update](std::ostream& out) {
    if (update->parsed() && !f->yes) {
      throw UsageError("--yes", "golden update rewrites the references; pass --yes to do it");
    }
    GoldenOptions options;
    options.threads = resolve_threads(f->threads);
    options.log = [](const std::string& message) { progress("oceanref", message); };
    for (std::size_t start = 0; !f->only.empty() && start <= f->only.size();) {
      const std::size_t comma = std::min(f->only.find(',', start), f->only.size());
      options.only.push_back(f->only.substr(start, comma - start));
      start = comma + 1;
    }
    GoldenReport report;
    try {
      report = update->parsed() ? update_golden(f->root, options) : verify_golden(f->root, options);
    } catch (const GoldenInputError& e) {
      throw UsageError("--" + e.option(), e.what());
    }
    out << golden_text(report);
    if (!report.pass()) throw CheckFailed{};
  };
}

}  // namespace oceanref::cli
