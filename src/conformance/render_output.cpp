#include "conformance/render_output.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <map>
#include <optional>
#include <utility>

#include "conformance/provenance.h"
#include "conformance/scene_objects.h"
#include "core/check.h"
#include "core/format.h"
#include "core/math.h"
#include "io/exr_camera.h"
#include "io/png.h"
#include "io/sha256.h"
#include "shading/tone_mapping.h"

namespace oceanref {

namespace {
bool adaptive(const Scene& scene) {
  return scene.image.pixel_tolerance > 0.0;
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

void note(const std::function<void(const std::string&)>& log, const std::string& message) {
  if (log) log(message);
}

// The channels of the render EXR for the rows of `image` (the whole image or a band), in the
// file's order: R, G, B, then with AOVs the layers (and `samples` when adaptive).
std::vector<ExrChannel> render_channels(const RenderedImage& image, bool aov, bool adaptive) {
  std::vector<ExrChannel> channels = channels_of("", image.radiance);
  if (!aov) return channels;
  for (const auto& [name, layer] :
       {std::pair{"sun.", &image.sun}, std::pair{"sky.", &image.sky}, std::pair{"sea.", &image.sea},
        std::pair{"foam.", &image.foam}, std::pair{"normal.", &image.normal},
        std::pair{"x0.", &image.x0}}) {
    for (ExrChannel& c : channels_of(name, *layer)) channels.push_back(std::move(c));
  }
  channels.push_back({"depth", 1, std::vector<float>(image.depth.begin(), image.depth.end())});
  channels.push_back(
      {"coverage", 1, std::vector<float>(image.coverage.begin(), image.coverage.end())});
  for (const auto& [name, layer] : {std::pair{"lighting_error.", &image.lighting_error},
                                    std::pair{"pixel_error.", &image.pixel_error}}) {
    for (ExrChannel& c : channels_of(name, *layer)) channels.push_back(std::move(c));
  }
  if (adaptive) {
    channels.push_back(
        {"samples", 1, std::vector<float>(image.pixel_samples.begin(), image.pixel_samples.end())});
  }
  return channels;
}

// Relative errors counted by the top bits of their doubles (sign 0, exponent, 8 bits of
// mantissa: 2¹⁹ bins, monotonic in the value), for quantiles of a render in bands.
constexpr int kHistogramShift = 44;
struct RelativeErrorHistogram {
  double max = 0.0;
  std::uint64_t count = 0;
  std::vector<std::uint64_t> bins;

  // The error e of a value l, relative (+inf for e > 0 at l = 0).
  void add(double e, double l) {
    if (bins.empty()) bins.assign(std::size_t{1} << (63 - kHistogramShift), 0);
    const double a = std::fabs(l);
    const double relative = a > 0.0 ? e / a : (e > 0.0 ? HUGE_VAL : 0.0);
    max = std::fmax(max, relative);
    ++bins[std::bit_cast<std::uint64_t>(relative) >> kHistogramShift];
    ++count;
  }
  // The lower edge of the bin holding the value of rank ⌊q n⌋ (0-based), as sorted.
  double quantile(double q) const {
    const auto rank = static_cast<std::uint64_t>(q * static_cast<double>(count));
    std::uint64_t below = 0;
    for (std::size_t b = 0; b < bins.size(); ++b) {
      below += bins[b];
      if (below > rank)
        return std::bit_cast<double>(static_cast<std::uint64_t>(b) << kHistogramShift);
    }
    return 0.0;
  }
};

// The lighting error over the channels of the pixels that see the sea.
struct LightingErrorTally {
  bool estimated = false;
  RelativeErrorHistogram histogram;

  void add(const RenderedImage& image) {
    for (std::size_t i = 0; i < image.lighting_error.size(); ++i) {
      if (!(image.coverage[i] > 0.0)) continue;
      for (std::size_t c = 0; c < 3; ++c) {
        const double e = image.lighting_error[i][c];
        if (e > 0.0) estimated = true;
        histogram.add(e, image.radiance[i][c]);
      }
    }
  }
  LightingErrorSummary result() const {
    if (!estimated) return {};
    return {true, histogram.max, histogram.quantile(0.5)};
  }
};

// The pixel integral's error over the channels of every pixel, and the samples behind them.
struct PixelErrorTally {
  int samples_per_pixel = 0;
  bool adaptive = false;
  double samples = 0.0;  // Σ samples per pixel (adaptive; exact below 2⁵³)
  double most_samples = 0.0;
  long pixels = 0;
  long capped_pixels = 0;
  long antialiased_pixels = 0;
  RelativeErrorHistogram histogram;

  void add(const RenderedImage& image) {
    samples_per_pixel = image.samples_per_axis * image.samples_per_axis;
    adaptive = !image.pixel_samples.empty();
    for (const double n : image.pixel_samples) {
      samples += n;
      most_samples = std::fmax(most_samples, n);
    }
    pixels += static_cast<long>(image.radiance.size());
    capped_pixels += image.capped_pixels;
    antialiased_pixels += image.antialiased_pixels;
    for (std::size_t i = 0; i < image.pixel_error.size(); ++i) {
      for (std::size_t c = 0; c < 3; ++c)
        histogram.add(image.pixel_error[i][c], image.radiance[i][c]);
    }
  }
  PixelErrorSummary result() const {
    PixelErrorSummary s;
    s.samples_per_pixel = samples_per_pixel;
    s.antialiased_pixels = antialiased_pixels;
    if (adaptive) {
      s.adaptive = true;
      s.mean_samples = samples / static_cast<double>(std::max(pixels, 1L));
      s.max_samples = most_samples;
      s.capped_pixels = capped_pixels;
    }
    if (samples_per_pixel < 2 && !adaptive) return s;
    s.estimated = true;
    s.p50_relative = histogram.quantile(0.5);
    s.p99_relative = histogram.quantile(0.99);
    s.max_relative = histogram.max;
    return s;
  }
};

// Everything a render reports and its preview needs, accumulated band by band in row order:
// the same values as from the whole image.
struct RenderTally {
  Sha256 pixels;    // R, G, B as float32 little-endian, row-major
  Sha256 radiance;  // the same as binary64
  LightingErrorTally lighting_error;
  PixelErrorTally pixel_error;
  double log_luminance_sum = 0.0;  // Σ ln(δ + L_w) in pixel order (log_average_luminance)
  std::size_t pixel_count = 0;
  double max_luminance = -HUGE_VAL;
  long unconverged_samples = 0;
  long integrand_evaluations = 0;
  long corrected_samples = 0;

  void add(const RenderedImage& band) {
    // Hashed row by row: the serialized bytes of one row at a time.
    std::vector<std::uint8_t> floats;
    std::vector<std::uint8_t> doubles;
    const auto width = static_cast<std::size_t>(band.width);
    for (std::size_t start = 0; start < band.radiance.size(); start += width) {
      floats.clear();
      doubles.clear();
      for (std::size_t i = start; i < start + width; ++i) {
        const Vec3& v = band.radiance[i];
        for (const double c : v) {
          append_bytes(floats, static_cast<float>(c));
          append_bytes(doubles, c);
        }
        log_luminance_sum += log_luminance_term(v);
        max_luminance = std::fmax(max_luminance, relative_luminance(v));
      }
      pixels.update(floats.data(), floats.size());
      radiance.update(doubles.data(), doubles.size());
    }
    pixel_count += band.radiance.size();
    lighting_error.add(band);
    pixel_error.add(band);
    unconverged_samples += band.unconverged_samples;
    integrand_evaluations += band.integrand_evaluations;
    corrected_samples += band.corrected_samples;
  }
  // Once, after the last band.
  RenderReport report() {
    return {pixels.hex_digest(),  radiance.hex_digest(), lighting_error.result(),
            pixel_error.result(), unconverged_samples,   integrand_evaluations,
            corrected_samples};
  }
};

RenderTally tally_of(const RenderedImage& image) {
  RenderTally t;
  t.add(image);
  return t;
}

// Reinhard's L̄_w and white point of the whole image (as log_average_luminance and a loop
// taking the largest scaled luminance would give: scaling by a positive factor and rounding
// are monotonic, so the largest scaled luminance is the scaled largest one).
struct PreviewScale {
  double log_average = 0.0;
  double white = 0.0;
};
PreviewScale preview_scale(const RenderTally& t, const ImageSettings& s,
                           const std::optional<SequenceFrame>& frame = std::nullopt) {
  PreviewScale p;
  // A frame of a sequence is seen by an eye adapted to L_a (Krawczyk), not to its own L̄_w.
  p.log_average = frame ? frame->adapted_luminance
                        : math::exp(t.log_luminance_sum / static_cast<double>(t.pixel_count));
  p.white = s.tone_white;
  if (!(p.white > 0.0)) p.white = std::max(p.white, s.tone_key / p.log_average * t.max_luminance);
  return p;
}

// One row of the preview from the float32 R, G, B of its pixels.
void preview_row(const float* r, const float* g, const float* b, int width, const PreviewScale& p,
                 const ImageSettings& s, std::vector<std::uint8_t>& out) {
  for (int x = 0; x < width; ++x) {
    const Vec3 c{static_cast<double>(r[x]), static_cast<double>(g[x]), static_cast<double>(b[x])};
    const Vec3 mapped = reinhard(c, p.log_average, s.tone_key, p.white);
    for (const double v : mapped) {
      out.push_back(static_cast<std::uint8_t>(std::lround(255.0 * srgb_encode(v))));
    }
  }
}

// The render EXR without pixels: size, channel names (the channels of an empty image),
// attributes; the two hashes as given.
ExrImage render_exr_header(const Scene& scene, const SlopeVariance& unresolved, bool aov,
                           const std::string& pixel_hash, const std::string& radiance_hash,
                           const std::string& pixel_error) {
  ExrImage exr;
  exr.width = scene.image.width;
  exr.height = scene.image.height;
  exr.channels = render_channels(RenderedImage{}, aov, adaptive(scene));
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
  const Camera camera = scene_camera(scene);
  exr.matrices["worldToCamera"] = world_to_camera_matrix(camera);
  exr.matrices["worldToNDC"] = world_to_ndc_matrix(camera);
  exr.attributes["oceanref.scene_sha256"] = sha256_hex(scene.canonical);
  exr.attributes["oceanref.seed"] = std::to_string(scene.seed);
  exr.attributes["oceanref.renderer"] = std::string(choice_name(kRenderers, scene.image.renderer));
  exr.attributes["oceanref.units"] = "radiance in cd/m^2 per channel of linear sRGB (D65)";
  exr.attributes["oceanref.pixel_sha256"] = pixel_hash;
  exr.attributes["oceanref.radiance_f64_sha256"] = radiance_hash;
  exr.attributes["oceanref.pixel_error"] = pixel_error;
  exr.attributes["oceanref.unresolved_slope_variance"] =
      format_number(unresolved.upwind) + "," + format_number(unresolved.crosswind);
  return exr;
}

// The attributes of a frame of a sequence (RenderOutputOptions::frame).
void add_frame_attributes(ExrImage& exr, const SequenceFrame& f) {
  exr.attributes["oceanref.frame"] = std::to_string(f.index);
  exr.attributes["oceanref.frame_rate"] = format_number(f.fps);
  exr.attributes["oceanref.frame_time"] = format_number(f.time);
  exr.attributes["oceanref.metered_luminance"] = format_number(f.metered_luminance);
  exr.attributes["oceanref.adapted_luminance"] = format_number(f.adapted_luminance);
  exr.attributes["oceanref.tone_key"] = format_number(f.key);
}

// The per-sample file's layout (`render --samples`): the image's header at S× its resolution,
// R, G, B of every sample, without the image's hashes and error summary.
ExrImage samples_exr_header(const Scene& scene, const SlopeVariance& unresolved, int s) {
  ExrImage exr = render_exr_header(scene, unresolved, false, "", "", "");
  exr.width *= s;
  exr.height *= s;
  exr.channels = {ExrChannel{"R", 1, {}}, ExrChannel{"G", 1, {}}, ExrChannel{"B", 1, {}}};
  for (const char* key :
       {"oceanref.pixel_sha256", "oceanref.radiance_f64_sha256", "oceanref.pixel_error"}) {
    exr.attributes.erase(key);
  }
  exr.attributes["oceanref.samples"] =
      "S = " + std::to_string(s) +
      " samples per pixel axis: sample (c, r) sits at image position ((c + 0.5)/S, (r + 0.5)/S) "
      "pixels; pixel (i, j) of the image is the mean of samples (i S + a, j S + b), a, b = 0 .. "
      "S-1, each weighted 1/S^2 and summed in row-major order in double precision";
  return exr;
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
  if (!p->scene.objects.empty()) note(log, "reading the objects");
  p->objects = load_scene_objects(p->scene);
  p->job = scene_render_job(p->scene, p->ocean, threads);
  p->job.objects = &p->objects;
  p->unresolved = unresolved_slope_variance(p->job, p->scene.waves);
  return p;
}

RenderedScene render_scene(const std::string& path, const RenderOutputOptions& options) {
  return render_scene(load_scene(path), options);
}

namespace {
// Bytes per pixel of the per-pixel buffers: radiance, the lighting and pixel errors, coverage; with
// --aov also the four terms, normal, x0 and depth (RenderJob::layers); adaptive sampling's sample
// counts. And the EXR channels.
double pixel_bytes(bool aov, bool adaptive) {
  const std::size_t bytes =
      (aov ? 9 * sizeof(Vec3) + 2 * sizeof(double) : 3 * sizeof(Vec3) + sizeof(double)) +
      (adaptive ? sizeof(double) : 0);
  return static_cast<double>(bytes);
}
double channel_count(bool aov, bool adaptive) {
  return aov ? (adaptive ? 30 : 29) : 3;
}
constexpr double kHistogramBytes = double(std::size_t{1} << 19) * sizeof(std::uint64_t);
// A kept sample (`render --samples`): its radiance, and R, G, B as written.
constexpr double kSampleBytes = sizeof(Vec3) + 3 * sizeof(float);

// "4 spp", or with adaptive sampling "4 spp refined to 1% up to 324".
std::string sampling_text(const RenderJob& job) {
  const int s = job.samples_per_axis;
  std::string text = std::to_string(s * s) + " spp";
  if (job.pixel_tolerance > 0.0) {
    text += " refined to a tolerance of " + format_number(job.pixel_tolerance) + " up to " +
            std::to_string(adaptive_samples(job.pixel_pattern, s, job.max_refinements));
    if (job.pixel_pattern == PixelPattern::sobol) text += " (Sobol')";
  }
  if (job.footprint_filtering) text += ", footprint-filtered";
  if (job.renderer == Renderer::raytrace) text += ", ray traced";
  if (job.renderer == Renderer::raytrace_surface) {
    text +=
        ", ray traced on the continuous surface to " + format_number(job.surface_tolerance) + " px";
  }
  return text;
}

int samples_per_axis_of(const Scene& scene, const RenderOutputOptions& options) {
  return options.samples_per_axis > 0 ? options.samples_per_axis : scene.image.samples_per_axis;
}
}  // namespace

int stream_band_rows(const Scene& scene, const RenderOutputOptions& options) {
  constexpr double kBandBytes = 256.0 * 1024 * 1024;
  const int axis = samples_per_axis_of(scene, options);
  const double row_bytes =
      static_cast<double>(scene.image.width) *
      (axis * axis *
           (static_cast<double>(sizeof(Fragment)) + (options.keep_samples ? kSampleBytes : 0.0)) +
       pixel_bytes(options.aov, adaptive(scene)) +
       channel_count(options.aov, adaptive(scene)) * sizeof(float));
  const double rows =
      options.band_rows > 0 ? options.band_rows : std::floor(kBandBytes / row_bytes);
  return static_cast<int>(std::clamp(rows, 1.0, static_cast<double>(scene.image.height)));
}

MemoryEstimate render_memory_estimate(const Scene& scene, const RenderOutputOptions& options) {
  const ImageSettings& im = scene.image;
  const int axis = samples_per_axis_of(scene, options);
  // A tile holds its own rows (written from its pixel buffers), a streamed render one band.
  const auto [first, last] = tile_rows(options.tile, options.tiles, im.height);
  const int rows = options.streamed ? stream_band_rows(scene, options) : last - first;
  const double pixels = static_cast<double>(im.width) * rows;
  const double samples = pixels * axis * axis;
  const double vertices = static_cast<double>(scene.grid.columns) * scene.grid.rows;
  // Per vertex: x0, the displaced position, its projection and two triangles of indices.
  const double vertex_bytes = sizeof(glm::dvec2) + sizeof(glm::dvec3) + sizeof(ScreenVertex) +
                              2 * sizeof(std::array<std::uint32_t, 3>);
  // Each item names the scene keys that size it (the scene-file contract: a size that would
  // exceed memory is rejected naming its keys).
  const std::string area = options.streamed && rows < im.height
                               ? "render.width x " + std::to_string(rows) + " rows, one band"
                               : "render.width x render.height";
  const std::string image = " (" + area + ")";
  // With direct summation an earlier instant holds its h(k, t), which wave_grid_bytes covers.
  const double foam_history =
      !scene.shading.whitecaps ? 0.0
      : scene.shading.interpolation == Interpolation::direct
          ? scene.foam.steps * wave_grid_bytes(scene.waves)
          : foam_history_bytes(scene.waves, scene.shading.normals, scene.foam.steps);
  return {
      {{kWaveGridsItem, wave_grid_bytes(scene.waves)},
       {kFootprintFilterItem, im.footprint_filtering ? footprint_filter_bytes(scene.waves) : 0.0},
       {"projected grid (grid.columns x grid.rows)", vertices * vertex_bytes},
       {"sample fragments (" + area + " x render.samples_per_pixel)", samples * sizeof(Fragment)},
       {"pixel buffers" + image, pixels * pixel_bytes(options.aov, adaptive(scene))},
       {"EXR channels" + image,
        pixels * channel_count(options.aov, adaptive(scene)) * sizeof(float)},
       {"error histograms (lighting, pixel)", 2 * kHistogramBytes},
       {"the accumulated foam's earlier instants (waves.foam.steps x the deformation's fields)",
        foam_history},
       {"per-sample radiance (--samples: " + area + " x render.samples_per_pixel)",
        options.keep_samples ? samples * kSampleBytes : 0.0},
       {"adaptive refinement (render.max_samples_per_pixel per thread)",
        adaptive(scene)
            ? std::max(options.threads, 1) *
                  refinement_bytes(adaptive_samples(im.pixel_pattern, axis, im.max_refinements),
                                   two_level_lighting(scene))
            : 0.0}}};
}

namespace {
// The image of the options' rows of the scene (all of them unless tiles > 1).
RenderedImage render_rows(PreparedRender& p, const RenderOutputOptions& options) {
  const auto [first, last] = tile_rows(options.tile, options.tiles, p.scene.image.height);
  note(options.log,
       "rendering " + std::to_string(p.scene.image.width) + "x" +
           std::to_string(p.scene.image.height) + " at " + sampling_text(p.job) +
           (options.tiles > 1 ? ", tile " + std::to_string(options.tile) + " of " +
                                    std::to_string(options.tiles) + " (rows " +
                                    std::to_string(first) + " to " + std::to_string(last - 1) + ")"
                              : std::string()));
  if (options.progress) p.job.progress = options.progress;
  // The error layer of a fast render is its difference from the reference (computed as well).
  p.job.estimate_fast_error = options.fast_lighting_error;
  p.job.layers = options.aov;
  if (options.renderer) p.job.renderer = *options.renderer;
  if (options.tiles > 1 && p.job.renderer != Renderer::raster) {
    throw SceneError("render.renderer",
                     "a tile (render --tile) is rasterized: raytrace renders the whole image");
  }
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
  RenderPiece piece;
  piece.scene_sha256 = sha256_hex(p->scene.canonical);
  piece.tile = options.tile;
  piece.tiles = options.tiles;
  piece.samples_per_axis = p->job.samples_per_axis;
  piece.layers = options.aov;
  piece.adaptive = adaptive(p->scene);
  piece.antialiased = p->scene.image.mastin_antialiasing > 0.0;
  piece.band = render_rows(*p, options);
  return piece;
}

RenderedScene scene_output(const Scene& scene, RenderedImage rendered, bool aov) {
  OCEANREF_EXPECTS(rendered.first_row == 0 && rendered.height == scene.image.height &&
                       rendered.width == scene.image.width,
                   "the whole image of the scene");
  RenderedScene r;
  r.settings = scene.image;
  r.image = std::move(rendered);
  const RenderReport report = tally_of(r.image).report();
  r.pixel_sha256 = report.pixel_sha256;
  r.radiance_f64_sha256 = report.radiance_f64_sha256;
  r.exr = render_exr_header(scene, r.image.unresolved, aov, r.pixel_sha256, r.radiance_f64_sha256,
                            pixel_error_attribute(report.pixel_error));
  r.exr.channels = render_channels(r.image, aov, adaptive(scene));
  return r;
}

GerstnerLoopCheck gerstner_loop_check(const Scene& scene, const Ocean& ocean) {
  OCEANREF_EXPECTS(ocean.gerstner.has_value(), "a Gerstner ocean");
  const GerstnerWaves& g = *ocean.gerstner;
  GerstnerLoopCheck c;
  c.steepness_bound = gerstner_steepness_bound(g);
  if (c.steepness_bound < 1.0) return c;
  c.sampled = true;
  c.extent = 2.0 * (2.0 * std::numbers::pi / g.min_wavenumber);
  c.loops = gerstner_loops(g, scene.time, scene.camera.position.x - 0.5 * c.extent,
                           scene.camera.position.z - 0.5 * c.extent, c.extent, 256);
  return c;
}

RenderReport report_of(const RenderedScene& rendered) {
  RenderReport r;
  r.pixel_sha256 = rendered.pixel_sha256;
  r.radiance_f64_sha256 = rendered.radiance_f64_sha256;
  r.lighting_error = summarize_lighting_error(rendered.image);
  r.pixel_error = summarize_pixel_error(rendered.image);
  r.unconverged_samples = rendered.image.unconverged_samples;
  r.integrand_evaluations = rendered.image.integrand_evaluations;
  r.corrected_samples = rendered.image.corrected_samples;
  return r;
}

RenderReport render_scene_to_files(const Scene& scene, const RenderOutputOptions& options,
                                   const std::string& exr_path, const std::string& png_path,
                                   const std::string& samples_path) {
  OCEANREF_EXPECTS(options.tiles == 1 && options.streamed,
                   "a streamed render of the whole image (options.streamed)");
  OCEANREF_EXPECTS(samples_path.empty() == !options.keep_samples,
                   "a samples file exactly when options.keep_samples");
  if (options.keep_samples && scene.image.mastin_antialiasing > 0.0) {
    throw SceneError("render.mastin_antialiasing",
                     "the samples of the fixed grid are exported (--samples), not Mastin's extra "
                     "ones: remove render.mastin_antialiasing");
  }
  if (options.keep_samples && adaptive(scene)) {
    throw SceneError("render.pixel_tolerance",
                     "the samples of the fixed grid are exported (--samples), not those of "
                     "adaptive sampling: remove render.pixel_tolerance");
  }
  require_within(render_memory_estimate(scene, options), options.max_memory,
                 "--max-memory (Python: max_memory=)");
  const auto p = prepare_render(scene, options.threads, options.samples_per_axis, options.log);
  p->job.estimate_fast_error = options.fast_lighting_error;
  p->job.layers = options.aov;
  if (options.renderer) p->job.renderer = p->scene.image.renderer = *options.renderer;
  p->job.keep_samples = options.keep_samples;
  const int height = p->scene.image.height;
  const int band = stream_band_rows(p->scene, options);
  note(options.log,
       "rendering " + std::to_string(p->scene.image.width) + "x" + std::to_string(height) + " at " +
           sampling_text(p->job) +
           (band < height ? " in bands of " + std::to_string(band) + " rows" : std::string()));
  const RenderFrame frame = prepare_frame(p->job, p->unresolved);
  RenderTally tally;
  // The hashes are known after the last band: placeholders in the header until then.
  const std::string placeholder(64, '0');
  ExrImage header = render_exr_header(p->scene, p->unresolved, options.aov, placeholder,
                                      placeholder, std::string(kPixelErrorAttributeLength, ' '));
  if (options.frame) add_frame_attributes(header, *options.frame);
  ExrRowWriter writer(exr_path, header,
                      {{"oceanref.pixel_sha256", 64},
                       {"oceanref.radiance_f64_sha256", 64},
                       {"oceanref.pixel_error", kPixelErrorAttributeLength}});
  const int s = p->job.samples_per_axis;
  std::optional<ExrRowWriter> samples;
  if (options.keep_samples) {
    samples.emplace(samples_path, samples_exr_header(p->scene, p->unresolved, s));
  }
  for (int first = 0; first < height; first += band) {
    const int last = std::min(height, first + band);
    std::function<void(double)> progress;
    if (options.progress) {
      progress = [&](double share) {
        options.progress((first + share * (last - first)) / static_cast<double>(height));
      };
    }
    const RenderedImage image = render_rows(frame, first, last, progress);
    tally.add(image);
    std::vector<std::vector<float>> values;
    for (ExrChannel& c : render_channels(image, options.aov, adaptive(p->scene))) {
      values.push_back(std::move(c.values));
    }
    writer.write_rows(values, last - first);
    if (samples) {
      std::vector<std::vector<float>> rgb(3);
      for (const Vec3& v : image.sample_radiance) {
        for (std::size_t c = 0; c < 3; ++c) rgb[c].push_back(static_cast<float>(v[c]));
      }
      samples->write_rows(rgb, (last - first) * s);
    }
  }
  if (samples) samples->finish();
  ImageSettings tone = p->scene.image;
  if (options.frame) tone.tone_key = options.frame->key;
  const PreviewScale scale = preview_scale(tally, tone, options.frame);
  RenderReport report = tally.report();
  writer.set_deferred("oceanref.pixel_sha256", report.pixel_sha256);
  writer.set_deferred("oceanref.radiance_f64_sha256", report.radiance_f64_sha256);
  writer.set_deferred("oceanref.pixel_error", pixel_error_attribute(report.pixel_error));
  writer.finish();
  if (png_path.empty()) return report;
  note(options.log, "writing " + png_path);
  const int width = p->scene.image.width;
  PngRowWriter png(png_path, width, height);
  std::vector<std::uint8_t> row;
  for (int first = 0; first < height; first += band) {
    const int last = std::min(height, first + band);
    const std::vector<std::vector<float>> rgb =
        read_exr_rows(exr_path, {"R", "G", "B"}, first, last);
    for (int y = 0; y < last - first; ++y) {
      const std::size_t at = static_cast<std::size_t>(y) * static_cast<std::size_t>(width);
      row.clear();
      preview_row(rgb[0].data() + at, rgb[1].data() + at, rgb[2].data() + at, width, scale, tone,
                  row);
      png.write_row(row.data());
    }
  }
  png.finish();
  return report;
}

std::string pixel_error_attribute(const PixelErrorSummary& e) {
  const std::string samples =
      e.adaptive ? "adaptive, mean " + format_number(e.mean_samples) + " samples per pixel (max " +
                       format_number(e.max_samples) + ", " + std::to_string(e.capped_pixels) +
                       " pixels capped above the tolerance)"
                 : "over " + std::to_string(e.samples_per_pixel) + " samples";
  std::string text = e.estimated
                         ? "3 standard errors of the pixel mean, " + samples +
                               ", relative to the radiance: p50 " + format_number(e.p50_relative) +
                               ", p99 " + format_number(e.p99_relative) + ", max " +
                               format_number(e.max_relative)
                         : std::string("not estimated: 1 sample per pixel");
  OCEANREF_EXPECTS(text.size() <= kPixelErrorAttributeLength, "the pixel error summary fits");
  text.resize(kPixelErrorAttributeLength, ' ');
  return text;
}

PixelErrorSummary summarize_pixel_error(const RenderedImage& image) {
  PixelErrorTally t;
  t.add(image);
  return t.result();
}

LightingErrorSummary summarize_lighting_error(const RenderedImage& image) {
  LightingErrorTally t;
  t.add(image);
  return t.result();
}

std::vector<std::uint8_t> preview_rgb8(const RenderedImage& image, const ImageSettings& s) {
  const PreviewScale scale = preview_scale(tally_of(image), s);
  const std::vector<ExrChannel> rgb = channels_of("", image.radiance);
  std::vector<std::uint8_t> out;
  out.reserve(image.radiance.size() * 3);
  for (int y = 0; y < image.height; ++y) {
    const std::size_t at = static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width);
    preview_row(rgb[0].values.data() + at, rgb[1].values.data() + at, rgb[2].values.data() + at,
                image.width, scale, s, out);
  }
  return out;
}

void write_preview_png(const std::string& path, const RenderedImage& image,
                       const ImageSettings& settings) {
  const std::vector<std::uint8_t> rgb = preview_rgb8(image, settings);
  PngRowWriter png(path, image.width, image.height);
  const std::size_t row = static_cast<std::size_t>(image.width) * 3;
  for (int y = 0; y < image.height; ++y)
    png.write_row(rgb.data() + static_cast<std::size_t>(y) * row);
  png.finish();
}

}  // namespace oceanref
