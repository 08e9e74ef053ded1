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

// The displaced point p(x0) = (x0 + Σu_i D_x,i, Σ η_i, z0 + Σu_i D_z,i) of the rasterized surface
// (Gamper eq. 4.19–4.20, 4.24): the same bits as the height and displacement of
// combine_shading_at, without the slopes (the projected grid's vertices need only these).
struct DisplacedPoint {
  double x = 0.0, height = 0.0, z = 0.0;
};
DisplacedPoint displaced_point(const Ocean& ocean, const std::vector<CascadeFields>& fields,
                               const std::vector<EvolvedCascade>& evolved, double x0, double z0,
                               Interpolation mode, ShadingNormals normals);

}  // namespace oceanref
