#include "conformance/float32_backend.h"

#include <fftw3.h>

#include <cstring>
#include <mutex>
#include <string>

#include "core/math.h"

namespace oceanref {

namespace {
struct ComplexF {
  float re, im;
};
ComplexF to_float(Complex a) {
  return {static_cast<float>(a.re), static_cast<float>(a.im)};
}
ComplexF multiply(ComplexF a, ComplexF b) {
  return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re};
}

// Rounds to 11 significant bits (the precision of a half float), keeping the float range.
float to_half_precision(float x) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &x, sizeof bits);
  bits = (bits + (1u << 12)) & ~((1u << 13) - 1u);
  float out = 0.0f;
  std::memcpy(&out, &bits, sizeof out);
  return out;
}

// FFTW's planner is not thread-safe.
std::mutex& planner_mutex() {
  static std::mutex m;
  return m;
}

std::string part_channel(std::size_t cascade, Field f) {
  return "c" + std::to_string(cascade) + "." +
         std::string(kFieldNames[static_cast<std::size_t>(f)]);
}

// Parts of one cascade: "c<i>" on N_h and, with multi-resolution, "c<i>.low" on N_l.
template <typename FieldValues>
void add_cascade_parts(std::vector<ExrPart>& parts, std::size_t i, int low, int high,
                       const FieldValues& values) {
  ExrPart h{"c" + std::to_string(i), 0, 0, {}};
  h.image.width = h.image.height = high;
  ExrPart l{"c" + std::to_string(i) + ".low", 0, 0, {}};
  l.image.width = l.image.height = low;
  for (int q = 0; q < kFieldCount; ++q) {
    const Field f = Field(q);
    ExrPart& target = (is_low_resolution_field(f) && low != high) ? l : h;
    target.image.channels.push_back({part_channel(i, f), 1, values(f)});
  }
  parts.push_back(std::move(h));
  if (low != high) parts.push_back(std::move(l));
}
}  // namespace

std::vector<float> float32_field(const PatternSpectrum& s, double time, Field field,
                                 Float32Defect defect) {
  const int n = s.pattern.resolution;
  const double dk = wavenumber_spacing(s.pattern.size);
  fftwf_complex* c = fftwf_alloc_complex(grid_cells(n));
  fftwf_plan plan = nullptr;
  {
    const std::lock_guard lock(planner_mutex());
    plan = fftwf_plan_dft_2d(n, n, c, c, FFTW_BACKWARD, FFTW_ESTIMATE);
  }
  for (int b = 0; b < n; ++b) {
    for (int a = 0; a < n; ++a) {
      const std::size_t i = grid_offset(a, b, n);
      const std::size_t ic =
          grid_offset(conjugate_array_index(a, n), conjugate_array_index(b, n), n);
      float phase = static_cast<float>(s.omega[i]) * static_cast<float>(time);
      if (defect == Float32Defect::half_float_phase) phase = to_half_precision(phase);
      // A shader's float cos/sin: the portable double value rounded to float.
      const math::SinCos e = math::sincos(static_cast<double>(phase));
      const ComplexF forward{static_cast<float>(e.cos), -static_cast<float>(e.sin)};
      const ComplexF a0 = multiply(to_float(s.h0[i]), forward);
      const ComplexF b0 = defect == Float32Defect::drop_conjugate_term
                              ? ComplexF{0.0f, 0.0f}
                              : multiply(to_float(s.h0[ic]), forward);
      const ComplexF h{0.5f * (a0.re + b0.re), 0.5f * (a0.im - b0.im)};  // ½(a + b*)
      const ComplexF v =
          multiply(to_float(field_multiplier(field, wave_index(a, n), wave_index(b, n), dk,
                                             s.inverse_wavenumber[i], n)),
                   h);
      c[i][0] = v.re;
      c[i][1] = v.im;
    }
  }
  fftwf_execute(plan);
  std::vector<float> out(grid_cells(n));
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = c[i][0];
  {
    const std::lock_guard lock(planner_mutex());
    fftwf_destroy_plan(plan);
  }
  fftwf_free(c);
  return out;
}

std::vector<ExrPart> float32_fields_parts(const Ocean& ocean, double time, Float32Defect defect) {
  std::vector<ExrPart> parts;
  for (std::size_t i = 0; i < ocean.cascades.size(); ++i) {
    const CascadeSpectra& c = ocean.cascades[i];
    add_cascade_parts(parts, i, c.low.pattern.resolution, c.high.pattern.resolution, [&](Field f) {
      return float32_field(is_low_resolution_field(f) ? c.low : c.high, time, f, defect);
    });
  }
  return parts;
}

std::vector<ExrPart> reference_fields_parts(const Ocean& ocean, double time, int threads) {
  const std::vector<CascadeFields> fields = synthesize_ocean(ocean, time, threads);
  std::vector<ExrPart> parts;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    add_cascade_parts(parts, i, fields[i].low_resolution, fields[i].high_resolution, [&](Field f) {
      const std::vector<double>& v = fields[i].values[static_cast<std::size_t>(f)];
      return std::vector<float>(v.begin(), v.end());
    });
  }
  return parts;
}

}  // namespace oceanref
