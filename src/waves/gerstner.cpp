#include "waves/gerstner.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "core/errors.h"
#include "core/format.h"
#include "core/math.h"
#include "core/quadrature.h"
#include "spectrum/dispersion.h"
#include "spectrum/moments.h"
#include "waves/random.h"

namespace oceanref {

namespace {
constexpr double kPi = std::numbers::pi;
constexpr int kMaxGerstnerLatticePoints = 4096;

// "gerstner <field> must be in <range>, got <value>" under the field's key.
[[noreturn]] void reject(const char* key, const std::string& range, double value) {
  throw SettingError(key, std::string("gerstner ") + key + " must be in " + range + ", got " +
                              shortest_number(value));
}

// Wavenumber bin edge i of n: k_min (k_max/k_min)^{i/n}, the ends exact (equal in log k;
// gerstner.h, draw_gerstner_waves).
double gerstner_wavenumber_edge(const GerstnerDraw& d, int i, int n) {
  if (i == 0) return d.min_wavenumber;
  if (i == n) return d.max_wavenumber;
  const double t = static_cast<double>(i) / static_cast<double>(n);
  return d.min_wavenumber * math::exp(t * math::log(d.max_wavenumber / d.min_wavenumber));
}

// Direction bin edge j of n: φ_wind − π + 2πj/n (the wind direction is an edge when n is even,
// so the cos-2s peak is split evenly; gerstner.h, draw_gerstner_waves).
double gerstner_direction_edge(const Spectrum& s, int j, int n) {
  return s.wind_direction - kPi + 2.0 * kPi * static_cast<double>(j) / static_cast<double>(n);
}

// The breakpoints of a list inside (lo, hi), with lo and hi around them, ascending (the form
// core/quadrature.h's integrate takes).
std::vector<double> gerstner_breakpoints(double lo, double hi, const std::vector<double>& inner) {
  std::vector<double> b{lo};
  for (const double x : inner) {
    if (x > lo && x < hi) b.push_back(x);
  }
  std::sort(b.begin() + 1, b.end());
  b.push_back(hi);
  return b;
}

// ∫_{θ0}^{θ1} D(k, θ) dθ  (model.h: D [1/rad]), split where the spreading functions peak or
// have kinks: the wind direction, ±π/2 and ±π from it.
double gerstner_direction_integral(const Spectrum& s, double k, double theta0, double theta1,
                                   const QuadratureTolerance& tolerance, int i, int j) {
  const double phi = s.wind_direction;
  const std::vector<double> inner{phi - kPi, phi - 0.5 * kPi, phi, phi + 0.5 * kPi, phi + kPi};
  const SpreadingAt d = spreading_at(s, angular_frequency(s.dispersion, k), k);
  const QuadratureResult r =
      integrate([&](double theta) { return directional_spreading(d, theta); },
                gerstner_breakpoints(theta0, theta1, inner), tolerance);
  if (!r.converged) {
    throw std::runtime_error("draw_gerstner_waves: the directional integral of cell (" +
                             std::to_string(i) + ", " + std::to_string(j) + ") did not converge");
  }
  return r.value;
}

// V = ∫∫cell Θ k dk dθ = ∫ Ψ(k) ∫ D dθ dk  (model.h: Θ = ΨD/k; the cell's variance).
double gerstner_cell_variance(const Spectrum& s, double k0, double k1, double theta0, double theta1,
                              const QuadratureTolerance& outer, const QuadratureTolerance& inner,
                              int i, int j) {
  const QuadratureResult r = integrate(
      [&](double k) {
        const double psi = wavenumber_spectrum(s, k);
        if (psi == 0.0) return 0.0;
        return psi * gerstner_direction_integral(s, k, theta0, theta1, inner, i, j);
      },
      gerstner_breakpoints(k0, k1, wavenumber_breakpoints(s, k1)), outer);
  if (!r.converged) {
    throw std::runtime_error("draw_gerstner_waves: the variance of cell (" + std::to_string(i) +
                             ", " + std::to_string(j) + ") did not converge");
  }
  return r.value;
}

// m_band = ∫_{k_min}^{k_max} Ψ dk  (Gamper A.1's m0 restricted to the band): the scale of the
// absolute quadrature tolerances.
double gerstner_band_variance(const Spectrum& s, double k_min, double k_max) {
  const QuadratureResult r =
      integrate([&](double k) { return wavenumber_spectrum(s, k); },
                gerstner_breakpoints(k_min, k_max, wavenumber_breakpoints(s, k_max)),
                QuadratureTolerance{1e-10, 0.0, 4000});
  if (!r.converged) throw std::runtime_error("draw_gerstner_waves: ∫Ψ dk did not converge");
  return r.value;
}

// A = √(2V), so ½A² = V: the cell's variance exactly, where Gamper eq. 4.2 gives it in the mean
// (E|h0|² = 2ΘΔk², η's amplitude |h0|).
double gerstner_amplitude(double variance) {
  return std::sqrt(2.0 * variance);
}

// The per-wave raw fields added into `sum` (the lines of the header comment; Tessendorf 2001
// §3.1 for η and D, their analytic derivatives as fields.h's multipliers ik and k_a k_b/k).
void gerstner_add_wave(const GerstnerWave& w, double x, double z, double time,
                       std::array<double, kFieldCount>& sum) {
  const math::SinCos dir = math::sincos(w.direction);
  const math::SinCos p = math::sincos(gerstner_phase(w, dir.cos, dir.sin, x, z, time));
  const double a_sin = w.amplitude * p.sin;
  const double ka_cos = w.wavenumber * (w.amplitude * p.cos);
  const double kx = w.wavenumber * dir.cos;
  const double kz = w.wavenumber * dir.sin;
  auto add = [&](Field f, double v) { sum[static_cast<std::size_t>(f)] += v; };
  add(Field::height, w.amplitude * p.cos);
  add(Field::slope_x, -kx * a_sin);
  add(Field::slope_z, -kz * a_sin);
  add(Field::displacement_x, dir.cos * a_sin);
  add(Field::displacement_z, dir.sin * a_sin);
  add(Field::ddx_dx, (dir.cos * dir.cos) * ka_cos);
  add(Field::ddz_dz, (dir.sin * dir.sin) * ka_cos);
  add(Field::ddx_dz, (dir.cos * dir.sin) * ka_cos);
}
}  // namespace

void validate(const GerstnerDraw& d) {
  if (!(d.count >= 1 && d.count <= kMaxGerstnerWaves)) reject("count", "[1, 1024]", d.count);
  if (!(d.direction_bins >= 1 && d.direction_bins <= d.count && d.count % d.direction_bins == 0)) {
    reject("direction_bins", "[1, count] and divide count = " + std::to_string(d.count),
           d.direction_bins);
  }
  if (!(d.choppiness <= 0.0 && std::isfinite(d.choppiness))) {
    reject("choppiness", "(-inf, 0]", d.choppiness);
  }
  if (!(d.min_wavenumber > 0.0 && d.min_wavenumber < kMaxMomentWavenumber)) {
    reject("min_wavenumber", "(0, 1e6) rad/m", d.min_wavenumber);
  }
  if (!(d.max_wavenumber > d.min_wavenumber && d.max_wavenumber <= kMaxMomentWavenumber)) {
    reject("max_wavenumber",
           "(min_wavenumber = " + shortest_number(d.min_wavenumber) + ", 1e6] rad/m",
           d.max_wavenumber);
  }
}

void validate(const GerstnerWaves& g) {
  if (!(g.choppiness <= 0.0 && std::isfinite(g.choppiness))) {
    reject("choppiness", "(-inf, 0]", g.choppiness);
  }
  for (const GerstnerWave& w : g.waves) {
    if (!(w.amplitude >= 0.0 && std::isfinite(w.amplitude))) {
      reject("amplitude", "[0, inf) m", w.amplitude);
    }
    if (!(w.wavenumber >= 0.0 && std::isfinite(w.wavenumber))) {
      reject("wavenumber", "[0, inf) rad/m", w.wavenumber);
    }
    if (!std::isfinite(w.direction)) reject("direction", "the finite numbers", w.direction);
    if (!std::isfinite(w.phase)) reject("phase", "the finite numbers", w.phase);
    if (!std::isfinite(w.angular_frequency)) {
      reject("angular_frequency", "the finite numbers", w.angular_frequency);
    }
  }
}

double gerstner_phase(const GerstnerWave& w, double cos_theta, double sin_theta, double x, double z,
                      double time) {
  const double kx = w.wavenumber * cos_theta;
  const double kz = w.wavenumber * sin_theta;
  return ((kx * x + kz * z) - w.angular_frequency * time) + w.phase;
}

std::array<double, kFieldCount> gerstner_raw_fields(const GerstnerWaves& g, double x, double z,
                                                    double time) {
  std::array<double, kFieldCount> sum{};
  for (const GerstnerWave& w : g.waves) gerstner_add_wave(w, x, z, time, sum);
  return sum;
}

SlopeVariance gerstner_slope_variance(const GerstnerWaves& g, double wind_direction) {
  SlopeVariance v;
  for (const GerstnerWave& w : g.waves) {
    const math::SinCos cs = math::sincos(w.direction - wind_direction);
    const double power = 0.5 * w.amplitude * w.amplitude * w.wavenumber * w.wavenumber;
    v.upwind += power * cs.cos * cs.cos;
    v.crosswind += power * cs.sin * cs.sin;
  }
  return v;
}

PointFields gerstner_point(const GerstnerWaves& g, double x, double z, double time) {
  PointFields p;
  add_cascade(p, gerstner_raw_fields(g, x, z, time), g.choppiness);
  finish_surface_combination(p);
  return p;
}

GerstnerWaves draw_gerstner_waves(const Spectrum& s, const GerstnerDraw& d, std::uint64_t seed) {
  validate(d);
  const int n_theta = d.direction_bins;
  const int n_k = d.count / n_theta;
  const double band = gerstner_band_variance(s, d.min_wavenumber, d.max_wavenumber);
  const double absolute = 1e-12 * band / static_cast<double>(d.count);
  const QuadratureTolerance outer{1e-10, absolute, 4000};
  const QuadratureTolerance inner{1e-11, 1e-12 / static_cast<double>(d.count), 4000};
  GerstnerWaves out;
  out.choppiness = d.choppiness;
  out.min_wavenumber = d.min_wavenumber;
  out.max_wavenumber = d.max_wavenumber;
  out.waves.reserve(static_cast<std::size_t>(d.count));
  for (int i = 0; i < n_k; ++i) {
    const double k0 = gerstner_wavenumber_edge(d, i, n_k);
    const double k1 = gerstner_wavenumber_edge(d, i + 1, n_k);
    for (int j = 0; j < n_theta; ++j) {
      const double theta0 = gerstner_direction_edge(s, j, n_theta);
      const double theta1 = gerstner_direction_edge(s, j + 1, n_theta);
      const double variance = gerstner_cell_variance(s, k0, k1, theta0, theta1, outer, inner, i, j);
      const std::uint64_t key = component_key(seed, kGerstnerCascade, i, j);
      const double xi_k = uniform_open(random_word(key, 0));
      const double xi_theta = uniform_open(random_word(key, 1));
      const double xi_phase = uniform_open(random_word(key, 2));
      GerstnerWave w;
      w.amplitude = gerstner_amplitude(variance);
      w.wavenumber = k0 * math::exp(xi_k * math::log(k1 / k0));
      w.direction = theta0 + xi_theta * (theta1 - theta0);
      w.phase = 2.0 * kPi * xi_phase;
      w.angular_frequency = angular_frequency(s.dispersion, w.wavenumber);
      out.waves.push_back(w);
    }
  }
  return out;
}

double gerstner_steepness_bound(const GerstnerWaves& g) {
  double sum = 0.0;
  for (const GerstnerWave& w : g.waves) sum += w.wavenumber * w.amplitude;
  return std::fabs(g.choppiness) * sum;
}

GerstnerLoops gerstner_loops(const GerstnerWaves& g, double time, double x_min, double z_min,
                             double extent, int points) {
  if (!(points >= 1 && points <= kMaxGerstnerLatticePoints)) {
    throw std::invalid_argument("gerstner_loops: points must be in [1, 4096], got " +
                                std::to_string(points));
  }
  if (!(extent > 0.0 && std::isfinite(extent))) {
    throw std::invalid_argument("gerstner_loops: extent must be in (0, inf) m, got " +
                                shortest_number(extent));
  }
  if (!(std::isfinite(time) && std::isfinite(x_min) && std::isfinite(z_min))) {
    throw std::invalid_argument("gerstner_loops: time, x_min and z_min must be finite");
  }
  const double h = extent / static_cast<double>(points);
  const double u = g.choppiness;
  GerstnerLoops out;
  out.min_jacobian = std::numeric_limits<double>::infinity();
  long long folded = 0;
  for (int n = 0; n < points; ++n) {
    const double z = z_min + static_cast<double>(n) * h;
    for (int m = 0; m < points; ++m) {
      const double x = x_min + static_cast<double>(m) * h;
      const std::array<double, kFieldCount> raw = gerstner_raw_fields(g, x, z, time);
      const auto field = [&](Field f) { return u * raw[static_cast<std::size_t>(f)]; };
      // det J = (1 + u∂D_x/∂x)(1 + u∂D_z/∂z) − (u∂D_x/∂z)²  (Gamper eq. 4.26)
      const double det =
          jacobian_determinant(field(Field::ddx_dx), field(Field::ddz_dz), field(Field::ddx_dz));
      if (det < 0.0) ++folded;
      if (det < out.min_jacobian) {
        out.min_jacobian = det;
        out.min_x = x;
        out.min_z = z;
      }
    }
  }
  const double total = static_cast<double>(points) * static_cast<double>(points);
  out.folded_fraction = static_cast<double>(folded) / total;
  return out;
}

}  // namespace oceanref
