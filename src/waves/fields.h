// Wave fields of one cascade by spectral synthesis (Gamper §4.2–4.3), and the combination of
// cascades (Gamper eq. 4.22–4.26).
//
// Fields (raw, per cascade, in this order): η (eq. 4.4), ∂η/∂x, ∂η/∂z (eq. 4.13–4.14),
// D_x, D_z (eq. 4.15–4.18), ∂D_x/∂x, ∂D_z/∂z, ∂D_x/∂z (eq. 4.13 applied to D; ∂D_z/∂x equals
// ∂D_x/∂z because both have the spectrum k_x k_z h/k). Each is the inverse DFT of h(k, t) times
// a multiplier; two real fields share one complex transform (eq. 4.8), so the 8 fields cost
// 4 transforms (5 with multi-resolution, where η and D live on the coarser grid).
//
// Choppiness u ≤ 0 (Gamper eq. 4.20): the displaced point is x + u·D. For one wave
// η = A cos(kx), D_x = Σ −i(k_x/k)h e^{ik·x} = A sin(kx), so near a crest x' = x(1 + uAk):
// u < 0 draws points towards the crests and sharpens them, u > 0 would flatten the crests and
// sharpen the troughs (rejected unless explicitly allowed).
#pragma once

#include <array>
#include <cmath>
#include <functional>
#include <string_view>
#include <vector>

#include "waves/fft.h"
#include "waves/realization.h"

namespace oceanref {

enum class Field {
  height,
  slope_x,
  slope_z,
  displacement_x,
  displacement_z,
  ddx_dx,
  ddz_dz,
  ddx_dz
};
inline constexpr int kFieldCount = 8;
inline constexpr std::array<std::string_view, kFieldCount> kFieldNames{
    "height", "slope_x", "slope_z", "disp_x", "disp_z", "ddx_dx", "ddz_dz", "ddx_dz"};
// η and D are the low-resolution fields of the multi-resolution scheme (Gamper §4.4).
bool is_low_resolution_field(Field f);

// d(k, 1) = ik, 0 on the Nyquist line of an even N  (Gamper eq. 4.12).
[[gnu::always_inline]] inline Complex derivative_factor(int index, double spacing, int resolution) {
  if (is_nyquist(index, resolution)) return 0.0;
  return {0.0, index * spacing};
}
// d(l, k) = −i l/k, 0 at k = 0 or on the Nyquist line of l  (Gamper eq. 4.18); 1/k is given
// (0 at k = 0), so the per-frame synthesis divides nothing.
[[gnu::always_inline]] inline Complex displacement_factor(int index, double spacing,
                                                          double inverse_k, int resolution) {
  if (is_nyquist(index, resolution)) return 0.0;
  return {0.0, -(index * spacing) * inverse_k};
}
// The spectral multiplier of a field for the wavevector (α, β)·Δk with 1/|k| given.
[[gnu::always_inline]] inline Complex field_multiplier(Field f, int alpha, int beta, double spacing,
                                                       double inverse_k, int n) {
  switch (f) {
    case Field::height:
      return 1.0;
    case Field::slope_x:
      return derivative_factor(alpha, spacing, n);
    case Field::slope_z:
      return derivative_factor(beta, spacing, n);
    case Field::displacement_x:
      return displacement_factor(alpha, spacing, inverse_k, n);
    case Field::displacement_z:
      return displacement_factor(beta, spacing, inverse_k, n);
    // d(k_x, 1)·d(k_x, k) = (ik_x)(−ik_x/k) = k_x²/k, and likewise: real multipliers.
    case Field::ddx_dx:
      return derivative_factor(alpha, spacing, n).im *
             -displacement_factor(alpha, spacing, inverse_k, n).im;
    case Field::ddz_dz:
      return derivative_factor(beta, spacing, n).im *
             -displacement_factor(beta, spacing, inverse_k, n).im;
    case Field::ddx_dz:
      return derivative_factor(beta, spacing, n).im *
             -displacement_factor(alpha, spacing, inverse_k, n).im;
  }
  return 0.0;
}

// The 8 raw fields of one cascade on their grids (row-major [n·N + m]).
struct CascadeFields {
  double size = 0.0;
  int low_resolution = 0;   // grid of η, D_x, D_z
  int high_resolution = 0;  // grid of the slopes and the derivatives of D
  std::array<std::vector<double>, kFieldCount> values;
  int transforms = 0;  // complex inverse FFTs used
};

// Wall-clock seconds spent in each synthesis stage, accumulated when requested (benchmarks).
struct SynthesisTimes {
  double evolve = 0.0;     // h(k, t), eq. 4.7
  double pack = 0.0;       // multipliers and pairing, eq. 4.8
  double transform = 0.0;  // inverse 2-D FFTs
  double unpack = 0.0;     // real and imaginary parts into fields
};

// An inverse 2-D DFT in the convention of inverse_fft_2d (benchmarks swap in FFTW).
using InverseFft2d = std::function<void(std::vector<Complex>& data, int resolution, int threads)>;

// Buffers reused from frame to frame (a sequence allocates them once).
struct SynthesisWorkspace {
  std::vector<Complex> h_low, h_high, packed;
};

// Which fields to synthesize (by Field index).
using FieldMask = std::array<bool, kFieldCount>;
inline constexpr FieldMask kAllFields{true, true, true, true, true, true, true, true};

// Synthesizes the raw fields at time t into `out`, reusing its storage and the workspace.
// `low` and `high` are the same cascade realized at the two resolutions (the same object when
// multi-resolution is off). With a mask, a transform (two fields) runs only when it computes a
// wanted field — its partner comes with it — and the other fields are left empty; every field
// computed has the same bits as without the mask (the pairs do not change).
void synthesize_cascade(const PatternSpectrum& low, const PatternSpectrum& high, double time,
                        int threads, CascadeFields& out, SynthesisWorkspace& work,
                        const InverseFft2d& fft = inverse_fft_2d, SynthesisTimes* times = nullptr,
                        const FieldMask& wanted = kAllFields);
// The same with fresh storage.
CascadeFields synthesize_cascade(const PatternSpectrum& low, const PatternSpectrum& high,
                                 double time, int threads, const InverseFft2d& fft = inverse_fft_2d,
                                 SynthesisTimes* times = nullptr);

// Fields combined over cascades at one point (Gamper eq. 4.22–4.26); per cascade the raw fields
// and its choppiness u_i.
struct PointFields {
  std::array<double, kFieldCount> raw{};  // summed raw fields Σ_i (displacements and their
                                          // derivatives scaled by u_i)
  // Σ_i u_i ∂D_z/∂x. For spectral fields it equals raw ∂D_x/∂z (one spectrum k_x k_z h/k); the
  // derivatives of separately interpolated D_x and D_z differ slightly (surface normals).
  double ddz_dx = 0.0;
  double height = 0.0;                  // y = Σ η_i                       (eq. 4.22)
  double slope_x = 0.0, slope_z = 0.0;  // slopes after displacement      (eq. 4.25, or J⁻ᵀ∇η)
  double jacobian = 1.0;                // det J                           (eq. 4.26)
  double foam = 0.0;                    // 1 where det J < 0, else 0
  std::array<double, 3> normal{0.0, 1.0, 0.0};  // the shading normal, unit, n_y ≥ 0
};
// Accumulates one cascade's raw values into the combination (u·D, u·∂D).
void add_cascade(PointFields& sum, const std::array<double, kFieldCount>& raw, double choppiness);
// Completes the combination the Gamper way: slopes (eq. 4.25), Jacobian (eq. 4.26), foam
// indicator, the normal of those slopes (§4.3).
void finish_combination(PointFields& sum);

// One cascade's fields and their derivatives at a point where ∂D_z/∂x is its own value
// (derivatives of interpolants; the direct sum on a Nyquist line).
struct CascadeSurface {
  std::array<double, kFieldCount> raw{};
  double ddz_dx = 0.0;
};
// Accumulates it like add_cascade, with ∂D_z/∂x taken from `ddz_dx`.
void add_cascade_surface(PointFields& sum, const CascadeSurface& c, double choppiness);
// Completes the combination as the exact displaced surface p(x0) = (x0 + uD, η) (eq. 4.20):
// J = ∂(x0 + uD)/∂x0 with both off-diagonal entries, slopes s = J⁻ᵀ∇η (eq. 4.25 without its
// diagonal approximation), n from displaced_surface_normal, det J and the foam indicator.
void finish_surface_combination(PointFields& sum);

// s = [∂η/∂x / (1 + u ∂D_x/∂x), ∂η/∂z / (1 + u ∂D_z/∂z)]  (Gamper eq. 4.21/4.25).
double displaced_slope(double slope, double scaled_displacement_derivative);
// det J = (1 + u∂D_x/∂x)(1 + u∂D_z/∂z) − (u∂D_x/∂z)(u∂D_z/∂x)  (Gamper eq. 4.26).
double jacobian_determinant(double u_ddx_dx, double u_ddz_dz, double u_ddx_dz);
// The same with the two off-diagonal entries given separately (Gamper eq. 4.26).
double jacobian_determinant(double u_ddx_dx, double u_ddz_dz, double u_ddx_dz, double u_ddz_dx);
// n = (−s_x, 1, −s_z)/‖·‖  (Gamper §4.3, normal vectors).
std::array<double, 3> surface_normal(double slope_x, double slope_z);
// The unit normal of the displaced surface p(x0) = (x0 + uD(x0), η(x0)) (Gamper eq. 4.20),
// ∝ ∂p/∂z0 × ∂p/∂x0 = (−(J_zz η_x − J_zx η_z), det J, −(J_xx η_z − J_xz η_x)), turned upward
// (n_y ≥ 0): (−s_x, 1, −s_z)/‖·‖ with s = J⁻ᵀ∇η where det J ≠ 0, horizontal where det J = 0,
// the folded sheet seen from above where det J < 0. J_ab = ∂(x0 + uD)_a/∂x0_b.
std::array<double, 3> displaced_surface_normal(double eta_x, double eta_z, double j_xx, double j_xz,
                                               double j_zx, double j_zz);
// Foam of a sequence (Vincevičius listing 2.4): accumulation = last − decay·Δt/max(current, ½),
// foam = max(accumulation, current); `current` is the indicator (1 where det J < 0).
double accumulated_foam(double last, double current, double decay, double time_step);
// accumulated_foam from 0 over the `steps` instants before now (oldest first) and then now's
// `current`, with `coverage(age)` the value of the instant `age` steps back (1 … steps), each
// in [0, 1] (a coverage or indicator; NaN counts as none, as in accumulated_foam). The instants
// are read from the newest back: what those not yet read can add to the foam is at most
// 1 − (the decays Σ decay·Δt/max(W, ½) of those read), so once that and the ones read, each
// decayed by the later ones, fall below `current` by more than any rounding, the older instants
// cannot reach the result, which is `current`, and they are not read (in a steady window most
// of a sea without whitecaps reads about half of them). Otherwise the recursion runs forward
// over all of them. The same bits as the forward recursion over every instant in either case.
template <class Coverage>
double accumulated_foam_of_history(int steps, double current, double decay, double time_step,
                                   const Coverage& coverage) {
  // Rounding: each step of the recursion and of the bounds below is exact to ~2^-52 of values
  // ≤ 1, so 1e-9 covers any number of steps a scene allows (waves.foam.steps ≤ 10⁴).
  constexpr double kMargin = 1e-9;
  const double now_decay = decay * time_step / std::fmax(current, 0.5);
  std::vector<double> read;  // newest first
  double later = 0.0;        // Σ of the decays of the instants read
  double bound = 0.0;        // the largest W_j decayed by the instants after it (≥ 0: foam ≥ 0)
  for (int age = 1; age <= steps; ++age) {
    const double w = coverage(age);
    read.push_back(w);
    bound = std::fmax(bound, w - later);
    later += decay * time_step / std::fmax(w, 0.5);
    if (std::fmax(bound, 1.0 - later) - now_decay + kMargin < current) return current;
  }
  double foam = 0.0;
  for (auto w = read.rbegin(); w != read.rend(); ++w) {
    foam = accumulated_foam(foam, *w, decay, time_step);
  }
  return accumulated_foam(foam, current, decay, time_step);
}

}  // namespace oceanref
