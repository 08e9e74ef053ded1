// KissFFT from Debian's source package is compiled with double scalars.
#include <doctest/doctest.h>

#include <kiss_fft.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

TEST_CASE("KissFFT runs in double precision and matches a direct DFT") {
  static_assert(sizeof(kiss_fft_scalar) == sizeof(double));
  constexpr int n = 24;
  kiss_fft_cfg cfg = kiss_fft_alloc(n, 0, nullptr, nullptr);
  REQUIRE(cfg != nullptr);
  std::vector<kiss_fft_cpx> in(n), out(n);
  for (int i = 0; i < n; ++i) {
    in[static_cast<std::size_t>(i)] = {std::sin(0.3 * i * i), std::cos(1.7 * i)};
  }
  kiss_fft(cfg, in.data(), out.data());
  kiss_fft_free(cfg);
  // A double DFT of length 24 is good to ~1e−14; float scalars would leave errors ~1e−6.
  for (int f = 0; f < n; ++f) {
    std::complex<double> sum = 0.0;
    for (int i = 0; i < n; ++i) {
      const auto& x = in[static_cast<std::size_t>(i)];
      sum += std::complex<double>(x.r, x.i) * std::polar(1.0, -2.0 * std::numbers::pi * f * i / n);
    }
    const auto& y = out[static_cast<std::size_t>(f)];
    CHECK(std::abs(std::complex<double>(y.r, y.i) - sum) < 1e-12);
  }
}
