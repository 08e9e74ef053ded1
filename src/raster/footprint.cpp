#include "raster/footprint.h"

#include <cmath>

namespace oceanref {

BaseDerivatives base_derivatives(const std::array<ScreenVertex, 3>& screen,
                                 const std::array<glm::dvec2, 3>& base,
                                 const std::array<double, 3>& weights) {
  const ScreenVertex &a = screen[0], &b = screen[1], &c = screen[2];
  const double area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);  // twice, signed
  if (!(std::fabs(area) > 0.0)) return {};
  // ∂λ_i/∂x, ∂λ_i/∂y of the affine barycentrics.
  const std::array<glm::dvec2, 3> gradient{glm::dvec2{b.y - c.y, c.x - b.x} / area,
                                           glm::dvec2{c.y - a.y, a.x - c.x} / area,
                                           glm::dvec2{a.y - b.y, b.x - a.x} / area};
  // λ_i ∝ w_i z_i, and Σ_j λ_j/z_j = 1/Σ_j w_j z_j.
  double wz = 0.0;
  for (std::size_t i = 0; i < 3; ++i) wz += weights[i] * screen[i].z;
  if (!(wz > 0.0)) return {};
  glm::dvec2 total{0.0};  // Σ_j ∂λ_j/z_j
  for (std::size_t j = 0; j < 3; ++j) total += gradient[j] / screen[j].z;
  BaseDerivatives d;
  for (std::size_t i = 0; i < 3; ++i) {
    const glm::dvec2 dw = (gradient[i] / screen[i].z - weights[i] * total) * wz;
    d.along_x += dw.x * base[i];
    d.along_y += dw.y * base[i];
  }
  return d;
}

Footprint sample_footprint(const BaseDerivatives& d, double cell) {
  const double v = cell * cell / 12.0;
  const glm::dvec2 &x = d.along_x, &y = d.along_y;
  return {v * (x.x * x.x + y.x * y.x), v * (x.x * x.y + y.x * y.y), v * (x.y * x.y + y.y * y.y)};
}

Footprint grid_vertex_footprint(const ProjectedGrid& grid, int i, int j) {
  const auto at = [&](int column, int row) {
    return grid.base[static_cast<std::size_t>(row) * static_cast<std::size_t>(grid.columns) +
                     static_cast<std::size_t>(column)];
  };
  const auto difference = [](glm::dvec2 from, glm::dvec2 to, int steps) {
    return steps > 0 ? (to - from) / static_cast<double>(steps) : glm::dvec2{0.0};
  };
  const int left = i > 0 ? i - 1 : i, right = i + 1 < grid.columns ? i + 1 : i;
  const int up = j > 0 ? j - 1 : j, down = j + 1 < grid.rows ? j + 1 : j;
  const glm::dvec2 u = difference(at(left, j), at(right, j), right - left);
  const glm::dvec2 v = difference(at(i, up), at(i, down), down - up);
  return {(u.x * u.x + v.x * v.x) / 12.0, (u.x * u.y + v.x * v.y) / 12.0,
          (u.y * u.y + v.y * v.y) / 12.0};
}

}  // namespace oceanref
