#include "cli/acf_command.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "cli/text.h"
#include "conformance/fields_output.h"
#include "core/format.h"
#include "core/memory.h"
#include "io/output_file.h"
#include "io/png.h"
#include "scene/scene.h"
#include "waves/autocorrelation.h"
#include "waves/ocean.h"

namespace oceanref::cli {

namespace {
constexpr NumberRange kLengthRange{0.03125, 1024.0, " periods"};
constexpr NumberRange kAreaRange{1.0, 1e6, " periods"};

struct AcfFlags {
  std::vector<std::string> scenes;
  std::string output, svg, map, direction = "0", length = "8", area = "256", max_memory;
  int lines = 4000, samples_per_period = 32, map_pixels = 256, threads = 0;
  std::uint64_t seed = 1;
};

struct SceneAcf {
  std::string name;  // the scene file's stem
  Autocorrelation acf;
  std::vector<double> map;  // heights, when --map
};

std::string xml_escaped(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// scene,tau_m,tau_periods,acf,acf_disp_x,acf_height,acf_disp_z (a component without variance:
// empty),variance_disp_x,variance_height,variance_disp_z (r̃_c(0) [m²], the same on every row).
void write_csv(std::ostream& out, const std::vector<SceneAcf>& results) {
  out << "scene,tau_m,tau_periods,acf,acf_disp_x,acf_height,acf_disp_z,variance_disp_x,"
         "variance_height,variance_disp_z\n";
  for (const SceneAcf& r : results) {
    const Autocorrelation& a = r.acf;
    for (std::size_t j = 0; j < a.lags.size(); ++j) {
      out << r.name << ',' << format_number(a.lags[j]) << ',' << format_number(a.lags[j] / a.period)
          << ',' << format_number(a.vector[j]);
      for (const std::vector<double>& c : a.components) {
        out << ',';
        if (!c.empty()) out << format_number(c[j]);
      }
      for (const double v : a.variance) out << ',' << format_number(v);
      out << '\n';
    }
  }
}

// The vector ACF of every scene against τ in exemplar periods, one line each (Lutz Fig. 8,
// bottom row).
std::string acf_svg(const std::vector<SceneAcf>& results) {
  constexpr double kWidth = 760.0, kHeight = 380.0;
  constexpr double kLeft = 60.0, kRight = 190.0, kTop = 40.0, kBottom = 50.0;
  constexpr double kLow = -0.6, kHigh = 1.0;
  static constexpr std::array<const char*, 8> kColours{"#1f77b4", "#d62728", "#2ca02c", "#9467bd",
                                                       "#ff7f0e", "#8c564b", "#e377c2", "#17becf"};
  double longest = 0.0;
  for (const SceneAcf& r : results) longest = std::fmax(longest, r.acf.lags.back() / r.acf.period);
  const double w = kWidth - kLeft - kRight, h = kHeight - kTop - kBottom;
  const auto x_of = [&](double periods) { return kLeft + w * periods / longest; };
  const auto y_of = [&](double v) {
    return kTop + h * (kHigh - std::clamp(v, kLow, kHigh)) / (kHigh - kLow);
  };
  const auto num = [](double v) { return shortest_number(std::round(v * 100.0) / 100.0); };
  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << num(kWidth) << "\" height=\""
    << num(kHeight) << "\" font-family=\"sans-serif\" font-size=\"11\">\n"
    << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    << "<text x=\"" << num(kLeft + w / 2) << "\" y=\"20\" text-anchor=\"middle\" "
    << "font-size=\"13\">Autocorrelation of the displacement (Lutz et al. 2024 eq. 22)</text>\n";
  for (int p = 0; p <= static_cast<int>(longest); ++p) {
    s << "<line x1=\"" << num(x_of(p)) << "\" y1=\"" << num(kTop) << "\" x2=\"" << num(x_of(p))
      << "\" y2=\"" << num(kTop + h) << "\" stroke=\"#ddd\"/>\n"
      << "<text x=\"" << num(x_of(p)) << "\" y=\"" << num(kTop + h + 16)
      << "\" text-anchor=\"middle\">" << p << "</text>\n";
  }
  for (int t = -6; t <= 10; t += 2) {
    const double v = t / 10.0;
    s << "<line x1=\"" << num(kLeft) << "\" y1=\"" << num(y_of(v)) << "\" x2=\"" << num(kLeft + w)
      << "\" y2=\"" << num(y_of(v)) << "\" stroke=\"" << (t == 0 ? "#888" : "#ddd") << "\"/>\n"
      << "<text x=\"" << num(kLeft - 6) << "\" y=\"" << num(y_of(v) + 4)
      << "\" text-anchor=\"end\">" << num(v) << "</text>\n";
  }
  s << "<text x=\"" << num(kLeft + w / 2) << "\" y=\"" << num(kHeight - 12)
    << "\" text-anchor=\"middle\">lag &#964; [exemplar periods L]</text>\n"
    << "<text x=\"16\" y=\"" << num(kTop + h / 2) << "\" transform=\"rotate(-90 16 "
    << num(kTop + h / 2) << ")\" text-anchor=\"middle\">r(&#964;)/r(0)</text>\n";
  for (std::size_t i = 0; i < results.size(); ++i) {
    const Autocorrelation& a = results[i].acf;
    const char* colour = kColours[i % kColours.size()];
    s << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"1.5\" points=\"";
    for (std::size_t j = 0; j < a.lags.size(); ++j) {
      s << (j == 0 ? "" : " ") << num(x_of(a.lags[j] / a.period)) << ',' << num(y_of(a.vector[j]));
    }
    const double y = kTop + 12.0 + 18.0 * static_cast<double>(i);
    s << "\"/>\n<line x1=\"" << num(kLeft + w + 12) << "\" y1=\"" << num(y) << "\" x2=\""
      << num(kLeft + w + 32) << "\" y2=\"" << num(y) << "\" stroke=\"" << colour
      << "\" stroke-width=\"2\"/>\n<text x=\"" << num(kLeft + w + 38) << "\" y=\"" << num(y + 4)
      << "\">" << xml_escaped(results[i].name) << "</text>\n";
  }
  s << "</svg>\n";
  return s.str();
}

// The scenes' height maps side by side, 8 grey pixels apart: grey = ½ + η/(6σ), σ² the scene's
// height variance r̃(0), clamped to [0, 1].
void write_maps(const std::string& path, const std::vector<SceneAcf>& results, int pixels) {
  constexpr std::size_t kGap = 8;
  const auto n = static_cast<std::size_t>(pixels);
  const std::size_t width = results.size() * (n + kGap) - kGap;
  std::vector<std::uint8_t> rgb(width * n * 3, 128);
  for (std::size_t i = 0; i < results.size(); ++i) {
    const SceneAcf& r = results[i];
    const double sigma = std::sqrt(r.acf.variance[1]);
    for (std::size_t row = 0; row < n; ++row) {
      for (std::size_t m = 0; m < n; ++m) {
        const double eta = r.map[row * n + m];
        const double grey = sigma > 0.0 ? std::clamp(0.5 + eta / (6.0 * sigma), 0.0, 1.0) : 0.5;
        const auto byte = static_cast<std::uint8_t>(std::lround(255.0 * grey));
        // z grows upwards in the map (rows top to bottom).
        const std::size_t p = ((n - 1 - row) * width + i * (n + kGap) + m) * 3;
        rgb[p] = rgb[p + 1] = rgb[p + 2] = byte;
      }
    }
  }
  write_png(path, static_cast<int>(width), pixels, rgb);
}
}  // namespace

std::function<void(std::ostream&)> add_acf_command(CLI::App& app) {
  auto flags = std::make_shared<AcfFlags>();
  CLI::App* cmd = app.add_subcommand(
      "acf",
      "The autocorrelation function of each scene's displacement q = p(x0) - (x0, 0, z0) (Lutz "
      "et al. 2024 eq. 22), as the renderer reads the surface (scene synthesis, interpolation "
      "and normals), over random start points and lags along one direction: CSV "
      "scene,tau_m,tau_periods,acf,acf_disp_x,acf_height,acf_disp_z,variance_disp_x,"
      "variance_height,variance_disp_z to stdout or -o (acf: the vector's; a component without "
      "variance is empty; variance_*: r~(0), m^2), an SVG plot, a PNG map of the heights.");
  cmd->add_option("SCENES", flags->scenes, "scene files (JSON), one line each in the plot")
      ->required();
  cmd->add_option("-o,--output", flags->output, "OUT.csv (default: stdout)");
  cmd->add_option("--svg", flags->svg, "OUT.svg: the vector ACF of every scene against tau / L");
  cmd->add_option("--map", flags->map,
                  "OUT.png: each scene's height over 4 x 4 exemplar periods from (0, 0), side by "
                  "side, grey = 1/2 + eta/(6 sigma)");
  cmd->add_option("--map-pixels", flags->map_pixels, "pixels per map side (default 256)")
      ->check(integer_in(16, 4096));
  cmd->add_option("--lines", flags->lines, "random start points (default 4000)")
      ->check(integer_in(2, 10'000'000));
  cmd->add_option("--length", flags->length,
                  "the largest lag in exemplar periods L, the largest cascade size (default 8)")
      ->check(number_in(kLengthRange));
  cmd->add_option("--samples-per-period", flags->samples_per_period, "lags per period (default 32)")
      ->check(integer_in(1, 4096));
  cmd->add_option("--direction-deg", flags->direction,
                  "the lags' direction from x towards z [degrees] (default 0)")
      ->check(number_in(kDegreesRange));
  cmd->add_option("--area", flags->area,
                  "the start points' square, in periods a side, from (0, 0) (default 256)")
      ->check(number_in(kAreaRange));
  cmd->add_option("--seed", flags->seed, "the start points' seed (default 1)");
  cmd->add_option("--threads", flags->threads,
                  "worker threads (default: all cores); the output is identical for any count")
      ->check(integer_in(0, 1024, " (0: all cores)"));
  cmd->add_option("--max-memory", flags->max_memory, kMaxMemoryHelp);
  return [flags](std::ostream& out) {
    AutocorrelationSettings settings;
    settings.lines = flags->lines;
    settings.samples_per_period = flags->samples_per_period;
    settings.length = parse_number_in("--length", flags->length, kLengthRange);
    settings.area = parse_number_in("--area", flags->area, kAreaRange);
    settings.direction = parse_number_in("--direction-deg", flags->direction, kDegreesRange) *
                         (3.141592653589793 / 180.0);
    settings.seed = flags->seed;
    if (settings.length * settings.samples_per_period > 1e6) {
      throw UsageError("--length", "times --samples-per-period must be at most 1e6 lags");
    }
    check_output_paths({{"--output", flags->output}, {"--svg", flags->svg}, {"--map", flags->map}},
                       flags->scenes);
    const int threads = resolve_threads(flags->threads);
    std::vector<SceneAcf> results;
    for (const std::string& path : flags->scenes) {
      const Scene scene = load_scene(path);
      require_within(fields_memory_estimate(scene), max_memory_flag(flags->max_memory),
                     "--max-memory");
      progress("oceanref acf", "synthesizing " + path);
      const Ocean ocean = realize_ocean(scene.waves, threads);
      const Interpolation mode = scene.shading.interpolation;
      const std::vector<CascadeFields> fields = mode == Interpolation::direct
                                                    ? std::vector<CascadeFields>{}
                                                    : synthesize_ocean(ocean, scene.time, threads);
      const std::vector<EvolvedCascade> evolved = mode == Interpolation::direct
                                                      ? evolve_ocean(ocean, scene.time)
                                                      : std::vector<EvolvedCascade>{};
      SceneAcf r;
      r.name = std::filesystem::path(path).stem().string();
      progress("oceanref acf", "sampling " + std::to_string(settings.lines) + " lines of " + path);
      r.acf = displacement_autocorrelation(ocean, fields, evolved, mode, scene.shading.normals,
                                           settings, threads);
      if (!flags->map.empty()) {
        r.map = height_map(ocean, fields, evolved, mode, scene.shading.normals, 4.0 * r.acf.period,
                           flags->map_pixels, threads);
      }
      results.push_back(std::move(r));
    }
    std::ostringstream csv;
    write_csv(csv, results);
    if (flags->output.empty()) {
      out << csv.str();
    } else {
      write_output_file(flags->output, csv.str());
    }
    if (!flags->svg.empty()) write_output_file(flags->svg, acf_svg(results));
    if (!flags->map.empty()) write_maps(flags->map, results, flags->map_pixels);
  };
}

}  // namespace oceanref::cli
