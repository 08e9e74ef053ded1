#include "waves/fft.h"

#include <kiss_fft.h>

#include <algorithm>
#include <cstddef>
#include <memory>
#include <stdexcept>

#include "core/check.h"
#include "core/math.h"
#include "core/parallel.h"

// KissFFT's twiddle factors from the portable cosine and sine (waves/kissfft_portable.c).
extern "C" double oceanref_kissfft_cos(double phase) {
  return oceanref::math::cos(phase);
}
extern "C" double oceanref_kissfft_sin(double phase) {
  return oceanref::math::sin(phase);
}

namespace oceanref {

namespace {
static_assert(sizeof(kiss_fft_scalar) == sizeof(double), "KissFFT must use double scalars");
static_assert(sizeof(kiss_fft_cpx) == sizeof(Complex) &&
              offsetof(kiss_fft_cpx, r) == offsetof(Complex, re) &&
              offsetof(kiss_fft_cpx, i) == offsetof(Complex, im));

struct KissConfig {
  KissConfig(int n, bool inverse) : cfg(kiss_fft_alloc(n, inverse ? 1 : 0, nullptr, nullptr)) {
    if (cfg == nullptr) throw std::bad_alloc();
  }
  ~KissConfig() { kiss_fft_free(cfg); }
  KissConfig(const KissConfig&) = delete;
  KissConfig& operator=(const KissConfig&) = delete;
  kiss_fft_cfg cfg;
};

kiss_fft_cpx* as_kiss(Complex* p) {
  return reinterpret_cast<kiss_fft_cpx*>(p);
}
}  // namespace

void inverse_fft_2d(std::vector<Complex>& data, int n, int threads) {
  fft_2d(data, n, threads, true);
}

void forward_fft_2d(std::vector<Complex>& data, int n, int threads) {
  fft_2d(data, n, threads, false);
}

void fft_2d(std::vector<Complex>& data, int n, int threads, bool inverse) {
  OCEANREF_EXPECTS(
      n >= 1 && data.size() == static_cast<std::size_t>(n) * static_cast<std::size_t>(n),
      "fft_2d: " + std::to_string(data.size()) + " values for N = " + std::to_string(n));
  const KissConfig config(n, inverse);
  const auto stride = static_cast<std::size_t>(n);
  parallel_for(n, threads, [&](int row) {
    std::vector<Complex> out(stride);
    kiss_fft(config.cfg, as_kiss(&data[static_cast<std::size_t>(row) * stride]),
             as_kiss(out.data()));
    std::copy(out.begin(), out.end(), data.begin() + static_cast<std::ptrdiff_t>(row * n));
  });
  // Columns in blocks of 8: gathered and scattered a row segment at a time (cache friendly);
  // each column's transform is the same computation whichever block or thread holds it.
  constexpr int kBlock = 8;
  parallel_for((n + kBlock - 1) / kBlock, threads, [&](int block) {
    const int first = block * kBlock;
    const auto count = static_cast<std::size_t>(std::min(kBlock, n - first));
    std::vector<Complex> in(count * stride);
    std::vector<Complex> out(count * stride);
    for (std::size_t r = 0; r < stride; ++r) {
      for (std::size_t c = 0; c < count; ++c) {
        in[c * stride + r] = data[r * stride + static_cast<std::size_t>(first) + c];
      }
    }
    for (std::size_t c = 0; c < count; ++c) {
      kiss_fft(config.cfg, as_kiss(&in[c * stride]), as_kiss(&out[c * stride]));
    }
    for (std::size_t r = 0; r < stride; ++r) {
      for (std::size_t c = 0; c < count; ++c) {
        data[r * stride + static_cast<std::size_t>(first) + c] = out[c * stride + r];
      }
    }
  });
}

}  // namespace oceanref
