// Where a sample's area lands on the mean sea plane, for footprint filtering
// (waves/footprint_filter.h): the screen-space derivatives of the undisplaced position x0 that
// the rasterizer interpolates, and the Gaussian footprint of a sample cell or a grid cell.
#pragma once

#include <array>

#include <glm/glm.hpp>

#include "raster/projected_grid.h"
#include "raster/rasterizer.h"
#include "waves/footprint_filter.h"

namespace oceanref {

// ∂x0/∂(image x) and ∂x0/∂(image y) [m per pixel].
struct BaseDerivatives {
  glm::dvec2 along_x{0.0}, along_y{0.0};
};

// The derivatives of x0 = Σ w_i b_i inside a triangle, with w_i the perspective-correct weights
// (w_i = (λ_i/z_i)/Σ_j λ_j/z_j, λ_i the affine screen barycentrics) at the point the weights
// belong to: ∂w_i = (∂λ_i/z_i − w_i Σ_j ∂λ_j/z_j)/Σ_j λ_j/z_j. Zero for a degenerate triangle.
BaseDerivatives base_derivatives(const std::array<ScreenVertex, 3>& screen,
                                 const std::array<glm::dvec2, 3>& base,
                                 const std::array<double, 3>& weights);

// A square of side `cell` pixels mapped by the derivatives, as the Gaussian of the same
// covariance: a box of width c has variance c²/12 per axis, so Σ = c²/12 (d_x d_xᵀ + d_y d_yᵀ).
Footprint sample_footprint(const BaseDerivatives& d, double cell);

// The cell around projected-grid vertex (i, j) on the sea plane: Σ = (e_u e_uᵀ + e_v e_vᵀ)/12
// with e_u, e_v the central (one-sided at the border) differences of the base positions along
// the grid's columns and rows.
Footprint grid_vertex_footprint(const ProjectedGrid& grid, int i, int j);

}  // namespace oceanref
