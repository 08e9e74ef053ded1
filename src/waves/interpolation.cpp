#include "waves/interpolation.h"

#include <cmath>
#include <numbers>

#include "core/check.h"
#include "core/math.h"
#include "waves/realization.h"

namespace oceanref {

namespace {
// A point of a periodic N-cell grid of size L: the cell (m, n) below-left of it and the fractions
// (f_u, f_v) ∈ [0, 1) across it. A point within 1e−9 cell of a node is that node.
struct GridPoint {
  int m, n;
  double fu, fv;
};
GridPoint locate(int cells, double size, double x, double z) {
  const double spacing = size / cells;
  const auto wrap = [&](double p) {
    double u = std::fmod(p, size) / spacing;
    if (u < 0.0) u += cells;
    const double node = std::nearbyint(u);
    if (std::fabs(u - node) < 1e-9) u = node;
    return u >= cells ? u - cells : u;
  };
  const double u = wrap(x);
  const double v = wrap(z);
  return {static_cast<int>(std::floor(u)) % cells, static_cast<int>(std::floor(v)) % cells,
          u - std::floor(u), v - std::floor(v)};
}

// i mod n in [0, n): without a division for the stencils' −1 … N + 1 (the hot path of every
// interpolated read).
int wrap_index(int i, int n) {
  if (i >= 0 && i < n) return i;
  if (i < 0 && i >= -n) return i + n;
  if (i >= n && i - n < n) return i - n;
  return (i % n + n) % n;
}

// A periodic grid as the readers below index it: N ≥ 1 cells of a positive size, N² values.
void expect_grid(const std::vector<double>& grid, int n, double size) {
  OCEANREF_EXPECTS(n >= 1 && grid.size() == grid_cells(n) && size > 0.0,
                   "a periodic grid of N x N values and positive size; N = " + std::to_string(n) +
                       ", " + std::to_string(grid.size()) + " values, size " +
                       std::to_string(size));
}
}  // namespace

std::array<double, 4> catmull_rom_weights(double t) {
  return {0.5 * ((-t + 2.0) * t - 1.0) * t, 0.5 * ((3.0 * t - 5.0) * t * t + 2.0),
          0.5 * ((-3.0 * t + 4.0) * t + 1.0) * t, 0.5 * (t - 1.0) * t * t};
}

std::array<double, 4> catmull_rom_weight_derivatives(double t) {
  return {0.5 * ((-3.0 * t + 4.0) * t - 1.0), 0.5 * (9.0 * t - 10.0) * t,
          0.5 * ((-9.0 * t + 8.0) * t + 1.0), 0.5 * (3.0 * t - 2.0) * t};
}

GridStencil grid_stencil(int n, double size, double x, double z, Interpolation mode) {
  OCEANREF_EXPECTS(n >= 1 && size > 0.0 && mode != Interpolation::direct,
                   "a periodic grid of N >= 1 cells and positive size read by bilinear or bicubic "
                   "interpolation; N = " +
                       std::to_string(n) + ", size " + std::to_string(size));
  const GridPoint p = locate(n, size, x, z);
  GridStencil s;
  s.mode = mode;
  s.resolution = n;
  s.inverse_spacing = n / size;
  s.at_node = p.fu == 0.0 && p.fv == 0.0;
  s.fu = p.fu;
  s.fv = p.fv;
  for (std::size_t i = 0; i < 4; ++i) {
    s.columns[i] = wrap_index(p.m + static_cast<int>(i) - 1, n);
    s.rows[i] = wrap_index(p.n + static_cast<int>(i) - 1, n);
  }
  if (mode == Interpolation::bicubic) {
    s.wu = catmull_rom_weights(p.fu);
    s.wv = catmull_rom_weights(p.fv);
    s.du = catmull_rom_weight_derivatives(p.fu);
    s.dv = catmull_rom_weight_derivatives(p.fv);
  }
  return s;
}

namespace {
// A grid of the stencil's resolution.
void expect_stencil_grid(const std::vector<double>& grid, const GridStencil& s) {
  OCEANREF_EXPECTS(grid.size() == grid_cells(s.resolution),
                   "a periodic grid of N x N values; N = " + std::to_string(s.resolution) + ", " +
                       std::to_string(grid.size()) + " values");
}

// The bicubic sums Σ_j w_v Σ_i w_u g (the value), with d/du and d/dv weights for the gradient.
struct BicubicSums {
  double value = 0.0, d_du = 0.0, d_dv = 0.0;
};
template <bool kGradient>
BicubicSums bicubic_sums(const std::vector<double>& grid, const GridStencil& s) {
  BicubicSums sums;
  for (std::size_t j = 0; j < 4; ++j) {
    double line = 0.0, line_du = 0.0;
    for (std::size_t i = 0; i < 4; ++i) {
      const double g = grid[grid_offset(s.columns[i], s.rows[j], s.resolution)];
      line += s.wu[i] * g;
      if constexpr (kGradient) line_du += s.du[i] * g;
    }
    sums.value += s.wv[j] * line;
    if constexpr (kGradient) {
      sums.d_du += s.wv[j] * line_du;
      sums.d_dv += s.dv[j] * line;
    }
  }
  return sums;
}
}  // namespace

double read_value(const std::vector<double>& grid, const GridStencil& s) {
  expect_stencil_grid(grid, s);
  const auto at = [&](std::size_t i, std::size_t j) {
    return grid[grid_offset(s.columns[i], s.rows[j], s.resolution)];
  };
  if (s.at_node) return at(1, 1);  // exactly the node value
  if (s.mode == Interpolation::bicubic) return bicubic_sums<false>(grid, s).value;
  return (1.0 - s.fv) * ((1.0 - s.fu) * at(1, 1) + s.fu * at(2, 1)) +
         s.fv * ((1.0 - s.fu) * at(1, 2) + s.fu * at(2, 2));
}

GridSample read_gradient(const std::vector<double>& grid, const GridStencil& s) {
  expect_stencil_grid(grid, s);
  const auto at = [&](std::size_t i, std::size_t j) {
    return grid[grid_offset(s.columns[i], s.rows[j], s.resolution)];
  };
  GridSample r;
  if (s.mode != Interpolation::bicubic) {
    // The gradient of the cell at the lower left of the point (a node starts its cell).
    const double f00 = at(1, 1), f10 = at(2, 1), f01 = at(1, 2), f11 = at(2, 2);
    r.value = s.at_node ? f00
                        : (1.0 - s.fv) * ((1.0 - s.fu) * f00 + s.fu * f10) +
                              s.fv * ((1.0 - s.fu) * f01 + s.fu * f11);
    r.d_dx = ((1.0 - s.fv) * (f10 - f00) + s.fv * (f11 - f01)) * s.inverse_spacing;
    r.d_dz = ((1.0 - s.fu) * (f01 - f00) + s.fu * (f11 - f10)) * s.inverse_spacing;
    return r;
  }
  const BicubicSums sums = bicubic_sums<true>(grid, s);
  r.value = s.at_node ? at(1, 1) : sums.value;
  r.d_dx = sums.d_du * s.inverse_spacing;
  r.d_dz = sums.d_dv * s.inverse_spacing;
  return r;
}

double sample_periodic(const std::vector<double>& grid, int n, double size, double x, double z) {
  expect_grid(grid, n, size);
  return read_value(grid, grid_stencil(n, size, x, z, Interpolation::bilinear));
}

double sample_periodic_bicubic(const std::vector<double>& grid, int n, double size, double x,
                               double z) {
  expect_grid(grid, n, size);
  return read_value(grid, grid_stencil(n, size, x, z, Interpolation::bicubic));
}

GridSample sample_periodic_gradient(const std::vector<double>& grid, int n, double size, double x,
                                    double z, Interpolation mode) {
  expect_grid(grid, n, size);
  return read_gradient(
      grid, grid_stencil(
                n, size, x, z,
                mode == Interpolation::bicubic ? Interpolation::bicubic : Interpolation::bilinear));
}

AxisTransfer linear_axis_transfer(double theta) {
  // Derived (FORMULAS.md, "Interpolation and slope variance"): a(t) = (1 − t) + t e^{iθ}.
  const double c = math::cos(theta);
  return {(2.0 + c) / 3.0, 2.0 - 2.0 * c, math::sin(theta)};
}

AxisTransfer catmull_rom_axis_transfer(double theta) {
  // Derived (FORMULAS.md, "Interpolation and slope variance"): Gram sums of the Catmull–Rom
  // weights, ∫w_j w_l, ∫w'_j w'_l, ∫w'_j w_l over t ∈ [0, 1], grouped by j − l.
  const double c1 = math::cos(theta), c2 = math::cos(2.0 * theta), c3 = math::cos(3.0 * theta);
  const double s1 = math::sin(theta), s2 = math::sin(2.0 * theta), s3 = math::sin(3.0 * theta);
  return {57.0 / 70.0 + 71.0 / 280.0 * c1 - 1.0 / 14.0 * c2 + 1.0 / 280.0 * c3,
          7.0 / 3.0 - 29.0 / 12.0 * c1 + 1.0 / 15.0 * c2 + 1.0 / 60.0 * c3,
          11.0 / 8.0 * s1 - 1.0 / 5.0 * s2 + 1.0 / 120.0 * s3};
}

AxisTransfer exact_axis_transfer(double theta, bool nyquist) {
  // cos(πx/Δ) on a Nyquist line: ⟨cos²⟩ = ½, ⟨π² sin²⟩ = ½π², ⟨−π sin·cos⟩ = 0.
  if (nyquist) return {0.5, 0.5 * theta * theta, 0.0};
  return {1.0, theta * theta, theta};
}

AxisTransfer axis_transfer(int alpha, int n, Interpolation mode) {
  const double theta = 2.0 * std::numbers::pi * alpha / n;
  switch (mode) {
    case Interpolation::bilinear:
      return linear_axis_transfer(theta);
    case Interpolation::bicubic:
      return catmull_rom_axis_transfer(theta);
    case Interpolation::direct:
      return exact_axis_transfer(theta, is_nyquist(alpha, n));
  }
  return {};
}

}  // namespace oceanref
