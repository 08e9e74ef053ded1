#include "conformance/render_output.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "conformance/provenance.h"
#include "core/check.h"
#include "core/format.h"
#include "io/exr_camera.h"
#include "io/png.h"
#include "io/sha256.h"
#include "shading/tone_mapping.h"

namespace oceanref {

namespace {
std::vector<ExrChannel> channels_of(const std::string& prefix, const std::vector<Vec3>& v) {
  std::vector<ExrChannel> out;
  for (std::size_t c = 0; c < 3; ++c) {
    ExrChannel ch{prefix + "RGB"[c], 1, std::vector<float>(v.size())};
    for (std::size_t i = 0; i < v.size(); ++i) ch.values[i] = static_cast<float>(v[i][c]);
    out.push_back(std::move(ch));
  }
  return out;
}

void note(const std::function<void(const std::string&)>& log, const std::string& message) {
  if (log) log(message);
}
}  // namespace

std::string pixel_sha256(const std::vector<ExrChannel>& rgb) {
  std::vector<std::uint8_t> bytes;
  bytes.reserve(rgb[0].values.size() * 12);
  for (std::size_t i = 0; i < rgb[0].values.size(); ++i) {
    for (std::size_t c = 0; c < 3; ++c) append_bytes(bytes, rgb[c].values[i]);
  }
  return sha256_hex(bytes);
}

std::string radiance_f64_sha256(const std::vector<Vec3>& radiance) {
  std::vector<std::uint8_t> bytes;
  bytes.reserve(radiance.size() * 24);
  for (const Vec3& v : radiance) {
    for (const double c : v) append_bytes(bytes, c);
  }
  return sha256_hex(bytes);
}

std::unique_ptr<PreparedRender> prepare_render(const Scene& scene, int threads,
                                               int samples_per_axis,
                                               const std::function<void(const std::string&)>& log) {
  auto p = std::make_unique<PreparedRender>();
  p->scene = scene;
  if (samples_per_axis > 0) p->scene.image.samples_per_axis = samples_per_axis;
  note(log, "realizing the wave spectrum");
  p->ocean = realize_ocean(p->scene.waves, threads);
  p->job = scene_render_job(p->scene, p->ocean, threads);
  p->unresolved = unresolved_slope_variance(p->job, p->scene.waves);
  return p;
}

RenderedScene render_scene(const std::string& path, const RenderOutputOptions& options) {
  return render_scene(load_scene(path), options);
}

MemoryEstimate render_memory_estimate(const Scene& scene, const RenderOutputOptions& options) {
  const ImageSettings& im = scene.image;
  const int axis = options.samples_per_axis > 0 ? options.samples_per_axis : im.samples_per_axis;
  // A tile holds its own rows (the piece's doubles are counted as the EXR channels and hash
  // input of a whole render: fewer bytes).
  const auto [first, last] = tile_rows(options.tile, options.tiles, im.height);
  const double pixels = static_cast<double>(im.width) * (last - first);
  const double samples = pixels * axis * axis;
  const double vertices = static_cast<double>(scene.grid.columns) * scene.grid.rows;
  // Per vertex: x0, the displaced position, its projection and two triangles of indices.
  const double vertex_bytes = sizeof(glm::dvec2) + sizeof(glm::dvec3) + sizeof(ScreenVertex) +
                              2 * sizeof(std::array<std::uint32_t, 3>);
  // Per pixel: radiance, the lighting error and coverage; with --aov also the four terms,
  // normal, x0 and depth (RenderJob::layers).
  const double pixel_bytes =
      options.aov ? 8 * sizeof(Vec3) + 2 * sizeof(double) : 2 * sizeof(Vec3) + sizeof(double);
  const double channels = options.aov ? 26 : 3;
  // Each item names the scene keys that size it (the scene-file contract: a size that would
  // exceed memory is rejected naming its keys).
  const std::string image = " (render.width x render.height)";
  return {{{kWaveGridsItem, wave_grid_bytes(scene.waves)},
           {"projected grid (grid.columns x grid.rows)", vertices * vertex_bytes},
           {"sample fragments (render.width x render.height x render.samples_per_pixel)",
            samples * sizeof(Fragment)},
           {"pixel buffers" + image, pixels * pixel_bytes},
           {"EXR channels" + image, pixels * channels * sizeof(float)},
           {"radiance hash input" + image, pixels * sizeof(Vec3)}}};
}

namespace {
// The image of the options' rows of the scene (all of them unless tiles > 1).
RenderedImage render_rows(PreparedRender& p, const RenderOutputOptions& options) {
  const auto [first, last] = tile_rows(options.tile, options.tiles, p.scene.image.height);
  note(options.log,
       "rendering " + std::to_string(p.scene.image.width) + "x" +
           std::to_string(p.scene.image.height) + " at " +
           std::to_string(p.job.samples_per_axis * p.job.samples_per_axis) + " spp" +
           (options.tiles > 1 ? ", tile " + std::to_string(options.tile) + " of " +
                                    std::to_string(options.tiles) + " (rows " +
                                    std::to_string(first) + " to " + std::to_string(last - 1) + ")"
                              : std::string()));
  if (options.progress) p.job.progress = options.progress;
  // The error layer of a fast render is its difference from the reference (computed as well).
  p.job.estimate_fast_error = options.aov;
  p.job.layers = options.aov;
  p.job.first_row = first;
  p.job.last_row = last;
  return render(p.job, p.unresolved);
}
}  // namespace

RenderedScene render_scene(const Scene& scene, const RenderOutputOptions& options) {
  OCEANREF_EXPECTS(options.tiles == 1, "render_scene renders the whole image (one tile)");
  require_within(render_memory_estimate(scene, options), options.max_memory,
                 "--max-memory (Python: max_memory=)");
  const auto p = prepare_render(scene, options.threads, options.samples_per_axis, options.log);
  return scene_output(p->scene, render_rows(*p, options), options.aov);
}

RenderPiece render_scene_piece(const Scene& scene, const RenderOutputOptions& options) {
  require_within(render_memory_estimate(scene, options), options.max_memory,
                 "--max-memory (Python: max_memory=)");
  const auto p = prepare_render(scene, options.threads, options.samples_per_axis, options.log);
  return {sha256_hex(p->scene.canonical), options.tile, options.tiles,
          p->job.samples_per_axis,        options.aov,  render_rows(*p, options)};
}

RenderedScene scene_output(const Scene& scene, RenderedImage rendered, bool aov) {
  OCEANREF_EXPECTS(rendered.first_row == 0 && rendered.height == scene.image.height &&
                       rendered.width == scene.image.width,
                   "the whole image of the scene");
  RenderedScene r;
  r.settings = scene.image;
  r.image = std::move(rendered);
  const RenderedImage& image = r.image;
  const Camera camera = scene_camera(scene);
  ExrImage& exr = r.exr;
  exr.width = image.width;
  exr.height = image.height;
  exr.channels = channels_of("", image.radiance);
  r.pixel_sha256 = pixel_sha256(exr.channels);
  r.radiance_f64_sha256 = radiance_f64_sha256(image.radiance);
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
  const ShadingSettings& shading = scene.shading;
  const bool reference = shading.accuracy == LightingAccuracy::reference;
  exr.attributes["oceanref.lighting_accuracy"] =
      reference ? "reference, relative tolerance " + format_number(shading.tolerance)
                : "fast, sky_order " + std::to_string(shading.sky_order) + ", sun_order " +
                      std::to_string(shading.sun_order);
  exr.srgb_chromaticities = true;
  exr.attributes["oceanref.version"] = oceanref_version();
  exr.attributes["oceanref.commit"] = oceanref_commit();
  // The view, as the standard attributes (io/exr_camera.h; docs/FILES.md).
  exr.matrices["worldToCamera"] = world_to_camera_matrix(camera);
  exr.matrices["worldToNDC"] = world_to_ndc_matrix(camera);
  exr.attributes["oceanref.scene_sha256"] = sha256_hex(scene.canonical);
  exr.attributes["oceanref.seed"] = std::to_string(scene.seed);
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

std::vector<std::uint8_t> preview_rgb8(const RenderedImage& image, const ImageSettings& s) {
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
  return rgb;
}

void write_preview_png(const std::string& path, const RenderedImage& image,
                       const ImageSettings& settings) {
  write_png(path, image.width, image.height, preview_rgb8(image, settings));
}

}  // namespace oceanref
