#include "waves/ocean.h"

#include <cmath>
#include <numbers>

#include "core/fp_environment.h"
#include "waves/direct_sum.h"
#include "waves/fft.h"
#include "waves/mastin.h"

namespace oceanref {

double default_minimum_wavelength(SpectrumModel model) {
  return model == SpectrumModel::unified ? 0.0 : kMinimumWavelength;
}

Ocean realize_ocean(const WaveSettings& settings, int threads) {
  const ReferenceFpEnvironment fp;
  Ocean ocean{make_spectrum(settings.spectrum), {}};
  const double k_max = settings.minimum_wavelength > 0.0
                           ? 2.0 * std::numbers::pi / settings.minimum_wavelength
                           : std::numeric_limits<double>::infinity();
  const std::vector<Band> high_bands =
      cascade_bands(settings.sizes, settings.resolution, settings.band_partitioning, k_max);
  const std::vector<Band> low_bands =
      cascade_bands(settings.sizes, settings.low_resolution, settings.band_partitioning, k_max);
  const int count = static_cast<int>(settings.sizes.size());
  ocean.cascades.resize(settings.sizes.size());
  parallel_for(count, threads, [&](int i) {
    const auto c = static_cast<std::size_t>(i);
    const auto index = static_cast<std::uint32_t>(i);
    CascadeSpectra& out = ocean.cascades[c];
    out.high = realize_pattern(ocean.spectrum, settings.seed,
                               {index, settings.sizes[c], settings.resolution, high_bands[c]});
    out.low =
        settings.low_resolution == settings.resolution
            ? out.high
            : realize_pattern(ocean.spectrum, settings.seed,
                              {index, settings.sizes[c], settings.low_resolution, low_bands[c]});
    out.choppiness = settings.choppiness[c];
  });
  return ocean;
}

std::vector<CascadeFields> synthesize_ocean(const Ocean& ocean, double time, int threads) {
  const ReferenceFpEnvironment fp;
  std::vector<CascadeFields> fields;
  for (const CascadeSpectra& c : ocean.cascades) {
    fields.push_back(synthesize_cascade(c.low, c.high, time, threads));
  }
  return fields;
}

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
}  // namespace

double sample_periodic(const std::vector<double>& grid, int n, double size, double x, double z) {
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
  const GridPoint p = locate(n, size, x, z);
  const int m0 = p.m;
  const int n0 = p.n;
  const double fu = p.fu;
  const double fv = p.fv;
  if (fu == 0.0 && fv == 0.0) return grid[grid_offset(m0, n0, n)];
  // Catmull–Rom weights of the nodes −1, 0, 1, 2.
  const auto weights = [](double t) {
    return std::array<double, 4>{0.5 * ((-t + 2.0) * t - 1.0) * t,
                                 0.5 * ((3.0 * t - 5.0) * t * t + 2.0),
                                 0.5 * ((-3.0 * t + 4.0) * t + 1.0) * t, 0.5 * (t - 1.0) * t * t};
  };
  const std::array<double, 4> wu = weights(fu);
  const std::array<double, 4> wv = weights(fv);
  double sum = 0.0;
  for (int j = 0; j < 4; ++j) {
    const int row = ((n0 + j - 1) % n + n) % n;
    double line = 0.0;
    for (int i = 0; i < 4; ++i) {
      const int column = ((m0 + i - 1) % n + n) % n;
      line += wu[static_cast<std::size_t>(i)] * grid[grid_offset(column, row, n)];
    }
    sum += wv[static_cast<std::size_t>(j)] * line;
  }
  return sum;
}

std::array<double, kFieldCount> cascade_from_grids(const CascadeFields& f, double x, double z,
                                                   Interpolation mode) {
  std::array<double, kFieldCount> raw{};
  for (int q = 0; q < kFieldCount; ++q) {
    const int n = is_low_resolution_field(Field(q)) ? f.low_resolution : f.high_resolution;
    const auto& grid = f.values[static_cast<std::size_t>(q)];
    raw[static_cast<std::size_t>(q)] = mode == Interpolation::bicubic
                                           ? sample_periodic_bicubic(grid, n, f.size, x, z)
                                           : sample_periodic(grid, n, f.size, x, z);
  }
  return raw;
}

PointFields combine_at(const Ocean& ocean, const std::vector<CascadeFields>& fields,
                       const std::vector<EvolvedCascade>& evolved, double x, double z,
                       Interpolation mode) {
  if (mode == Interpolation::direct) return combine_direct(ocean, evolved, x, z);
  PointFields sum;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    add_cascade(sum, cascade_from_grids(fields[i], x, z, mode), ocean.cascades[i].choppiness);
  }
  finish_combination(sum);
  return sum;
}

double height_bound(const Ocean& ocean) {
  double bound = 0.0;
  for (const CascadeSpectra& c : ocean.cascades) {
    for (const Complex& h : c.low.h0) bound += abs(h);  // η and D live on the low grid
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
  return evolved;
}

PointFields combine_direct(const Ocean& ocean, double x, double z, double time) {
  return combine_direct(ocean, evolve_ocean(ocean, time), x, z);
}

PointFields combine_direct(const Ocean& ocean, const std::vector<EvolvedCascade>& evolved, double x,
                           double z) {
  PointFields sum;
  for (std::size_t i = 0; i < ocean.cascades.size(); ++i) {
    const CascadeSpectra& c = ocean.cascades[i];
    add_cascade(sum, direct_sum(c.low, c.high, evolved[i], x, z), c.choppiness);
  }
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
                                              const std::vector<CascadeFields>& fields,
                                              int threads) {
  const int n = fields[0].high_resolution;
  const double spacing = fields[0].size / n;
  std::vector<PointFields> out(grid_cells(n));
  parallel_for(n, threads, [&](int row) {
    for (int m = 0; m < n; ++m) {
      out[grid_offset(m, row, n)] = combine_from_grids(ocean, fields, m * spacing, row * spacing);
    }
  });
  return out;
}

AccumulatedFoam accumulate_foam(const Ocean& ocean, double time, const FoamSequence& sequence,
                                int threads) {
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
    const std::vector<PointFields> sum = combine_on_footprint(ocean, frame, threads);
    if (foam.combined.empty()) foam.combined.assign(sum.size(), 0.0);
    for (std::size_t c = 0; c < sum.size(); ++c) {
      foam.combined[c] =
          accumulated_foam(foam.combined[c], sum[c].foam, sequence.decay, sequence.time_step);
    }
  }
  return foam;
}

}  // namespace oceanref
