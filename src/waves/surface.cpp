#include "waves/surface.h"

#include "core/check.h"
#include "waves/ocean.h"

namespace oceanref {

CascadeSurface cascade_surface_from_grids(const CascadeFields& f, double x, double z,
                                          Interpolation mode) {
  const auto read = [&](Field q) {
    return sample_periodic_gradient(f.values[static_cast<std::size_t>(q)], f.low_resolution, f.size,
                                    x, z, mode);
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

}  // namespace oceanref
