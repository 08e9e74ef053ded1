#include "waves/direct_sum.h"

#include <cmath>
#include <numbers>

#include "core/math.h"

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

void add_pattern(const PatternSpectrum& s, const std::vector<Complex>& h, double x, double z,
                 bool low_fields, std::array<Complex, kFieldCount>& sum) {
  const Pattern& p = s.pattern;
  const int n = p.resolution;
  const double dk = wavenumber_spacing(p.size);
  for (int b = 0; b < n; ++b) {
    const int beta = wave_index(b, n);
    const AxisBasis bz = axis_basis(beta, z, p.size, n);
    for (int a = 0; a < n; ++a) {
      const Complex amplitude = h[grid_offset(a, b, n)];
      if (amplitude == 0.0) continue;
      const int alpha = wave_index(a, n);
      const AxisBasis bx = axis_basis(alpha, x, p.size, n);
      const double inverse_k = s.inverse_wavenumber[grid_offset(a, b, n)];
      const Complex gx = displacement_factor(alpha, dk, inverse_k, n);
      const Complex gz = displacement_factor(beta, dk, inverse_k, n);
      const Complex e = bx.value * bz.value;
      auto add = [&](Field f, Complex term) {
        sum[static_cast<std::size_t>(f)] += amplitude * term;
      };
      if (low_fields) {
        add(Field::height, e);
        add(Field::displacement_x, gx * e);
        add(Field::displacement_z, gz * e);
      } else {
        add(Field::slope_x, bx.derivative * bz.value);
        add(Field::slope_z, bx.value * bz.derivative);
        add(Field::ddx_dx, gx * bx.derivative * bz.value);
        add(Field::ddz_dz, gz * bx.value * bz.derivative);
        add(Field::ddx_dz, gx * bx.value * bz.derivative);
      }
    }
  }
}
}  // namespace

EvolvedCascade evolve_cascade(const PatternSpectrum& low, const PatternSpectrum& high,
                              double time) {
  return {spectrum_at_time(low, time), spectrum_at_time(high, time)};
}

std::array<double, kFieldCount> direct_sum(const PatternSpectrum& low, const PatternSpectrum& high,
                                           double x, double z, double time) {
  return direct_sum(low, high, evolve_cascade(low, high, time), x, z);
}

std::array<double, kFieldCount> direct_sum(const PatternSpectrum& low, const PatternSpectrum& high,
                                           const EvolvedCascade& h, double x, double z) {
  std::array<Complex, kFieldCount> sum{};
  add_pattern(low, h.low, x, z, true, sum);
  add_pattern(high, h.high, x, z, false, sum);
  std::array<double, kFieldCount> out{};
  for (std::size_t f = 0; f < out.size(); ++f) out[f] = sum[f].re;
  return out;
}

}  // namespace oceanref
