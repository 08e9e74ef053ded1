// The whole wave model of a scene: the spectrum, its cascades with their bands and frozen
// random spectra, and the synthesis of every cascade's fields at a time (Gamper §4.4).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/choice.h"
#include "spectrum/model.h"
#include "waves/cascades.h"
#include "waves/direct_sum.h"
#include "waves/fields.h"
#include "waves/gerstner.h"
#include "waves/interpolation.h"
#include "waves/mastin.h"
#include "waves/noise.h"
#include "waves/realization.h"
#include "waves/surface.h"
#include "waves/tiling.h"

namespace oceanref {

// How h0 is drawn: Gaussian amplitudes (Gamper eq. 4.2) or Mastin's filtered white noise.
enum class Realization { gaussian, mastin };
inline constexpr std::array<Choice<Realization>, 2> kRealizations{{
    {Realization::gaussian, "gaussian"},
    {Realization::mastin, "mastin"},
}};

// The wave model (`waves.model`): the FFT ocean of cascades (Gamper) or a Gerstner wave set drawn
// from the same spectrum and summed explicitly (Vincevičius §1.2.1; waves/gerstner.h).
enum class WaveModel { fft, gerstner };
inline constexpr std::array<Choice<WaveModel>, 2> kWaveModels{{
    {WaveModel::fft, "fft"},
    {WaveModel::gerstner, "gerstner"},
}};

struct WaveSettings {
  std::uint64_t seed = 1;
  WaveModel model = WaveModel::fft;
  GerstnerDraw gerstner;  // model gerstner: the draw (its choppiness is choppiness[0])
  Realization realization = Realization::gaussian;
  MastinSettings mastin;  // the filter and animation of the mastin realization
  SpectrumSettings spectrum;
  std::vector<double> sizes{1000.0};    // L_i [m], decreasing when band-partitioned
  int resolution = 256;                 // N_h: slopes and derivatives of D
  int low_resolution = 256;             // N_l ≤ N_h: η and D (multi-resolution when smaller)
  std::vector<double> choppiness{0.0};  // u_i ≤ 0 per cascade (eq. 4.20, 4.24)
  bool band_partitioning = true;
  // Chosen hand-over wavenumbers [rad/m] between the partitioned cascades (cascade_bands); empty:
  // each cascade's Nyquist wavenumber.
  std::vector<double> band_edges;
  // The shortest wave [m]: λ_min = 1.73 cm for spectra without capillary physics (Gamper §4.4),
  // 0 (no floor) for the Unified spectrum.
  double minimum_wavelength = kMinimumWavelength;
  // How the cascades' periodic exemplar covers the plane (waves/tiling.h).
  Synthesis synthesis = Synthesis::periodic;
  TilingSettings tiling;  // tiling_and_blending only
  // noise_blended only: w_P (Lutz Fig. 8: 33%) and the noise lattice's spacing in exemplar periods.
  double noise_weight = 0.33;
  double noise_cell_size = 1.0;
};

struct CascadeSpectra {
  PatternSpectrum low;   // on N_l
  PatternSpectrum high;  // on N_h (a copy of low when N_l = N_h)
  double choppiness = 0.0;
};

struct Ocean {
  Spectrum spectrum;
  std::vector<CascadeSpectra> cascades;
  // The filter whose power Θ_f the mastin realization drew h0 from (the spectrum's Θ otherwise).
  MastinFilterModel filter;
  // periodic: the cascades' sum repeated; tiling_and_blending: that sum is the exemplar of
  // `tiling`, which every reading of the surface (combine_at, combine_surface_at,
  // displaced_point, ...) blends. The FFT grids, direct sums and footprint lattices of single
  // cascades are the exemplar's.
  Synthesis synthesis = Synthesis::periodic;
  Tiling tiling;
  NoiseBlend noise;  // noise_blended
  // WaveModel::gerstner: the wave set, and no cascades. It has no grids: it is read by direct
  // summation only (Interpolation::direct), at the time of the last evolved entry
  // (evolve_ocean appends one for it).
  std::optional<GerstnerWaves> gerstner;
};

// The raw sums at (x, z) (before finish_combination) of the ocean's synthesis, from the
// exemplar's raw sums exemplar(x', z') at any point: the exemplar itself (periodic), the blend of
// its tiles (tiling_and_blending), or its mix with the noise (noise_blended, Lutz eq. 2).
template <class ExemplarSum>
PointFields synthesized_sum(const Ocean& ocean, double x, double z, const ExemplarSum& exemplar) {
  switch (ocean.synthesis) {
    case Synthesis::tiling_and_blending:
      return blended_sum(ocean.tiling, x, z, exemplar);
    case Synthesis::noise_blended: {
      PointFields sum = exemplar(x, z);
      mix_noise(sum, noise_fields(ocean.noise, x, z), ocean.noise.weight);
      return sum;
    }
    case Synthesis::periodic:
      break;
  }
  return exemplar(x, z);
}

// Bytes the wave grids of `settings` need: per cell of each cascade's two grids the frozen
// spectrum (h0, 1/k, ω), h(k, t), the packed transform and its copies, the eight
// fields. For the memory checks (core/memory.h).
double wave_grid_bytes(const WaveSettings& settings);
// Its name in a memory estimate, with the scene keys that size it.
inline constexpr const char* kWaveGridsItem =
    "wave grids (waves.resolution, waves.low_resolution, waves.cascades)";

// λ_min for a spectrum: 0 for Unified (it models capillary waves), 1.73 cm otherwise.
double default_minimum_wavelength(SpectrumModel model);

// Resolves the spectrum and realizes every cascade at both resolutions by settings.realization
// (eq. 4.2, or Mastin's filtered white noise, waves/mastin.h; cascade i keys its draws
// with index i). Throws SettingError for invalid spectrum settings.
Ocean realize_ocean(const WaveSettings& settings, int threads);

// The resolved tiling of `settings` (tiling_and_blending): the edge from the tile size and the
// exemplar's period, the largest cascade size.
Tiling resolve_tiling(const WaveSettings& settings);

// Raw fields of every cascade at time t.
// With a mask: only the transforms that compute a wanted field (synthesize_cascade).
std::vector<CascadeFields> synthesize_ocean(const Ocean& ocean, double time, int threads,
                                            const FieldMask& wanted = kAllFields);

// h(k, t) of every cascade, for direct summation at many points of one frame (and, for a
// Gerstner ocean, one more entry that holds only the time t).
std::vector<EvolvedCascade> evolve_ocean(const Ocean& ocean, double time);

// The combined fields at (x, z) from the FFT grids (bilinear between nodes) and by direct
// summation over every component of every cascade (at time t, or from evolve_ocean).
PointFields combine_from_grids(const Ocean& ocean, const std::vector<CascadeFields>& fields,
                               double x, double z);
// combine_direct is the exemplar's (never tiled).
PointFields combine_direct(const Ocean& ocean, double x, double z, double time);
PointFields combine_direct(const Ocean& ocean, const std::vector<EvolvedCascade>& evolved, double x,
                           double z);
// The raw fields of one cascade at (x, z) from its FFT grids.
std::array<double, kFieldCount> cascade_from_grids(const CascadeFields& f, double x, double z,
                                                   Interpolation mode = Interpolation::bilinear);
// The combined fields at (x, z) with the chosen interpolation; `direct` sums `evolved` (from
// evolve_ocean, which the other modes do not read).
PointFields combine_at(const Ocean& ocean, const std::vector<CascadeFields>& fields,
                       const std::vector<EvolvedCascade>& evolved, double x, double z,
                       Interpolation mode);
// Σ|h0| over every cascade: a bound of |η| at any point and time (|h(k, t)| ≤ ½(|h0(k)| +
// |h0(−k)|)), and of |D| per unit choppiness; √3 times that when tiled (Σ_v|w_v| ≤ √3).
double height_bound(const Ocean& ocean);

// One cascade's Jacobian determinant (eq. 4.26 with its own u) on its high-resolution grid.
std::vector<double> cascade_jacobian(const CascadeFields& f, double choppiness);

// The combined fields on cascade 0's footprint (L_0 × L_0 at N_h × N_h points, spacing L_0/N_h)
// at the time of `evolved` (evolve_ocean): every cascade's band-limited fields evaluated exactly
// at those points (direct_sum_on_lattice), not interpolated — reading the N_l grid of η between
// its nodes, and the other cascades' grids anywhere, would lose variance (interpolation.h).
// Combined as the renderer shades with direct summation: finish_surface_combination of the N_l
// bands for `surface`, finish_combination with the N_h slopes for `high_resolution`.
std::vector<PointFields> combine_on_footprint(const Ocean& ocean,
                                              const std::vector<EvolvedCascade>& evolved,
                                              ShadingNormals normals, int threads);

// Foam accumulated over a sequence (Vincevičius listing 2.4): the negative-Jacobian indicator
// of the frames t − steps·Δt, …, t folded with accumulated_foam, starting from no foam.
inline constexpr int kMaxFoamSteps = 10000;
struct FoamSequence {
  double decay = 1.0;             // per second
  double time_step = 1.0 / 30.0;  // Δt [s]
  int steps = 0;                  // earlier frames; 0: the instantaneous indicator
};
// The number of earlier instants after which the foam no longer depends on when its accumulation
// started ("steps": "steady"): every step removes at least δ = decay·Δt (accumulated_foam with a
// current value ≤ 1), so whatever stood before is below every current value (≥ 0) after
// ⌊1/δ⌋ + 1 steps — one more covers the rounding of the subtractions. From then on the result is
// the same bits as an accumulation started at any earlier time (tested). decay > 0.
int steady_foam_steps(double decay, double time_step);
struct AccumulatedFoam {
  std::vector<std::vector<double>> cascades;  // per cascade, on its high-resolution grid
  std::vector<double> combined;               // on cascade 0's footprint
};
// The combined foam follows the Jacobian of combine_on_footprint with `normals`.
AccumulatedFoam accumulate_foam(const Ocean& ocean, double time, const FoamSequence& sequence,
                                ShadingNormals normals, int threads);

}  // namespace oceanref
