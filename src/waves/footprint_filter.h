// Footprint filtering (issue 20, point 3): a sample that stands for an area of the sea — a
// pixel's footprint, or a projected-grid cell — reads the waves pre-filtered to that area, and
// the slope variance the filter removed under it joins the BRDF's σ² (Bruneton 2010 §5, as in
// his FFT ocean: filtered slopes for the normal, a footprint slope-variance table for σ²).
//
// The footprint is a Gaussian on the mean sea plane with covariance Σ [m²] (Footprint). The
// fields are filtered by isotropic Gaussians: level l ≥ 1 is every cascade synthesized from
// h(k, t)·G_l(k), G_l(k) = exp(−½ r_l²|k|²), r_l = r_1·2^{l−1} — exact (a product in k-space),
// on the coarsest power-of-two grid with spacing ≤ r_l/2 (the modes it drops have G_l < 3e-9);
// level 0 is the frame's own fields. A footprint is read at r² = the larger eigenvalue of Σ (no
// wave shorter than the footprint's long axis is left to alias in the normal), blended linearly
// in log r between the two nearest levels, so the read fields have the transfer T(k) of that
// blend. Of the slopes under the footprint, the read value is the mean only where T equals the
// footprint's own transfer ŵ(k) = exp(−½ kᵀΣk); the mean square of the slopes under the
// footprint about the read slope is, per wind axis ê (over the frame's modes h(k, t)),
//   V_ê(Σ) = Σ_k |h(k, t)|² (k·ê)² [(1 − ŵ(k)²) + (ŵ(k) − T(k))²]
// — the footprint's own spread plus what the isotropic read removed beyond it — and V is added
// to the unresolved σ² (the BRDF's slope distribution stays axis-aligned in the wind frame: V's
// cross term is dropped). V is tabulated over Σ per frame (FootprintVarianceTable).
#pragma once

#include <vector>

#include "spectrum/slope_variance.h"
#include "waves/ocean.h"
#include "waves/surface.h"
#include "waves/whitecaps.h"

namespace oceanref {

// A Gaussian footprint on the mean sea plane: the covariance of (x, z) [m²].
struct Footprint {
  double xx = 0.0, xz = 0.0, zz = 0.0;
};

// The larger eigenvalue of Σ [m²]: the squared radius the fields are read at.
double footprint_major_variance(const Footprint& f);

// G(k) = exp(−½ r²k²): the transfer of an isotropic Gaussian of radius r [m] at |k| [rad/m].
double gaussian_transfer(double radius, double wavenumber);

// The two levels a squared radius r² is read from: `level` and level + 1 with weight `weight`
// of the latter (level 0 is the unfiltered fields): between r_l and r_{l+1} the weight is
// log2(r/r_l), below r_1 it is r²/r_1², beyond the last level it is that level alone.
struct LevelBlend {
  int level = 0;
  double weight = 0.0;
};
LevelBlend level_blend(const std::vector<double>& radii, double read_variance);
// T(k) of a blend: (1 − w)·G_l(k) + w·G_{l+1}(k).
double blend_transfer(const std::vector<double>& radii, const LevelBlend& blend, double wavenumber);

// One filtered level: the ocean with h0·G_l on the level's grids, and its frame.
struct FilterLevel {
  Ocean ocean;
  std::vector<CascadeFields> grids;     // grid interpolation
  std::vector<EvolvedCascade> evolved;  // direct summation
};

// V(Σ) of one frame, tabulated over Σ in the wind frame: the larger eigenvalue λ₁ (√λ₁ in
// steps of ½ octave from r_1/8 to 2 r_L, and ∝ λ₁ towards 0), the axis ratio (log2 √(λ₂/λ₁)
// in octaves from −8 to 0, held below) and the major axis' angle (16 steps over π), trilinear
// between nodes. The modes enter binned (⅛ octave of |k| × π/64 of direction, each bin at its
// weighted mean wavevector).
struct FootprintVarianceTable {
  double first_radius_variance = 0.0;  // r_1² [m²]
  int radius_nodes = 0;
  std::vector<SlopeVariance> values;  // [(radius·kRatioNodes + ratio)·kAngleNodes + angle]
  // The same loss for the displacement gradient's moments, Σ u²|h|² k_a^a k_c^b/k² [(1 − ŵ²) +
  // (ŵ − T)²] (waves/whitecaps.h), per node; only when the filter is made for whitecaps.
  std::vector<JacobianMoments> jacobian;
};

struct FootprintFilter {
  std::vector<double> radii;              // r_l [m]; radii[0] = 0 (the unfiltered fields)
  std::vector<FilterLevel> levels;        // levels[l − 1] is level l ≥ 1
  double wind_cos = 1.0, wind_sin = 0.0;  // (cos φ, sin φ): the table's wind frame
  FootprintVarianceTable variance;        // V(Σ)
};

// The filter of the frame at time t for the renderer's interpolation and normals (the slopes of
// the N_l patterns for `surface` normals, of the N_h patterns otherwise, as slope_budget).
// Levels and table entries are independent tasks on up to `threads` threads (the same bits for
// any count). `jacobian`: also tabulate the displacement gradient's moments (whitecaps).
FootprintFilter make_footprint_filter(const Ocean& ocean, double time, Interpolation mode,
                                      ShadingNormals normals, bool jacobian, int threads);

// Bytes the filter of `settings` holds at most (its levels' spectra and fields, the table).
double footprint_filter_bytes(const WaveSettings& settings);
// Its name in a memory estimate, with the scene key that asks for it.
inline constexpr const char* kFootprintFilterItem =
    "the footprint filter's levels (render.footprint_filtering)";

// The combined fields at (x, z) read at footprint `f`: the blend of two levels' combine_shading_at
// (every field linear in the weight; the normal the normalized blend of the two normals).
// `fields`/`evolved` are the frame's own (level 0).
PointFields filtered_fields_at(const Ocean& ocean, const std::vector<CascadeFields>& fields,
                               const std::vector<EvolvedCascade>& evolved,
                               const FootprintFilter& filter, double x, double z,
                               const Footprint& f, Interpolation mode, ShadingNormals normals);
// The displaced point of (x0, z0) read at footprint `f` (the blend of two levels'
// displaced_point).
DisplacedPoint filtered_displaced_point(const Ocean& ocean,
                                        const std::vector<CascadeFields>& fields,
                                        const std::vector<EvolvedCascade>& evolved,
                                        const FootprintFilter& filter, double x0, double z0,
                                        const Footprint& f, Interpolation mode,
                                        ShadingNormals normals);

// A wavevector in the wind frame folded to the half-plane of directions [0, π), where V's table
// bins it (V is even in k: k and −k share a bin): −k when k_across < 0, or k_across = 0 and
// k_along < 0; k itself otherwise.
struct WindFrameWavevector {
  double along = 0.0, across = 0.0;  // [rad/m]
};
WindFrameWavevector folded_wavevector(WindFrameWavevector k);

// V(Σ) per wind axis from the table.
SlopeVariance footprint_slope_variance(const FootprintFilter& filter, const Footprint& f);
// The displacement gradient's moments under footprint Σ about the read fields (× u² per cascade),
// from the table (a filter made with `jacobian`): with the read det J they give the whitecap
// coverage of the footprint (waves/whitecaps.h).
JacobianMoments footprint_jacobian_moments(const FootprintFilter& filter, const Footprint& f);
// Both summed over every mode of the frame without bins or table (for tests).
struct FootprintResidual {
  SlopeVariance slopes;
  JacobianMoments jacobian;
};
FootprintResidual footprint_residual_exact(const Ocean& ocean, double time, ShadingNormals normals,
                                           const std::vector<double>& radii, const Footprint& f);

}  // namespace oceanref
