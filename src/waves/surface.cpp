#include "waves/surface.h"

#include <algorithm>
#include <cmath>

#include "core/check.h"
#include "waves/ocean.h"

namespace oceanref {

namespace {
// One cascade's surface at a point located on its N_l grid: D_x, D_z and their gradients, and
// with `heights` η and its gradient (the deformation does not need them: deformation_at).
CascadeSurface cascade_surface_at(const CascadeFields& f, const GridStencil& stencil,
                                  bool heights) {
  const auto read = [&](Field q) {
    return read_gradient(f.values[static_cast<std::size_t>(q)], stencil);
  };
  CascadeSurface c;
  const auto set = [&](Field q, double v) { c.raw[static_cast<std::size_t>(q)] = v; };
  if (heights) {
    const GridSample eta = read(Field::height);
    set(Field::height, eta.value);
    set(Field::slope_x, eta.d_dx);
    set(Field::slope_z, eta.d_dz);
  }
  const GridSample dx = read(Field::displacement_x);
  const GridSample dz = read(Field::displacement_z);
  set(Field::displacement_x, dx.value);
  set(Field::displacement_z, dz.value);
  set(Field::ddx_dx, dx.d_dx);
  set(Field::ddz_dz, dz.d_dz);
  set(Field::ddx_dz, dx.d_dz);
  c.ddz_dx = dz.d_dx;
  return c;
}
}  // namespace

CascadeSurface cascade_surface_from_grids(const CascadeFields& f, double x, double z,
                                          Interpolation mode) {
  // η, D_x and D_z share the N_l grid: the point is located once.
  return cascade_surface_at(f,
                            grid_stencil(f.low_resolution, f.size, x, z,
                                         mode == Interpolation::bicubic ? Interpolation::bicubic
                                                                        : Interpolation::bilinear),
                            true);
}

namespace {
// The exemplar's raw sums of the rendered surface at (x, z), before finish_surface_combination.
PointFields exemplar_surface_sum(const Ocean& ocean, const std::vector<CascadeFields>& fields,
                                 const std::vector<EvolvedCascade>& evolved, double x, double z,
                                 Interpolation mode) {
  PointFields sum;
  for (std::size_t i = 0; i < ocean.cascades.size(); ++i) {
    const CascadeSpectra& c = ocean.cascades[i];
    const CascadeSurface s = mode == Interpolation::direct
                                 ? direct_sum_surface(c.low, evolved[i].low, x, z)
                                 : cascade_surface_from_grids(fields[i], x, z, mode);
    add_cascade_surface(sum, s, c.choppiness);
  }
  if (ocean.gerstner) {  // ∂D_z/∂x = ∂D_x/∂z for every wave
    OCEANREF_EXPECTS(mode == Interpolation::direct, "a Gerstner ocean is read directly");
    CascadeSurface s;
    s.raw = gerstner_raw_fields(*ocean.gerstner, x, z, evolved.back().time);
    s.ddz_dx = s.raw[static_cast<std::size_t>(Field::ddx_dz)];
    add_cascade_surface(sum, s, ocean.gerstner->choppiness);
  }
  return sum;
}

void expect_fields(const Ocean& ocean, const std::vector<CascadeFields>& fields,
                   const std::vector<EvolvedCascade>& evolved, Interpolation mode) {
  OCEANREF_EXPECTS(
      (mode == Interpolation::direct ? evolved.size() : fields.size()) ==
          ocean.cascades.size() + (mode == Interpolation::direct && ocean.gerstner ? 1 : 0),
      "one field set (or evolved spectrum, for direct) per cascade");
}
}  // namespace

PointFields combine_surface_at(const Ocean& ocean, const std::vector<CascadeFields>& fields,
                               const std::vector<EvolvedCascade>& evolved, double x, double z,
                               Interpolation mode) {
  expect_fields(ocean, fields, evolved, mode);
  const auto exemplar = [&](double ex, double ez) {
    return exemplar_surface_sum(ocean, fields, evolved, ex, ez, mode);
  };
  PointFields sum = synthesized_sum(ocean, x, z, exemplar);
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

FieldMask deformation_fields(ShadingNormals normals) {
  FieldMask read{};
  read[static_cast<std::size_t>(Field::displacement_x)] = true;
  read[static_cast<std::size_t>(Field::displacement_z)] = true;
  if (normals == ShadingNormals::high_resolution) {
    for (const Field q : {Field::ddx_dx, Field::ddz_dz, Field::ddx_dz}) {
      read[static_cast<std::size_t>(q)] = true;
    }
  }
  return read;
}

double foam_history_bytes(const WaveSettings& settings, ShadingNormals normals, int steps) {
  if (settings.model == WaveModel::gerstner) return 0.0;  // no grids (as wave_grid_bytes)
  const double low = static_cast<double>(settings.low_resolution) * settings.low_resolution;
  const double high = static_cast<double>(settings.resolution) * settings.resolution;
  const FieldMask kept = deformation_fields(normals);
  double per_cascade = 0.0;
  for (std::size_t q = 0; q < kept.size(); ++q) {
    if (kept[q]) per_cascade += (is_low_resolution_field(Field(q)) ? low : high) * sizeof(double);
  }
  return static_cast<double>(steps) * static_cast<double>(settings.sizes.size()) * per_cascade;
}

namespace {
// The stencils of exemplar point (x, z) for every cascade: those kept from an earlier frame, or
// made (as cascade_surface_from_grids and cascade_from_grids make them) and kept. Returns the
// point's index.
std::size_t point_stencils(const std::vector<CascadeFields>& fields, double x, double z,
                           Interpolation mode, ShadingNormals normals, FrameStencils& s) {
  for (std::size_t p = 0; p < s.points.size(); ++p) {
    if (s.points[p][0] == x && s.points[p][1] == z) return p;
  }
  const Interpolation read =
      mode == Interpolation::bicubic ? Interpolation::bicubic : Interpolation::bilinear;
  for (const CascadeFields& f : fields) {
    const GridStencil low = grid_stencil(f.low_resolution, f.size, x, z, read);
    s.low.push_back(low);
    if (normals == ShadingNormals::high_resolution) {
      s.high.push_back(f.high_resolution == f.low_resolution
                           ? low
                           : grid_stencil(f.high_resolution, f.size, x, z, read));
    }
  }
  s.points.push_back({x, z});
  return s.points.size() - 1;
}

// The exemplar's sums of the deformation's fields at one of the stencils' points, cascade by
// cascade as exemplar_surface_sum (surface) and exemplar_sum (high_resolution) sum them.
PointFields exemplar_deformation_sum(const Ocean& ocean, const std::vector<CascadeFields>& fields,
                                     const FrameStencils& s, std::size_t point,
                                     ShadingNormals normals) {
  const FieldMask read = deformation_fields(normals);
  PointFields sum;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const CascadeFields& f = fields[i];
    const GridStencil& low = s.low[point * fields.size() + i];
    const double u = ocean.cascades[i].choppiness;
    if (normals == ShadingNormals::surface) {
      add_cascade_surface(sum, cascade_surface_at(f, low, false), u);
    } else {  // as cascade_from_grids reads them
      const GridStencil& high = s.high[point * fields.size() + i];
      std::array<double, kFieldCount> raw{};
      for (std::size_t q = 0; q < raw.size(); ++q) {
        if (read[q]) {
          raw[q] = read_value(f.values[q], is_low_resolution_field(Field(q)) ? low : high);
        }
      }
      add_cascade(sum, raw, u);
    }
  }
  return sum;
}
}  // namespace

SurfaceDeformation deformation_at(const Ocean& ocean, const std::vector<CascadeFields>& fields,
                                  const std::vector<EvolvedCascade>& evolved, double x, double z,
                                  Interpolation mode, ShadingNormals normals,
                                  FrameStencils& stencils) {
  const auto index = [](Field q) { return static_cast<std::size_t>(q); };
  const auto deformation = [&](const PointFields& p, double jacobian) {
    return SurfaceDeformation{p.raw[index(Field::ddx_dx)], p.raw[index(Field::ddx_dz)], p.ddz_dx,
                              p.raw[index(Field::ddz_dz)], jacobian};
  };
  if (mode == Interpolation::direct || ocean.gerstner) {  // no grids to locate the point on
    const PointFields p = combine_shading_at(ocean, fields, evolved, x, z, mode, normals);
    return deformation(p, p.jacobian);
  }
  OCEANREF_EXPECTS(fields.size() == ocean.cascades.size(), "one field set per cascade");
  const PointFields sum = synthesized_sum(ocean, x, z, [&](double ex, double ez) {
    return exemplar_deformation_sum(
        ocean, fields, stencils, point_stencils(fields, ex, ez, mode, normals, stencils), normals);
  });
  // As finish_surface_combination and finish_combination compute det J.
  const double jacobian =
      normals == ShadingNormals::surface
          ? jacobian_determinant(sum.raw[index(Field::ddx_dx)], sum.raw[index(Field::ddz_dz)],
                                 sum.raw[index(Field::ddx_dz)], sum.ddz_dx)
          : jacobian_determinant(sum.raw[index(Field::ddx_dx)], sum.raw[index(Field::ddz_dz)],
                                 sum.raw[index(Field::ddx_dz)]);
  return deformation(sum, jacobian);
}

namespace {
// The exemplar's offset q = (Σ u_i D_x,i, Σ η_i, Σ u_i D_z,i) at (x, z) from the grids, summed as
// add_cascade and add_cascade_surface do: cascade by cascade, from 0.
DisplacedPoint exemplar_offset(const Ocean& ocean, const std::vector<CascadeFields>& fields,
                               double x, double z, Interpolation mode) {
  const auto index = [](Field q) { return static_cast<std::size_t>(q); };
  DisplacedPoint q;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const CascadeFields& f = fields[i];
    const double u = ocean.cascades[i].choppiness;
    const GridStencil stencil = grid_stencil(f.low_resolution, f.size, x, z, mode);
    q.height += 1.0 * read_value(f.values[index(Field::height)], stencil);
    q.x += u * read_value(f.values[index(Field::displacement_x)], stencil);
    q.z += u * read_value(f.values[index(Field::displacement_z)], stencil);
  }
  return q;
}
}  // namespace

// Gamper eq. 4.19–4.20, 4.24: p(x0) = (x0 + Σ u_i D_i, Σ η_i); tiled, Lutz eq. 6 and 8 as
// add_tile sums them.
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
  DisplacedPoint q;
  if (ocean.synthesis == Synthesis::tiling_and_blending) {
    for (const TileReading& r : tile_readings(ocean.tiling, x0, z0)) {
      DisplacedPoint e = exemplar_offset(ocean, fields, r.x, r.z, mode);
      turn_by_tile(r, e.x, e.z);
      q.height += r.weight * e.height;
      q.x += r.weight * e.x;
      q.z += r.weight * e.z;
    }
  } else {
    q = exemplar_offset(ocean, fields, x0, z0, mode);
    if (ocean.synthesis == Synthesis::noise_blended) {
      // As mix_noise does (Lutz eq. 2).
      const PointFields n = noise_fields(ocean.noise, x0, z0);
      const double w = ocean.noise.weight;
      q.height = (1.0 - w) * q.height + w * n.raw[index(Field::height)];
      q.x = (1.0 - w) * q.x + w * n.raw[index(Field::displacement_x)];
      q.z = (1.0 - w) * q.z + w * n.raw[index(Field::displacement_z)];
    }
  }
  return {x0 + q.x, q.height, z0 + q.z};
}

DisplacedPointDerivatives displaced_point_derivatives(const Ocean& ocean,
                                                      const std::vector<CascadeFields>& fields,
                                                      const std::vector<EvolvedCascade>& evolved,
                                                      double x0, double z0, Interpolation mode) {
  const PointFields p = combine_surface_at(ocean, fields, evolved, x0, z0, mode);
  const auto raw = [&](Field q) { return p.raw[static_cast<std::size_t>(q)]; };
  DisplacedPointDerivatives d;
  d.point = {x0 + raw(Field::displacement_x), p.height, z0 + raw(Field::displacement_z)};
  d.d_dx0 = {1.0 + raw(Field::ddx_dx), raw(Field::slope_x), p.ddz_dx};
  d.d_dz0 = {raw(Field::ddx_dz), raw(Field::slope_z), 1.0 + raw(Field::ddz_dz)};
  return d;
}

namespace {
// Bounds of one field over the plane: |∂f/∂x| ≤ d_dx, |∂f/∂z| ≤ d_dz, |f| ≤ value.
struct FieldBounds {
  double d_dx = 0.0, d_dz = 0.0, value = 0.0;
};

// Catmull–Rom: max over t of Σ_j|w_j(t)| = 1 + t(1 − t) ≤ 5/4, and of Σ_j|c_j(t)| ≤ 3/2
// (FORMULAS.md, "Bounds of the interpolated surface").
constexpr double kCatmullRomValueSum = 1.25;
constexpr double kCatmullRomDifferenceSum = 1.5;

// From the N×N grid of a field read by bilinear or bicubic interpolation.
FieldBounds grid_field_bounds(const std::vector<double>& f, int n, double size,
                              Interpolation mode) {
  double dx = 0.0, dz = 0.0, value = 0.0;
  for (int b = 0; b < n; ++b) {
    for (int a = 0; a < n; ++a) {
      const double v = f[grid_offset(a, b, n)];
      value = std::max(value, std::fabs(v));
      dx = std::max(dx, std::fabs(f[grid_offset((a + 1) % n, b, n)] - v));
      dz = std::max(dz, std::fabs(f[grid_offset(a, (b + 1) % n, n)] - v));
    }
  }
  const double per_spacing = n / size;
  if (mode == Interpolation::bicubic) {
    const double k = kCatmullRomDifferenceSum * kCatmullRomValueSum * per_spacing;
    return {k * dx, k * dz, kCatmullRomValueSum * kCatmullRomValueSum * value};
  }
  return {per_spacing * dx, per_spacing * dz, value};
}

// From the summed components of one pattern (direct summation), for η (axis −1) or D along the
// axis 0 (x) or 1 (z).
FieldBounds summed_field_bounds(const PatternSpectrum& s, const std::vector<Complex>& h, int axis) {
  const int n = s.pattern.resolution;
  const double dk = wavenumber_spacing(s.pattern.size);
  FieldBounds bounds;
  for (int b = 0; b < n; ++b) {
    for (int a = 0; a < n; ++a) {
      const std::size_t k = grid_offset(a, b, n);
      const int alpha = wave_index(a, n), beta = wave_index(b, n);
      const Complex g =
          axis < 0 ? Complex(1.0)
                   : displacement_factor(axis == 0 ? alpha : beta, dk, s.inverse_wavenumber[k], n);
      const double amplitude = abs(g * h[k]);
      bounds.value += amplitude;
      bounds.d_dx += amplitude * std::fabs(alpha * dk);
      bounds.d_dz += amplitude * std::fabs(beta * dk);
    }
  }
  return bounds;
}
}  // namespace

DisplacedSurfaceBounds displaced_surface_bounds(const Ocean& ocean,
                                                const std::vector<CascadeFields>& fields,
                                                const std::vector<EvolvedCascade>& evolved,
                                                Interpolation mode) {
  expect_fields(ocean, fields, evolved, mode);
  // Sums over cascades of the bounds of D_x, η, D_z (D scaled by |u|).
  std::array<FieldBounds, 3> sum{};
  for (std::size_t i = 0; i < ocean.cascades.size(); ++i) {
    const double u = std::fabs(ocean.cascades[i].choppiness);
    static constexpr std::array<Field, 3> kComponents{Field::displacement_x, Field::height,
                                                      Field::displacement_z};
    static constexpr std::array<int, 3> kAxes{0, -1, 1};  // summed_field_bounds' axis
    for (std::size_t c = 0; c < 3; ++c) {
      const FieldBounds f =
          mode == Interpolation::direct
              ? summed_field_bounds(ocean.cascades[i].low, evolved[i].low, kAxes[c])
              : grid_field_bounds(fields[i].values[static_cast<std::size_t>(kComponents[c])],
                                  fields[i].low_resolution, fields[i].size, mode);
      const double scale = c == 1 ? 1.0 : u;
      sum[c].d_dx += scale * f.d_dx;
      sum[c].d_dz += scale * f.d_dz;
      sum[c].value += scale * f.value;
    }
  }
  DisplacedSurfaceBounds out;
  // sqrt is correctly rounded everywhere (hypot is not): the same bits on every platform.
  for (std::size_t c = 0; c < 3; ++c) {
    out.lipschitz[c] = std::sqrt(sum[c].d_dx * sum[c].d_dx + sum[c].d_dz * sum[c].d_dz);
  }
  out.offset = {sum[0].value, sum[1].value, sum[2].value};
  if (ocean.synthesis == Synthesis::tiling_and_blending) {
    // A tile turned by θ mixes D_x and D_z: each bounded by |D| ≤ √(M_x² + M_z²), its gradient by
    // L_x + L_z. The blend Σ w_v f_v: |·| ≤ √3 M, |∇·| ≤ √3 L + (12/a) M (tiling.h).
    if (ocean.tiling.flow.kind != FlowKind::none) {
      const double m = std::sqrt(out.offset[0] * out.offset[0] + out.offset[2] * out.offset[2]);
      const double l = out.lipschitz[0] + out.lipschitz[2];
      out.offset[0] = out.offset[2] = m;
      out.lipschitz[0] = out.lipschitz[2] = l;
    }
    const double g = blend_weight_gradient_bound(ocean.tiling);
    for (std::size_t c = 0; c < 3; ++c) {
      out.lipschitz[c] = kBlendWeightSumBound * out.lipschitz[c] + g * out.offset[c];
      out.offset[c] *= kBlendWeightSumBound;
    }
  } else if (ocean.synthesis == Synthesis::noise_blended) {
    // (1 − w)q + w A n(x/λ): |n| ≤ √2, |∇n| ≤ kGradientNoiseSlopeBound per lattice unit.
    const NoiseBlend& n = ocean.noise;
    for (std::size_t c = 0; c < 3; ++c) {
      out.lipschitz[c] = (1.0 - n.weight) * out.lipschitz[c] +
                         n.weight * n.amplitude[c] * kGradientNoiseSlopeBound / n.cell;
      out.offset[c] =
          (1.0 - n.weight) * out.offset[c] + n.weight * n.amplitude[c] * kGradientNoiseValueBound;
    }
  }
  return out;
}

}  // namespace oceanref
