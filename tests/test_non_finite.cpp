// Never a silent NaN: a non-finite value in a render or a fields file is an error naming where it
// is and which term it came from (raster/renderer.h require_finite, conformance/fields_output).
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "raster/renderer.h"
#include "spectrum/model.h"
#include "spectrum/moments.h"

using namespace oceanref;

namespace {
RenderedImage finite_image(int width, int height) {
  RenderedImage image;
  image.width = width;
  image.height = height;
  const std::size_t n = static_cast<std::size_t>(width * height);
  for (auto* b : {&image.radiance, &image.sun, &image.sky, &image.sea, &image.foam, &image.normal,
                  &image.x0, &image.lighting_error}) {
    b->assign(n, Vec3{1.0, 2.0, 3.0});
  }
  image.depth.assign(n, 10.0);
  image.coverage.assign(n, 1.0);
  return image;
}
}  // namespace

TEST_CASE("require_finite: a finite image passes; a non-finite value names pixel, term, channel") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  CHECK_NOTHROW(require_finite(finite_image(5, 4)));

  // The first bad pixel in row-major order; its term is named before the radiance it spoils.
  RenderedImage image = finite_image(5, 4);
  image.sky[13][1] = nan;       // pixel (3, 2)
  image.radiance[13][1] = nan;  // what the NaN sky made of it
  image.sun[17][0] = inf;       // pixel (2, 3): later
  CHECK_THROWS_WITH_AS(require_finite(image),
                       doctest::Contains("pixel (3, 2): sky.G is nan (coverage 1; terms: sun = "
                                         "(1, 2, 3), sky = (1, nan, 3)"),
                       NonFiniteOutputError);
  // Every buffer is checked, including the scalar ones.
  for (int which = 0; which < 4; ++which) {
    RenderedImage one = finite_image(3, 3);
    if (which == 0) one.depth[4] = -inf;
    if (which == 1) one.coverage[4] = nan;
    if (which == 2) one.normal[4][2] = nan;
    if (which == 3) one.lighting_error[4][0] = inf;
    CAPTURE(which);
    CHECK_THROWS_WITH_AS(require_finite(one), doctest::Contains("pixel (1, 1): "),
                         NonFiniteOutputError);
  }
}

TEST_CASE("spectral_moments refuses k_max where its integrands overflow") {
  const Spectrum s = make_spectrum(SpectrumSettings{});
  CHECK_THROWS_AS(spectral_moments(s, 1e308), std::invalid_argument);
  CHECK_THROWS_AS(spectral_moments(s, kMaxMomentWavenumber * 2.0), std::invalid_argument);
  // The range is (0, 1e6] rad/m or inf: an empty band (k_max = 0) is refused with the others.
  for (const double k_max : {0.0, -0.0, -1.0, -HUGE_VAL, std::nan("")}) {
    CAPTURE(k_max);
    CHECK_THROWS_WITH_AS(spectral_moments(s, k_max),
                         doctest::Contains("k_max must be in (0, 1e6] rad/m or inf"),
                         std::invalid_argument);
  }
  CHECK(spectral_moments(s, 1e-3).m0 >= 0.0);
  // Up to the limit it converges, and the slope moment keeps growing with k_max (log-divergent
  // for a k^-3 tail): it never falls back as it did past ~1e150 before.
  const SpectralMoments a = spectral_moments(s, 1e4);
  const SpectralMoments b = spectral_moments(s, kMaxMomentWavenumber);
  CHECK(b.mss > a.mss);
  CHECK(b.m0 == doctest::Approx(a.m0).epsilon(1e-6));
}
