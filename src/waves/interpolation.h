// Reading a periodic N×N field grid of size L between its nodes, and what that reading does to
// the field's variance.
//
// A grid node (m, n) sits at (m, n)·Δ, Δ = L/N. Bilinear and periodic Catmull–Rom bicubic
// interpolation are separable: along one axis the value at x = (m + t)Δ, t ∈ [0, 1), is
// Σ_j w_j(t) f[m + j]. Both are exact at the nodes; the bicubic one is C¹.
//
// Variance transfer (derived in src/FORMULAS.md, "Interpolation and slope variance"): a grid
// mode f[m] = e^{iθm}, θ = kΔ, read by the interpolant is e^{ikx}·G(t) with G 1-periodic, and
// distinct grid modes stay orthogonal under the mean over uniformly random positions. So the
// mean square of an interpolated field Σ_k c_k e^{ik·x} over random positions is
// Σ_k |c_k|² V(θ_x)V(θ_z), and that of its derivative along x is Σ_k |c_k|² W(θ_x)V(θ_z)/Δ²,
// with the per-axis factors of AxisTransfer below.
#pragma once

#include <array>
#include <vector>

#include "core/choice.h"

namespace oceanref {

// How the cascade grids are read between nodes: bilinear, periodic Catmull–Rom bicubic, or the
// exact direct summation of every component (slow). All are exact at the nodes.
enum class Interpolation { bilinear, bicubic, direct };
inline constexpr std::array<Choice<Interpolation>, 3> kInterpolations{{
    {Interpolation::bilinear, "bilinear"},
    {Interpolation::bicubic, "bicubic"},
    {Interpolation::direct, "direct"},
}};

// A periodic grid sampled at a world point: exact at nodes, bilinear in between.
double sample_periodic(const std::vector<double>& grid, int resolution, double size, double x,
                       double z);
// The same with periodic Catmull–Rom bicubic interpolation (C¹, exact for quadratics).
double sample_periodic_bicubic(const std::vector<double>& grid, int resolution, double size,
                               double x, double z);

// The interpolated value and its exact first derivatives [per m] at a point.
struct GridSample {
  double value = 0.0;
  double d_dx = 0.0;
  double d_dz = 0.0;
};
// The interpolant (bilinear or bicubic; the value bit-identical to sample_periodic and
// sample_periodic_bicubic) and its gradient. Bilinear: the gradient of the cell at the lower
// left of the point (a node belongs to the cell it starts).
GridSample sample_periodic_gradient(const std::vector<double>& grid, int resolution, double size,
                                    double x, double z, Interpolation mode);

// Where a point falls on a periodic N×N grid of size L, with the interpolation weights there:
// computed once per point and grid, then read for every field on that grid (read_value,
// read_gradient: the same bits as sample_periodic, sample_periodic_bicubic and
// sample_periodic_gradient, which locate the point each time).
struct GridStencil {
  Interpolation mode = Interpolation::bilinear;  // bilinear or bicubic
  int resolution = 1;                            // N
  double inverse_spacing = 1.0;                  // N/L [1/m]
  bool at_node = false;                          // the point is a node (f_u = f_v = 0)
  double fu = 0.0, fv = 0.0;                     // fractions across the cell
  // Grid indices of the nodes −1, 0, 1, 2 per axis (wrapped); bilinear reads 0 and 1.
  std::array<int, 4> columns{}, rows{};
  // Catmull–Rom weights and their derivatives d/dt per axis (bicubic only).
  std::array<double, 4> wu{}, wv{}, du{}, dv{};
};
GridStencil grid_stencil(int resolution, double size, double x, double z, Interpolation mode);
// The interpolated value of `grid` (N×N values, N the stencil's) at the stencil's point.
double read_value(const std::vector<double>& grid, const GridStencil& stencil);
// The value and its exact first derivatives [per m].
GridSample read_gradient(const std::vector<double>& grid, const GridStencil& stencil);

// Catmull–Rom weights of the nodes −1, 0, 1, 2 at t ∈ [0, 1] and their derivatives d/dt.
std::array<double, 4> catmull_rom_weights(double t);
std::array<double, 4> catmull_rom_weight_derivatives(double t);

// Per-axis variance factors of a grid mode e^{iθm} read between nodes, averaged over t ∈ [0, 1):
//   value      V = ⟨|G|²⟩                         (mean square of the interpolated mode)
//   derivative W = ⟨|d/dt (e^{iθt}G)|²⟩          (mean square of its derivative, per Δ²)
//   cross      c = ⟨(d/dt a)·a*⟩ / i            (real; a = e^{iθt}G; per Δ)
// Exact reading: V = 1, W = θ², c = θ.
struct AxisTransfer {
  double value = 1.0;
  double derivative = 0.0;
  double cross = 0.0;
};
// Linear interpolation: V = (2 + cos θ)/3, W = 2 − 2cos θ, c = sin θ.
AxisTransfer linear_axis_transfer(double theta);
// Catmull–Rom: V = 57/70 + 71/280 cos θ − 1/14 cos 2θ + 1/280 cos 3θ,
// W = 7/3 − 29/12 cos θ + 1/15 cos 2θ + 1/60 cos 3θ, c = 11/8 sin θ − 1/5 sin 2θ + 1/120 sin 3θ.
AxisTransfer catmull_rom_axis_transfer(double theta);
// Direct summation: exact (V = 1, W = θ², c = θ), except on a Nyquist line, where the sum
// holds the standing wave cos(πx/Δ) (waves/direct_sum.h): V = ½, W = ½π², c = 0.
AxisTransfer exact_axis_transfer(double theta, bool nyquist);
// The factors of a mode of an axis wave index α on an N-point grid (θ = 2πα/N) for a reading.
AxisTransfer axis_transfer(int alpha, int resolution, Interpolation mode);

}  // namespace oceanref
