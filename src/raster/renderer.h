// The reference image: wave fields (waves/) on the projected grid (projected_grid.h), rasterized
// with supersampling (rasterizer.h) and shaded per sample with the Bruneton terms under the
// Preetham sky and sun (shading/, sky/). Deterministic: every sample is computed alone, the
// raster and shading passes split sample rows among threads, the resolve averages the S×S
// samples of a pixel in a fixed order.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <stdexcept>
#include <vector>

#include "core/choice.h"
#include "raster/camera.h"
#include "raster/projected_grid.h"
#include "raster/rasterizer.h"
#include "shading/lighting_terms.h"
#include "spectrum/moments.h"
#include "trace/height_field_tracer.h"
#include "trace/scene_objects.h"
#include "trace/surface_tracer.h"
#include "waves/footprint_filter.h"
#include "waves/ocean.h"
#include "waves/slope_budget.h"
#include "waves/surface.h"
#include "waves/whitecaps.h"

namespace oceanref {

// The largest S of S×S samples per pixel (1024 spp, the scene's and --spp's range).
inline constexpr int kMaxSamplesPerAxis = 32;
// The finest grid of adaptive sampling: S·3^r ≤ 243 = 3⁵ samples per axis (59049 per pixel); every
// S has at least one refinement.
inline constexpr int kMaxAdaptiveSamplesPerAxis = 243;
static_assert(3 * kMaxSamplesPerAxis <= kMaxAdaptiveSamplesPerAxis);
// The pixel error (RenderedImage::pixel_error) in standard errors of the pixel's mean.
inline constexpr double kPixelErrorStandardErrors = 3.0;
// The smallest pixel tolerance a scene may ask for (relative to the pixel's largest channel).
inline constexpr double kMinPixelTolerance = 1e-4;
// The two-level estimate's reference tolerance without shading.tolerance: this share of
// render.pixel_tolerance, so that the integrators' estimates take about a tenth of the bound.
inline constexpr double kTwoLevelLightingShare = 0.1;
// The two-level estimate's Gauss–Hermite order of its fast samples without shading.sky_order: 16×16
// nodes (~35 µs a sample) leave a correction several times narrower than the fast mode's 4×4
// (reference/ACCURACY.md, "One error budget per pixel").
inline constexpr int kTwoLevelSkyOrder = 16;
// The finest level of the two-level correction on the grid pattern: the 3S×3S grid ((3S)²
// reference samples; the Sobol' pattern's: kMaxSobolCorrectionLevel). A
// level finer still costs about 0.4 s of CPU per pixel at S = 2; a pixel whose bound needs it is
// capped. (Finer only while none of the level's samples sees the sea and others of the pixel do:
// then nothing estimates the correction, and only those few samples are lit again.)
inline constexpr int kMaxCorrectionRefinements = 1;

// Where an adaptive pixel's samples lie (`render.pixel_pattern`): the nested grid (S×S, whose
// cells are split 3×3 at each refinement; the standard error from the spread of its nine
// interleaved grids) or Owen-scrambled Sobol' points (raster/pixel_pattern.h) in
// kPixelReplicates independent replicates of N points each, N doubled at each refinement (the
// standard error from the spread of the replicates' means).
enum class PixelPattern { grid, sobol };
inline constexpr std::array<Choice<PixelPattern>, 2> kPixelPatterns{{
    {PixelPattern::grid, "grid"},
    {PixelPattern::sobol, "sobol"},
}};
// The Sobol' pattern's replicates per pixel: 15 degrees of freedom for the standard error (with
// 8, a pixel that stops as soon as its estimate meets the tolerance is outside its bound too
// often: reference/ACCURACY.md, "Converged pixels").
inline constexpr int kPixelReplicates = 16;
// The Sobol' pattern's two-level correction at level l: its first 4·2^l samples, the first point
// of that many replicates or the first points of all 16 (sobol_correction_samples); the finest
// level 3, 32 reference samples (the grid's finest at S = 2 has 36).
inline constexpr int kMaxSobolCorrectionLevel = 3;
inline int sobol_correction_samples(int level) {
  return 4 << level;
}
// The Sobol' pattern's points per replicate before refinement: the fewest N (a power of 2) with
// kPixelReplicates·N ≥ S².
int sobol_first_points(int samples_per_axis);
// The samples of an adaptive pixel after `refinements` refinements: (S·3^r)², or
// kPixelReplicates · sobol_first_points(S) · 2^r.
int adaptive_samples(PixelPattern pattern, int samples_per_axis, int refinements);

// Which renderer decides what a sample sees (`render --renderer`): the scanline rasterizer
// (raster/rasterizer.h) or Mastin's height-field ray tracer (trace/height_field_tracer.h), both
// on the same displaced projected grid, or the ray tracer against the continuous surface the
// grid samples (trace/surface_tracer.h: ground-truth visibility); all shaded the same way.
enum class Renderer { raster, raytrace, raytrace_surface };
inline constexpr std::array<Choice<Renderer>, 3> kRenderers{{
    {Renderer::raster, "raster"},
    {Renderer::raytrace, "raytrace"},
    {Renderer::raytrace_surface, "raytrace_surface"},
}};
inline bool is_ray_traced(Renderer r) {
  return r != Renderer::raster;
}
// The default and the range of RenderJob::surface_tolerance [pixels].
inline constexpr double kDefaultSurfaceTolerance = 0.1;
inline constexpr double kMinSurfaceTolerance = 1e-3;
inline constexpr double kMaxSurfaceTolerance = 1.0;

struct RenderJob {
  const Ocean* ocean = nullptr;
  Renderer renderer = Renderer::raster;
  // The scene's objects in world space (none when null or empty): both renderers show them,
  // depth-tested against the sea (the part under the surface hidden by it); the ray tracer also
  // reflects them in the sea when object_reflections is set — each sea sample's mirror ray about
  // its shading normal, where it meets an object, reflects that object's radiance times the
  // Fresnel reflectance F(V·N) instead of the sky (a sharp reflection: the BRDF's slope lobe
  // is not integrated over the object). No shadows, in either renderer.
  const SceneObjects* objects = nullptr;
  bool object_reflections = true;
  // Renderer::raytrace_surface (`render.surface_tolerance`): a patch of the surface is resolved
  // when its bounding box, seen from the camera, spans at most this many pixels (of the pixel
  // angle at the image centre, vertical_fov / height); rays that pass the surface by more are
  // decided exactly (trace/surface_tracer.h).
  double surface_tolerance = kDefaultSurfaceTolerance;
  double time = 0.0;
  Camera camera;
  ProjectedGridSettings grid;  // columns, rows, margin (the bound is filled in)
  Sky sky;
  ShadingSettings shading;
  // shading.whitecaps: the displacement-gradient moments (× u²) of the waves the renderer does
  // not draw (unresolved_jacobian_moments; scene_render_job fills them): the variance of det J
  // every sample adds to what its footprint holds (waves/whitecaps.h).
  JacobianMoments unresolved_jacobian;
  // shading.whitecaps with foam.steps > 0 (`waves.foam`): the coverage accumulates over the
  // instants t − steps·Δt, …, t at each sample's x0 (Vincevičius listing 2.4 applied to W;
  // foam_coverage_at). Not with footprint_filtering (the earlier instants are not filtered).
  FoamSequence foam;
  int samples_per_axis = 2;  // S: S×S stratified samples per pixel, 1…kMaxSamplesPerAxis
  // Adaptive sampling (`render.pixel_tolerance`): a pixel whose estimated error exceeds
  // pixel_tolerance × its largest channel is refined — in pixel_pattern: the Sobol' pattern's
  // replicates doubled, or the nested grid's S×S becoming 3S×3S, whose cell centres are the S×S
  // samples (kept), then 9S×9S, … — until the estimate meets the tolerance or the pixel has
  // adaptive_samples(pixel_pattern, S, max_refinements) samples (the cap). The stopping rule
  // reads the pixel's own samples only: any thread count, band or tile gives the same bits.
  // 0: the fixed S×S grid (no refinement).
  double pixel_tolerance = 0.0;
  int max_refinements = 0;  // adaptive_samples(pixel_pattern, S, max_refinements) at the cap
  PixelPattern pixel_pattern = PixelPattern::sobol;
  // The two-level estimate of adaptive sampling with reference lighting (`render.pixel_tolerance`
  // with shading.accuracy reference; README, "One error budget per pixel"): every sample is shaded
  // by the fast rules (shading.sky_order, sun_order: FrameLighting's nodes), and the pixel is
  // corrected by the mean of (reference − fast) over one level of its samples (the Sobol'
  // pattern's first sobol_correction_samples(l); the grid's S×S, or 3S×3S where needed), the
  // reference at shading.tolerance. The pixel's expected value is the reference's; pixel_error
  // bounds the fast level's pixel integral, lighting_error the correction
  // (kPixelErrorStandardErrors standard errors of its mean + the reference's own estimates), and
  // each pixel is refined (the fast level or the correction's, whichever misses its share; the
  // correction up to kMaxSobolCorrectionLevel or kMaxCorrectionRefinements) until pixel_error +
  // lighting_error ≤ pixel_tolerance × its largest channel.
  bool lighting_correction = false;
  // Mastin's adaptive anti-aliasing (`render.mastin_antialiasing`; Mastin, Watterberg & Mareda
  // 1987: "16 extra rays per pixel in the neighborhood of large color discontinuities"): after
  // the S×S grid, a pixel whose luminance contrast with one of its four neighbours,
  // |Y_p − Y_q|/(Y_p + Y_q) of the S×S means, exceeds this value gets 16 more samples at
  // ((a + ½)/4, (b + ½)/4), a, b = 0…3, and is resolved from all S² + 16 (each weighted
  // 1/(S² + 16), the S² first). The neighbours above and below a band are rendered too, so a
  // band gives the bits of the whole image. 0: off. Not with pixel_tolerance or keep_samples.
  double antialiasing_contrast = 0.0;
  int threads = 1;
  // The pixel rows rendered, [first_row, last_row) of the camera's image (last_row −1: to the
  // bottom): a band of the image, each pixel the same bits as in the whole image (tiles,
  // `render --tile`).
  int first_row = 0;
  int last_row = -1;
  // Footprint filtering (`render.footprint_filtering`, waves/footprint_filter.h): each sample
  // reads the waves filtered to its cell's footprint on the sea (1/S pixel through the
  // projected grid's screen-space derivatives) with the slope variance under it added to σ²,
  // and each grid vertex the waves filtered to its grid cell.
  bool footprint_filtering = false;
  // Fast accuracy only: also compute the reference lighting of every sample, so that the
  // lighting error is |fast − reference| + the reference's estimate (reference accuracy always
  // reports its estimate).
  bool estimate_fast_error = false;
  // Also fill the per-pixel layers sun, sky, sea, foam, depth, normal and x0 (`render --aov`);
  // without them the image holds radiance, coverage and lighting_error only.
  bool layers = false;
  // Also keep every sample's radiance (RenderedImage::sample_radiance; `render --samples`):
  // the fixed grid only, not with pixel_tolerance.
  bool keep_samples = false;
  // Called with 0 when the rows start (after the frame's preparation and the raster pass), then
  // with the finished share of the rows after each row, from any worker thread; the rows are
  // rendered in spread order (spread_order), so the share is a sample of the work. For progress
  // display only.
  std::function<void(double)> progress;
};

// Per-pixel outputs (box-filtered over the samples); `coverage` is the share of samples that hit
// the sea. The layers sun … x0 are empty unless the job asked for them (RenderJob::layers).
struct RenderedImage {
  int width = 0;
  int height = 0;              // rows held (the job's band)
  int first_row = 0;           // the image row of row 0 (0 unless the job rendered a band)
  int samples_per_axis = 1;    // S of the S×S samples behind each pixel
  std::vector<Vec3> radiance;  // cd/m², linear sRGB
  std::vector<Vec3> sun, sky, sea, foam;  // the terms (AOVs), 0 where the sea is not seen
  std::vector<double> depth;              // mean view depth of the sea samples [m], 0 if none
  std::vector<Vec3> normal;               // mean shading normal of the sea samples, 0 if none
  std::vector<Vec3> x0;  // mean undisplaced position (x0, 0, z0) of the sea samples
  std::vector<double> coverage;
  // Estimated absolute error of `radiance` from the lighting integrals, per channel (0 where
  // not estimated: fast accuracy without estimate_fast_error).
  std::vector<Vec3> lighting_error;
  // Estimated absolute error of `radiance` as the pixel integral (the box filter over the
  // pixel), per channel, as a bound: kPixelErrorStandardErrors standard errors of the pixel's
  // mean — of the S² samples of the fixed grid taken as independent (pixel_standard_error; 0
  // with one sample, where nothing estimates it), or after a refinement to n×n samples the
  // spread of the nine interleaved (n/3)×(n/3) grids' means (each a stratified estimate); on the
  // Sobol' pattern the spread of its kPixelReplicates replicates' means.
  std::vector<Vec3> pixel_error;
  // Adaptive sampling only (RenderJob::pixel_tolerance > 0), else empty: the samples behind each
  // pixel (adaptive_samples after r refinements).
  std::vector<double> pixel_samples;
  // RenderJob::keep_samples only, else empty: the radiance of every sample of the band's S×S
  // grid, row-major over its (height·S) × (width·S) samples (sample (c, r) of the band sits at
  // image position ((c + ½)/S, first_row + (r + ½)/S)); each pixel's radiance is the mean of
  // its S×S samples, 1/S² each, summed in row-major order.
  std::vector<Vec3> sample_radiance;
  // Adaptive pixels that reached the cap above the tolerance: those whose pixel_error +
  // lighting_error exceeds pixel_tolerance × their largest channel in some channel.
  long capped_pixels = 0;
  // RenderJob::lighting_correction: the samples lit again by the reference to correct their
  // pixels ((S·3^l)² of a pixel at the correction's level l; those that see the sea).
  long corrected_samples = 0;
  long antialiased_pixels = 0;   // pixels that got Mastin's 16 extra samples
  long unconverged_samples = 0;  // samples whose reference integrals missed the tolerance
  long integrand_evaluations = 0;
  SlopeVariance unresolved;  // the BRDF roughness used
  double displacement_bound = 0.0;
};

// The extra samples per axis of Mastin's adaptive anti-aliasing (4 × 4 = 16).
inline constexpr int kMastinExtraSamplesPerAxis = 4;
// Luminance Y of linear sRGB (ITU-R BT.709 weights) and the contrast |Y_a − Y_b|/(Y_a + Y_b) of
// two pixels (0 when both are black): the discontinuity measure of Mastin's anti-aliasing.
double luminance_contrast(const Vec3& a, const Vec3& b);

// The indices 0 … count − 1 in bit-reversed order (van der Corput's sequence, those < count):
// every prefix is spread evenly over the range (the first 2^j cover it at a stride of
// 2^(bits − j)). The order in which render_rows renders a band's rows.
std::vector<int> spread_order(int count);

// S·3^refinements: the samples per axis of a pixel of S×S refined `refinements` times (the cap
// of adaptive sampling; S without refinement).
int refined_samples_per_axis(int samples_per_axis, int refinements);
// The bytes the resolve keeps of one sample (its radiance, layers and hit; sizeof(SampleValue)).
inline constexpr std::size_t kResolvedSampleBytes = 208;
// The bytes the two-level estimate keeps of one sample's correction (reference − fast of the
// radiance and the three terms, and the reference's estimate).
inline constexpr std::size_t kCorrectionSampleBytes = 5 * sizeof(Vec3);
// The scratch memory of one thread's adaptive refinement up to `samples` per pixel (the cap,
// adaptive_samples): two sample buffers (a level and the next, trading places), one fragment
// buffer, the Sobol' pattern's positions and with the two-level lighting
// (RenderJob::lighting_correction) one buffer of the samples' corrections, each reserved for the
// finest level [bytes].
double refinement_bytes(int samples, bool lighting_correction);

// The standard error of the mean of a pixel's samples, per channel:
// √(Σᵢ (xᵢ − mean)² / (n (n − 1))), summed in sample order; 0 for n < 2. The samples are those of
// the S×S stratified grid, treated as independent draws: where a sub-pixel feature (a sun
// glint, the horizon) is hit by some samples and missed by others it is the error's size;
// where the radiance is smooth across the pixel it overestimates the error of the stratified
// mean (which falls faster than n^{-1/2}).
Vec3 pixel_standard_error(std::span<const Vec3> samples, const Vec3& mean);

// The slope variance budget of the job's frame (waves/slope_budget.h): the spectrum's mean
// square slope per wind axis up to λ_min, split into what the shaded slope field carries (its
// bands, as interpolated) and the rest.
SlopeVarianceBudget slope_budget(const RenderJob& job, const WaveSettings& waves);
// The unresolved slope variance, the BRDF's σ²: every slope variance the shaded fields do not
// carry — the spectrum beyond their bands, what interpolation removes, and the realization's
// deficit — so that resolved + σ² equals the spectrum's moment per axis.
SlopeVariance unresolved_slope_variance(const RenderJob& job, const WaveSettings& waves);

// Wall-clock seconds per stage (benchmarks).
struct RenderTimes {
  double synthesis = 0.0;  // wave fields of every cascade
  double grid = 0.0;       // projected grid and vertex displacement
  double raster = 0.0;
  double shading = 0.0;  // per-sample shading and the resolve
};

// A non-finite value in an output: never written, never a success (the program exits 1).
class NonFiniteOutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws NonFiniteOutputError when any buffer of `image` holds a non-finite value: the first
// such pixel in row-major order, with the buffer (the term: radiance, sun, sky, sea, foam,
// lighting_error, depth, normal, x0, coverage), the channel and the terms of that pixel.
void require_finite(const RenderedImage& image);

// Renders the job (prepare_frame, then render_rows of the job's rows); the image is checked
// with require_finite (a non-finite pixel is an error, whatever its cause).
RenderedImage render(const RenderJob& job, const SlopeVariance& unresolved,
                     RenderTimes* times = nullptr);

// The waves of one frame as the chosen interpolation reads them: FFT grids, or for direct
// summation h(k, t) of every cascade.
struct FrameFields {
  std::vector<CascadeFields> grids;
  std::vector<EvolvedCascade> evolved;
};
// The projected grid of one frame with its vertices on the displaced surface and on screen.
struct FrameGeometry {
  ProjectedGrid grid;
  std::vector<glm::dvec3> world;  // [j·columns + i], like grid.base
  std::vector<ScreenVertex> screen;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  // Renderer::raytrace only: the triangles a ray may hit (not those the rasterizer skips at the
  // near plane) and the bounds quadtree over the grid's cells (trace/height_field_tracer.h).
  std::vector<bool> untraced;
  BoundsTree bounds;
  // The objects (RenderJob::objects): their vertices follow the grid's in `world` and `screen`,
  // their triangles the sea's in `triangles` (so the rasterizer's depth test and tie order — the
  // sea first — decide between them), from index sea_triangles on. For the ray tracer, the same
  // triangles again (object_triangles, object_untraced) with their own bounds tree.
  std::size_t sea_triangles = 0;
  std::vector<std::array<std::uint32_t, 3>> object_triangles;
  std::vector<bool> object_untraced;
  BoundsTree object_bounds;
  // Renderer::raytrace_surface only: the unfiltered surface p(x0) at the grid's vertices (its
  // vertices in `world` are filtered with render.footprint_filtering), its proven bounds and the
  // tree over its cells (trace/surface_tracer.h).
  std::vector<glm::dvec3> surface_corners;
  DisplacedSurfaceBounds surface_bounds;
  BoundsTree surface_tree;
};
// What every band of a frame shares, computed once: a render in bands (streaming, bounded
// memory) prepares the frame, then renders its rows band by band.
struct RenderFrame {
  RenderJob job;  // its first_row/last_row are not used: render_rows names the rows
  SlopeVariance unresolved;
  double wind_cos = 1.0, wind_sin = 0.0;  // the wind direction (cos φ, sin φ)
  // The fields at t − j·Δt, j = foam.steps … 1 (oldest first), for the accumulated foam.
  std::vector<FrameFields> foam_history;
  double displacement_bound = 0.0;
  FrameFields fields;
  FrameGeometry geometry;
  FrameLighting light;
  // The shading of the pixel grids' samples: job.shading, lit by the fast rules under a two-level
  // estimate (RenderJob::lighting_correction), whose correction uses job.shading itself.
  ShadingSettings sample_shading;
  std::optional<FootprintFilter> filter;  // RenderJob::footprint_filtering
};
RenderFrame prepare_frame(const RenderJob& job, const SlopeVariance& unresolved,
                          RenderTimes* times = nullptr);
// The whitecap coverage at x0 = (x, z) of the frame's sea (Dupuy & Bruneton 2012): W = P(det J <
// ε) with det J normal, its mean the fields' det J and its variance that of `residual` (the waves
// the read fields lack, waves/whitecaps.h); with job.foam.steps > 0, W accumulated over the
// frame's foam_history and the frame itself by accumulated_foam (Vincevičius listing 2.4),
// starting from no foam — as accumulate_foam folds the indicator (`oceanref fields`), which it
// equals where the variance is 0 and the threshold 0. `fields` are the frame's at (x, z).
double foam_coverage_at(const RenderFrame& frame, const PointFields& fields, double x, double z,
                        const JacobianMoments& residual);

// Pixel rows [first_row, last_row) of the frame: the same bits as those rows of a whole render
// (checked with require_finite). `progress` (may be empty) gets the band's finished share.
RenderedImage render_rows(const RenderFrame& frame, int first_row, int last_row,
                          const std::function<void(double)>& progress = {},
                          RenderTimes* times = nullptr);

// The mesh render rasterizes for the job's frame: the projected grid (its displacement bound
// the ocean's height_bound), every vertex on the displaced surface, (x0 + Σu_iD_i, Σ η_i, z0 +
// Σu_iD_i) with the fields read as the shading reads them (combine_shading_at), and the grid's
// triangles (grid_triangles).
struct SurfaceMesh {
  ProjectedGrid grid;
  std::vector<glm::dvec3> world;  // [j·columns + i], like grid.base
  std::vector<std::array<std::uint32_t, 3>> triangles;
};
SurfaceMesh surface_mesh(const RenderJob& job);

// Everything behind one sample, for `oceanref probe`.
struct SampleProbe {
  double image_x = 0.0, image_y = 0.0;  // the sample position [pixels]
  bool hit = false;                     // the sea
  bool object = false;  // an object (then only depth, triangle, position, normal and radiance)
  bool reflects_object = false;  // the sea sample's sky term is an object's reflection
  double depth = 0.0;
  std::int64_t triangle = -1;
  glm::dvec2 x0{0.0};
  glm::dvec3 position{0.0};
  PointFields fields;
  Vec3 normal{};
  Vec3 view{};
  SlopeVariance roughness;  // the BRDF's σ²: the unresolved one (+ the footprint's when filtering)
  Footprint footprint;      // the sample's footprint on the sea (when filtering) [m²]
  LightingTerms lighting;   // sun, sky, sea, F̄ and their estimated errors
  Vec3 foam{}, radiance{};
  // shading.whitecaps: det J under the sample's footprint, mean and variance (waves/whitecaps.h),
  // and W = P(det J < ε) (Dupuy & Bruneton 2012).
  double jacobian_mean = 1.0, jacobian_variance = 0.0;
  double whitecap_coverage = 0.0;
  Vec3 lighting_error{};  // of `radiance` (see RenderedImage::lighting_error)
};
// The shading of each sample of one pixel (its fragment from a full raster pass), in the
// order render averages them: sample rows top to bottom, each left to right.
std::vector<SampleProbe> probe_pixel(const RenderJob& job, const SlopeVariance& unresolved,
                                     int pixel_x, int pixel_y);
// The pixel's radiance from its samples as render resolves it: Σ (1/S²)·radiance in sample
// order, from 0 — the same bits as RenderedImage::radiance for that pixel.
Vec3 resolve_pixel(const std::vector<SampleProbe>& samples);

}  // namespace oceanref
