// Memory as a checked resource (issue 15 point 3): the estimate's arithmetic and message, the
// allocation failure that names its buffer, and the wave-grid estimate against the capacity of
// the buffers a realized and synthesized ocean actually holds.
#include <doctest/doctest.h>

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "conformance/render_output.h"
#include "core/memory.h"
#include "raster/rasterizer.h"
#include "raster/renderer.h"
#include "scene/scene.h"
#include "waves/footprint_filter.h"
#include "waves/ocean.h"
#include "waves/surface.h"

using namespace oceanref;

TEST_CASE("memory: mebibytes in messages") {
  CHECK(mebibytes(0.0) == "0 MiB");
  CHECK(mebibytes(1.0) == "0.1 MiB");  // something is never shown as nothing
  CHECK(mebibytes(1.5 * kMebibyte) == "1.5 MiB");
  CHECK(mebibytes(8192.0 * kMebibyte) == "8192 MiB");
}

TEST_CASE("memory: an estimate over the limit names its largest buffers and the flag") {
  const MemoryEstimate e{{{"a", 1.0 * kMebibyte},
                          {"b", 40.0 * kMebibyte},
                          {"c", 3.0 * kMebibyte},
                          {"d", 20.0 * kMebibyte}}};
  CHECK(e.total() == 64.0 * kMebibyte);
  CHECK_NOTHROW(require_within(e, 64.0 * kMebibyte, "--max-memory"));
  std::string message;
  try {
    require_within(e, 63.0 * kMebibyte, "--max-memory");
  } catch (const MemoryLimitError& error) {
    message = error.what();
  }
  CHECK(message ==
        "needs an estimated 64 MiB of memory (largest: b 40 MiB, d 20 MiB, c 3 MiB), over the "
        "limit of 63 MiB; raise it with --max-memory or make the job smaller");
}

TEST_CASE("memory: a failed allocation names what it was for and how much") {
  // More elements than a vector can hold: std::length_error before any allocation (the same
  // path as std::bad_alloc, and safe under AddressSanitizer).
  const std::size_t count = std::size_t{1} << 62;
  std::string message;
  try {
    (void)allocate_buffer<double>(count, "the test buffer");
  } catch (const OutOfMemoryError& error) {
    message = error.what();
  }
  CHECK(message ==
        "out of memory: could not allocate 35184372088832 MiB for the test buffer (free memory, "
        "or lower the resolution or sample count)");
  CHECK(allocate_buffer<int>(3, "three", 7) == std::vector<int>{7, 7, 7});
}

namespace {
// Two cascades of 64² (N_h) and 32² (N_l).
WaveSettings two_cascades() {
  WaveSettings w;
  w.sizes = {120.0, 12.0};
  w.resolution = 64;
  w.low_resolution = 32;
  w.choppiness = {-0.5, -0.5};
  return w;
}

// The bytes an ocean's spectra (h0, 1/k, ω of both patterns) and its field grids hold.
double held_bytes(const Ocean& ocean, const std::vector<CascadeFields>& grids) {
  double held = 0.0;
  for (const CascadeSpectra& c : ocean.cascades) {
    for (const PatternSpectrum* s : {&c.low, &c.high}) {
      held += static_cast<double>(s->h0.capacity() * sizeof(Complex) +
                                  s->inverse_wavenumber.capacity() * sizeof(double) +
                                  s->omega.capacity() * sizeof(double));
    }
  }
  for (const CascadeFields& f : grids) {
    for (const std::vector<double>& v : f.values) {
      held += static_cast<double>(v.capacity() * sizeof(double));
    }
  }
  return held;
}
}  // namespace

TEST_CASE("memory: the wave-grid estimate covers what a realized ocean holds") {
  const WaveSettings w = two_cascades();
  const Ocean ocean = realize_ocean(w, 1);
  const double held = held_bytes(ocean, synthesize_ocean(ocean, 1.5, 1));
  const double estimate = wave_grid_bytes(w);
  // The estimate also counts h(k, t), the packed transform and its copies (transient) and all
  // eight fields on both grids (a multi-resolution ocean keeps three of them on the coarse grid
  // only), so it lies above what stays held, but within a factor of 2.5 (2.33 here).
  CHECK(estimate >= held);
  CHECK(estimate <= 2.5 * held);
}

TEST_CASE("memory: the footprint filter's estimate covers what its levels hold") {
  const WaveSettings w = two_cascades();
  const Ocean ocean = realize_ocean(w, 1);
  const FootprintFilter f =
      make_footprint_filter(ocean, 1.5, Interpolation::bicubic, ShadingNormals::surface, false, 1);
  REQUIRE(f.levels.size() >= 2);
  double held = 0.0;
  for (const FilterLevel& level : f.levels) held += held_bytes(level.ocean, level.grids);
  // Each level counted as wave grids of its own sizes (wave_grid_bytes: with the transform's
  // transient buffers, so above what stays held, within 2.5×: 2.33 here, over 13 levels).
  const double estimate = footprint_filter_bytes(w);
  CHECK(estimate >= held);
  CHECK(estimate <= 2.5 * held);
}

TEST_CASE("memory: render_scene refuses a scene over the limit before it allocates") {
  // Eight 8192² cascades: 160 B per cell of two grids each, 160 GiB of wave grids. The check
  // comes first, so the test allocates nothing large (and finishes at once).
  const Scene scene = parse_scene(nlohmann::json::parse(R"({"waves": {"resolution": 8192,
      "cascades": {"sizes": [900, 500, 300, 200, 100, 50, 20, 10]}}})"));
  CHECK(render_memory_estimate(scene, {}).items.front().bytes == 8.0 * 2 * 8192.0 * 8192 * 160);
  std::string message;
  try {
    (void)render_scene(scene, RenderOutputOptions{});
  } catch (const MemoryLimitError& e) {
    message = e.what();
  }
  CHECK(message.rfind("needs an estimated 163", 0) == 0);
  CHECK(message.find("(largest: wave grids (waves.resolution, waves.low_resolution, "
                     "waves.cascades) 163840 MiB,") != std::string::npos);
  CHECK(message.find("over the limit of 8192 MiB; raise it with --max-memory") !=
        std::string::npos);
}

TEST_CASE(
    "memory: adaptive refinement holds, per thread, two sample buffers and one fragment "
    "buffer of the finest level, and with the two-level lighting a correction buffer") {
  // The resolve refines a pixel's S×S samples to 3S×3S, 9S×9S, … up to n = S·3^r per axis
  // (render.max_samples_per_pixel = n²). Its two sample buffers trade places at each level, so
  // across pixels either may hold the finest level: both are reserved for n² samples, and the
  // fragment window for n² fragments, once per row. With reference lighting (the scenes' default)
  // the two-level estimate also keeps the corrections of up to n² samples.
  RenderOutputOptions options;
  options.threads = 3;
  const auto refinement_item = [&](const char* render, const char* accuracy = "reference") {
    const Scene scene = parse_scene(nlohmann::json::parse(
        std::string(R"({"waves": {}, "shading": {"accuracy": ")") + accuracy +
        R"("}, "render": {"width": 16, "height": 8, "samples_per_pixel": 4)" + render + "}}"));
    for (const MemoryItem& item : render_memory_estimate(scene, options).items) {
      if (item.what.rfind("adaptive refinement", 0) == 0) return item.bytes;
    }
    FAIL("no adaptive refinement item");
    return -1.0;
  };
  // Each sample also has its position (the Sobol' pattern's points).
  const double per_sample =
      static_cast<double>(sizeof(Fragment) + 2 * kResolvedSampleBytes + 2 * sizeof(double));
  const double corrected = per_sample + static_cast<double>(kCorrectionSampleBytes);
  constexpr const char* grid = R"(, "pixel_tolerance": 0.01, "pixel_pattern": "grid")";
  CHECK(refinement_item((std::string(grid) + R"(, "max_samples_per_pixel": 324)").c_str()) ==
        3 * 18 * 18 * corrected);
  CHECK(refinement_item((std::string(grid) + R"(, "max_samples_per_pixel": 36)").c_str()) ==
        3 * 6 * 6 * corrected);
  CHECK(refinement_item((std::string(grid) + R"(, "max_samples_per_pixel": 36)").c_str(), "fast") ==
        3 * 6 * 6 * per_sample);
  // The Sobol' pattern (the default): its cap, 256 for S = 2.
  CHECK(refinement_item(R"(, "pixel_tolerance": 0.01)") == 3 * 256 * corrected);
  CHECK(refinement_item("") == 0.0);  // fixed samples: no refinement
}

TEST_CASE("memory: a foam history holds the deformation's fields, as its estimate counts") {
  // The stormy golden scene with steady foam: each earlier frame keeps D_x and D_z (surface
  // normals), or those and the N_h ∂D fields (high_resolution); the estimate is exactly that.
  for (const ShadingNormals normals : {ShadingNormals::surface, ShadingNormals::high_resolution}) {
    Scene scene = load_scene(std::string(OCEANREF_SOURCE_DIR) +
                             "/reference/scenes/golden/jonswap_storm_foam_steady.json");
    scene.shading.normals = normals;
    scene.foam.steps = 3;
    REQUIRE(scene.shading.whitecaps);
    const Ocean ocean = realize_ocean(scene.waves, 1);
    const RenderFrame frame =
        prepare_frame(scene_render_job(scene, ocean, 1), {0.01, 0.01}, nullptr);
    REQUIRE(frame.foam_history.size() == 3);
    double held = 0.0;
    for (const FrameFields& f : frame.foam_history) {
      for (const CascadeFields& c : f.grids) {
        for (const std::vector<double>& v : c.values) {
          held += static_cast<double>(v.capacity() * sizeof(double));
        }
      }
    }
    CHECK(held == foam_history_bytes(scene.waves, normals, 3));
    int items = 0;
    for (const MemoryItem& i : render_memory_estimate(scene, {}).items) {
      if (i.what.rfind("the accumulated foam", 0) != 0) continue;
      CHECK(i.bytes == held);
      ++items;
    }
    CHECK(items == 1);
  }
}
