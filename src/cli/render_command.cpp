#include "cli/render_command.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>
#include <memory>
#include <ostream>
#include <string>

#include "cli/provenance.h"
#include "cli/text.h"
#include "io/exr.h"
#include "io/exr_camera.h"
#include "io/png.h"
#include "io/sha256.h"
#include "scene/scene.h"
#include "shading/tone_mapping.h"

namespace oceanref::cli {

namespace {
struct Prepared {
  Scene scene;
  Ocean ocean;
  RenderJob job;
  WindSlopeVariance unresolved;
};

std::unique_ptr<Prepared> prepare(const std::string& path, int threads, int spp) {
  auto p = std::make_unique<Prepared>();
  p->scene = load_scene(path);
  if (spp != 0) {
    const int axis = static_cast<int>(std::lround(std::sqrt(static_cast<double>(spp))));
    if (spp < 1 || spp > 256 || axis * axis != spp) {
      throw UsageError("--spp", "must be a square number in [1, 256], got " + std::to_string(spp));
    }
    p->scene.image.samples_per_axis = axis;
  }
  progress("oceanref", "realizing the wave spectrum");
  p->ocean = realize_ocean(p->scene.waves, threads);
  p->job = scene_render_job(p->scene, p->ocean, threads);
  p->unresolved = unresolved_slope_variance(p->job, p->scene.waves);
  return p;
}

// SHA-256 of the decoded pixel data: R, G, B as float32 little-endian, pixels row-major.
std::string pixel_hash(const std::vector<ExrChannel>& rgb) {
  std::vector<std::uint8_t> bytes;
  bytes.reserve(rgb[0].values.size() * 12);
  for (std::size_t i = 0; i < rgb[0].values.size(); ++i) {
    for (std::size_t c = 0; c < 3; ++c) append_bytes(bytes, rgb[c].values[i]);
  }
  return sha256_hex(bytes);
}

// SHA-256 of the double-precision radiance before the float32 conversion: R, G, B as binary64
// little-endian, pixels row-major. A one-ulp change anywhere in the pipeline that the float32
// rounding would hide still changes this hash.
std::string radiance_hash(const std::vector<Vec3>& radiance) {
  std::vector<std::uint8_t> bytes;
  bytes.reserve(radiance.size() * 24);
  for (const Vec3& v : radiance) {
    for (const double c : v) append_bytes(bytes, c);
  }
  return sha256_hex(bytes);
}

std::vector<ExrChannel> channels_of(const std::string& prefix, const std::vector<Vec3>& v) {
  std::vector<ExrChannel> out;
  for (std::size_t c = 0; c < 3; ++c) {
    ExrChannel ch{prefix + "RGB"[c], 1, std::vector<float>(v.size())};
    for (std::size_t i = 0; i < v.size(); ++i) ch.values[i] = static_cast<float>(v[i][c]);
    out.push_back(std::move(ch));
  }
  return out;
}

void write_preview(const std::string& path, const RenderedImage& image, const ImageSettings& s) {
  const double average = log_average_luminance(image.radiance);
  double white = s.tone_white;
  if (!(white > 0.0)) {  // Reinhard's default: the largest scaled luminance
    for (const Vec3& c : image.radiance) {
      white = std::max(white, s.tone_key / average * relative_luminance(c));
    }
  }
  std::vector<std::uint8_t> rgb;
  rgb.reserve(image.radiance.size() * 3);
  for (const Vec3& c : image.radiance) {
    const Vec3 mapped = reinhard(c, average, s.tone_key, white);
    for (const double v : mapped) {
      rgb.push_back(static_cast<std::uint8_t>(std::lround(255.0 * srgb_encode(v))));
    }
  }
  write_png(path, image.width, image.height, rgb);
}
}  // namespace

RenderedScene render_scene(const std::string& path, int threads, int spp, bool aov,
                           bool show_progress) {
  const auto p = prepare(path, threads, spp);
  progress("oceanref", "rendering " + std::to_string(p->scene.image.width) + "x" +
                           std::to_string(p->scene.image.height) + " at " +
                           std::to_string(p->job.samples_per_axis * p->job.samples_per_axis) +
                           " spp");
  if (show_progress) {
    p->job.progress = [](double share) {
      const int width = 40;
      const int filled = static_cast<int>(share * width);
      std::cerr << "\r  [" << std::string(static_cast<std::size_t>(filled), '#')
                << std::string(static_cast<std::size_t>(width - filled), ' ') << "] "
                << static_cast<int>(share * 100.0) << "%" << (share >= 1.0 ? "\n" : "")
                << std::flush;
    };
  }
  RenderedScene r;
  r.settings = p->scene.image;
  // The error layer of a fast render is its difference from the reference (computed as well).
  p->job.estimate_fast_error = aov;
  r.image = render(p->job, p->unresolved);
  const RenderedImage& image = r.image;
  ExrImage& exr = r.exr;
  exr.width = image.width;
  exr.height = image.height;
  exr.channels = channels_of("", image.radiance);
  r.pixel_sha256 = pixel_hash(exr.channels);
  r.radiance_f64_sha256 = radiance_hash(image.radiance);
  if (aov) {
    for (const auto& [name, layer] :
         {std::pair{"sun.", &image.sun}, std::pair{"sky.", &image.sky},
          std::pair{"sea.", &image.sea}, std::pair{"foam.", &image.foam},
          std::pair{"normal.", &image.normal}, std::pair{"x0.", &image.x0}}) {
      for (ExrChannel& c : channels_of(name, *layer)) exr.channels.push_back(std::move(c));
    }
    exr.channels.push_back(
        {"depth", 1, std::vector<float>(image.depth.begin(), image.depth.end())});
    exr.channels.push_back(
        {"coverage", 1, std::vector<float>(image.coverage.begin(), image.coverage.end())});
    for (ExrChannel& c : channels_of("lighting_error.", image.lighting_error)) {
      exr.channels.push_back(std::move(c));
    }
  }
  const ShadingSettings& shading = p->scene.shading;
  const bool reference = shading.accuracy == LightingAccuracy::reference;
  exr.attributes["oceanref.lighting_accuracy"] =
      reference ? "reference, relative tolerance " + format_number(shading.tolerance)
                : "fast, sky_order " + std::to_string(shading.sky_order) + ", sun_order " +
                      std::to_string(shading.sun_order);
  exr.srgb_chromaticities = true;
  exr.attributes["oceanref.version"] = oceanref_version();
  exr.attributes["oceanref.commit"] = oceanref_commit();
  // The view, as the standard attributes (io/exr_camera.h; docs/FILES.md).
  exr.matrices["worldToCamera"] = world_to_camera_matrix(p->job.camera);
  exr.matrices["worldToNDC"] = world_to_ndc_matrix(p->job.camera);
  exr.attributes["oceanref.scene_sha256"] = sha256_hex(p->scene.canonical);
  exr.attributes["oceanref.seed"] = std::to_string(p->scene.seed);
  exr.attributes["oceanref.units"] = "radiance in cd/m^2 per channel of linear sRGB (D65)";
  exr.attributes["oceanref.pixel_sha256"] = r.pixel_sha256;
  exr.attributes["oceanref.radiance_f64_sha256"] = r.radiance_f64_sha256;
  exr.attributes["oceanref.unresolved_slope_variance"] =
      format_number(image.unresolved.upwind) + "," + format_number(image.unresolved.crosswind);
  return r;
}

LightingErrorSummary summarize_lighting_error(const RenderedImage& image) {
  LightingErrorSummary summary;
  std::vector<double> relative;
  for (std::size_t i = 0; i < image.lighting_error.size(); ++i) {
    if (!(image.coverage[i] > 0.0)) continue;
    for (std::size_t c = 0; c < 3; ++c) {
      const double e = image.lighting_error[i][c];
      if (e > 0.0) summary.estimated = true;
      const double l = std::fabs(image.radiance[i][c]);
      relative.push_back(l > 0.0 ? e / l : (e > 0.0 ? HUGE_VAL : 0.0));
    }
  }
  if (!summary.estimated) return summary;
  std::sort(relative.begin(), relative.end());
  summary.max_relative = relative.back();
  summary.median_relative = relative[relative.size() / 2];
  return summary;
}

std::function<void(std::ostream&)> add_render_command(CLI::App& app) {
  struct Flags {
    std::string scene, output, png;
    int threads = 0;
    int spp = 0;
    bool aov = false;
  };
  auto f = std::make_shared<Flags>();
  CLI::App* cmd = app.add_subcommand(
      "render",
      "Render a scene to a linear EXR (cd/m^2 per linear sRGB channel), bit-identical "
      "for any thread count; optional tone-mapped PNG preview.");
  cmd->add_option("SCENE", f->scene, "scene file (JSON)")->required();
  cmd->add_option("-o,--output", f->output, "OUT.exr")->required();
  cmd->add_option("--png", f->png, "PREVIEW.png: Reinhard 2002 tone mapping, sRGB transfer");
  cmd->add_option("--threads", f->threads, "worker threads (default: all cores)");
  cmd->add_option("--spp", f->spp, "samples per pixel, a square number (overrides the scene)");
  cmd->add_flag(
      "--aov", f->aov,
      "also write the layers depth, coverage, normal.RGB (= x, y, z), x0.RGB (= x0, 0, z0), "
      "sun.RGB, sky.RGB, sea.RGB, foam.RGB, lighting_error.RGB (the estimated absolute error of "
      "the lighting per channel; for shading.accuracy fast, |fast - reference| + the reference's "
      "estimate, which costs a reference render)");
  return [f](std::ostream& out) {
    const RenderedScene r =
        render_scene(f->scene, resolve_threads(f->threads), f->spp, f->aov, isatty(STDERR_FILENO));
    const ExrImage& exr = r.exr;
    const std::string& hash = r.pixel_sha256;
    progress("oceanref", "writing " + f->output);
    write_exr(f->output, exr);
    if (!f->png.empty()) write_preview(f->png, r.image, r.settings);
    out << "pixel_sha256," << hash << '\n';
    out << "radiance_f64_sha256," << r.radiance_f64_sha256 << '\n';
    const LightingErrorSummary e = summarize_lighting_error(r.image);
    if (e.estimated) {
      out << "lighting_error_max_relative," << format_number(e.max_relative) << '\n';
      out << "lighting_error_median_relative," << format_number(e.median_relative) << '\n';
    }
    out << "unconverged_samples," << r.image.unconverged_samples << '\n';
    out << "integrand_evaluations," << r.image.integrand_evaluations << '\n';
    if (r.image.unconverged_samples > 0) {
      progress("oceanref", "warning: " + std::to_string(r.image.unconverged_samples) +
                               " samples missed the lighting tolerance (their error estimates "
                               "are in --aov lighting_error)");
    }
  };
}

std::function<void(std::ostream&)> add_probe_command(CLI::App& app) {
  struct Flags {
    std::string scene, pixel;
    int threads = 0;
  };
  auto f = std::make_shared<Flags>();
  CLI::App* cmd = app.add_subcommand(
      "probe",
      "Every intermediate value behind one pixel: per sample the triangle hit, x0, the "
      "displaced position, fields, normal, F_mean, each lighting term and its estimated error "
      "(reference accuracy: the integrator's estimate; fast: |fast - reference| + that "
      "estimate); then the pixel.");
  cmd->add_option("SCENE", f->scene, "scene file (JSON)")->required();
  cmd->add_option("--pixel", f->pixel, "x,y (column, row from the top-left)")->required();
  cmd->add_option("--threads", f->threads, "worker threads (default: all cores)");
  return [f](std::ostream& out) {
    const int threads = resolve_threads(f->threads);
    const std::vector<double> xy = parse_number_list("--pixel", f->pixel);
    const auto p = prepare(f->scene, threads, 0);
    p->job.estimate_fast_error = true;  // probe prints each term's error in either mode
    if (xy.size() != 2 || xy[0] < 0 || xy[1] < 0 || xy[0] >= p->scene.image.width ||
        xy[1] >= p->scene.image.height || xy[0] != std::floor(xy[0]) ||
        xy[1] != std::floor(xy[1])) {
      throw UsageError("--pixel", "expected integer x,y inside the " +
                                      std::to_string(p->scene.image.width) + "x" +
                                      std::to_string(p->scene.image.height) + " image, got '" +
                                      f->pixel + "'");
    }
    const std::vector<SampleProbe> samples =
        probe_pixel(p->job, p->unresolved, static_cast<int>(xy[0]), static_cast<int>(xy[1]));
    out << "sample,image_x,image_y,hit,depth,triangle,x0,z0,x,y,z,height,slope_x,slope_z,jacobian,"
           "normal_x,"
           "normal_y,normal_z,view_x,view_y,view_z,sigma2_upwind,sigma2_crosswind,F_mean,"
           "sun_R,sun_G,sun_B,sky_R,sky_G,sky_B,sea_R,sea_G,sea_B,foam_coverage,R,G,B,F_mean_error,"
           "sun_error_R,sun_error_G,sun_error_B,sky_error_R,sky_error_G,sky_error_B,sea_error_R,"
           "sea_error_G,sea_error_B,error_R,error_G,error_B,evaluations,converged\n";
    Vec3 pixel{};
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const SampleProbe& s = samples[i];
      const double values[] = {s.depth,
                               static_cast<double>(s.triangle),
                               s.x0.x,
                               s.x0.y,
                               s.position.x,
                               s.position.y,
                               s.position.z,
                               s.fields.height,
                               s.fields.slope_x,
                               s.fields.slope_z,
                               s.fields.jacobian,
                               s.normal[0],
                               s.normal[1],
                               s.normal[2],
                               s.view[0],
                               s.view[1],
                               s.view[2],
                               p->unresolved.upwind,
                               p->unresolved.crosswind,
                               s.lighting.mean_fresnel,
                               s.lighting.sun[0],
                               s.lighting.sun[1],
                               s.lighting.sun[2],
                               s.lighting.sky[0],
                               s.lighting.sky[1],
                               s.lighting.sky[2],
                               s.lighting.sea[0],
                               s.lighting.sea[1],
                               s.lighting.sea[2],
                               s.whitecap_coverage,
                               s.radiance[0],
                               s.radiance[1],
                               s.radiance[2],
                               s.lighting.mean_fresnel_error,
                               s.lighting.sun_error[0],
                               s.lighting.sun_error[1],
                               s.lighting.sun_error[2],
                               s.lighting.sky_error[0],
                               s.lighting.sky_error[1],
                               s.lighting.sky_error[2],
                               s.lighting.sea_error[0],
                               s.lighting.sea_error[1],
                               s.lighting.sea_error[2],
                               s.lighting_error[0],
                               s.lighting_error[1],
                               s.lighting_error[2],
                               static_cast<double>(s.lighting.evaluations),
                               s.lighting.converged ? 1.0 : 0.0};
      out << i << ',' << format_number(s.image_x) << ',' << format_number(s.image_y) << ','
          << (s.hit ? 1 : 0);
      for (const double v : values) out << ',' << format_number(v);
      out << '\n';
      for (std::size_t c = 0; c < 3; ++c)
        pixel[c] += s.radiance[c] / static_cast<double>(samples.size());
    }
    out << "pixel,R,G,B\npixel," << format_number(pixel[0]) << ',' << format_number(pixel[1]) << ','
        << format_number(pixel[2]) << '\n';
  };
}

}  // namespace oceanref::cli
