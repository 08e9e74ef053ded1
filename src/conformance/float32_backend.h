// The float32 example backend: the worked example of a backend checked against oceanref stage by
// stage (docs/BACKENDS.md). It follows the recipe of docs/BACKENDS.md as a GPU port would and
// computes every stage itself, in float32 arithmetic:
//   spectrum  Θ(k) and Θ(k)Δk² on each cascade grid (the spectra, spreading functions and
//             dispersion relations of src/spectrum in float), the band mask;
//   h0        the counter-based Gaussian draws of waves/random.h (the 64-bit integer hash exactly,
//             the uniforms and Box–Muller in float) times √(Θ(k)Δk²)  (Gamper eq. 4.2);
//   omega     ω(|k|) by the dispersion relation, k_x, k_z, |k|;
//   hkt       h(k, t) = ½h0(k)e^{−iωt} + ½h0(−k)* e^{iωt}  (Gamper eq. 4.7) with float phases;
//   fields    the field multipliers of waves/fields.h in float and an FFTW single-precision inverse
//             2-D transform (FFTW_BACKWARD: e^{+i…}, unnormalized, the convention of waves/fft.h).
// What it takes from oceanref is what a port computes once on the host from the scene: the
// spectrum's scalar constants resolved by make_spectrum (α, ω_p, γ, σ, s_p, …, rounded to float
// like shader uniforms) and the cascade layout (L_i, N, the band edges of cascade_bands). It
// never reads oceanref's h0, ω or h(k, t).
//
// Elementary functions: a GPU's float exp, log, cos, … are accurate to about 1 ulp; this backend
// stands them in by the project's portable double functions rounded to float
// (static_cast<float>(math::exp(double(x)))), never libm, so its output is the same on every
// machine up to FFTW's own rounding. sqrt is IEEE's correctly rounded float sqrt.
//
// Supported: realization gaussian; spectra phillips, pierson-moskowitz (u10, u19.5), jonswap, tma
// (tma_attenuation thompson-vincent), donelan; every spreading but unified (cos2, cos4 and donelan
// normalized or printed, the cos-2s family with swell and spread blend, donelan-banner);
// dispersion deep, finite-depth and capillary. Anything else is refused by
// check_float32_support with a message naming the setting.
//
// Its stages are compared with `oceanref fields --stage X` by the compare library with
// reference/profiles/<stage>_float32.json (tests/test_conformance.cpp, tests/cli_test.sh,
// `oceanref bench float32 --stage X`).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "io/exr.h"
#include "waves/fields.h"
#include "waves/ocean.h"
#include "waves/stages.h"

namespace oceanref {

// Deliberate defects, to show that the shipped profiles catch real bugs.
enum class Float32Defect {
  none,
  drop_conjugate_term,  // h = ½h0(k)e^{−iωt} only: not Hermitian (a classic port bug)
  half_float_phase,     // ωt rounded to float16-like precision (11 significant bits)
  half_float_output,    // every value written rounded to 11 significant bits (a float16 copy)
  flip_one_phase,       // h0 of cascade 0's strongest wave negated (one mode's phase off by π)
  drop_polar_jacobian,  // Θ = Ψ·D instead of Ψ·D/k (eq. 3.61's 1/k forgotten)
};
inline constexpr const char* kFloat32DefectNames[] = {
    "none",           "drop-conjugate-term", "half-float-phase", "half-float-output",
    "flip-one-phase", "drop-polar-jacobian"};

struct ComplexF {
  float re = 0.0f;
  float im = 0.0f;
};

// One pattern (cascade i on one grid) with every stage before the fields, in float32; arrays
// N × N, row-major [b·N + a] (FFT order, waves/realization.h).
struct Float32Pattern {
  Pattern pattern;               // cascade index, L, N and band, as oceanref lays them out
  std::vector<float> theta;      // Θ(k) [m⁴], 0 at k = 0
  std::vector<float> variance;   // Θ(k)Δk² [m²] where in_band, else 0
  std::vector<float> in_band;    // 1 where k ≠ 0 and lower ≤ |k| < upper, else 0
  std::vector<ComplexF> h0;      // [m]
  std::vector<float> omega;      // ω(|k|) [rad/s]
  std::vector<float> kx, kz, k;  // [rad/m]
  std::vector<float> inverse_k;  // 1/|k| [m/rad], 0 at k = 0
};

struct Float32Cascade {
  Float32Pattern high;  // N_h
  Float32Pattern low;   // N_l (a copy of high when N_l = N_h)
};

// Throws std::invalid_argument naming the scene key and the supported values when the example
// backend cannot reproduce the scene's waves.
void check_float32_support(const WaveSettings& waves);

// Every cascade's patterns (spectrum, h0 and omega stages) from the scene's wave settings.
std::vector<Float32Cascade> float32_cascades(const WaveSettings& waves,
                                             Float32Defect defect = Float32Defect::none);

// h(k, t) of one pattern (eq. 4.7) in float32.
std::vector<ComplexF> float32_hkt(const Float32Pattern& p, double time,
                                  Float32Defect defect = Float32Defect::none);

// One field of one pattern from its h(k, t), row-major [n·N + m] like CascadeFields::values.
std::vector<float> float32_field(const Float32Pattern& p, const std::vector<ComplexF>& hkt,
                                 Field field);

// The synthesis alone in float32 from oceanref's double h0 and ω (the study's float-vs-double
// figure of the FFT synthesis, reference/ACCURACY.md): one field of one pattern at time t.
std::vector<float> float32_field(const PatternSpectrum& s, double time, Field field,
                                 Float32Defect defect = Float32Defect::none);

// One stage of the scene's waves as EXR parts in the layout of `oceanref fields --stage X`: one
// part per cascade i and grid, "c<i>" (N_h) and, when N_l < N_h, "c<i>.low" (N_l); channels
// "<part>.<channel>.V" with the channel names of waves/stages.h (spectrum: theta, variance,
// in_band; h0: h0.re, h0.im; omega: omega, kx, kz, k; hkt: hkt.re, hkt.im) and for the fields
// stage the raw fields "c<i>.<field>.V" (η, D_x, D_z in c<i>.low when multi-resolution; no
// Jacobian, foam or sum part): exr_channel_name (conformance/channel_name.h), as oceanref names
// them. Throws std::invalid_argument as check_float32_support.
std::vector<ExrPart> float32_stage_parts(const WaveSettings& waves, Stage stage, double time,
                                         Float32Defect defect = Float32Defect::none);

}  // namespace oceanref
