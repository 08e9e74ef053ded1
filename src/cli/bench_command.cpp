#include "cli/bench_command.h"

#include <cmath>
#include <iterator>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "cli/text.h"
#include "conformance/fields_output.h"
#include "conformance/float32_backend.h"
#include "conformance/lean_study.h"
#include "conformance/lighting_map.h"
#include "conformance/study.h"
#include "io/exr.h"
#include "io/output_file.h"
#include "scene/scene.h"
#include "waves/ocean.h"
#include "waves/stages.h"

namespace oceanref::cli {

std::function<void(std::ostream&)> add_bench_command(CLI::App& app) {
  auto flags = std::make_shared<SynthesisBenchOptions>();
  CLI::App* bench = app.add_subcommand(
      "bench", "Speed and accuracy figures (see reference/ACCURACY.md); not part of the tests.");
  bench->require_subcommand(1);
  CLI::App* synthesis = bench->add_subcommand(
      "synthesis",
      "Time one frame of wave synthesis per stage with KissFFT and, in the same run, FFTW "
      "double; report the float-vs-double difference of every field.");
  synthesis->add_option("--cascades", flags->cascades, "number of cascades")
      ->check(integer_in(1, 16))
      ->capture_default_str();
  synthesis->add_option("--resolution", flags->resolution, "N_h, a power of two in [4, 4096]")
      ->check(integer_in(4, 4096, " (a power of two)"))
      ->capture_default_str();
  synthesis
      ->add_option("--low-resolution", flags->low_resolution,
                   "N_l for eta and D (default: N_h, no multi-resolution)")
      ->check(integer_in(0, 4096, " (a power of two <= --resolution; 0: = --resolution)"));
  synthesis->add_option("--threads", flags->threads, "worker threads")
      ->check(integer_in(1, 1024))
      ->capture_default_str();
  synthesis->add_option("--frames", flags->frames, "timed frames (median reported)")
      ->check(integer_in(1, 100000))
      ->capture_default_str();
  auto lighting_order = std::make_shared<int>(64);
  CLI::App* lighting = bench->add_subcommand(
      "lighting",
      "Errors of the shader approximations (Schlick Fresnel, rational erfc, mean-Fresnel fit, "
      "mirror sky lookup) against the exact forms, the printed-vs-physical sun transmittance, "
      "and the convergence of the sky quadrature.");
  lighting->add_option("--order", *lighting_order, "Gauss-Hermite order of the exact terms")
      ->check(integer_in(4, 512))
      ->capture_default_str();
  struct MapFlags {
    std::string csv, svg;
    int threads = 2;
    bool quick = false;
  };
  auto map_options = std::make_shared<MapFlags>();
  CLI::App* lighting_map = bench->add_subcommand(
      "lighting-map",
      "The speed/accuracy map of the lighting integrals (reflected sky, mean Fresnel, sun "
      "disk): over a fixed sweep of views (V.N 0.9 to 0.002), roughness (sigma^2 1e-6 to 1, "
      "anisotropic too), flat and tilted normals and suns high, low and at the horizon, the "
      "median, 95th percentile and largest relative error against a truth (reference at "
      "tolerance 1e-10) and the time per integral of every fast order and every reference "
      "tolerance 1e-2..1e-9, and the count of reference error estimates below the actual "
      "error. Prints markdown tables; takes a few minutes (tools/lighting_accuracy_map.sh).");
  lighting_map->add_option("--csv", map_options->csv, "OUT.csv: every row of the map");
  lighting_map->add_option("--svg", map_options->svg,
                           "OUT.svg: error versus time per integral, log-log");
  lighting_map->add_option("--threads", map_options->threads, "worker threads for the truths")
      ->check(integer_in(1, 1024))
      ->capture_default_str();
  lighting_map->add_flag("--quick", map_options->quick,
                         "a tiny sweep, fewer orders and tolerances (a smoke test, not a "
                         "measurement)");
  struct PixelFlags {
    std::string fast, reference;
  };
  auto pixel_flags = std::make_shared<PixelFlags>();
  CLI::App* lighting_pixels = bench->add_subcommand(
      "lighting-pixels",
      "The per-pixel error of a fast render against a reference render of the same scene over "
      "sea pixels (coverage > 0): |fast - reference|/|reference| (largest channel per pixel) "
      "and the same from the fast render's lighting_error layer; CSV of median, 95th "
      "percentile and largest.");
  lighting_pixels
      ->add_option("FAST_AOV", pixel_flags->fast, "fast render written with --aov --lighting-error")
      ->required()
      ->check(CLI::ExistingFile);
  lighting_pixels->add_option("REFERENCE", pixel_flags->reference, "reference render (.exr)")
      ->required()
      ->check(CLI::ExistingFile);
  struct RenderFlags {
    std::string scene = "reference/scenes/default.json";
    int threads = 2, width = 1280, height = 720, spp = 4;
  };
  auto render_flags = std::make_shared<RenderFlags>();
  CLI::App* render_cmd = bench->add_subcommand(
      "render",
      "Time one render per stage (synthesis, grid, raster, shading) and samples/s; "
      "the interpolation modes' error against direct summation; the slope variance budget "
      "(resolved + sigma^2 = the spectrum's moment) for every shading.normals and interpolation.");
  render_cmd->add_option("--scene", render_flags->scene, "scene file")->capture_default_str();
  render_cmd->add_option("--threads", render_flags->threads, "worker threads")
      ->check(integer_in(1, 1024))
      ->capture_default_str();
  render_cmd->add_option("--width", render_flags->width, "image width")
      ->check(integer_in(1, 16384))
      ->capture_default_str();
  render_cmd->add_option("--height", render_flags->height, "image height")
      ->check(integer_in(1, 16384))
      ->capture_default_str();
  render_cmd->add_option("--spp", render_flags->spp, "samples per pixel (a square)")
      ->check(integer_in(1, 256, " (a square number)"))
      ->capture_default_str();
  struct StudyFlags {
    std::string scene = "reference/scenes/default.json";
    int threads = 2;
    bool quick = false;
  };
  auto study_flags = std::make_shared<StudyFlags>();
  CLI::App* study = bench->add_subcommand(
      "study",
      "The speed/accuracy study: FFT vs direct, FFT resolution and cascades (Hs, mss), "
      "projected-grid resolution, samples per pixel, whitecap statistics, "
      "interpolation; each against its most exact setting in the same run.");
  study->add_option("--scene", study_flags->scene, "scene file")->capture_default_str();
  study->add_option("--threads", study_flags->threads, "worker threads")
      ->check(integer_in(1, 1024))
      ->capture_default_str();
  study->add_flag("--quick", study_flags->quick,
                  "the same tables on small sizes, in seconds (a test of the study, not a "
                  "measurement)");
  struct LeanFlags {
    std::string scene;
    std::string sizes;
    int footprints = 12, samples = 64, threads = 2;
  };
  auto lean_flags = std::make_shared<LeanFlags>();
  CLI::App* lean = bench->add_subcommand(
      "lean",
      "Filtered shading at a distance (Lutz et al. 2024 Fig. 7): the specular lobe of pixel "
      "footprints by normal mapping, LEAN of the tiles without and with the rotation correction "
      "(eq. 13, 16, 19-21) and LEAN of the surface's own moments, against the supersampled "
      "lobe; CSV method,footprint_m,lobe_error_mean,lobe_error_max,glint_error_mean "
      "(src/conformance/lean_study.h).");
  lean->add_option("--scene", lean_flags->scene, "scene file")->required();
  lean->add_option("--footprint-sizes", lean_flags->sizes,
                   "footprint widths [m], comma-separated (default: 1/16, 1/4 and 1 exemplar "
                   "period); each 8 times as long along x");
  lean->add_option("--footprints", lean_flags->footprints, "footprints per size")
      ->check(integer_in(1, 10000))
      ->capture_default_str();
  lean->add_option("--samples", lean_flags->samples, "supersamples per footprint axis")
      ->check(integer_in(2, 1024))
      ->capture_default_str();
  lean->add_option("--threads", lean_flags->threads, "worker threads")
      ->check(integer_in(1, 1024))
      ->capture_default_str();
  struct Float32Flags {
    std::string scene, output, golden, defect = "none", stage = "fields";
    double time = 0.0;
    int threads = 2;
  };
  auto float32_flags = std::make_shared<Float32Flags>();
  CLI::App* float32 = bench->add_subcommand(
      "float32",
      "The float32 example backend (src/conformance/float32_backend.h): one stage of the scene's "
      "waves computed entirely in float32 from the scene (spectrum, h0 with the counter-based "
      "draws, omega, hkt, fields with FFTW float), written as a candidate EXR in the layout of "
      "`oceanref fields --stage STAGE` (parts c<i> on N_h and, with multi-resolution, c<i>.low "
      "on N_l); --golden also writes what `oceanref fields --stage STAGE` writes. Then: oceanref "
      "compare CANDIDATE GOLDEN --profile reference/profiles/STAGE_float32.json.");
  float32->add_option("SCENE", float32_flags->scene, "scene file")->required();
  float32->add_option("-o,--output", float32_flags->output, "candidate: OUT.exr")->required();
  float32
      ->add_option("--stage", float32_flags->stage,
                   "spectrum, h0, omega, hkt or fields (the raw fields c<i>.<field>.V, no "
                   "jacobian, foam or sum part)")
      ->check(CLI::IsMember({"spectrum", "h0", "omega", "hkt", "fields"}))
      ->capture_default_str();
  float32->add_option(
      "--golden", float32_flags->golden,
      "also write oceanref's STAGE (as `oceanref fields --stage STAGE`): GOLDEN.exr");
  float32->add_option("--time", float32_flags->time, "time t [s] (default: the scene's)")
      ->check(number_in(0.0, 1e7, " s"));
  float32
      ->add_option(
          "--defect", float32_flags->defect,
          "a deliberate bug, to see the profile catch it: drop-conjugate-term, "
          "half-float-phase (hkt, fields), flip-one-phase (cascade 0's strongest h0 "
          "negated: h0, hkt, fields), half-float-output (every value written rounded to "
          "11 significant bits: any stage), drop-polar-jacobian (Theta = Psi D without the 1/k: "
          "every stage but omega)")
      ->check(CLI::IsMember(
          std::vector<std::string>(std::begin(kFloat32DefectNames), std::end(kFloat32DefectNames))))
      ->capture_default_str();
  float32->add_option("--threads", float32_flags->threads, "worker threads (golden)")
      ->check(integer_in(1, 1024))
      ->capture_default_str();
  return [float32, float32_flags, flags, synthesis, lighting, lighting_order, render_cmd,
          render_flags, study, study_flags, lighting_map, map_options, lighting_pixels, pixel_flags,
          lean, lean_flags](std::ostream& out) {
    if (float32->parsed()) {
      const Float32Flags& g = *float32_flags;
      Scene scene;
      try {
        scene = load_scene(g.scene);
      } catch (const std::exception& e) {
        throw UsageError("SCENE", e.what());
      }
      if (float32->count("--time") > 0) scene.time = g.time;
      Stage stage = Stage::fields;
      for (std::size_t i = 0; i < kStageNames.size(); ++i) {
        if (g.stage == kStageNames[i]) stage = Stage(i);
      }
      Float32Defect defect = Float32Defect::none;
      for (std::size_t i = 0; i < std::size(kFloat32DefectNames); ++i) {
        if (g.defect == kFloat32DefectNames[i]) defect = Float32Defect(i);
      }
      std::vector<ExrPart> candidate;
      try {
        candidate = float32_stage_parts(scene.waves, stage, scene.time, defect);
      } catch (const std::invalid_argument& e) {
        throw UsageError("SCENE", g.scene + ": " + e.what());
      }
      for (ExrPart& part : candidate) {
        part.image.attributes["oceanref.time_s"] = format_number(scene.time);
        part.image.attributes["oceanref.stage"] = g.stage;
        part.image.attributes["oceanref.backend"] =
            std::string("float32 example backend, defect ") + g.defect;
      }
      write_exr_parts(g.output, candidate);
      out << "wrote " << g.output << " (" << candidate.size() << " parts)\n";
      if (!g.golden.empty()) {
        const Ocean ocean = realize_ocean(scene.waves, g.threads);
        const std::vector<ExrPart> golden = stage == Stage::fields
                                                ? fields_image(scene, ocean, g.threads).parts
                                                : stage_image(scene, ocean, stage, g.threads);
        write_exr_parts(g.golden, golden);
        out << "wrote " << g.golden << " (" << golden.size() << " parts)\n";
      }
      return;
    }
    if (lighting_map->parsed()) {
      const MapFlags& m = *map_options;
      check_output_paths({{"--csv", m.csv}, {"--svg", m.svg}}, {});
      const LightingMap map = measure_lighting_map(lighting_map_sweep(m.quick), m.threads);
      if (!m.csv.empty()) write_output_file(m.csv, lighting_map_csv(map));
      if (!m.svg.empty()) write_output_file(m.svg, lighting_map_svg(map));
      out << lighting_map_markdown(map);
      return;
    }
    if (lighting_pixels->parsed()) {
      try {
        out << lighting_pixels_csv(
            lighting_pixel_errors(read_exr(pixel_flags->fast), read_exr(pixel_flags->reference)));
      } catch (const LightingPixelsInputError& e) {
        throw UsageError(e.reference ? "REFERENCE" : "FAST_AOV", e.what());
      }
      return;
    }
    if (lean->parsed()) {
      const LeanFlags& l = *lean_flags;
      LeanStudySettings settings;
      settings.footprints = l.footprints;
      settings.samples_per_axis = l.samples;
      settings.threads = l.threads;
      if (!l.sizes.empty()) {
        settings.footprint_sizes = parse_number_list("--footprint-sizes", l.sizes, "(0, 1e6] m");
        for (const double v : settings.footprint_sizes) {
          if (!(v > 0.0 && v <= 1e6)) {
            throw UsageError("--footprint-sizes",
                             "each must be in (0, 1e6] m, got " + shortest_number(v));
          }
        }
      }
      bench_lean(out, lean_study(load_scene(l.scene), settings));
      return;
    }
    if (study->parsed()) {
      bench_study(out, study_flags->scene, study_flags->threads, study_flags->quick);
      return;
    }
    if (lighting->parsed()) {
      bench_lighting(out, *lighting_order);
      return;
    }
    if (render_cmd->parsed()) {
      const RenderFlags& r = *render_flags;
      const int axis = static_cast<int>(std::lround(std::sqrt(static_cast<double>(r.spp))));
      if (axis * axis != r.spp) {
        throw UsageError("--spp",
                         "must be a square number in [1, 256], got " + std::to_string(r.spp));
      }
      bench_render(out, r.scene, r.threads, r.width, r.height, r.spp);
      bench_interpolation(out, r.scene, r.threads);
      bench_slope_budget(out, r.scene, r.threads);
      return;
    }
    const auto power_of_two = [](int n, int hi) { return n >= 4 && n <= hi && (n & (n - 1)) == 0; };
    if (!power_of_two(flags->resolution, 4096)) {
      throw UsageError("--resolution", "must be a power of two in [4, 4096], got " +
                                           std::to_string(flags->resolution));
    }
    if (flags->low_resolution != 0 && !power_of_two(flags->low_resolution, flags->resolution)) {
      throw UsageError("--low-resolution", "must be a power of two in [4, --resolution], got " +
                                               std::to_string(flags->low_resolution));
    }
    if (synthesis->parsed()) bench_synthesis(out, *flags);
  };
}

}  // namespace oceanref::cli
