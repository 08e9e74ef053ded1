#include "cli/fields_command.h"

#include <cmath>
#include <iostream>
#include <map>
#include <memory>
#include <ostream>
#include <string>

#include "cli/text.h"
#include "io/exr.h"
#include "io/sha256.h"
#include "scene/scene.h"
#include "waves/direct_sum.h"
#include "waves/ocean.h"

namespace oceanref::cli {

namespace {
struct FieldsFlags {
  std::string scene, output, at, time;
  int threads = 0;
};

std::vector<float> to_float(const std::vector<double>& v) {
  return std::vector<float>(v.begin(), v.end());
}

}  // namespace

FieldsImage fields_image(const Scene& scene, const Ocean& ocean, int threads) {
  progress("oceanref fields",
           "synthesizing " + std::to_string(ocean.cascades.size()) + " cascades");
  const std::vector<CascadeFields> fields = synthesize_ocean(ocean, scene.time, threads);
  const int n = scene.waves.resolution;
  ExrImage image;
  std::map<std::string, std::vector<double>> exact;  // the doubles behind each channel
  const auto add_channel = [&](const std::string& name, int sampling,
                               const std::vector<double>& values) {
    image.channels.push_back({name, sampling, to_float(values)});
    exact[name] = values;
  };
  image.width = n;
  image.height = n;
  std::string sizes;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const std::string prefix = "c" + std::to_string(i) + ".";
    sizes += (i ? "," : "") + format_number(fields[i].size);
    for (int q = 0; q < kFieldCount; ++q) {
      const int sampling = is_low_resolution_field(Field(q)) ? n / fields[i].low_resolution : 1;
      add_channel(prefix + std::string(kFieldNames[static_cast<std::size_t>(q)]), sampling,
                  fields[i].values[static_cast<std::size_t>(q)]);
    }
    const std::vector<double> jacobian = cascade_jacobian(fields[i], ocean.cascades[i].choppiness);
    std::vector<double> foam(jacobian.size());
    for (std::size_t c = 0; c < foam.size(); ++c) foam[c] = jacobian[c] < 0.0 ? 1.0 : 0.0;
    add_channel(prefix + "jacobian", 1, jacobian);
    add_channel(prefix + "foam", 1, foam);
  }
  std::vector<PointFields> sum =
      combine_on_footprint(ocean, evolve_ocean(ocean, scene.time), scene.shading.normals, threads);
  // Foam of a sequence: the indicator accumulated over the earlier frames (listing 2.4).
  if (scene.foam.steps > 0) {
    progress("oceanref fields",
             "accumulating foam over " + std::to_string(scene.foam.steps) + " earlier frames");
    const AccumulatedFoam foam =
        accumulate_foam(ocean, scene.time, scene.foam, scene.shading.normals, threads);
    for (std::size_t i = 0; i < fields.size(); ++i) {
      const std::string name = "c" + std::to_string(i) + ".foam";
      for (ExrChannel& c : image.channels) {
        if (c.name == name) c.values = to_float(foam.cascades[i]);
      }
      exact[name] = foam.cascades[i];
    }
    for (std::size_t c = 0; c < sum.size(); ++c) sum[c].foam = foam.combined[c];
  }
  const auto sum_channel = [&](const char* name, double PointFields::*member) {
    std::vector<double> v(sum.size());
    for (std::size_t i = 0; i < sum.size(); ++i) v[i] = sum[i].*member;
    add_channel(std::string("sum.") + name, 1, v);
  };
  sum_channel("height", &PointFields::height);
  sum_channel("slope_x", &PointFields::slope_x);
  sum_channel("slope_z", &PointFields::slope_z);
  sum_channel("jacobian", &PointFields::jacobian);
  for (int axis = 0; axis < 3; ++axis) {  // the shading normal (shading.normals)
    std::vector<double> v(sum.size());
    for (std::size_t i = 0; i < sum.size(); ++i) {
      v[i] = sum[i].normal[static_cast<std::size_t>(axis)];
    }
    add_channel(std::string("sum.normal_") + "xyz"[axis], 1, v);
  }
  sum_channel("foam", &PointFields::foam);
  image.attributes["oceanref.cascade_sizes_m"] = sizes;
  image.attributes["oceanref.time_s"] = format_number(scene.time);
  image.attributes["oceanref.seed"] = std::to_string(scene.seed);
  image.attributes["oceanref.layout"] =
      "sample (m, n) at x = m L/N, z = n L/N (EXR column m, row n); c<i>.height, disp_x, disp_z "
      "are subsampled by N_h/N_l; sum.* covers cascade 0 (L_0) at N_h x N_h points, every "
      "cascade evaluated exactly there (no interpolation), combined as shading.normals = " +
      std::string(scene.shading.normals == ShadingNormals::surface ? "surface"
                                                                   : "high_resolution") +
      "; lengths in m, slopes and Jacobian dimensionless";
  std::vector<std::uint8_t> bytes;
  for (const auto& [name, values] : exact) {  // std::map: name order
    bytes.insert(bytes.end(), name.begin(), name.end());
    bytes.push_back(0);
    for (const double v : values) append_bytes(bytes, v);
  }
  return {std::move(image), sha256_hex(bytes)};
}

namespace {
void write_fields_exr(const std::string& path, const Scene& scene, const Ocean& ocean,
                      int threads) {
  const ExrImage image = fields_image(scene, ocean, threads).exr;
  progress("oceanref fields", "writing " + path);
  write_exr(path, image);
}

void write_point(std::ostream& out, const Scene& scene, const Ocean& ocean, double x, double z,
                 int threads) {
  const std::vector<CascadeFields> fields = synthesize_ocean(ocean, scene.time, threads);
  out << "cascade,field,fft,direct,difference\n";
  const auto row = [&](const std::string& cascade, std::string_view name, double fft,
                       double direct) {
    out << cascade << ',' << name << ',' << format_number(fft) << ',' << format_number(direct)
        << ',' << format_number(fft - direct) << '\n';
  };
  const std::vector<EvolvedCascade> evolved = evolve_ocean(ocean, scene.time);
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const CascadeSpectra& c = ocean.cascades[i];
    const auto grid = cascade_from_grids(fields[i], x, z);
    const auto direct = direct_sum(c.low, c.high, evolved[i], x, z);
    for (std::size_t q = 0; q < kFieldNames.size(); ++q) {
      row(std::to_string(i), kFieldNames[q], grid[q], direct[q]);
    }
  }
  // The combination as the renderer shades it (shading.normals): from the grids read
  // bilinearly, and by direct summation.
  const ShadingNormals normals = scene.shading.normals;
  const PointFields g =
      combine_shading_at(ocean, fields, evolved, x, z, Interpolation::bilinear, normals);
  const PointFields d =
      combine_shading_at(ocean, fields, evolved, x, z, Interpolation::direct, normals);
  row("sum", "height", g.height, d.height);
  row("sum", "slope_x", g.slope_x, d.slope_x);
  row("sum", "slope_z", g.slope_z, d.slope_z);
  row("sum", "jacobian", g.jacobian, d.jacobian);
  const auto& ng = g.normal;
  const auto& nd = d.normal;
  row("sum", "normal_x", ng[0], nd[0]);
  row("sum", "normal_y", ng[1], nd[1]);
  row("sum", "normal_z", ng[2], nd[2]);
  row("sum", "foam", g.foam, d.foam);
}
}  // namespace

std::function<void(std::ostream&)> add_fields_command(CLI::App& app) {
  auto flags = std::make_shared<FieldsFlags>();
  CLI::App* cmd = app.add_subcommand(
      "fields",
      "Synthesize the wave fields of a scene: every field of every cascade as float EXR channels "
      "(-o), or every field at one point from the FFT grid and by direct summation (--at).");
  cmd->add_option("SCENE", flags->scene, "scene file (JSON; sections seed, time, waves)")
      ->required();
  cmd->add_option("--time", flags->time, "time t [s], overrides the scene's time");
  auto* output = cmd->add_option(
      "-o,--output", flags->output,
      "OUT.exr: channels c<i>.height, slope_x, slope_z, disp_x, disp_z, ddx_dx, ddz_dz, ddx_dz, "
      "jacobian, foam per cascade i and sum.height, slope_x, slope_z, jacobian, normal_x, "
      "normal_y, normal_z, foam");
  auto* at = cmd->add_option("--at", flags->at,
                             "x,z [m] -> CSV cascade,field,fft,direct,difference (FFT grid: exact "
                             "at nodes, bilinear between; direct: summation of every component; "
                             "sum rows combined as shading.normals)");
  output->excludes(at);
  cmd->add_option("--threads", flags->threads,
                  "worker threads (default: all cores); the output is identical for any count");
  return [flags](std::ostream& out) {
    if (flags->output.empty() && flags->at.empty()) {
      throw UsageError("fields", "give -o OUT.exr or --at x,z");
    }
    const int threads = resolve_threads(flags->threads);
    Scene scene = load_scene(flags->scene);
    if (!flags->time.empty()) {
      scene.time = parse_number("--time", flags->time);
      if (std::fabs(scene.time) > 1e7) {
        throw UsageError("--time", "must be in [-1e7, 1e7] s, got " + flags->time);
      }
    }
    progress("oceanref fields", "realizing the spectrum");
    const Ocean ocean = realize_ocean(scene.waves, threads);
    if (!flags->output.empty()) {
      write_fields_exr(flags->output, scene, ocean, threads);
      return;
    }
    const std::vector<double> point = parse_number_list("--at", flags->at);
    if (point.size() != 2) throw UsageError("--at", "expected x,z, got '" + flags->at + "'");
    if (std::fabs(point[0]) > 1e9 || std::fabs(point[1]) > 1e9) {
      throw UsageError("--at", "coordinates must be in [-1e9, 1e9] m");
    }
    write_point(out, scene, ocean, point[0], point[1], threads);
  };
}

}  // namespace oceanref::cli
