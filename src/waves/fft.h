// The unnormalized inverse 2-D DFT of Gamper eq. 4.4 with KissFFT in double precision:
//   out(m, n) = Σ_{a,b} in(a, b) e^{+2πi(am + bn)/N},  arrays row-major [n·N + m].
// Rows first, then columns; with threads > 1 the rows (columns) are split among threads, and
// each 1-D transform is the same computation whichever thread runs it, so the result is
// bit-identical for every thread count.
#pragma once

#include <vector>

#include "core/complex.h"

namespace oceanref {

void inverse_fft_2d(std::vector<Complex>& data, int resolution, int threads);
// The forward transform, e^{−2πi(am + bn)/N}, unnormalized (Mastin's white-noise analysis).
void forward_fft_2d(std::vector<Complex>& data, int resolution, int threads);
// Either direction: inverse (e^{+…}) or forward (e^{−…}).
void fft_2d(std::vector<Complex>& data, int resolution, int threads, bool inverse);

// Runs body(i) for i in [0, count) on up to `threads` threads, each taking the next index.
template <class Body>
void parallel_for(int count, int threads, const Body& body);

}  // namespace oceanref

#include <atomic>
#include <thread>

template <class Body>
void oceanref::parallel_for(int count, int threads, const Body& body) {
  if (threads <= 1 || count <= 1) {
    for (int i = 0; i < count; ++i) body(i);
    return;
  }
  // Indices are handed out one at a time (the cost of rows varies: sky rows are cheap, sea rows
  // with reference lighting are not); which thread runs an index never changes its result.
  const int used = threads < count ? threads : count;
  std::atomic<int> next{0};
  std::vector<std::jthread> workers;
  for (int t = 0; t < used; ++t) {
    workers.emplace_back([&body, &next, count] {
      for (int i = next++; i < count; i = next++) body(i);
    });
  }
}
