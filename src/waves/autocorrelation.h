// The autocorrelation function of the rendered surface's displacement (Lutz, Schoentgen & Gilet
// 2024 §7.1, eq. 22): how much the ocean at x + τ resembles the ocean at x. A periodic ocean's is
// 1 at every multiple of its period; tiling and blending's decays to 0 (Lutz Fig. 8 and 9).
//
// The displacement is the offset of the displaced surface from its undisplaced point, q(x0) =
// p(x0) − (x0, 0, z0) = (Σu_iD_x,i, Σ η_i, Σu_iD_z,i), read as the renderer reads it
// (displaced_point, with the scene's interpolation, normals and synthesis). Estimated over
// `lines` random start points x_l, uniform over a square of `area` exemplar periods a side, and
// lags τ_j = j·L/samples_per_period along the direction (cos φ, sin φ), j = 0 … length·samples:
//   μ̃_c = the mean of q_c over every sample,
//   r̃_c(τ) = (1/lines) Σ_l (q_c(x_l) − μ̃_c)(q_c(x_l + τ) − μ̃_c)            (Lutz eq. 22)
// and the ACF r̃_c(τ)/r̃_c(0) per component c, and of the whole vector, Σ_c r̃_c(τ)/Σ_c r̃_c(0).
// The start points are a pure function of `seed` (waves/random.h: words 2l and 2l + 1 of the key
// mix(mix(seed) ^ 0x6163) as uniform_open); the result is the same for any thread count.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "waves/direct_sum.h"
#include "waves/fields.h"
#include "waves/interpolation.h"
#include "waves/surface.h"

namespace oceanref {

struct Ocean;

struct AutocorrelationSettings {
  int lines = 4000;
  double length = 8.0;          // the largest lag, in exemplar periods
  int samples_per_period = 32;  // lags per period
  double direction = 0.0;       // φ [rad], from x towards z
  double area = 256.0;          // the start points' square, in exemplar periods a side
  std::uint64_t seed = 1;
};

struct Autocorrelation {
  double period = 0.0;       // L: the exemplar's (the largest cascade size) [m]
  std::vector<double> lags;  // τ_j [m]
  // r̃_c(τ)/r̃_c(0) for c = D_x, η, D_z (empty for a component without variance, e.g. D without
  // choppiness), and for the vector.
  std::array<std::vector<double>, 3> components;
  std::vector<double> vector;
  std::array<double, 3> variance{};  // r̃_c(0) [m²]
};

// Throws std::invalid_argument for settings outside their ranges (lines ≥ 2, length > 0,
// samples_per_period ≥ 1, area > 0).
Autocorrelation displacement_autocorrelation(const Ocean& ocean,
                                             const std::vector<CascadeFields>& fields,
                                             const std::vector<EvolvedCascade>& evolved,
                                             Interpolation mode, ShadingNormals normals,
                                             const AutocorrelationSettings& settings, int threads);

// The height η of the rendered surface at its undisplaced points (x0, z0) = (m + ½, n + ½)·side/
// pixels, m, n = 0 … pixels − 1, row-major from z0 = 0 (Lutz Fig. 8 and 9, middle rows: the
// displacement over several periods). Throws std::invalid_argument unless side > 0 and pixels
// in [1, 4096].
std::vector<double> height_map(const Ocean& ocean, const std::vector<CascadeFields>& fields,
                               const std::vector<EvolvedCascade>& evolved, Interpolation mode,
                               ShadingNormals normals, double side, int pixels, int threads);

}  // namespace oceanref
