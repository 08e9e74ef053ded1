#include "waves/stages.h"

#include <stdexcept>

#include "core/fp_environment.h"
#include "core/math.h"

namespace oceanref {

std::vector<double> cell_variances(const Spectrum& spectrum, const Pattern& p) {
  const int n = p.resolution;
  std::vector<double> v(grid_cells(n));
  for (int b = 0; b < n; ++b) {
    for (int a = 0; a < n; ++a) {
      v[grid_offset(a, b, n)] = cell_variance(spectrum, p, wave_index(a, n), wave_index(b, n));
    }
  }
  return v;
}

std::vector<StageChannel> stage_channels(const Spectrum& spectrum, const PatternSpectrum& s,
                                         Stage stage, double time, int threads,
                                         const MastinFilterModel& filter) {
  const ReferenceFpEnvironment fp;
  const Pattern& p = s.pattern;
  const int n = p.resolution;
  const double dk = wavenumber_spacing(p.size);
  const std::size_t cells = grid_cells(n);
  const auto complex_channels = [](const std::string& name, const std::vector<Complex>& z) {
    StageChannel re{name + ".re", "m", std::vector<double>(z.size())};
    StageChannel im{name + ".im", "m", std::vector<double>(z.size())};
    for (std::size_t i = 0; i < z.size(); ++i) {
      re.values[i] = z[i].re;
      im.values[i] = z[i].im;
    }
    return std::vector<StageChannel>{std::move(re), std::move(im)};
  };
  switch (stage) {
    case Stage::spectrum: {
      StageChannel theta{"theta", "m^4", std::vector<double>(cells)};
      const bool power_law = filter.filter != MastinFilter::spectrum;
      StageChannel variance{"variance", "m^2",
                            power_law ? std::vector<double>(cells) : cell_variances(spectrum, p)};
      StageChannel in_band{"in_band", "1", std::vector<double>(cells)};
      for (int b = 0; b < n; ++b) {
        for (int a = 0; a < n; ++a) {
          const std::size_t i = grid_offset(a, b, n);
          const double kx = wave_index(a, n) * dk;
          const double kz = wave_index(b, n) * dk;
          const double k = math::hypot(kx, kz);
          theta.values[i] = k > 0.0 ? mastin_filter_power(spectrum, filter, kx, kz) : 0.0;
          in_band.values[i] = k > 0.0 && p.band.contains(k) ? 1.0 : 0.0;
          if (power_law) variance.values[i] = in_band.values[i] * theta.values[i] * dk * dk;
        }
      }
      return {std::move(theta), std::move(variance), std::move(in_band)};
    }
    case Stage::h0:
      return complex_channels("h0", s.h0);
    case Stage::omega: {
      StageChannel kx{"kx", "rad/m", std::vector<double>(cells)};
      StageChannel kz{"kz", "rad/m", std::vector<double>(cells)};
      StageChannel k{"k", "rad/m", std::vector<double>(cells)};
      for (int b = 0; b < n; ++b) {
        for (int a = 0; a < n; ++a) {
          const std::size_t i = grid_offset(a, b, n);
          kx.values[i] = wave_index(a, n) * dk;
          kz.values[i] = wave_index(b, n) * dk;
          k.values[i] = math::hypot(kx.values[i], kz.values[i]);
        }
      }
      return {StageChannel{"omega", "rad/s", s.omega}, std::move(kx), std::move(kz), std::move(k)};
    }
    case Stage::hkt:
      return complex_channels("hkt", spectrum_at_time(s, time, threads));
    case Stage::fields:
      break;
  }
  throw std::invalid_argument("stage_channels: the fields stage is synthesize_cascade's");
}

}  // namespace oceanref
