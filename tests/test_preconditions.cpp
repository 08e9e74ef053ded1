// The library's preconditions (src/core/check.h): kept in every build type (this binary is
// built Release, with NDEBUG), they throw PreconditionError naming the file, line, condition and
// message when code calls a function wrongly. Each check here calls one function the way a bug
// would and expects the throw; the correct call right beside it does not throw.
#include <doctest/doctest.h>

#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/check.h"
#include "raster/projected_grid.h"
#include "raster/rasterizer.h"
#include "raster/renderer.h"
#include "shading/ocean_lighting.h"
#include "sky/preetham.h"
#include "spectrum/moments.h"
#include "waves/fft.h"
#include "waves/interpolation.h"
#include "waves/ocean.h"
#include "waves/slope_budget.h"

using namespace oceanref;

namespace {
int checked_line = 0;
void fails_on_purpose(int value) {
  checked_line = __LINE__ + 1;
  OCEANREF_EXPECTS(value > 0, "value must be positive, got " + std::to_string(value));
}
}  // namespace

TEST_CASE("OCEANREF_EXPECTS: active with NDEBUG, a logic_error naming file, line and condition") {
#ifdef NDEBUG
  MESSAGE("built with NDEBUG: the check below must still fire");
#endif
  CHECK_NOTHROW(fails_on_purpose(1));
  CHECK_THROWS_AS(fails_on_purpose(-3), PreconditionError);
  CHECK_THROWS_AS(fails_on_purpose(-3), std::logic_error);
  try {
    fails_on_purpose(-3);
    FAIL("no throw");
  } catch (const PreconditionError& e) {
    const std::string what = e.what();
    CAPTURE(what);
    CHECK(what.starts_with("internal error: precondition failed at "));
    CHECK(what.ends_with("test_preconditions.cpp:" + std::to_string(checked_line) +
                         ": value > 0 (value must be positive, got -3)"));
  }
  // The message is built only when the check fails (so it may cost a string).
  int built = 0;
  const auto message = [&] {
    ++built;
    return std::string("never");
  };
  OCEANREF_EXPECTS(built == 0, message());
  CHECK(built == 0);
}

TEST_CASE("preconditions of the wave stages fire on wrong calls") {
  // FFT: N² values for N.
  std::vector<Complex> data(16);
  CHECK_NOTHROW(inverse_fft_2d(data, 4, 1));
  CHECK_THROWS_AS(inverse_fft_2d(data, 8, 1), PreconditionError);
  // A pattern's N is a power of two, its size positive.
  const Spectrum spectrum = make_spectrum({});
  CHECK_NOTHROW(pattern_grid(spectrum, Pattern{0, 100.0, 8, Band{}}));
  CHECK_THROWS_AS(pattern_grid(spectrum, Pattern{0, 100.0, 12, Band{}}), PreconditionError);
  CHECK_THROWS_AS(pattern_grid(spectrum, Pattern{0, -1.0, 8, Band{}}), PreconditionError);
  // h(k, t) of the pattern's size.
  const PatternSpectrum p = realize_pattern(spectrum, 1, Pattern{0, 100.0, 8, Band{}});
  std::vector<Complex> h = spectrum_at_time(p, 0.0);
  CHECK_NOTHROW(resolved_slope_variance(p, h, 0.0, Interpolation::bicubic,
                                        SlopeReading::derivative_of_height));
  h.pop_back();
  CHECK_THROWS_AS(resolved_slope_variance(p, h, 0.0, Interpolation::bicubic,
                                          SlopeReading::derivative_of_height),
                  PreconditionError);
  CHECK_THROWS_AS(direct_sum_on_lattice(p, h, 4, 1.0, {Field::height}, false, 1),
                  PreconditionError);
  PatternSpectrum broken = p;
  broken.omega.resize(3);
  CHECK_THROWS_AS(spectrum_at_time(broken, 1.0), PreconditionError);
  // Interpolation reads an N × N grid of positive size.
  const std::vector<double> grid(64, 1.0);
  CHECK(sample_periodic(grid, 8, 10.0, 3.3, 4.4) == 1.0);
  CHECK_THROWS_AS(sample_periodic(grid, 16, 10.0, 3.3, 4.4), PreconditionError);
  CHECK_THROWS_AS(sample_periodic_bicubic(grid, 8, 0.0, 3.3, 4.4), PreconditionError);
  CHECK_THROWS_AS(sample_periodic_gradient(grid, 7, 10.0, 3.3, 4.4, Interpolation::bicubic),
                  PreconditionError);
  // The two patterns of a cascade: the same size, N_l ≤ N_h.
  const PatternSpectrum q = realize_pattern(spectrum, 1, Pattern{0, 50.0, 8, Band{}});
  CHECK_THROWS_AS(synthesize_cascade(p, q, 0.0, 1), PreconditionError);
  // One field set (or evolved spectrum) per cascade.
  WaveSettings waves;
  waves.sizes = {200.0, 60.0};
  waves.choppiness = {-0.5, -0.5};
  waves.resolution = 16;
  waves.low_resolution = 16;
  const Ocean ocean = realize_ocean(waves, 1);
  std::vector<CascadeFields> fields = synthesize_ocean(ocean, 0.0, 1);
  CHECK_NOTHROW(combine_at(ocean, fields, {}, 1.0, 2.0, Interpolation::bilinear));
  fields.pop_back();
  CHECK_THROWS_AS(combine_at(ocean, fields, {}, 1.0, 2.0, Interpolation::bilinear),
                  PreconditionError);
  CHECK_THROWS_AS(combine_shading_at(ocean, fields, {}, 1.0, 2.0, Interpolation::bicubic,
                                     ShadingNormals::surface),
                  PreconditionError);
  CHECK_THROWS_AS(combine_direct(ocean, std::vector<EvolvedCascade>(1), 1.0, 2.0),
                  PreconditionError);
  // One choppiness per cascade size (a missing one would be read past the end).
  WaveSettings unmatched = waves;
  unmatched.choppiness = {-0.5};
  CHECK_THROWS_AS(realize_ocean(unmatched, 1), PreconditionError);
  unmatched.sizes.clear();
  unmatched.choppiness.clear();
  CHECK_THROWS_AS(realize_ocean(unmatched, 1), PreconditionError);
  // A band starts at k ≥ 0.
  CHECK_THROWS_AS(band_slope_variance(spectrum, -1.0, 1.0), PreconditionError);
}

TEST_CASE("preconditions of the shading and raster stages fire on wrong calls") {
  const SurfaceFrame frame = wind_frame({0.0, 1.0, 0.0}, 0.0);
  const Vec3 view{0.0, 0.6, 0.8};
  CHECK_NOTHROW(view_terms(view, frame, {0.02, 0.01}));
  // Not normalized (|d|² = 1.0002: the tolerance is 1e-6), or a zero variance.
  CHECK_THROWS_AS(view_terms({0.0, 0.6, 0.8001}, frame, {0.02, 0.01}), PreconditionError);
  CHECK_THROWS_AS(view_terms(view, frame, {0.0, 0.01}), PreconditionError);
  CHECK_THROWS_AS(ocean_brdf({0.0, 2.0, 0.0}, {0.0, 1.0, 1.0}, frame, {0.02, 0.01}),
                  PreconditionError);
  CHECK_THROWS_AS(mean_fresnel(view, frame, {0.02, 0.01}, QuadratureRule{}), PreconditionError);
  CHECK_THROWS_AS(mean_fresnel({0.0, 3.0, 0.0}, frame, {0.02, 0.01}, 4), PreconditionError);
  CHECK_THROWS_AS(sun_disk_nodes({0.0, 0.5, 0.0}, kSunAngularRadius, QuadratureRule{}),
                  PreconditionError);
  CHECK_THROWS_AS(whitecap_coverage(0.5, -1e-3, 0.0), PreconditionError);
  CHECK_THROWS_AS(refracted_sea(1.5, {0.1, 0.1, 0.1}, {1.0, 1.0, 1.0}), PreconditionError);
  // Rasterizer: one fragment per sample, rows in range, vertex indices in range.
  const std::vector<ScreenVertex> vertices{{1, 1, 5}, {9, 1, 5}, {1, 9, 5}};
  const SampleGrid samples{10, 10, 1};
  std::vector<Fragment> fragments(100);
  CHECK_NOTHROW(rasterize(vertices, {{0, 1, 2}}, samples, 0, 10, 0.1, fragments));
  using Corners = std::array<std::uint32_t, 3>;
  for (const Corners bad : {Corners{3, 1, 2}, Corners{0, 3, 2}, Corners{0, 1, 3}}) {
    CHECK_THROWS_AS(rasterize(vertices, {bad}, samples, 0, 10, 0.1, fragments),
                    PreconditionError);  // each corner one past the last vertex
  }
  CHECK_THROWS_AS(rasterize(vertices, {{0, 1, 2}}, samples, 0, 11, 0.1, fragments),
                  PreconditionError);
  std::vector<Fragment> too_few(99);
  CHECK_THROWS_AS(rasterize(vertices, {{0, 1, 2}}, samples, 0, 10, 0.1, too_few),
                  PreconditionError);
  // A band of fragments (rows 5…9): rows outside it, or a band past the grid, are refused.
  std::vector<Fragment> band(50);
  CHECK_NOTHROW(rasterize(vertices, {{0, 1, 2}}, samples, 5, 10, 0.1, band, 5));
  CHECK_THROWS_AS(rasterize(vertices, {{0, 1, 2}}, samples, 4, 10, 0.1, band, 5),
                  PreconditionError);
  CHECK_THROWS_AS(rasterize(vertices, {{0, 1, 2}}, samples, 5, 10, 0.1, band, 6),
                  PreconditionError);
  // A subset of the triangles: ascending indices of existing triangles.
  const std::vector<std::array<std::uint32_t, 3>> two{{0, 1, 2}, {0, 2, 1}};
  CHECK_NOTHROW(rasterize(vertices, two, {0, 1}, samples, 0, 10, 0.1, fragments));
  CHECK_THROWS_AS(rasterize(vertices, two, {1, 0}, samples, 0, 10, 0.1, fragments),
                  PreconditionError);
  CHECK_THROWS_AS(rasterize(vertices, two, {0, 2}, samples, 0, 10, 0.1, fragments),
                  PreconditionError);
  // The camera: each refusal with its message; the ends of the field of view, (0, π), are out.
  const auto camera_refusal = [](glm::dvec3 look_at, glm::dvec3 up, double fov, int w, int h) {
    try {
      (void)make_camera({0, 5, 0}, look_at, up, fov, w, h);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string fov_range = "camera: vertical field of view must be in (0, 180) degrees";
  CHECK(camera_refusal({0, 0, 50}, {0, 1, 0}, 1.0, 32, 18).empty());
  CHECK(camera_refusal({0, 5, 0}, {0, 1, 0}, 1.0, 32, 18) == "camera: look_at equals position");
  CHECK(camera_refusal({0, 0, 50}, {0, 1, 0}, 0.0, 32, 18) == fov_range);
  CHECK(camera_refusal({0, 0, 50}, {0, 1, 0}, std::numbers::pi, 32, 18) == fov_range);
  CHECK(camera_refusal({0, 0, 50}, {0, 1, 0}, std::numeric_limits<double>::quiet_NaN(), 32, 18) ==
        fov_range);
  CHECK(camera_refusal({0, 0, 50}, {0, 1, 0}, 3.1, 32, 18).empty());
  CHECK(camera_refusal({0, 0, 50}, {0, 1, 0}, 1.0, 0, 18) == "camera: image size must be >= 1");
  CHECK(camera_refusal({0, 0, 50}, {0, 1, 0}, 1.0, 32, 0) == "camera: image size must be >= 1");
  CHECK(camera_refusal({0, 0, 50}, {0, 1, 0}, 1.0, 1, 1).empty());
  CHECK(camera_refusal({0, -5, 0}, {0, 1, 0}, 1.0, 32, 18) ==
        "camera: up must not be parallel to the viewing direction");
  // Projected grid settings.
  const Camera camera = make_camera({0, 5, 0}, {0, 0, 50}, {0, 1, 0}, 1.0, 32, 18);
  ProjectedGridSettings settings;
  settings.columns = 8;
  settings.rows = 8;
  CHECK_NOTHROW(project_grid(camera, settings));
  settings.displacement_bound = -1.0;
  CHECK_THROWS_AS(project_grid(camera, settings), PreconditionError);
  // A render job without its ocean; a probe outside the image; a pixel without samples.
  RenderJob job;
  job.camera = camera;
  job.sky = make_sky(2.5, 1.0, 0.0);
  CHECK_THROWS_AS(render(job, {0.01, 0.01}), PreconditionError);
  WaveSettings waves;
  waves.resolution = 16;
  waves.low_resolution = 16;
  const Ocean ocean = realize_ocean(waves, 1);
  job.ocean = &ocean;
  job.samples_per_axis = 1;
  job.grid.columns = 8;
  job.grid.rows = 8;
  job.shading.accuracy = LightingAccuracy::fast;
  CHECK(probe_pixel(job, {0.01, 0.01}, 31, 17).size() == 1u);
  CHECK_THROWS_AS(probe_pixel(job, {0.01, 0.01}, 32, 0), PreconditionError);
  CHECK_THROWS_AS(probe_pixel(job, {0.01, 0.01}, 0, -1), PreconditionError);
  CHECK_THROWS_AS(resolve_pixel({}), PreconditionError);
}
