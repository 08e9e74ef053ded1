#include "waves/footprint_filter.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>
#include <utility>

#include "core/check.h"
#include "core/fp_environment.h"
#include "core/math.h"
#include "core/parallel.h"

namespace oceanref {

WindFrameWavevector folded_wavevector(WindFrameWavevector k) {
  if (k.across < 0.0 || (k.across == 0.0 && k.along < 0.0)) return {-k.along, -k.across};
  return k;
}

namespace {
constexpr double kPi = std::numbers::pi;
// The table's axes (footprint_filter.h).
// Node r of the radius axis is λ₁ = r_1²·2^{r − kRadiusOffset}: √λ₁ from r_1/8 in ½ octaves.
constexpr int kRadiusOffset = 6;
constexpr int kRatioNodes = 9;   // log2 √(λ₂/λ₁) = −8, −7, …, 0
constexpr int kAngleNodes = 16;  // over [0, π)
// The mode bins.
constexpr int kBinsPerOctave = 8;
constexpr int kAngleBins = 64;

double log2_of(double x) {
  return math::log(x) / std::numbers::ln2;
}

// A footprint in the wind frame (u along the wind, v across it): its eigen-decomposition.
struct FootprintAxes {
  double major = 0.0;  // λ₁ ≥ λ₂ ≥ 0 [m²]
  double minor = 0.0;
  double angle = 0.0;  // of the major axis from the wind, in [0, π)
};

// The major axis' direction in the wind frame and the eigenvalues, for kᵀΣk.
struct FootprintQuadratic {
  double major = 0.0, minor = 0.0, cos_angle = 1.0, sin_angle = 0.0;
  explicit FootprintQuadratic(const FootprintAxes& a)
      : major(a.major),
        minor(a.minor),
        cos_angle(math::cos(a.angle)),
        sin_angle(math::sin(a.angle)) {}
  // kᵀΣk for a wavevector in the wind frame.
  double exponent(double k_along, double k_across) const {
    const double along_major = cos_angle * k_along + sin_angle * k_across;
    const double along_minor = -sin_angle * k_along + cos_angle * k_across;
    return major * along_major * along_major + minor * along_minor * along_minor;
  }
};

// (c, s) = (cos φ, sin φ) of the wind.
FootprintAxes footprint_axes(const Footprint& f, double c, double s) {
  // Σ_wind = Rᵀ Σ R with R's columns the wind (c, s) and across it (−s, c).
  const double uu = c * c * f.xx + 2.0 * c * s * f.xz + s * s * f.zz;
  const double vv = s * s * f.xx - 2.0 * c * s * f.xz + c * c * f.zz;
  const double uv = (c * c - s * s) * f.xz + c * s * (f.zz - f.xx);
  const double mean = 0.5 * (uu + vv);
  const double spread = math::hypot(0.5 * (uu - vv), uv);
  FootprintAxes a;
  a.major = mean + spread;
  a.minor = std::fmax(0.0, mean - spread);
  double angle = 0.5 * math::atan2(2.0 * uv, uu - vv);  // (−π/2, π/2]
  if (angle < 0.0) angle += kPi;
  a.angle = angle >= kPi ? 0.0 : angle;
  return a;
}

// The per-axis weights of one mode (or bin) in V: |h|²(k·ê)² for ê along and across the wind.
struct ModeWeight {
  double k_along = 0.0, k_across = 0.0;  // the wavevector in the wind frame [rad/m]
  double along = 0.0, across = 0.0;      // Σ|h|²k_along², Σ|h|²k_across² [1]
  JacobianMoments jacobian;              // Σ u²|h|² k_a^a k_c^b/k² (a + b = 4) [1]
};

// The bracket of V for one mode: (1 − ŵ²) + (ŵ − T)².
double footprint_loss(double exponent, double transfer) {
  const double w = math::exp(-0.5 * exponent);
  return (1.0 - w * w) + (w - transfer) * (w - transfer);
}

// The slopes' patterns (as slope_budget).
const PatternSpectrum& slope_pattern(const CascadeSpectra& c, ShadingNormals normals) {
  return normals == ShadingNormals::surface ? c.low : c.high;
}

// Calls visit(k_along, k_across, |h|², u) for every mode with |h| > 0 of the frame's slope
// patterns (u the choppiness of its cascade).
template <class Visit>
void for_each_mode(const Ocean& ocean, double time, ShadingNormals normals, const Visit& visit) {
  const double c = math::cos(ocean.spectrum.wind_direction);
  const double s = math::sin(ocean.spectrum.wind_direction);
  for (const CascadeSpectra& cascade : ocean.cascades) {
    const PatternSpectrum& p = slope_pattern(cascade, normals);
    const std::vector<Complex> h = spectrum_at_time(p, time);
    const int n = p.pattern.resolution;
    const double dk = wavenumber_spacing(p.pattern.size);
    for (int b = 0; b < n; ++b) {
      for (int a = 0; a < n; ++a) {
        const Complex v = h[grid_offset(a, b, n)];
        const double power = v.re * v.re + v.im * v.im;
        if (power == 0.0) continue;
        const double kx = wave_index(a, n) * dk, kz = wave_index(b, n) * dk;
        visit(c * kx + s * kz, -s * kx + c * kz, power, cascade.choppiness);
      }
    }
  }
}

// The modes of the frame in bins of |k| and direction (folded to [0, π): V is even in k).
std::vector<ModeWeight> binned_modes(const Ocean& ocean, double time, ShadingNormals normals) {
  struct Bin {
    double weight = 0.0, k_along = 0.0, k_across = 0.0, along = 0.0, across = 0.0;
    JacobianMoments jacobian;
  };
  double smallest = std::numeric_limits<double>::infinity();
  for (const CascadeSpectra& c : ocean.cascades) {
    smallest = std::fmin(smallest, wavenumber_spacing(slope_pattern(c, normals).pattern.size));
  }
  const double origin = std::floor(log2_of(smallest) * kBinsPerOctave) - 1.0;
  std::vector<Bin> bins;
  for_each_mode(ocean, time, normals, [&](double k_along, double k_across, double power, double u) {
    const auto [ka, kc] = folded_wavevector({k_along, k_across});
    const double k2 = ka * ka + kc * kc;
    const auto radial =
        static_cast<std::size_t>(std::floor(0.5 * log2_of(k2) * kBinsPerOctave) - origin);
    const auto angular = std::min<std::size_t>(
        kAngleBins - 1, static_cast<std::size_t>(math::atan2(kc, ka) / kPi * kAngleBins));
    const std::size_t index = radial * kAngleBins + angular;
    if (index >= bins.size()) bins.resize(index + 1);
    Bin& bin = bins[index];
    const double weight = power * k2;
    bin.weight += weight;
    bin.k_along += weight * ka;
    bin.k_across += weight * kc;
    bin.along += power * ka * ka;
    bin.across += power * kc * kc;
    bin.jacobian = bin.jacobian + jacobian_moments_of_mode(ka, kc, u * u * power);
  });
  std::vector<ModeWeight> modes;
  for (const Bin& bin : bins) {
    if (bin.weight == 0.0) continue;
    modes.push_back(
        {bin.k_along / bin.weight, bin.k_across / bin.weight, bin.along, bin.across, bin.jacobian});
  }
  return modes;
}

// h0·G on the first `resolution` wave indices (α, β ∈ [−N′/2, N′/2)) of a pattern.
PatternSpectrum filtered_pattern(const PatternSpectrum& p, double radius, int resolution) {
  const int n = p.pattern.resolution;
  PatternSpectrum out;
  out.pattern = p.pattern;
  out.pattern.resolution = resolution;
  const std::size_t cells = grid_cells(resolution);
  out.h0.resize(cells);
  out.inverse_wavenumber.resize(cells);
  out.omega.resize(cells);
  const double dk = wavenumber_spacing(p.pattern.size);
  for (int b = 0; b < resolution; ++b) {
    for (int a = 0; a < resolution; ++a) {
      const int alpha = wave_index(a, resolution), beta = wave_index(b, resolution);
      const std::size_t from = grid_offset(array_index(alpha, n), array_index(beta, n), n);
      const std::size_t to = grid_offset(a, b, resolution);
      const double g = gaussian_transfer(radius, dk * math::hypot(alpha, beta));
      out.h0[to] = {g * p.h0[from].re, g * p.h0[from].im};
      out.inverse_wavenumber[to] = p.inverse_wavenumber[from];
      out.omega[to] = p.omega[from];
    }
  }
  return out;
}

// The grid of a level: the coarsest power of two ≥ 4 with spacing ≤ r/2, at most N.
int level_resolution(double size, int resolution, double radius) {
  int n = 4;
  while (n < resolution && size / n > 0.5 * radius) n *= 2;
  return std::min(n, resolution);
}

// A cascade's N_l and N_h grids at a level. With multi-resolution the two patterns hold
// different bands (cascade_bands per resolution): their levels keep distinct grids, N_h's finer
// (synthesize_cascade reads one spectrum when the two resolutions are equal).
std::pair<int, int> level_grids(double size, int low_resolution, int high_resolution,
                                double radius) {
  const int low = level_resolution(size, low_resolution, radius);
  if (low_resolution == high_resolution) return {low, low};
  return {low, std::max(level_resolution(size, high_resolution, radius), 2 * low)};
}

Ocean filtered_ocean(const Ocean& ocean, double radius) {
  OCEANREF_EXPECTS(!ocean.gerstner, "a footprint filter of an FFT ocean");
  Ocean out{ocean.spectrum, {}, ocean.filter, ocean.synthesis, ocean.tiling, ocean.noise, {}};
  for (const CascadeSpectra& c : ocean.cascades) {
    CascadeSpectra f;
    const auto [low, high] = level_grids(c.low.pattern.size, c.low.pattern.resolution,
                                         c.high.pattern.resolution, radius);
    f.low = filtered_pattern(c.low, radius, low);
    f.high = high == low ? f.low : filtered_pattern(c.high, radius, high);
    f.choppiness = c.choppiness;
    out.cascades.push_back(std::move(f));
  }
  return out;
}

// r_1 = a quarter of the finest grid spacing (sizes L_i on N_h); levels up to the first r_L ≥
// the largest size.
std::vector<double> level_radii(const std::vector<double>& sizes, int resolution) {
  double finest = std::numeric_limits<double>::infinity(), largest = 0.0;
  for (const double size : sizes) {
    finest = std::fmin(finest, size / resolution);
    largest = std::fmax(largest, size);
  }
  std::vector<double> radii{0.0, 0.25 * finest};
  while (radii.back() < largest) radii.push_back(2.0 * radii.back());
  return radii;
}

template <class T>
T blend(const T& a, const T& b, double weight) {
  return (1.0 - weight) * a + weight * b;
}

std::size_t table_index(int radius, int ratio, int angle) {
  return (static_cast<std::size_t>(radius) * kRatioNodes + static_cast<std::size_t>(ratio)) *
             kAngleNodes +
         static_cast<std::size_t>(angle);
}

FootprintVarianceTable variance_table(const Ocean& ocean, double time, ShadingNormals normals,
                                      const std::vector<double>& radii, bool jacobian,
                                      int threads) {
  const std::vector<ModeWeight> modes = binned_modes(ocean, time, normals);
  FootprintVarianceTable t;
  t.first_radius_variance = radii[1] * radii[1];
  // Up to λ₁ = (2 r_L)² = r_1²·4^L.
  t.radius_nodes = 2 * static_cast<int>(radii.size() - 1) + kRadiusOffset + 1;
  t.values.resize(table_index(t.radius_nodes, 0, 0));
  if (jacobian) t.jacobian.resize(t.values.size());
  parallel_for(t.radius_nodes, threads, [&](int r) {
    const double major = std::ldexp(t.first_radius_variance, r - kRadiusOffset);
    const LevelBlend read = level_blend(radii, major);
    std::vector<double> transfer(modes.size());
    for (std::size_t m = 0; m < modes.size(); ++m) {
      transfer[m] = blend_transfer(radii, read, math::hypot(modes[m].k_along, modes[m].k_across));
    }
    for (int q = 0; q < kRatioNodes; ++q) {
      for (int a = 0; a < kAngleNodes; ++a) {
        const FootprintQuadratic sigma(FootprintAxes{
            major, std::ldexp(major, 2 * (q - (kRatioNodes - 1))), kPi * a / kAngleNodes});
        SlopeVariance v;
        JacobianMoments j;
        for (std::size_t m = 0; m < modes.size(); ++m) {
          const double loss =
              footprint_loss(sigma.exponent(modes[m].k_along, modes[m].k_across), transfer[m]);
          v.upwind += modes[m].along * loss;
          v.crosswind += modes[m].across * loss;
          if (jacobian) j = j + scaled(modes[m].jacobian, loss);
        }
        t.values[table_index(r, q, a)] = v;
        if (jacobian) t.jacobian[table_index(r, q, a)] = j;
      }
    }
  });
  return t;
}
}  // namespace

double footprint_major_variance(const Footprint& f) {
  return 0.5 * (f.xx + f.zz) + math::hypot(0.5 * (f.xx - f.zz), f.xz);
}

// A Gaussian of standard deviation r has the Fourier transform exp(−½ r²k²).
double gaussian_transfer(double radius, double wavenumber) {
  return math::exp(-0.5 * radius * radius * wavenumber * wavenumber);
}

LevelBlend level_blend(const std::vector<double>& radii, double read_variance) {
  OCEANREF_EXPECTS(radii.size() >= 2 && radii[0] == 0.0, "filter levels from radius 0");
  const int last = static_cast<int>(radii.size()) - 1;
  if (!(read_variance > 0.0)) return {0, 0.0};
  if (read_variance < radii[1] * radii[1]) return {0, read_variance / (radii[1] * radii[1])};
  const double octaves = 0.5 * log2_of(read_variance / (radii[1] * radii[1]));
  if (!(octaves < last - 1)) return {last, 0.0};
  const auto level = static_cast<int>(std::floor(octaves));
  return {level + 1, octaves - level};
}

double blend_transfer(const std::vector<double>& radii, const LevelBlend& b, double wavenumber) {
  const auto l = static_cast<std::size_t>(b.level);
  const double first = gaussian_transfer(radii[l], wavenumber);
  return b.weight == 0.0 ? first
                         : blend(first, gaussian_transfer(radii[l + 1], wavenumber), b.weight);
}

FootprintFilter make_footprint_filter(const Ocean& ocean, double time, Interpolation mode,
                                      ShadingNormals normals, bool jacobian, int threads) {
  const ReferenceFpEnvironment fp;
  FootprintFilter f;
  std::vector<double> sizes;
  for (const CascadeSpectra& c : ocean.cascades) sizes.push_back(c.high.pattern.size);
  f.radii = level_radii(sizes, ocean.cascades.front().high.pattern.resolution);
  f.wind_cos = math::cos(ocean.spectrum.wind_direction);
  f.wind_sin = math::sin(ocean.spectrum.wind_direction);
  f.levels.resize(f.radii.size() - 1);
  parallel_for(static_cast<int>(f.levels.size()), threads, [&](int l) {
    FilterLevel& level = f.levels[static_cast<std::size_t>(l)];
    level.ocean = filtered_ocean(ocean, f.radii[static_cast<std::size_t>(l) + 1]);
    if (mode == Interpolation::direct) {
      level.evolved = evolve_ocean(level.ocean, time);
    } else {
      level.grids = synthesize_ocean(level.ocean, time, 1);
    }
  });
  f.variance = variance_table(ocean, time, normals, f.radii, jacobian, threads);
  return f;
}

double footprint_filter_bytes(const WaveSettings& settings) {
  // Every level's cascades as wave grids of their own size (the table is small).
  const std::vector<double> radii = level_radii(settings.sizes, settings.resolution);
  double bytes = 0.0;
  for (std::size_t l = 1; l < radii.size(); ++l) {
    for (const double size : settings.sizes) {
      WaveSettings level;
      level.sizes = {size};
      std::tie(level.low_resolution, level.resolution) =
          level_grids(size, settings.low_resolution, settings.resolution, radii[l]);
      bytes += wave_grid_bytes(level);
    }
  }
  return bytes;
}

namespace {
// read(ocean, grids, evolved) of the two levels footprint `f` is read from (level 0: the frame's
// own), with the blend's weight; `second` is read only when the weight is not 0.
template <class Read>
auto read_levels(const Ocean& ocean, const std::vector<CascadeFields>& fields,
                 const std::vector<EvolvedCascade>& evolved, const FootprintFilter& filter,
                 const Footprint& f, const Read& read) {
  const LevelBlend b = level_blend(filter.radii, footprint_major_variance(f));
  const auto at = [&](int level) {
    if (level == 0) return read(ocean, fields, evolved);
    const FilterLevel& l = filter.levels[static_cast<std::size_t>(level) - 1];
    return read(l.ocean, l.grids, l.evolved);
  };
  const auto first = at(b.level);
  return std::tuple{first, b.weight == 0.0 ? first : at(b.level + 1), b.weight};
}
}  // namespace

PointFields filtered_fields_at(const Ocean& ocean, const std::vector<CascadeFields>& fields,
                               const std::vector<EvolvedCascade>& evolved,
                               const FootprintFilter& filter, double x, double z,
                               const Footprint& f, Interpolation mode, ShadingNormals normals) {
  const auto [first, second, weight] = read_levels(
      ocean, fields, evolved, filter, f, [&](const Ocean& o, const auto& g, const auto& e) {
        return combine_shading_at(o, g, e, x, z, mode, normals);
      });
  if (weight == 0.0) return first;
  const double w = weight;
  PointFields p;
  for (std::size_t i = 0; i < p.raw.size(); ++i) {
    p.raw[i] = blend(first.raw[i], second.raw[i], w);
  }
  p.ddz_dx = blend(first.ddz_dx, second.ddz_dx, w);
  p.height = blend(first.height, second.height, w);
  p.slope_x = blend(first.slope_x, second.slope_x, w);
  p.slope_z = blend(first.slope_z, second.slope_z, w);
  p.jacobian = blend(first.jacobian, second.jacobian, w);
  p.foam = blend(first.foam, second.foam, w);
  std::array<double, 3> n{};
  for (std::size_t c = 0; c < 3; ++c) n[c] = blend(first.normal[c], second.normal[c], w);
  const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (std::size_t c = 0; c < 3; ++c) p.normal[c] = n[c] / length;
  return p;
}

DisplacedPoint filtered_displaced_point(const Ocean& ocean,
                                        const std::vector<CascadeFields>& fields,
                                        const std::vector<EvolvedCascade>& evolved,
                                        const FootprintFilter& filter, double x0, double z0,
                                        const Footprint& f, Interpolation mode,
                                        ShadingNormals normals) {
  const auto [first, second, weight] = read_levels(
      ocean, fields, evolved, filter, f, [&](const Ocean& o, const auto& g, const auto& e) {
        return displaced_point(o, g, e, x0, z0, mode, normals);
      });
  if (weight == 0.0) return first;
  const double w = weight;
  return {blend(first.x, second.x, w), blend(first.height, second.height, w),
          blend(first.z, second.z, w)};
}

namespace {
// The table's `values` (one per node) at footprint f: trilinear between nodes, below node 0 of the
// radius axis that node's value scaled by λ₁/λ₁(node 0) (V ∝ λ₁ as λ₁ → 0).
template <class T>
T table_value(const FootprintFilter& filter, const std::vector<T>& values, const Footprint& f) {
  const FootprintVarianceTable& t = filter.variance;
  const FootprintAxes axes = footprint_axes(f, filter.wind_cos, filter.wind_sin);
  if (!(axes.major > 0.0)) return {};
  const double first = std::ldexp(t.first_radius_variance, -kRadiusOffset);
  double position = log2_of(axes.major / first);
  double scale = 1.0;
  if (position < 0.0) {
    scale = axes.major / first;
    position = 0.0;
  }
  position = std::fmin(position, t.radius_nodes - 1.0);
  const double ratio =
      axes.minor > 0.0 ? std::clamp(0.5 * log2_of(axes.minor / axes.major) + (kRatioNodes - 1.0),
                                    0.0, kRatioNodes - 1.0)
                       : 0.0;
  const double angle = axes.angle / kPi * kAngleNodes;
  const int r0 = std::min(static_cast<int>(position), t.radius_nodes - 2);
  const int q0 = std::min(static_cast<int>(ratio), kRatioNodes - 2);
  const int a0 = std::min(static_cast<int>(angle), kAngleNodes - 1);
  const double wr = position - r0, wq = ratio - q0, wa = angle - a0;
  T v{};
  for (int i = 0; i < 8; ++i) {
    const int dr = i & 1, dq = (i >> 1) & 1, da = (i >> 2) & 1;
    const double w =
        (dr != 0 ? wr : 1.0 - wr) * (dq != 0 ? wq : 1.0 - wq) * (da != 0 ? wa : 1.0 - wa);
    v = v + scaled(values[table_index(r0 + dr, q0 + dq, (a0 + da) % kAngleNodes)], w);
  }
  return scaled(v, scale);
}
}  // namespace

SlopeVariance footprint_slope_variance(const FootprintFilter& filter, const Footprint& f) {
  return table_value(filter, filter.variance.values, f);
}

JacobianMoments footprint_jacobian_moments(const FootprintFilter& filter, const Footprint& f) {
  OCEANREF_EXPECTS(!filter.variance.jacobian.empty(),
                   "a footprint filter made with its Jacobian moments");
  return table_value(filter, filter.variance.jacobian, f);
}

FootprintResidual footprint_residual_exact(const Ocean& ocean, double time, ShadingNormals normals,
                                           const std::vector<double>& radii, const Footprint& f) {
  // kᵀΣk with k back in the world frame (x, z), not through the table's axes (footprint_axes):
  // an independent path for the tests of the table.
  const double c = math::cos(ocean.spectrum.wind_direction);
  const double s = math::sin(ocean.spectrum.wind_direction);
  const LevelBlend read = level_blend(radii, footprint_major_variance(f));
  FootprintResidual v;
  for_each_mode(ocean, time, normals, [&](double ka, double kc, double power, double u) {
    const double kx = c * ka - s * kc, kz = s * ka + c * kc;
    const double exponent = f.xx * kx * kx + 2.0 * f.xz * kx * kz + f.zz * kz * kz;
    const double loss = footprint_loss(exponent, blend_transfer(radii, read, math::hypot(ka, kc)));
    v.slopes.upwind += power * ka * ka * loss;
    v.slopes.crosswind += power * kc * kc * loss;
    v.jacobian = v.jacobian + jacobian_moments_of_mode(ka, kc, u * u * power * loss);
  });
  return v;
}

}  // namespace oceanref
