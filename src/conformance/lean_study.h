// Filtered shading of a synthesized ocean at a distance (Lutz, Schoentgen & Gilet 2024 §6 and
// Fig. 7): the specular lobe of a pixel's footprint by normal mapping, LEAN mapping of the tiles
// without and with the rotation correction (Lutz eq. 13, 16, 19–21), and LEAN of the blended
// surface's own moments, each against the supersampled ground truth (`oceanref bench lean`,
// reference/ACCURACY.md "LEAN mapping").
//
// The lobe is the density of the half vector's slope h̃ (shading/lean.h). The ground truth over a
// footprint is the mean over a stratified grid of its points x of the base lobe around the
// surface's own slope: mean_x P(h̃; ñ(x), (1/s)I), with ñ(x) the shading normal of the rendered
// surface (blended, turned by the flow map) and 1/s the scene's unresolved slope variance (the
// BRDF's σ², mean of its two axes). The methods, with the tiles of the footprint's centre (their
// weights w_i and turns there, as a shader has them) and each tile's filtered moments B_i, M_i
// (the exemplar's moments averaged over the footprint's points moved into that tile: an exact
// MIP map):
//   normal_mapping   P(h̃; Σ w_i R_i B_i, (1/s)I): the filtered normal, no variance;
//   lean             eq. 13 with B_i turned (eq. 16) and M_i not: Lutz's "uncorrected" LEAN;
//   lean_corrected   eq. 13 with B_i and M_i turned (eq. 16, 19–21);
//   lean_exact       eq. 11 with the blended surface's own footprint moments (no tiles).
// Without a flow map lean = lean_corrected; on a periodic ocean all three LEAN forms coincide.
// Footprints are rectangles, `across` metres wide (z) and elongation × across long (x, the view
// direction: a pixel seen at about asin(1/elongation) above the horizon), centred at fixed
// random points. Errors per footprint: the relative L2 distance of the lobe over a 24 × 24 grid
// of h̃ around the ground truth (±4 of its standard deviations), and the relative error at the
// half vector of a glint near the horizon (view 5° above the horizon looking along +x, sun 10°
// above it, 3° to the side).
#pragma once

#include <array>
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "shading/lean.h"
#include "waves/direct_sum.h"
#include "waves/fields.h"
#include "waves/interpolation.h"
#include "waves/ocean.h"

namespace oceanref {

struct LeanStudySettings {
  std::vector<double> footprint_sizes;  // across [m]; empty: 1/16, 1/4 and 1 exemplar period
  double elongation = 8.0;
  int footprints = 12;  // per size
  int samples_per_axis = 64;
  std::uint64_t seed = 1;
  int threads = 2;
};

struct LeanStudyRow {
  std::string method;
  double footprint = 0.0;        // across [m]
  double lobe_error_mean = 0.0;  // relative L2 over the slope plane, mean over footprints
  double lobe_error_max = 0.0;
  double glint_error_mean = 0.0;  // |P − P_truth|/P_truth at the glint's half vector
};

// The points h̃ at which a footprint's lobe errors are summed: the cell centres of a 24 × 24 grid
// over the box centre ± half_width, row by row (h̃_x fastest).
std::vector<std::array<double, 2>> lobe_grid(const std::array<double, 2>& centre,
                                             const std::array<double, 2>& half_width);
// μ_B, μ_M of Lutz eq. 13: the LEAN moments (lean_moments) of the rendered surface's normal
// (combine_surface_at) of the periodic `exemplar`, averaged over one period [m] (its largest
// cascade) by the midpoint rule on a 128 × 128 grid of cell centres.
LeanMoments exemplar_mean_moments(const Ocean& exemplar, const std::vector<CascadeFields>& fields,
                                  const std::vector<EvolvedCascade>& evolved, Interpolation mode,
                                  double period);
// Rows per method and footprint size. Throws std::invalid_argument for bad settings.
std::vector<LeanStudyRow> lean_study(const Scene& scene, const LeanStudySettings& settings);
// CSV: method,footprint_m,lobe_error_mean,lobe_error_max,glint_error_mean.
void bench_lean(std::ostream& out, const std::vector<LeanStudyRow>& rows);

}  // namespace oceanref
