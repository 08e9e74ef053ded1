#include "cli/fields_command.h"

#include <cmath>
#include <iostream>
#include <memory>
#include <ostream>
#include <string>

#include "cli/text.h"
#include "conformance/fields_output.h"
#include "io/exr.h"
#include "io/output_file.h"
#include "scene/scene.h"
#include "waves/ocean.h"
#include "waves/stages.h"

namespace oceanref::cli {

namespace {
constexpr NumberRange kTimeRange{-1e7, 1e7, " s"};

struct FieldsFlags {
  std::string scene, output, at, time, stage, max_memory;
  int threads = 0;
};

void log_progress(const std::string& message) {
  progress("oceanref fields", message);
}

void write_stage_exr(const std::string& path, const Scene& scene, const Ocean& ocean, Stage stage,
                     int threads) {
  const std::vector<ExrPart> parts = stage == Stage::fields
                                         ? fields_image(scene, ocean, threads, log_progress).parts
                                         : stage_image(scene, ocean, stage, threads);
  progress("oceanref fields", "writing " + path);
  write_exr_parts(path, parts);
}

void write_point(std::ostream& out, const Scene& scene, const Ocean& ocean, double x, double z,
                 int threads) {
  out << "cascade,field,fft,direct,difference\n";
  for (const PointFieldRow& r : fields_at_point(scene, ocean, x, z, threads)) {
    out << r.cascade << ',' << r.field << ',' << format_number(r.fft) << ','
        << format_number(r.direct) << ',' << format_number(r.fft - r.direct) << '\n';
  }
}
}  // namespace

std::function<void(std::ostream&)> add_fields_command(CLI::App& app) {
  auto flags = std::make_shared<FieldsFlags>();
  CLI::App* cmd = app.add_subcommand(
      "fields",
      "Synthesize the wave fields of a scene, or export an earlier stage: every cascade as a "
      "part of a multi-part float EXR (-o; docs/FILES.md, docs/BACKENDS.md), or every field at "
      "one point from the FFT grid and by direct summation (--at).");
  cmd->add_option("SCENE", flags->scene, "scene file (JSON; sections seed, time, waves)")
      ->required();
  cmd->add_option("--time", flags->time, "time t [s], overrides the scene's time")
      ->check(number_in(kTimeRange));
  auto* output = cmd->add_option(
      "-o,--output", flags->output,
      "OUT.exr, one part per cascade i and grid: c<i> (N_h x N_h) and, when low_resolution < "
      "resolution, c<i>.low (N_l x N_l); every channel is a field name plus .V (Blender's "
      "layer.pass.channel rule; docs/FILES.md). Stage fields: channels c<i>.height.V, disp_x.V, "
      "disp_z.V (in c<i>.low when multi-resolution), c<i>.slope_x.V, slope_z.V, ddx_dx.V, "
      "ddz_dz.V, ddx_dz.V, jacobian.V, foam.V, and a part sum: sum.height.V, slope_x.V, "
      "slope_z.V, jacobian.V, normal_x.V, normal_y.V, normal_z.V, foam.V");
  cmd->add_option("--stage", flags->stage,
                  "with -o: fields (default); spectrum (<part>.theta.V = Theta(k) [m^4], "
                  "<part>.variance.V = Theta(k) dk^2 [m^2], <part>.in_band.V), h0 "
                  "(<part>.h0.re.V, .im.V [m]), omega (<part>.omega.V [rad/s], .kx.V, .kz.V, .k.V "
                  "[rad/m]) or hkt (<part>.hkt.re.V, .im.V [m] at --time) on each cascade's "
                  "wavevector grid, k = 0 at pixel (0, 0), FFT order")
      ->check(CLI::IsMember({"spectrum", "h0", "omega", "hkt", "fields"}));
  auto* at = cmd->add_option("--at", flags->at,
                             "x,z [m] -> CSV cascade,field,fft,direct,difference (FFT grid: exact "
                             "at nodes, bilinear between; direct: summation of every component; "
                             "sum rows combined as shading.normals)");
  output->excludes(at);
  cmd->add_option("--threads", flags->threads,
                  "worker threads (default: all cores); the output is identical for any count")
      ->check(integer_in(0, 1024, " (0: all cores)"));
  cmd->add_option("--max-memory", flags->max_memory, kMaxMemoryHelp);
  return [flags](std::ostream& out) {
    if (flags->output.empty() && flags->at.empty()) {
      throw UsageError("fields", "give -o OUT.exr or --at x,z");
    }
    if (!flags->stage.empty() && flags->output.empty()) {
      throw UsageError("--stage", "needs -o OUT.exr (--at prints the fields only)");
    }
    Stage stage = Stage::fields;
    for (std::size_t i = 0; i < kStageNames.size(); ++i) {
      if (flags->stage == kStageNames[i]) stage = Stage(i);
    }
    check_output_paths({{"--output", flags->output}}, {flags->scene});
    const int threads = resolve_threads(flags->threads);
    Scene scene = load_scene(flags->scene);
    if (!flags->time.empty()) {
      scene.time = parse_number_in("--time", flags->time, kTimeRange);
    }
    require_within(fields_memory_estimate(scene), max_memory_flag(flags->max_memory),
                   "--max-memory");
    progress("oceanref fields", "realizing the spectrum");
    const Ocean ocean = realize_ocean(scene.waves, threads);
    if (!flags->output.empty()) {
      write_stage_exr(flags->output, scene, ocean, stage, threads);
      return;
    }
    const std::vector<double> point = parse_number_list("--at", flags->at, "[-1e9, 1e9] m each");
    if (point.size() != 2)
      throw UsageError("--at", "expected x,z, got '" + escape_value(flags->at) + "'");
    if (std::fabs(point[0]) > 1e9 || std::fabs(point[1]) > 1e9) {
      throw UsageError(
          "--at", "coordinates must be in [-1e9, 1e9] m, got '" + escape_value(flags->at) + "'");
    }
    write_point(out, scene, ocean, point[0], point[1], threads);
  };
}

}  // namespace oceanref::cli
