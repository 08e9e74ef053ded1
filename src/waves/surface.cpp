#include "waves/surface.h"

#include "core/check.h"
#include "waves/ocean.h"

namespace oceanref {

CascadeSurface cascade_surface_from_grids(const CascadeFields& f, double x, double z,
                                          Interpolation mode) {
  // η, D_x and D_z share the N_l grid: the point is located once.
  const GridStencil stencil = grid_stencil(
      f.low_resolution, f.size, x, z,
      mode == Interpolation::bicubic ? Interpolation::bicubic : Interpolation::bilinear);
  const auto read = [&](Field q) {
    return read_gradient(f.values[static_cast<std::size_t>(q)], stencil);
  };
  const GridSample eta = read(Field::height);
  const GridSample dx = read(Field::displacement_x);
  const GridSample dz = read(Field::displacement_z);
  CascadeSurface c;
  const auto set = [&](Field q, double v) { c.raw[static_cast<std::size_t>(q)] = v; };
  set(Field::height, eta.value);
  set(Field::slope_x, eta.d_dx);
  set(Field::slope_z, eta.d_dz);
  set(Field::displacement_x, dx.value);
  set(Field::displacement_z, dz.value);
  set(Field::ddx_dx, dx.d_dx);
  set(Field::ddz_dz, dz.d_dz);
  set(Field::ddx_dz, dx.d_dz);
  c.ddz_dx = dz.d_dx;
  return c;
}

PointFields combine_surface_at(const Ocean& ocean, const std::vector<CascadeFields>& fields,
                               const std::vector<EvolvedCascade>& evolved, double x, double z,
                               Interpolation mode) {
  OCEANREF_EXPECTS(
      (mode == Interpolation::direct ? evolved.size() : fields.size()) == ocean.cascades.size(),
      "one field set (or evolved spectrum, for direct) per cascade");
  PointFields sum;
  for (std::size_t i = 0; i < ocean.cascades.size(); ++i) {
    const CascadeSpectra& c = ocean.cascades[i];
    const CascadeSurface s = mode == Interpolation::direct
                                 ? direct_sum_surface(c.low, evolved[i].low, x, z)
                                 : cascade_surface_from_grids(fields[i], x, z, mode);
    add_cascade_surface(sum, s, c.choppiness);
  }
  finish_surface_combination(sum);
  return sum;
}

PointFields combine_shading_at(const Ocean& ocean, const std::vector<CascadeFields>& fields,
                               const std::vector<EvolvedCascade>& evolved, double x, double z,
                               Interpolation mode, ShadingNormals normals) {
  if (normals == ShadingNormals::surface) {
    return combine_surface_at(ocean, fields, evolved, x, z, mode);
  }
  return combine_at(ocean, fields, evolved, x, z, mode);
}

// Gamper eq. 4.19–4.20, 4.24: p(x0) = (x0 + Σ u_i D_i, Σ η_i).
DisplacedPoint displaced_point(const Ocean& ocean, const std::vector<CascadeFields>& fields,
                               const std::vector<EvolvedCascade>& evolved, double x0, double z0,
                               Interpolation mode, ShadingNormals normals) {
  const auto index = [](Field q) { return static_cast<std::size_t>(q); };
  if (mode == Interpolation::direct) {
    const PointFields p = combine_shading_at(ocean, fields, evolved, x0, z0, mode, normals);
    return {x0 + p.raw[index(Field::displacement_x)], p.height,
            z0 + p.raw[index(Field::displacement_z)]};
  }
  OCEANREF_EXPECTS(fields.size() == ocean.cascades.size(), "one field set per cascade");
  // Summed as add_cascade and add_cascade_surface do: cascade by cascade, from 0.
  double height = 0.0, dx = 0.0, dz = 0.0;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const CascadeFields& f = fields[i];
    const double u = ocean.cascades[i].choppiness;
    const GridStencil stencil = grid_stencil(f.low_resolution, f.size, x0, z0, mode);
    height += 1.0 * read_value(f.values[index(Field::height)], stencil);
    dx += u * read_value(f.values[index(Field::displacement_x)], stencil);
    dz += u * read_value(f.values[index(Field::displacement_z)], stencil);
  }
  return {x0 + dx, height, z0 + dz};
}

}  // namespace oceanref
