// The surface a renderer draws and shades (issue 12, "one consistent surface").
//
// The rasterized surface is the displaced surface of Gamper eq. 4.20, p(x0) = (x0 + Σu_i D_i(x0),
// Σ η_i(x0)), with η and D read from the cascades' low-resolution grids (N_l) by the chosen
// interpolation; the projected grid's vertices are its samples. Its normal follows from
// ∂p/∂x0 and ∂p/∂z0, i.e. from ∇η and the Jacobian J = I + u∇D of the same interpolated fields
// (fields.h, displaced_surface_normal). Two ways to shade it:
//   * surface (default): the normal of exactly that surface — the derivatives of the
//     interpolants of η and D on the N_l grids (or, for direct summation, the exact
//     derivatives of the N_l bands), with the full Jacobian. The shading normal is the gradient
//     of what is rasterized, and every slope the N_l bands do not carry is left to the BRDF
//     (slope_budget.h).
//   * high_resolution: Gamper §4.4's multi-resolution split — the spectral slopes and ∂D of the
//     N_h bands, interpolated, combined by eq. 4.25. Finer normals on a coarser geometry; the
//     normal is not the gradient of the rasterized surface.
#pragma once

#include <array>
#include <vector>

#include "core/choice.h"
#include "waves/direct_sum.h"
#include "waves/fields.h"
#include "waves/interpolation.h"

namespace oceanref {

struct Ocean;
struct WaveSettings;

// The shading normal: of the rasterized surface (the N_l bands), or from the slopes of the N_h
// bands (Gamper 4.4).
enum class ShadingNormals { surface, high_resolution };
inline constexpr std::array<Choice<ShadingNormals>, 2> kShadingNormals{{
    {ShadingNormals::surface, "surface"},
    {ShadingNormals::high_resolution, "high_resolution"},
}};

// One cascade's rendered surface at (x, z) from its grids: η, D_x, D_z from the N_l grids by
// `mode` (bilinear or bicubic) and the exact derivatives of those interpolants (raw slope and
// ∂D entries, and ∂D_z/∂x).
CascadeSurface cascade_surface_from_grids(const CascadeFields& f, double x, double z,
                                          Interpolation mode);

// The combined rendered surface at (x, z) (finish_surface_combination): from the grids, or for
// `direct` from the N_l bands summed exactly (`evolved` from evolve_ocean).
PointFields combine_surface_at(const Ocean& ocean, const std::vector<CascadeFields>& fields,
                               const std::vector<EvolvedCascade>& evolved, double x, double z,
                               Interpolation mode);

// The fields a renderer uses at (x, z): combine_surface_at for `surface`, combine_at for
// `high_resolution`. The height and displacement are the same in both.
PointFields combine_shading_at(const Ocean& ocean, const std::vector<CascadeFields>& fields,
                               const std::vector<EvolvedCascade>& evolved, double x, double z,
                               Interpolation mode, ShadingNormals normals);

// The deformation's raw sums Σu_i ∂D_i (∂D_z/∂x as combine_shading_at's ddz_dx) and det J at a
// point: what whitecap coverage reads (deformation_at).
struct SurfaceDeformation {
  double ddx_dx = 0.0, ddx_dz = 0.0, ddz_dx = 0.0, ddz_dz = 0.0;
  double jacobian = 1.0;
};
// The stencils of the exemplar points one point's synthesis reads (one point, or a tiling's
// several), per cascade: [point · cascades + cascade]; `high` only for high_resolution normals.
struct FrameStencils {
  std::vector<std::array<double, 2>> points;
  std::vector<GridStencil> low, high;
};
// The fields deformation_at reads: D_x and D_z for `surface` (the deformation is their
// gradient), and the N_h ∂D fields as well for `high_resolution`.
FieldMask deformation_fields(ShadingNormals normals);
// The bytes a foam history of `steps` earlier frames holds: those fields of every cascade.
double foam_history_bytes(const WaveSettings& settings, ShadingNormals normals, int steps);
// The deformation of combine_shading_at at (x, z). A sample's foam history reads it from many
// frames of one ocean at the same point; their grids share every size, so the exemplar points
// and each cascade's grid stencils are computed for the first frame and kept in `stencils` for
// the next, and η, which the deformation does not depend on, is not read. The same bits as
// those entries of combine_shading_at (tests/test_surface.cpp).
SurfaceDeformation deformation_at(const Ocean& ocean, const std::vector<CascadeFields>& fields,
                                  const std::vector<EvolvedCascade>& evolved, double x, double z,
                                  Interpolation mode, ShadingNormals normals,
                                  FrameStencils& stencils);

// The displaced point p(x0) = (x0 + Σu_i D_x,i, Σ η_i, z0 + Σu_i D_z,i) of the rasterized surface
// (Gamper eq. 4.19–4.20, 4.24): the same bits as the height and displacement of
// combine_shading_at, without the slopes (the projected grid's vertices need only these).
struct DisplacedPoint {
  double x = 0.0, height = 0.0, z = 0.0;
};
DisplacedPoint displaced_point(const Ocean& ocean, const std::vector<CascadeFields>& fields,
                               const std::vector<EvolvedCascade>& evolved, double x0, double z0,
                               Interpolation mode, ShadingNormals normals);

// p(x0) with its partial derivatives ∂p/∂x0 and ∂p/∂z0 (the columns of the Jacobian of eq. 4.20:
// (1 + u∂D_x/∂x, ∂η/∂x, u∂D_z/∂x) and (u∂D_x/∂z, ∂η/∂z, 1 + u∂D_z/∂z)), from combine_surface_at:
// what Newton's method on a ray's hit with the continuous surface needs.
struct DisplacedPointDerivatives {
  DisplacedPoint point;
  std::array<double, 3> d_dx0{}, d_dz0{};  // (x, y, z) components
};
DisplacedPointDerivatives displaced_point_derivatives(const Ocean& ocean,
                                                      const std::vector<CascadeFields>& fields,
                                                      const std::vector<EvolvedCascade>& evolved,
                                                      double x0, double z0, Interpolation mode);

// Bounds of the displaced surface p(x0) over the whole plane, proven from the fields (not
// sampled), for the ray tracer against the continuous surface (trace/surface_tracer.h). They
// bound the offset q(x0) = p(x0) − (x0, 0, z0) = (Σu_iD_x,i, Σ η_i, Σu_iD_z,i):
//   |q_j(a) − q_j(b)| ≤ lipschitz[j]·|a − b|   and   |q_j(x0)| ≤ offset[j].
// Per cascade and field f, a bound B_x of |∂f/∂x| and B_z of |∂f/∂z| and M of |f|:
//   bilinear: B_x = max|f[m+1, n] − f[m, n]|/Δ (the interpolant's slope in a cell is a mean of
//     two such differences), M = max|f[m, n]|;
//   bicubic (Catmull–Rom): B_x = (3/2)(5/4)·max|f[m+1, n] − f[m, n]|/Δ, M = (5/4)²·max|f| —
//     5/4 = max Σ_j|w_j(t)| and 3/2 = max Σ_j|c_j(t)|, where the derivative Σ_j w'_j f_j is
//     written Σ_j c_j (f_{j+1} − f_j) (src/FORMULAS.md, "Bounds of the interpolated surface");
//   direct: B_x = Σ_k |g h(k, t)|·|k_x|, M = Σ_k |g h(k, t)| over the low band (g the field's
//     multiplier: 1 for η, d(k_x, k) for D_x, eq. 4.18).
// Then lipschitz_j = |(Σ|u|B_x, Σ|u|B_z)| of its field (u = 1 for η), offset_j = Σ|u|M.
struct DisplacedSurfaceBounds {
  std::array<double, 3> lipschitz{};  // of q's components x, y, z [m/m]
  std::array<double, 3> offset{};     // of |q|'s components [m]
};
DisplacedSurfaceBounds displaced_surface_bounds(const Ocean& ocean,
                                                const std::vector<CascadeFields>& fields,
                                                const std::vector<EvolvedCascade>& evolved,
                                                Interpolation mode);

}  // namespace oceanref
