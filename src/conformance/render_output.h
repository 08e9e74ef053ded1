// The render file (`oceanref render`, docs/FILES.md "The render EXR"): a scene rendered to the
// EXR image oceanref writes — channels R, G, B and, with AOVs, the layers; provenance, camera
// matrices and lighting attributes — and its two hashes, the contract the golden suite checks.
#pragma once

#include "core/memory.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "conformance/render_piece.h"
#include "io/exr.h"
#include "raster/renderer.h"
#include "scene/scene.h"

namespace oceanref {

// SHA-256 of the decoded pixel data: R, G, B as float32 little-endian, pixels row-major
// (`rgb` holds the three channels R, G, B, in this order).
std::string pixel_sha256(const std::vector<ExrChannel>& rgb);
// SHA-256 of the double-precision radiance before the float32 conversion: R, G, B as binary64
// little-endian, pixels row-major. A one-ulp change anywhere in the pipeline that the float32
// rounding would hide still changes this hash.
std::string radiance_f64_sha256(const std::vector<Vec3>& radiance);

// A scene ready to render: the scene, its ocean, the job (which points into `ocean`: keep the
// whole struct where it is) and the unresolved slope variance.
struct PreparedRender {
  Scene scene;
  Ocean ocean;
  SceneObjects objects;  // the job's (load_scene_objects)
  RenderJob job;
  SlopeVariance unresolved;
};
// `samples_per_axis` > 0 overrides the scene's; `log` (may be empty) receives progress notes.
std::unique_ptr<PreparedRender> prepare_render(
    const Scene& scene, int threads, int samples_per_axis = 0,
    const std::function<void(const std::string&)>& log = {});

// A frame of a sequence (`render --frames`, conformance/sequence.h): where it sits in time and
// the state of the temporal adaptation (Krawczyk et al. 2005) its preview is tone-mapped with.
struct SequenceFrame {
  int index = 0;                   // k: the frame at scene time + k/fps
  double fps = 30.0;               // frames per second
  double time = 0.0;               // scene time + k/fps [s]
  double metered_luminance = 0.0;  // L̄_w of the frame's metering render [cd/m²]
  double adapted_luminance = 0.0;  // L_a after this frame (Krawczyk eq. 5) [cd/m²]
  double key = 0.18;               // a = automatic_key(L_a) (Krawczyk eq. 12)
};

struct RenderOutputOptions {
  int threads = 1;
  int samples_per_axis = 0;  // 0: the scene's
  bool aov = false;          // also the layers
  // shading.accuracy fast: also the reference lighting of every sample, so that lighting_error
  // is the fast mode's error (|fast − reference| + the reference's estimate; costs a reference
  // render). Without it a fast render's lighting_error is 0 (not estimated).
  bool fast_lighting_error = false;
  std::function<void(const std::string&)> log;  // progress notes (may be empty)
  std::function<void(double)> progress;         // share of the image done (may be empty)
  // render_scene refuses (MemoryLimitError) a render whose estimate is over this many bytes.
  double max_memory = kDefaultMaxMemory;
  // render_scene_piece: tile `tile` of `tiles` (render_piece.h); render_scene: the whole image.
  int tile = 0;
  int tiles = 1;
  // The image rendered and written band by band (render_scene_to_files): the memory estimate
  // counts one band (stream_band_rows), not the whole image.
  bool streamed = false;
  int band_rows = 0;  // streamed: rows per band; 0: stream_band_rows' choice (tests set it)
  // render_scene_to_files: also write every sample's radiance (`render --samples`).
  bool keep_samples = false;
  // What decides visibility (`render --renderer`): the rasterizer or the ray tracer; unset: the
  // scene's render.renderer.
  std::optional<Renderer> renderer;
  // render_scene_to_files: a frame of a sequence (its attributes oceanref.frame,
  // oceanref.frame_rate, oceanref.frame_time, oceanref.metered_luminance,
  // oceanref.adapted_luminance and oceanref.tone_key in the EXR; the preview mapped with L_a as
  // Reinhard's log-average and Krawczyk's key a). The scene is the frame's (its time t_k).
  std::optional<SequenceFrame> frame;
};

// The pixel rows a streamed render holds at once: options.band_rows if set, else as many as fit
// in 256 MiB of band buffers (sample fragments, pixel buffers, EXR channels); at least 1, at
// most the image's.
int stream_band_rows(const Scene& scene, const RenderOutputOptions& options);

// Every large buffer render_scene (or, with options.streamed, render_scene_to_files) allocates
// for `scene` with `options` (bytes): the wave grids, the projected grid, the sample fragments,
// the per-pixel buffers and the EXR channels — of the whole image, of the tile, or of one band
// — and the lighting error's histogram.
MemoryEstimate render_memory_estimate(const Scene& scene, const RenderOutputOptions& options);

// A scene rendered to the EXR that `render` writes (attributes included) and its pixel hashes.
struct RenderedScene {
  ExrImage exr;
  std::string pixel_sha256;         // the float32 pixels as written
  std::string radiance_f64_sha256;  // the double radiance behind them
  RenderedImage image;
  ImageSettings settings;
};
RenderedScene render_scene(const Scene& scene, const RenderOutputOptions& options);
RenderedScene render_scene(const std::string& path, const RenderOutputOptions& options);
// The EXR (attributes included) and the hashes of a whole rendered image of `scene` (whose
// samples per axis are those rendered); with `aov` the image holds the layers, written too.
// render_scene's output, and merge's (the same bytes from the same image).
RenderedScene scene_output(const Scene& scene, RenderedImage image, bool aov);
// Tile options.tile of options.tiles of the scene, as a piece for `oceanref merge`.
RenderPiece render_scene_piece(const Scene& scene, const RenderOutputOptions& options);

// The estimated lighting error relative to the radiance, over the channels of the pixels that
// see the sea (`estimated` false when the image carries no estimate). The median is that of a
// histogram with bins 2⁻⁸ wide (relative; the double's exponent and 8 bits of its mantissa),
// so that a render in bands needs no list of every value: the lower edge of the bin holding
// the value of rank ⌊n/2⌋ (0 exactly when that value is 0), within 0.4% below it.
struct LightingErrorSummary {
  bool estimated = false;
  double max_relative = 0.0;
  double median_relative = 0.0;
};
LightingErrorSummary summarize_lighting_error(const RenderedImage& image);

// The estimated error of the pixels as pixel integrals (RenderedImage::pixel_error) relative to
// their radiance, over the channels of every pixel: p50 and p99 are lower bin edges of the same
// histogram as the lighting error's (rank ⌊q n⌋, within 0.4% below), the max is exact.
// `estimated` false with one sample per pixel (nothing to estimate it from).
struct PixelErrorSummary {
  bool estimated = false;
  int samples_per_pixel = 0;  // S² of the fixed grid (adaptive: before refinement)
  bool adaptive = false;      // adaptive sampling (render.pixel_tolerance): then also
  double mean_samples = 0.0;  // the mean and largest samples per pixel,
  double max_samples = 0.0;
  long capped_pixels = 0;       // the pixels that reached the cap above the tolerance
  long antialiased_pixels = 0;  // render.mastin_antialiasing: the pixels given 16 more samples
  double p50_relative = 0.0;
  double p99_relative = 0.0;
  double max_relative = 0.0;
};
// The render EXR's attribute oceanref.pixel_error: the summary in words, padded with spaces to
// kPixelErrorAttributeLength bytes (a streamed render writes it after its last band).
inline constexpr std::size_t kPixelErrorAttributeLength = 256;
std::string pixel_error_attribute(const PixelErrorSummary& e);
// The summary of one image (as a render in bands accumulates it).
PixelErrorSummary summarize_pixel_error(const RenderedImage& image);

// What `render` and `merge` print for an image (cli print_report).
struct RenderReport {
  std::string pixel_sha256;
  std::string radiance_f64_sha256;
  LightingErrorSummary lighting_error;
  PixelErrorSummary pixel_error;
  long unconverged_samples = 0;
  long integrand_evaluations = 0;
  long corrected_samples = 0;  // RenderedImage::corrected_samples
};
RenderReport report_of(const RenderedScene& rendered);

// The known limit of a Gerstner ocean (waves.model gerstner), loops: the bound b = |u|Σ k_i A_i
// (det J ≥ 1 − b everywhere, so b < 1 means none) and, when b ≥ 1, det J sampled on a 256²
// lattice over a square of twice the longest drawn wavelength centred below the camera at the
// scene's time (gerstner_loops). `render` prints both and warns when the sea folds.
struct GerstnerLoopCheck {
  double steepness_bound = 0.0;
  bool sampled = false;  // b ≥ 1
  GerstnerLoops loops;
  double extent = 0.0;  // the square's side [m]
};
GerstnerLoopCheck gerstner_loop_check(const Scene& scene, const Ocean& ocean);

// A scene rendered band by band straight to `exr_path` (the bytes render_scene's EXR would
// have: its hashes are set in the header after the last band) and, when `png_path` is not
// empty, the preview (a second pass reading the EXR back band by band). Memory: one band
// (stream_band_rows) besides the frame's waves and grid, whatever the image size. With
// options.keep_samples, also every sample's R, G, B to `samples_path` (`render --samples`: an
// EXR at S× the image's resolution, written band by band; the fixed grid only — a scene with
// render.pixel_tolerance is a SceneError).
RenderReport render_scene_to_files(const Scene& scene, const RenderOutputOptions& options,
                                   const std::string& exr_path, const std::string& png_path,
                                   const std::string& samples_path = "");

// The tone-mapped preview (Reinhard 2002 with the scene's key and white, sRGB transfer): 8-bit
// RGB, row-major; write_preview_png writes it as a PNG. The key's log-average luminance and the
// white point come from the double radiance, each pixel is mapped from its float32 value (what
// the EXR holds: a streamed render maps the pixels it reads back).
std::vector<std::uint8_t> preview_rgb8(const RenderedImage& image, const ImageSettings& settings);
void write_preview_png(const std::string& path, const RenderedImage& image,
                       const ImageSettings& settings);

}  // namespace oceanref
