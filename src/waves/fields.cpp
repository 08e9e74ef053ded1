#include "waves/fields.h"

#include <chrono>
#include <cmath>

#include "core/check.h"
#include "core/parallel.h"
#include "waves/fft.h"

namespace oceanref {

bool is_low_resolution_field(Field f) {
  return f == Field::height || f == Field::displacement_x || f == Field::displacement_z;
}

namespace {
double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Inverse transforms of M_f·h for the given fields, two per complex transform (eq. 4.8):
// c = F⁻¹(M₁h + i·M₂h), field₁ = Re c, field₂ = Im c.
int synthesize_fields(const std::vector<Complex>& h, const PatternSpectrum& s,
                      const std::vector<Field>& fields, CascadeFields& out, int threads,
                      const InverseFft2d& fft, SynthesisTimes* times, std::vector<Complex>& c,
                      const FieldMask& wanted) {
  const int n = s.pattern.resolution;
  const double dk = wavenumber_spacing(s.pattern.size);
  int transforms = 0;
  c.resize(h.size());
  const auto is_wanted = [&](Field q) { return wanted[static_cast<std::size_t>(q)]; };
  for (std::size_t f = 0; f < fields.size(); f += 2) {
    const bool paired = f + 1 < fields.size();
    if (!is_wanted(fields[f]) && !(paired && is_wanted(fields[f + 1]))) {
      out.values[static_cast<std::size_t>(fields[f])].clear();
      if (paired) out.values[static_cast<std::size_t>(fields[f + 1])].clear();
      continue;
    }
    auto start = std::chrono::steady_clock::now();
    parallel_for(n, threads, [&](int b) {
      const int beta = wave_index(b, n);
      for (int a = 0; a < n; ++a) {
        const std::size_t i = grid_offset(a, b, n);
        const int alpha = wave_index(a, n);
        const double k = s.inverse_wavenumber[i];
        c[i] = field_multiplier(fields[f], alpha, beta, dk, k, n) * h[i];
        if (paired) {
          c[i] += times_i(field_multiplier(fields[f + 1], alpha, beta, dk, k, n) * h[i]);
        }
      }
    });
    if (times != nullptr) times->pack += seconds_since(start);
    start = std::chrono::steady_clock::now();
    fft(c, n, threads);
    if (times != nullptr) times->transform += seconds_since(start);
    ++transforms;
    start = std::chrono::steady_clock::now();
    auto& first = out.values[static_cast<std::size_t>(fields[f])];
    auto& second = out.values[static_cast<std::size_t>(paired ? fields[f + 1] : fields[f])];
    first.resize(c.size());
    second.resize(c.size());
    parallel_for(n, threads, [&](int row) {
      for (std::size_t i = grid_offset(0, row, n); i < grid_offset(0, row + 1, n); ++i) {
        first[i] = c[i].re;
        if (paired) second[i] = c[i].im;
      }
    });
    if (times != nullptr) times->unpack += seconds_since(start);
  }
  return transforms;
}
}  // namespace

void synthesize_cascade(const PatternSpectrum& low, const PatternSpectrum& high, double time,
                        int threads, CascadeFields& out, SynthesisWorkspace& work,
                        const InverseFft2d& fft, SynthesisTimes* times, const FieldMask& wanted) {
  OCEANREF_EXPECTS(
      low.pattern.size == high.pattern.size && low.pattern.resolution <= high.pattern.resolution,
      "the low and high patterns of one cascade: the same size L and N_l <= N_h");
  out.size = high.pattern.size;
  out.low_resolution = low.pattern.resolution;
  out.high_resolution = high.pattern.resolution;
  const auto evolve = [&](const PatternSpectrum& s, std::vector<Complex>& h) {
    const auto start = std::chrono::steady_clock::now();
    evolve_spectrum(s, time, threads, h);
    if (times != nullptr) times->evolve += seconds_since(start);
  };
  bool high_fields = false;  // a field of the N_h grid wanted
  for (int q = 0; q < kFieldCount; ++q) {
    high_fields =
        high_fields ||
        (wanted[static_cast<std::size_t>(q)] &&
         (low.pattern.resolution == high.pattern.resolution || !is_low_resolution_field(Field(q))));
  }
  if (high_fields) evolve(high, work.h_high);
  if (low.pattern.resolution == high.pattern.resolution) {
    out.transforms = synthesize_fields(
        work.h_high, high,
        {Field::height, Field::ddx_dz, Field::slope_x, Field::slope_z, Field::displacement_x,
         Field::displacement_z, Field::ddx_dx, Field::ddz_dz},
        out, threads, fft, times, work.packed, wanted);
    return;
  }
  evolve(low, work.h_low);
  out.transforms = synthesize_fields(work.h_low, low,
                                     {Field::height, Field::displacement_x, Field::displacement_z},
                                     out, threads, fft, times, work.packed, wanted) +
                   synthesize_fields(work.h_high, high,
                                     {Field::slope_x, Field::slope_z, Field::ddx_dx, Field::ddz_dz,
                                      Field::ddx_dz},
                                     out, threads, fft, times, work.packed, wanted);
}

CascadeFields synthesize_cascade(const PatternSpectrum& low, const PatternSpectrum& high,
                                 double time, int threads, const InverseFft2d& fft,
                                 SynthesisTimes* times) {
  CascadeFields out;
  SynthesisWorkspace work;
  synthesize_cascade(low, high, time, threads, out, work, fft, times);
  return out;
}

void add_cascade(PointFields& sum, const std::array<double, kFieldCount>& raw, double u) {
  for (int f = 0; f < kFieldCount; ++f) {
    const double scale = f >= static_cast<int>(Field::displacement_x) ? u : 1.0;
    sum.raw[static_cast<std::size_t>(f)] += scale * raw[static_cast<std::size_t>(f)];
  }
  sum.ddz_dx += u * raw[static_cast<std::size_t>(Field::ddx_dz)];
}

void add_cascade_surface(PointFields& sum, const CascadeSurface& c, double u) {
  for (int f = 0; f < kFieldCount; ++f) {
    const double scale = f >= static_cast<int>(Field::displacement_x) ? u : 1.0;
    sum.raw[static_cast<std::size_t>(f)] += scale * c.raw[static_cast<std::size_t>(f)];
  }
  sum.ddz_dx += u * c.ddz_dx;
}

double displaced_slope(double slope, double scaled_displacement_derivative) {
  return slope / (1.0 + scaled_displacement_derivative);
}

double jacobian_determinant(double u_ddx_dx, double u_ddz_dz, double u_ddx_dz) {
  return (1.0 + u_ddx_dx) * (1.0 + u_ddz_dz) - u_ddx_dz * u_ddx_dz;
}

double jacobian_determinant(double u_ddx_dx, double u_ddz_dz, double u_ddx_dz, double u_ddz_dx) {
  return (1.0 + u_ddx_dx) * (1.0 + u_ddz_dz) - u_ddx_dz * u_ddz_dx;
}

void finish_combination(PointFields& sum) {
  const auto raw = [&](Field f) { return sum.raw[static_cast<std::size_t>(f)]; };
  sum.height = raw(Field::height);
  sum.slope_x = displaced_slope(raw(Field::slope_x), raw(Field::ddx_dx));
  sum.slope_z = displaced_slope(raw(Field::slope_z), raw(Field::ddz_dz));
  sum.jacobian = jacobian_determinant(raw(Field::ddx_dx), raw(Field::ddz_dz), raw(Field::ddx_dz));
  sum.foam = sum.jacobian < 0.0 ? 1.0 : 0.0;
  sum.normal = surface_normal(sum.slope_x, sum.slope_z);
}

void finish_surface_combination(PointFields& sum) {
  const auto raw = [&](Field f) { return sum.raw[static_cast<std::size_t>(f)]; };
  const double eta_x = raw(Field::slope_x);
  const double eta_z = raw(Field::slope_z);
  const double j_xx = 1.0 + raw(Field::ddx_dx);
  const double j_zz = 1.0 + raw(Field::ddz_dz);
  const double j_xz = raw(Field::ddx_dz);
  const double j_zx = sum.ddz_dx;
  sum.height = raw(Field::height);
  sum.jacobian = jacobian_determinant(raw(Field::ddx_dx), raw(Field::ddz_dz), j_xz, j_zx);
  // s = J⁻ᵀ∇η = adj(J)ᵀ∇η / det J
  sum.slope_x = (j_zz * eta_x - j_zx * eta_z) / sum.jacobian;
  sum.slope_z = (j_xx * eta_z - j_xz * eta_x) / sum.jacobian;
  sum.foam = sum.jacobian < 0.0 ? 1.0 : 0.0;
  sum.normal = displaced_surface_normal(eta_x, eta_z, j_xx, j_xz, j_zx, j_zz);
}

std::array<double, 3> surface_normal(double slope_x, double slope_z) {
  const double length = std::sqrt(slope_x * slope_x + 1.0 + slope_z * slope_z);
  return {-slope_x / length, 1.0 / length, -slope_z / length};
}

std::array<double, 3> displaced_surface_normal(double eta_x, double eta_z, double j_xx, double j_xz,
                                               double j_zx, double j_zz) {
  const double det = j_xx * j_zz - j_xz * j_zx;
  const double orientation = det < 0.0 ? -1.0 : 1.0;
  const double nx = -(j_zz * eta_x - j_zx * eta_z) * orientation;
  const double ny = det * orientation;
  const double nz = -(j_xx * eta_z - j_xz * eta_x) * orientation;
  const double length = std::sqrt(nx * nx + ny * ny + nz * nz);
  if (!(length > 0.0)) return {0.0, 1.0, 0.0};
  return {nx / length, ny / length, nz / length};
}

double accumulated_foam(double last, double current, double decay, double time_step) {
  const double accumulation = last - decay * time_step / std::fmax(current, 0.5);
  return std::fmax(accumulation, current);
}

}  // namespace oceanref
