// probe_pixel (what `oceanref probe` prints) against render (what `oceanref render` writes), bit
// for bit: the default scene (reference accuracy, bicubic, whitecaps) at a small size, every
// pixel's samples shaded alone by the probe, resolved by resolve_pixel, equal to the double
// radiance of the render and, rounded, to the float32 the render file holds. Pixels: the four
// corners, a horizon pixel (part sea, part sky), open sea and sky.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <string>

#include "conformance/render_output.h"
#include "scene/scene.h"
#include "test_support.h"

using namespace oceanref;

namespace {
using testing::channel;
using testing::same_bits;
}  // namespace

TEST_CASE("probe == render: every probed pixel has the bits render writes") {
  Scene scene =
      load_scene(std::string(OCEANREF_SOURCE_DIR) + "/reference/scenes/default.json", nullptr);
  scene.image.width = 24;
  scene.image.height = 14;
  scene.grid.columns = 128;  // the grid's cost is paid by the render and again by every probe
  scene.grid.rows = 128;
  // 9 samples: 1/S² = 1/9 is not a power of two, so a resolve that divides by 9 instead of
  // multiplying by 1/9 gives other bits.
  scene.image.samples_per_axis = 3;
  RenderOutputOptions options;
  options.threads = 2;
  const RenderedScene rendered = render_scene(scene, options);
  const RenderedImage& image = rendered.image;
  const auto prepared = prepare_render(scene, 2);
  int horizon = 0, sea = 0, sky = 0;
  const auto probe = [&](int x, int y) {
    CAPTURE(x);
    CAPTURE(y);
    const std::size_t i = static_cast<std::size_t>(y * image.width + x);
    const std::vector<SampleProbe> samples = probe_pixel(prepared->job, prepared->unresolved, x, y);
    REQUIRE(samples.size() == 9u);
    const Vec3 pixel = resolve_pixel(samples);
    CHECK(pixel == image.radiance[i]);
    for (std::size_t c = 0; c < 3; ++c) {
      const float written = channel(rendered.exr, std::string(1, "RGB"[c])).values[i];
      CHECK(same_bits(static_cast<float>(pixel[c]), written));
    }
    int hits = 0;
    for (const SampleProbe& p : samples) hits += p.hit ? 1 : 0;
    CHECK(hits / 9.0 == image.coverage[i]);
    horizon += hits > 0 && hits < 9 ? 1 : 0;
    sea += hits == 9 ? 1 : 0;
    sky += hits == 0 ? 1 : 0;
  };
  for (const auto& [x, y] : {std::pair{0, 0}, std::pair{23, 0}, std::pair{0, 13}, std::pair{23, 13},
                             std::pair{12, 12}}) {
    probe(x, y);
  }
  // The first pixel of column 12 from the top that is partly sea: on the horizon.
  int y = 0;
  while (y < image.height && !(image.coverage[static_cast<std::size_t>(y * 24 + 12)] > 0.0)) ++y;
  REQUIRE(y < image.height);
  probe(12, y);
  probe(12, y - 1);  // and the sky above it
  CHECK(horizon >= 1);
  CHECK(sea >= 2);
  CHECK(sky >= 2);
}

TEST_CASE("probe: without choppiness a sea sample's position lies above its undisplaced x0") {
  // position interpolates the displaced grid vertices, x0 the same vertices before displacement,
  // with the same weights: without choppiness (no horizontal displacement) their x and z are
  // the same numbers (a point reflected through the origin, or another vertex's, would not be).
  Scene scene =
      load_scene(std::string(OCEANREF_SOURCE_DIR) + "/reference/scenes/default.json", nullptr);
  scene.image.width = 24;
  scene.image.height = 14;
  scene.grid.columns = 128;
  scene.grid.rows = 128;
  scene.image.samples_per_axis = 2;
  for (double& u : scene.waves.choppiness) u = 0.0;
  const auto prepared = prepare_render(scene, 2);
  int samples = 0;
  for (const auto& [x, y] : {std::pair{0, 13}, std::pair{12, 12}, std::pair{23, 9}}) {
    for (const SampleProbe& p : probe_pixel(prepared->job, prepared->unresolved, x, y)) {
      REQUIRE(p.hit);
      CHECK(std::hypot(p.x0.x, p.x0.y) > 1.0);  // away from the origin, where -x0 = x0
      CHECK(p.position.x == p.x0.x);
      CHECK(p.position.z == p.x0.y);
      ++samples;
    }
  }
  CHECK(samples == 12);
}
