#include "waves/direct_sum.h"

#include <cmath>
#include <numbers>

#include "core/check.h"
#include "core/math.h"
#include "core/parallel.h"
#include "waves/fft.h"

namespace oceanref {

namespace {
// e^{i·2π·α·x/L}, with the phase reduced modulo 2π exactly before the sine and cosine.
Complex wave_phase(int index, double position, double size) {
  const double cycles = index * (std::fmod(position, size) / size);
  const double turn = cycles - std::nearbyint(cycles);
  return unit_phasor(2.0 * std::numbers::pi * turn);
}

// The basis function along one axis and its derivative: e^{ikx}, ik e^{ikx}; or cos(kx),
// −k sin(kx) on the Nyquist line.
struct AxisBasis {
  Complex value;
  Complex derivative;
};
AxisBasis axis_basis(int index, double position, double size, int n) {
  const Complex e = wave_phase(index, position, size);
  const double k = index * wavenumber_spacing(size);
  if (is_nyquist(index, n)) return {e.re, -k * e.im};
  return {e, Complex(0.0, k) * e};
}

// The multipliers of one component: the displacement factors d(k_x, k), d(k_z, k) (eq. 4.18).
struct ComponentFactors {
  Complex gx, gz;
};
ComponentFactors component_factors(const PatternSpectrum& s, int a, int b) {
  const int n = s.pattern.resolution;
  const double dk = wavenumber_spacing(s.pattern.size);
  const double inverse_k = s.inverse_wavenumber[grid_offset(a, b, n)];
  return {displacement_factor(wave_index(a, n), dk, inverse_k, n),
          displacement_factor(wave_index(b, n), dk, inverse_k, n)};
}

// Which fields a pattern contributes: η and D, the slopes and ∂D, or both (and ∂D_z/∂x).
enum class Group { low, high, all };

void add_pattern(const PatternSpectrum& s, const std::vector<Complex>& h, double x, double z,
                 Group group, std::array<Complex, kFieldCount>& sum, Complex* ddz_dx) {
  const Pattern& p = s.pattern;
  const int n = p.resolution;
  for (int b = 0; b < n; ++b) {
    const int beta = wave_index(b, n);
    const AxisBasis bz = axis_basis(beta, z, p.size, n);
    for (int a = 0; a < n; ++a) {
      const Complex amplitude = h[grid_offset(a, b, n)];
      if (amplitude == 0.0) continue;
      const int alpha = wave_index(a, n);
      const AxisBasis bx = axis_basis(alpha, x, p.size, n);
      const ComponentFactors g = component_factors(s, a, b);
      const Complex e = bx.value * bz.value;
      auto add = [&](Field f, Complex term) {
        sum[static_cast<std::size_t>(f)] += amplitude * term;
      };
      if (group != Group::high) {
        add(Field::height, e);
        add(Field::displacement_x, g.gx * e);
        add(Field::displacement_z, g.gz * e);
      }
      if (group != Group::low) {
        add(Field::slope_x, bx.derivative * bz.value);
        add(Field::slope_z, bx.value * bz.derivative);
        add(Field::ddx_dx, g.gx * bx.derivative * bz.value);
        add(Field::ddz_dz, g.gz * bx.value * bz.derivative);
        add(Field::ddx_dz, g.gx * bx.value * bz.derivative);
      }
      if (ddz_dx != nullptr) *ddz_dx += amplitude * (g.gz * bx.derivative * bz.value);
    }
  }
}

// The lattice sums of one pattern: for each β, Σ_α over the value or derivative basis along x of
// h, g_x h or g_z h (the x-part), then Σ_β with the value or derivative basis along z.
enum class AlongX { value, derivative };
enum class Factor { one, gx, gz };
struct LatticeTerm {
  AlongX x;
  Factor factor;
  AlongX z;
};
LatticeTerm lattice_term(Field f) {
  switch (f) {
    case Field::height:
      return {AlongX::value, Factor::one, AlongX::value};
    case Field::slope_x:
      return {AlongX::derivative, Factor::one, AlongX::value};
    case Field::slope_z:
      return {AlongX::value, Factor::one, AlongX::derivative};
    case Field::displacement_x:
      return {AlongX::value, Factor::gx, AlongX::value};
    case Field::displacement_z:
      return {AlongX::value, Factor::gz, AlongX::value};
    case Field::ddx_dx:
      return {AlongX::derivative, Factor::gx, AlongX::value};
    case Field::ddz_dz:
      return {AlongX::value, Factor::gz, AlongX::derivative};
    case Field::ddx_dz:
      return {AlongX::value, Factor::gx, AlongX::derivative};
  }
  return {};
}
}  // namespace

EvolvedCascade evolve_cascade(const PatternSpectrum& low, const PatternSpectrum& high,
                              double time) {
  return {spectrum_at_time(low, time), spectrum_at_time(high, time), time};
}

std::array<double, kFieldCount> direct_sum(const PatternSpectrum& low, const PatternSpectrum& high,
                                           double x, double z, double time) {
  return direct_sum(low, high, evolve_cascade(low, high, time), x, z);
}

std::array<double, kFieldCount> direct_sum(const PatternSpectrum& low, const PatternSpectrum& high,
                                           const EvolvedCascade& h, double x, double z) {
  std::array<Complex, kFieldCount> sum{};
  add_pattern(low, h.low, x, z, Group::low, sum, nullptr);
  add_pattern(high, h.high, x, z, Group::high, sum, nullptr);
  std::array<double, kFieldCount> out{};
  for (std::size_t f = 0; f < out.size(); ++f) out[f] = sum[f].re;
  return out;
}

CascadeSurface direct_sum_surface(const PatternSpectrum& s, const std::vector<Complex>& h, double x,
                                  double z) {
  std::array<Complex, kFieldCount> sum{};
  Complex ddz_dx{};
  add_pattern(s, h, x, z, Group::all, sum, &ddz_dx);
  CascadeSurface out;
  for (std::size_t f = 0; f < out.raw.size(); ++f) out.raw[f] = sum[f].re;
  out.ddz_dx = ddz_dx.re;
  return out;
}

LatticeFields direct_sum_on_lattice(const PatternSpectrum& s, const std::vector<Complex>& h,
                                    int points, double spacing, const std::vector<Field>& fields,
                                    bool ddz_dx, int threads) {
  const int n = s.pattern.resolution;
  OCEANREF_EXPECTS(points >= 1 && spacing > 0.0 && h.size() == grid_cells(n),
                   "a lattice of >= 1 points with positive spacing and h(k, t) of N x N entries");
  const auto np = static_cast<std::size_t>(points);
  // The bases along one axis at the lattice positions: [index a][point m].
  std::vector<Complex> value(static_cast<std::size_t>(n) * np), derivative(value.size());
  parallel_for(n, threads, [&](int a) {
    for (int m = 0; m < points; ++m) {
      const AxisBasis e = axis_basis(wave_index(a, n), m * spacing, s.pattern.size, n);
      value[static_cast<std::size_t>(a) * np + static_cast<std::size_t>(m)] = e.value;
      derivative[static_cast<std::size_t>(a) * np + static_cast<std::size_t>(m)] = e.derivative;
    }
  });
  // Every (x-part, factor) pair the requested fields need, and the rows β that carry waves.
  std::vector<LatticeTerm> terms;
  for (const Field f : fields) terms.push_back(lattice_term(f));
  if (ddz_dx) terms.push_back({AlongX::derivative, Factor::gz, AlongX::value});
  const auto x_part = [](const LatticeTerm& t) {
    return static_cast<int>(t.x) * 3 + static_cast<int>(t.factor);
  };
  std::array<std::vector<Complex>, 6> partial;  // [x-part][b·points + m]
  for (const LatticeTerm& t : terms)
    partial[static_cast<std::size_t>(x_part(t))].assign(static_cast<std::size_t>(n) * np,
                                                        Complex{});
  std::vector<int> rows;
  for (int b = 0; b < n; ++b) {
    for (int a = 0; a < n; ++a) {
      if (!(h[grid_offset(a, b, n)] == 0.0)) {
        rows.push_back(b);
        break;
      }
    }
  }
  parallel_for(static_cast<int>(rows.size()), threads, [&](int r) {
    const int b = rows[static_cast<std::size_t>(r)];
    for (int a = 0; a < n; ++a) {
      const Complex amplitude = h[grid_offset(a, b, n)];
      if (amplitude == 0.0) continue;
      const ComponentFactors g = component_factors(s, a, b);
      const std::array<Complex, 3> scaled{amplitude, g.gx * amplitude, g.gz * amplitude};
      for (std::size_t part = 0; part < partial.size(); ++part) {
        std::vector<Complex>& out = partial[part];
        if (out.empty()) continue;
        const Complex c = scaled[part % 3];
        const std::vector<Complex>& basis = part < 3 ? value : derivative;
        const std::size_t in = static_cast<std::size_t>(a) * np;
        const std::size_t row = static_cast<std::size_t>(b) * np;
        for (std::size_t m = 0; m < np; ++m) out[row + m] += c * basis[in + m];
      }
    }
  });
  LatticeFields out;
  out.points = points;
  out.spacing = spacing;
  const auto sum_rows = [&](const LatticeTerm& t, std::vector<double>& result) {
    result.assign(np * np, 0.0);
    const std::vector<Complex>& part = partial[static_cast<std::size_t>(x_part(t))];
    const std::vector<Complex>& basis = t.z == AlongX::value ? value : derivative;
    parallel_for(points, threads, [&](int zn) {
      const auto zi = static_cast<std::size_t>(zn);
      for (std::size_t m = 0; m < np; ++m) {
        double sum = 0.0;  // Re Σ_β e_β(z) T_β(x), β in array order
        for (const int b : rows) {
          const Complex e = basis[static_cast<std::size_t>(b) * np + zi];
          const Complex p = part[static_cast<std::size_t>(b) * np + m];
          sum += e.re * p.re - e.im * p.im;
        }
        result[zi * np + m] = sum;
      }
    });
  };
  for (std::size_t i = 0; i < fields.size(); ++i) {
    sum_rows(terms[i], out.values[static_cast<std::size_t>(fields[i])]);
  }
  if (ddz_dx) sum_rows(terms.back(), out.ddz_dx);
  return out;
}

}  // namespace oceanref
