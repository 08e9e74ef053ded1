// The stages of the wave synthesis on one pattern's grid, exported so that another backend can
// be checked stage by stage (docs/BACKENDS.md): Θ(k)Δk² (the variance per wavevector cell),
// h0(k) (eq. 4.2), ω(k) and h(k, t) (eq. 4.7), before the inverse FFT to the fields (eq. 4.4).
//
// Every grid is N×N, row-major [b·N + a], with array index (a, b) ↔ integer wavevector
// (α, β) = (a < N/2 ? a : a − N, likewise b), k = (α, β)·2π/L (waves/realization.h). The
// fields are the unnormalized inverse DFT of M_f·h (waves/fft.h: e^{+2πi(am + bn)/N}, no 1/N²).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/complex.h"
#include "spectrum/model.h"
#include "waves/mastin.h"
#include "waves/realization.h"

namespace oceanref {

enum class Stage { spectrum, h0, omega, hkt, fields };
inline constexpr std::array<const char*, 5> kStageNames{"spectrum", "h0", "omega", "hkt", "fields"};

// One real channel of a stage on a pattern's grid (N×N doubles, [b·N + a]).
struct StageChannel {
  std::string name;  // e.g. "variance", "h0.re" (a file's channel: "c0.h0.re.V", docs/FILES.md)
  std::string unit;  // SI: "m^2", "m", "rad/s", "rad/m", "1"
  std::vector<double> values;
};

// The channels of one stage (not `fields`) on the grid of `s`:
//   spectrum: theta = Θ(k) [m^4] at every entry (0 at k = 0); variance = Θ(k)Δk² [m^2] where h0
//             is drawn (k ≠ 0 inside the pattern's band), else 0; in_band = 1 there, else 0;
//             with a power-law `filter` (Mastin's Figs. 2–3) Θ is that filter's power Θ_f;
//   h0:       h0.re, h0.im [m] (the frozen draw of realize_ocean: eq. 4.2 or Mastin's filter);
//   omega:    omega = ω(|k|) [rad/s] from the dispersion relation (for Mastin's constant-shift
//             animation, the phase rate it uses instead), kx, kz, k [rad/m];
//   hkt:      hkt.re, hkt.im [m] = ½h0(k)e^{−iωt} + ½h0(−k)* e^{iωt} (eq. 4.7) at `time` [s].
// Throws std::invalid_argument for Stage::fields.
std::vector<StageChannel> stage_channels(const Spectrum& spectrum, const PatternSpectrum& s,
                                         Stage stage, double time, int threads,
                                         const MastinFilterModel& filter = {});

// Θ(k)Δk² of every entry of a pattern where h0 is drawn (see initial_amplitude), else 0.
std::vector<double> cell_variances(const Spectrum& spectrum, const Pattern& p);

}  // namespace oceanref
