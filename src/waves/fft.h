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

}  // namespace oceanref
