#include "waves/ocean.h"

#include <cmath>
#include <numbers>

#include "core/check.h"
#include "core/fp_environment.h"
#include "core/parallel.h"
#include "waves/direct_sum.h"
#include "waves/fft.h"
#include "waves/mastin.h"

namespace oceanref {

double default_minimum_wavelength(SpectrumModel model) {
  return model == SpectrumModel::unified ? 0.0 : kMinimumWavelength;
}

double wave_grid_bytes(const WaveSettings& settings) {
  if (settings.model == WaveModel::gerstner) return 0.0;  // no grids (the set is small)
  const double high = static_cast<double>(settings.resolution) * settings.resolution;
  const double low = static_cast<double>(settings.low_resolution) * settings.low_resolution;
  // h0, 1/k and ω (PatternSpectrum); h(k, t) and the packed transform; the transform's input
  // and output copies; the eight fields.
  const double per_cell = sizeof(Complex) + 2 * sizeof(double) + 2 * sizeof(Complex) +
                          2 * sizeof(Complex) + kFieldCount * sizeof(double);
  return static_cast<double>(settings.sizes.size()) * (high + low) * per_cell;
}

Tiling resolve_tiling(const WaveSettings& settings) {
  double period = 0.0;
  for (const double size : settings.sizes) period = std::fmax(period, size);
  return {0.5 * settings.tiling.tile_size * period, period, settings.seed,
          settings.spectrum.wind_direction, settings.tiling.flow};
}

namespace {
// ½Σ_k|g h0(k)|² for g = d(k_x, k), 1, d(k_z, k) (eq. 4.18): the time mean of the spatial mean
// square of D_x, η and D_z of one pattern (|h(k, t)|² averages to ¼(|h0(k)|² + |h0(−k)|²)).
std::array<double, 3> pattern_mean_squares(const PatternSpectrum& s) {
  const int n = s.pattern.resolution;
  const double dk = wavenumber_spacing(s.pattern.size);
  std::array<double, 3> sums{};
  for (int b = 0; b < n; ++b) {
    for (int a = 0; a < n; ++a) {
      const std::size_t k = grid_offset(a, b, n);
      const double power = s.h0[k].re * s.h0[k].re + s.h0[k].im * s.h0[k].im;
      const double gx = displacement_factor(wave_index(a, n), dk, s.inverse_wavenumber[k], n).im;
      const double gz = displacement_factor(wave_index(b, n), dk, s.inverse_wavenumber[k], n).im;
      sums[0] += gx * gx * power;
      sums[1] += power;
      sums[2] += gz * gz * power;
    }
  }
  return {0.5 * sums[0], 0.5 * sums[1], 0.5 * sums[2]};
}

// Lutz eq. 2's noise for a realized ocean (noise.h): its mean squares those of the exemplar.
NoiseBlend resolve_noise(const WaveSettings& settings, const Ocean& ocean, double period) {
  std::array<double, 3> mean_squares{};
  for (const CascadeSpectra& c : ocean.cascades) {
    const std::array<double, 3> m = pattern_mean_squares(c.low);
    const double u2 = c.choppiness * c.choppiness;
    mean_squares[0] += u2 * m[0];
    mean_squares[1] += m[1];
    mean_squares[2] += u2 * m[2];
  }
  return make_noise_blend(settings.seed, settings.noise_weight, settings.noise_cell_size * period,
                          mean_squares);
}
}  // namespace

Ocean realize_ocean(const WaveSettings& settings, int threads) {
  const ReferenceFpEnvironment fp;
  Ocean ocean{make_spectrum(settings.spectrum), {}, {}, settings.synthesis, {}, {}, {}};
  if (settings.model == WaveModel::gerstner) {
    OCEANREF_EXPECTS(settings.synthesis == Synthesis::periodic,
                     "a Gerstner wave set is summed anywhere (no tiling or noise)");
    ocean.gerstner = draw_gerstner_waves(ocean.spectrum, settings.gerstner, settings.seed);
    return ocean;
  }
  OCEANREF_EXPECTS(!settings.sizes.empty() && settings.choppiness.size() == settings.sizes.size(),
                   "one choppiness per cascade: " + std::to_string(settings.choppiness.size()) +
                       " for " + std::to_string(settings.sizes.size()) + " sizes");
  if (settings.synthesis == Synthesis::tiling_and_blending) ocean.tiling = resolve_tiling(settings);
  if (settings.realization == Realization::mastin) {
    ocean.filter = make_mastin_filter(ocean.spectrum, settings.mastin);
  }
  const double k_max = settings.minimum_wavelength > 0.0
                           ? 2.0 * std::numbers::pi / settings.minimum_wavelength
                           : std::numeric_limits<double>::infinity();
  const std::vector<Band> high_bands = cascade_bands(
      settings.sizes, settings.resolution, settings.band_partitioning, k_max, settings.band_edges);
  const std::vector<Band> low_bands =
      cascade_bands(settings.sizes, settings.low_resolution, settings.band_partitioning, k_max,
                    settings.band_edges);
  const int count = static_cast<int>(settings.sizes.size());
  ocean.cascades.resize(settings.sizes.size());
  // h0 of one pattern by the scene's realization (one thread inside: the cascades are the
  // parallel loop, and the Mastin transform is the same for any thread count).
  const auto realize = [&](const Pattern& p) {
    return settings.realization == Realization::mastin
               ? realize_pattern_mastin(ocean.spectrum, settings.mastin, ocean.filter,
                                        settings.seed, p, 1)
               : realize_pattern(ocean.spectrum, settings.seed, p);
  };
  parallel_for(count, threads, [&](int i) {
    const auto c = static_cast<std::size_t>(i);
    const auto index = static_cast<std::uint32_t>(i);
    CascadeSpectra& out = ocean.cascades[c];
    out.high = realize({index, settings.sizes[c], settings.resolution, high_bands[c]});
    out.low = settings.low_resolution == settings.resolution
                  ? out.high
                  : realize({index, settings.sizes[c], settings.low_resolution, low_bands[c]});
    out.choppiness = settings.choppiness[c];
  });
  if (settings.synthesis == Synthesis::noise_blended) {
    ocean.noise = resolve_noise(settings, ocean, resolve_tiling(settings).period);
  }
  return ocean;
}

std::vector<CascadeFields> synthesize_ocean(const Ocean& ocean, double time, int threads,
                                            const FieldMask& wanted) {
  const ReferenceFpEnvironment fp;
  std::vector<CascadeFields> fields(ocean.cascades.size());
  SynthesisWorkspace work;
  for (std::size_t i = 0; i < ocean.cascades.size(); ++i) {
    const CascadeSpectra& c = ocean.cascades[i];
    synthesize_cascade(c.low, c.high, time, threads, fields[i], work, inverse_fft_2d, nullptr,
                       wanted);
  }
  return fields;
}

std::array<double, kFieldCount> cascade_from_grids(const CascadeFields& f, double x, double z,
                                                   Interpolation mode) {
  // The point is located once per grid resolution (N_l and N_h), not once per field.
  const Interpolation read =
      mode == Interpolation::bicubic ? Interpolation::bicubic : Interpolation::bilinear;
  const GridStencil low = grid_stencil(f.low_resolution, f.size, x, z, read);
  const GridStencil high = f.high_resolution == f.low_resolution
                               ? low
                               : grid_stencil(f.high_resolution, f.size, x, z, read);
  std::array<double, kFieldCount> raw{};
  for (int q = 0; q < kFieldCount; ++q) {
    raw[static_cast<std::size_t>(q)] = read_value(f.values[static_cast<std::size_t>(q)],
                                                  is_low_resolution_field(Field(q)) ? low : high);
  }
  return raw;
}

namespace {
void expect_evolved(const Ocean& ocean, const std::vector<EvolvedCascade>& evolved) {
  OCEANREF_EXPECTS(
      evolved.size() == ocean.cascades.size() + (ocean.gerstner ? 1 : 0),
      "one evolved spectrum per cascade (evolve_ocean): " + std::to_string(evolved.size()) +
          " for " + std::to_string(ocean.cascades.size()));
}

// The exemplar's raw sums over the cascades at (x, z), before finish_combination.
PointFields exemplar_sum(const Ocean& ocean, const std::vector<CascadeFields>& fields,
                         const std::vector<EvolvedCascade>& evolved, double x, double z,
                         Interpolation mode) {
  PointFields sum;
  for (std::size_t i = 0; i < ocean.cascades.size(); ++i) {
    const CascadeSpectra& c = ocean.cascades[i];
    add_cascade(sum,
                mode == Interpolation::direct ? direct_sum(c.low, c.high, evolved[i], x, z)
                                              : cascade_from_grids(fields[i], x, z, mode),
                c.choppiness);
  }
  if (ocean.gerstner) {
    OCEANREF_EXPECTS(mode == Interpolation::direct, "a Gerstner ocean is read directly");
    add_cascade(sum, gerstner_raw_fields(*ocean.gerstner, x, z, evolved.back().time),
                ocean.gerstner->choppiness);
  }
  return sum;
}
}  // namespace

PointFields combine_at(const Ocean& ocean, const std::vector<CascadeFields>& fields,
                       const std::vector<EvolvedCascade>& evolved, double x, double z,
                       Interpolation mode) {
  if (mode == Interpolation::direct) {
    expect_evolved(ocean, evolved);
  } else {
    OCEANREF_EXPECTS(fields.size() == ocean.cascades.size(),
                     "one field set per cascade: " + std::to_string(fields.size()) + " for " +
                         std::to_string(ocean.cascades.size()));
  }
  const auto exemplar = [&](double ex, double ez) {
    return exemplar_sum(ocean, fields, evolved, ex, ez, mode);
  };
  PointFields sum = synthesized_sum(ocean, x, z, exemplar);
  finish_combination(sum);
  return sum;
}

double height_bound(const Ocean& ocean) {
  double bound = 0.0;
  if (ocean.gerstner) {  // |η| ≤ ΣA, |D| ≤ ΣA
    for (const GerstnerWave& w : ocean.gerstner->waves) bound += w.amplitude;
  }
  for (const CascadeSpectra& c : ocean.cascades) {
    for (const Complex& h : c.low.h0) bound += abs(h);  // η and D live on the low grid
  }
  switch (ocean.synthesis) {
    case Synthesis::tiling_and_blending:
      return kBlendWeightSumBound * bound;
    case Synthesis::noise_blended:
      return (1.0 - ocean.noise.weight) * bound +
             ocean.noise.weight * ocean.noise.amplitude[1] * kGradientNoiseValueBound;
    case Synthesis::periodic:
      break;
  }
  return bound;
}

PointFields combine_from_grids(const Ocean& ocean, const std::vector<CascadeFields>& fields,
                               double x, double z) {
  return combine_at(ocean, fields, {}, x, z, Interpolation::bilinear);
}

std::vector<EvolvedCascade> evolve_ocean(const Ocean& ocean, double time) {
  std::vector<EvolvedCascade> evolved;
  for (const CascadeSpectra& c : ocean.cascades) {
    evolved.push_back(evolve_cascade(c.low, c.high, time));
  }
  if (ocean.gerstner) evolved.push_back({{}, {}, time});
  return evolved;
}

PointFields combine_direct(const Ocean& ocean, double x, double z, double time) {
  return combine_direct(ocean, evolve_ocean(ocean, time), x, z);
}

PointFields combine_direct(const Ocean& ocean, const std::vector<EvolvedCascade>& evolved, double x,
                           double z) {
  expect_evolved(ocean, evolved);
  PointFields sum = exemplar_sum(ocean, {}, evolved, x, z, Interpolation::direct);
  finish_combination(sum);
  return sum;
}

std::vector<double> cascade_jacobian(const CascadeFields& f, double u) {
  const auto& dxx = f.values[static_cast<std::size_t>(Field::ddx_dx)];
  const auto& dzz = f.values[static_cast<std::size_t>(Field::ddz_dz)];
  const auto& dxz = f.values[static_cast<std::size_t>(Field::ddx_dz)];
  std::vector<double> j(dxx.size());
  for (std::size_t i = 0; i < j.size(); ++i) {
    j[i] = jacobian_determinant(u * dxx[i], u * dzz[i], u * dxz[i]);
  }
  return j;
}

std::vector<PointFields> combine_on_footprint(const Ocean& ocean,
                                              const std::vector<EvolvedCascade>& evolved,
                                              ShadingNormals normals, int threads) {
  const ReferenceFpEnvironment fp;
  const CascadeSpectra& first = ocean.cascades[0];
  const int n = first.high.pattern.resolution;
  const double spacing = first.high.pattern.size / n;
  std::vector<PointFields> out(grid_cells(n));
  const std::vector<Field> low_fields{Field::height, Field::displacement_x, Field::displacement_z};
  const std::vector<Field> high_fields{Field::slope_x, Field::slope_z, Field::ddx_dx, Field::ddz_dz,
                                       Field::ddx_dz};
  const std::vector<Field> all_fields{Field::height,         Field::slope_x,        Field::slope_z,
                                      Field::displacement_x, Field::displacement_z, Field::ddx_dx,
                                      Field::ddz_dz,         Field::ddx_dz};
  for (std::size_t i = 0; i < ocean.cascades.size(); ++i) {
    const CascadeSpectra& c = ocean.cascades[i];
    const EvolvedCascade& h = evolved[i];
    LatticeFields lattice;
    if (normals == ShadingNormals::surface) {
      lattice = direct_sum_on_lattice(c.low, h.low, n, spacing, all_fields, true, threads);
    } else {
      lattice = direct_sum_on_lattice(c.low, h.low, n, spacing, low_fields, false, threads);
      LatticeFields high =
          direct_sum_on_lattice(c.high, h.high, n, spacing, high_fields, false, threads);
      for (const Field f : high_fields) {
        lattice.values[static_cast<std::size_t>(f)] =
            std::move(high.values[static_cast<std::size_t>(f)]);
      }
    }
    parallel_for(n, threads, [&](int row) {
      for (std::size_t p = grid_offset(0, row, n); p < grid_offset(0, row + 1, n); ++p) {
        CascadeSurface s;
        for (std::size_t f = 0; f < s.raw.size(); ++f) s.raw[f] = lattice.values[f][p];
        if (normals == ShadingNormals::surface) {
          s.ddz_dx = lattice.ddz_dx[p];
          add_cascade_surface(out[p], s, c.choppiness);
        } else {
          add_cascade(out[p], s.raw, c.choppiness);
        }
      }
    });
  }
  for (PointFields& p : out) {
    if (normals == ShadingNormals::surface) {
      finish_surface_combination(p);
    } else {
      finish_combination(p);
    }
  }
  return out;
}

int steady_foam_steps(double decay, double time_step) {
  OCEANREF_EXPECTS(decay > 0.0 && time_step > 0.0, "foam that decays over a positive time step");
  return static_cast<int>(std::floor(1.0 / (decay * time_step))) + 2;
}

AccumulatedFoam accumulate_foam(const Ocean& ocean, double time, const FoamSequence& sequence,
                                ShadingNormals normals, int threads) {
  const ReferenceFpEnvironment fp;
  AccumulatedFoam foam;
  foam.cascades.resize(ocean.cascades.size());
  for (int s = sequence.steps; s >= 0; --s) {
    const double t = time - s * sequence.time_step;
    const std::vector<CascadeFields> frame = synthesize_ocean(ocean, t, threads);
    for (std::size_t i = 0; i < frame.size(); ++i) {
      const std::vector<double> j = cascade_jacobian(frame[i], ocean.cascades[i].choppiness);
      std::vector<double>& f = foam.cascades[i];
      if (f.empty()) f.assign(j.size(), 0.0);
      for (std::size_t c = 0; c < j.size(); ++c) {
        f[c] = accumulated_foam(f[c], j[c] < 0.0 ? 1.0 : 0.0, sequence.decay, sequence.time_step);
      }
    }
    const std::vector<PointFields> sum =
        combine_on_footprint(ocean, evolve_ocean(ocean, t), normals, threads);
    if (foam.combined.empty()) foam.combined.assign(sum.size(), 0.0);
    for (std::size_t c = 0; c < sum.size(); ++c) {
      foam.combined[c] =
          accumulated_foam(foam.combined[c], sum[c].foam, sequence.decay, sequence.time_step);
    }
  }
  return foam;
}

}  // namespace oceanref
