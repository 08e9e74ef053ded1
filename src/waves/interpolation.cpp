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

int wrap_index(int i, int n) {
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

double sample_periodic(const std::vector<double>& grid, int n, double size, double x, double z) {
  expect_grid(grid, n, size);
  const GridPoint p = locate(n, size, x, z);
  const int m1 = (p.m + 1) % n;
  const int n1 = (p.n + 1) % n;
  const auto at = [&](int m, int k) { return grid[grid_offset(m, k, n)]; };
  if (p.fu == 0.0 && p.fv == 0.0) return at(p.m, p.n);  // exactly the node value
  return (1.0 - p.fv) * ((1.0 - p.fu) * at(p.m, p.n) + p.fu * at(m1, p.n)) +
         p.fv * ((1.0 - p.fu) * at(p.m, n1) + p.fu * at(m1, n1));
}

double sample_periodic_bicubic(const std::vector<double>& grid, int n, double size, double x,
                               double z) {
  expect_grid(grid, n, size);
  const GridPoint p = locate(n, size, x, z);
  if (p.fu == 0.0 && p.fv == 0.0) return grid[grid_offset(p.m, p.n, n)];
  const std::array<double, 4> wu = catmull_rom_weights(p.fu);
  const std::array<double, 4> wv = catmull_rom_weights(p.fv);
  double sum = 0.0;
  for (std::size_t j = 0; j < 4; ++j) {
    const int row = wrap_index(p.n + static_cast<int>(j) - 1, n);
    double line = 0.0;
    for (std::size_t i = 0; i < 4; ++i) {
      line += wu[i] * grid[grid_offset(wrap_index(p.m + static_cast<int>(i) - 1, n), row, n)];
    }
    sum += wv[j] * line;
  }
  return sum;  // the value of sample_periodic_gradient, without the derivatives
}

GridSample sample_periodic_gradient(const std::vector<double>& grid, int n, double size, double x,
                                    double z, Interpolation mode) {
  expect_grid(grid, n, size);
  const GridPoint p = locate(n, size, x, z);
  const double inverse_spacing = n / size;
  const auto at = [&](int m, int k) {
    return grid[grid_offset(wrap_index(m, n), wrap_index(k, n), n)];
  };
  GridSample s;
  if (mode != Interpolation::bicubic) {
    const double f00 = at(p.m, p.n), f10 = at(p.m + 1, p.n);
    const double f01 = at(p.m, p.n + 1), f11 = at(p.m + 1, p.n + 1);
    s.value = p.fu == 0.0 && p.fv == 0.0 ? f00
                                         : (1.0 - p.fv) * ((1.0 - p.fu) * f00 + p.fu * f10) +
                                               p.fv * ((1.0 - p.fu) * f01 + p.fu * f11);
    s.d_dx = ((1.0 - p.fv) * (f10 - f00) + p.fv * (f11 - f01)) * inverse_spacing;
    s.d_dz = ((1.0 - p.fu) * (f01 - f00) + p.fu * (f11 - f10)) * inverse_spacing;
    return s;
  }
  const std::array<double, 4> wu = catmull_rom_weights(p.fu);
  const std::array<double, 4> wv = catmull_rom_weights(p.fv);
  const std::array<double, 4> du = catmull_rom_weight_derivatives(p.fu);
  const std::array<double, 4> dv = catmull_rom_weight_derivatives(p.fv);
  double sum = 0.0, sum_dx = 0.0, sum_dz = 0.0;
  for (std::size_t j = 0; j < 4; ++j) {
    const int row = p.n + static_cast<int>(j) - 1;
    double line = 0.0, line_dx = 0.0;
    for (std::size_t i = 0; i < 4; ++i) {
      const double g = at(p.m + static_cast<int>(i) - 1, row);
      line += wu[i] * g;
      line_dx += du[i] * g;
    }
    sum += wv[j] * line;
    sum_dx += wv[j] * line_dx;
    sum_dz += dv[j] * line;
  }
  s.value = p.fu == 0.0 && p.fv == 0.0 ? at(p.m, p.n) : sum;
  s.d_dx = sum_dx * inverse_spacing;
  s.d_dz = sum_dz * inverse_spacing;
  return s;
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
