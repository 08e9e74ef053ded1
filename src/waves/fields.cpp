#include "waves/fields.h"

#include <cmath>

#include "waves/fft.h"

namespace oceanref {

bool is_low_resolution_field(Field f) {
  return f == Field::height || f == Field::displacement_x || f == Field::displacement_z;
}

Complex derivative_factor(int index, double spacing, int resolution) {
  if (is_nyquist(index, resolution)) return 0.0;
  return {0.0, index * spacing};
}

Complex displacement_factor(int index, double spacing, double k, int resolution) {
  if (!(k > 0.0) || is_nyquist(index, resolution)) return 0.0;
  return {0.0, -index * spacing / k};
}

Complex field_multiplier(Field f, int alpha, int beta, double spacing, int n) {
  const double k = std::hypot(alpha * spacing, beta * spacing);
  switch (f) {
    case Field::height:
      return 1.0;
    case Field::slope_x:
      return derivative_factor(alpha, spacing, n);
    case Field::slope_z:
      return derivative_factor(beta, spacing, n);
    case Field::displacement_x:
      return displacement_factor(alpha, spacing, k, n);
    case Field::displacement_z:
      return displacement_factor(beta, spacing, k, n);
    case Field::ddx_dx:
      return derivative_factor(alpha, spacing, n) * displacement_factor(alpha, spacing, k, n);
    case Field::ddz_dz:
      return derivative_factor(beta, spacing, n) * displacement_factor(beta, spacing, k, n);
    case Field::ddx_dz:
      return derivative_factor(beta, spacing, n) * displacement_factor(alpha, spacing, k, n);
  }
  return 0.0;
}

namespace {
// Inverse transforms of M_f·h for the given fields, two per complex transform (eq. 4.8):
// c = F⁻¹(M₁h + i·M₂h), field₁ = Re c, field₂ = Im c.
int synthesize_fields(const std::vector<Complex>& h, const Pattern& p,
                      const std::vector<Field>& fields, CascadeFields& out, int threads) {
  const int n = p.resolution;
  const double dk = wavenumber_spacing(p.size);
  int transforms = 0;
  for (std::size_t f = 0; f < fields.size(); f += 2) {
    const bool paired = f + 1 < fields.size();
    std::vector<Complex> c(h.size());
    for (int b = 0; b < n; ++b) {
      for (int a = 0; a < n; ++a) {
        const std::size_t i = grid_offset(a, b, n);
        const int alpha = wave_index(a, n);
        const int beta = wave_index(b, n);
        c[i] = field_multiplier(fields[f], alpha, beta, dk, n) * h[i];
        if (paired) {
          c[i] += Complex(0.0, 1.0) * (field_multiplier(fields[f + 1], alpha, beta, dk, n) * h[i]);
        }
      }
    }
    inverse_fft_2d(c, n, threads);
    ++transforms;
    auto& first = out.values[static_cast<std::size_t>(fields[f])];
    first.resize(c.size());
    for (std::size_t i = 0; i < c.size(); ++i) first[i] = c[i].real();
    if (paired) {
      auto& second = out.values[static_cast<std::size_t>(fields[f + 1])];
      second.resize(c.size());
      for (std::size_t i = 0; i < c.size(); ++i) second[i] = c[i].imag();
    }
  }
  return transforms;
}
}  // namespace

CascadeFields synthesize_cascade(const PatternSpectrum& low, const PatternSpectrum& high,
                                 double time, int threads) {
  CascadeFields out;
  out.size = high.pattern.size;
  out.low_resolution = low.pattern.resolution;
  out.high_resolution = high.pattern.resolution;
  const std::vector<Complex> h_high = spectrum_at_time(high, time);
  if (low.pattern.resolution == high.pattern.resolution) {
    out.transforms = synthesize_fields(
        h_high, high.pattern,
        {Field::height, Field::ddx_dz, Field::slope_x, Field::slope_z, Field::displacement_x,
         Field::displacement_z, Field::ddx_dx, Field::ddz_dz},
        out, threads);
    return out;
  }
  const std::vector<Complex> h_low = spectrum_at_time(low, time);
  out.transforms = synthesize_fields(h_low, low.pattern,
                                     {Field::height, Field::displacement_x, Field::displacement_z},
                                     out, threads) +
                   synthesize_fields(h_high, high.pattern,
                                     {Field::slope_x, Field::slope_z, Field::ddx_dx, Field::ddz_dz,
                                      Field::ddx_dz},
                                     out, threads);
  return out;
}

void add_cascade(PointFields& sum, const std::array<double, kFieldCount>& raw, double u) {
  for (int f = 0; f < kFieldCount; ++f) {
    const double scale = f >= static_cast<int>(Field::displacement_x) ? u : 1.0;
    sum.raw[static_cast<std::size_t>(f)] += scale * raw[static_cast<std::size_t>(f)];
  }
}

double displaced_slope(double slope, double scaled_displacement_derivative) {
  return slope / (1.0 + scaled_displacement_derivative);
}

double jacobian_determinant(double u_ddx_dx, double u_ddz_dz, double u_ddx_dz) {
  return (1.0 + u_ddx_dx) * (1.0 + u_ddz_dz) - u_ddx_dz * u_ddx_dz;
}

void finish_combination(PointFields& sum) {
  const auto raw = [&](Field f) { return sum.raw[static_cast<std::size_t>(f)]; };
  sum.height = raw(Field::height);
  sum.slope_x = displaced_slope(raw(Field::slope_x), raw(Field::ddx_dx));
  sum.slope_z = displaced_slope(raw(Field::slope_z), raw(Field::ddz_dz));
  sum.jacobian = jacobian_determinant(raw(Field::ddx_dx), raw(Field::ddz_dz), raw(Field::ddx_dz));
  sum.foam = sum.jacobian < 0.0 ? 1.0 : 0.0;
}

std::array<double, 3> surface_normal(double slope_x, double slope_z) {
  const double length = std::sqrt(slope_x * slope_x + 1.0 + slope_z * slope_z);
  return {-slope_x / length, 1.0 / length, -slope_z / length};
}

double accumulated_foam(double last, double current, double decay, double time_step) {
  const double accumulation = last - decay * time_step / std::fmax(current, 0.5);
  return std::fmax(accumulation, current);
}

}  // namespace oceanref
