#include "waves/autocorrelation.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/fp_environment.h"
#include "core/math.h"
#include "core/parallel.h"
#include "waves/ocean.h"
#include "waves/random.h"

namespace oceanref {

namespace {
// The tag of the start points' stream ("ac").
constexpr std::uint64_t kStartPointTag = 0x6163;

void check_settings(const AutocorrelationSettings& s) {
  const auto fail = [](const std::string& what) {
    throw std::invalid_argument("autocorrelation: " + what);
  };
  if (s.lines < 2 || s.lines > 10'000'000) fail("lines must be in [2, 1e7]");
  if (!(s.length > 0.0 && s.length <= 1024.0)) fail("length must be in (0, 1024] periods");
  if (s.samples_per_period < 1 || s.samples_per_period > 4096) {
    fail("samples per period must be in [1, 4096]");
  }
  if (!(s.area > 0.0 && s.area <= 1e6)) fail("area must be in (0, 1e6] periods");
  if (s.length * s.samples_per_period > 1e6) fail("at most 1e6 lags");
  if (!std::isfinite(s.direction)) fail("the direction must be finite");
}
}  // namespace

// Lutz eq. 22, estimated over random start points.
Autocorrelation displacement_autocorrelation(const Ocean& ocean,
                                             const std::vector<CascadeFields>& fields,
                                             const std::vector<EvolvedCascade>& evolved,
                                             Interpolation mode, ShadingNormals normals,
                                             const AutocorrelationSettings& settings, int threads) {
  check_settings(settings);
  const ReferenceFpEnvironment fp;
  Autocorrelation out;
  for (const CascadeSpectra& c : ocean.cascades) {
    out.period = std::fmax(out.period, c.low.pattern.size);
  }
  const int spp = settings.samples_per_period;
  const auto count = static_cast<std::size_t>(std::lround(settings.length * spp)) + 1;
  for (std::size_t j = 0; j < count; ++j) {
    out.lags.push_back(out.period * static_cast<double>(j) / spp);
  }
  const double dx = math::cos(settings.direction), dz = math::sin(settings.direction);
  const std::uint64_t key = mix64(mix64(settings.seed) ^ kStartPointTag);
  const double side = settings.area * out.period;
  const auto lines = static_cast<std::size_t>(settings.lines);
  // q_c at start l and lag j: [(l·count + j)·3 + c].
  std::vector<double> q(lines * count * 3);
  parallel_for(settings.lines, threads, [&](int line) {
    const auto l = static_cast<std::size_t>(line);
    const double x0 = side * uniform_open(random_word(key, 2 * l));
    const double z0 = side * uniform_open(random_word(key, 2 * l + 1));
    for (std::size_t j = 0; j < count; ++j) {
      const double x = x0 + out.lags[j] * dx, z = z0 + out.lags[j] * dz;
      const DisplacedPoint p = displaced_point(ocean, fields, evolved, x, z, mode, normals);
      double* s = &q[(l * count + j) * 3];
      s[0] = p.x - x;
      s[1] = p.height;
      s[2] = p.z - z;
    }
  });
  std::array<double, 3> mean{};
  for (std::size_t i = 0; i < q.size(); ++i) mean[i % 3] += q[i];
  for (double& m : mean) m /= static_cast<double>(q.size() / 3);
  std::array<std::vector<double>, 3> r;  // r̃_c(τ_j)
  for (std::size_t c = 0; c < 3; ++c) {
    r[c].assign(count, 0.0);
    for (std::size_t l = 0; l < lines; ++l) {
      const double first = q[(l * count) * 3 + c] - mean[c];
      for (std::size_t j = 0; j < count; ++j) {
        r[c][j] += first * (q[(l * count + j) * 3 + c] - mean[c]);
      }
    }
    for (double& v : r[c]) v /= static_cast<double>(lines);
    out.variance[c] = r[c][0];
  }
  const double total = r[0][0] + r[1][0] + r[2][0];
  out.vector.assign(count, 0.0);
  for (std::size_t j = 0; j < count; ++j) {
    out.vector[j] = total > 0.0 ? (r[0][j] + r[1][j] + r[2][j]) / total : 0.0;
  }
  for (std::size_t c = 0; c < 3; ++c) {
    if (!(r[c][0] > 0.0)) continue;
    for (std::size_t j = 0; j < count; ++j) out.components[c].push_back(r[c][j] / r[c][0]);
  }
  return out;
}

std::vector<double> height_map(const Ocean& ocean, const std::vector<CascadeFields>& fields,
                               const std::vector<EvolvedCascade>& evolved, Interpolation mode,
                               ShadingNormals normals, double side, int pixels, int threads) {
  if (!(side > 0.0 && side <= 1e9) || pixels < 1 || pixels > 4096) {
    throw std::invalid_argument("height map: side in (0, 1e9] m and 1 to 4096 pixels");
  }
  const ReferenceFpEnvironment fp;
  const auto n = static_cast<std::size_t>(pixels);
  std::vector<double> map(n * n);
  parallel_for(pixels, threads, [&](int row) {
    const double z = side * (row + 0.5) / pixels;
    for (std::size_t m = 0; m < n; ++m) {
      const double x = side * (static_cast<double>(m) + 0.5) / pixels;
      map[static_cast<std::size_t>(row) * n + m] =
          displaced_point(ocean, fields, evolved, x, z, mode, normals).height;
    }
  });
  return map;
}

}  // namespace oceanref
