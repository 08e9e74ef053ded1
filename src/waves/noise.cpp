#include "waves/noise.h"

#include <array>
#include <cmath>
#include <numbers>

#include "core/math.h"
#include "waves/random.h"

namespace oceanref {

namespace {
// Perlin 2002: s(t) = 6t⁵ − 15t⁴ + 10t³ and s′(t) = 30t²(1 − t)².
double fade(double t) {
  return t * t * t * (t * (6.0 * t - 15.0) + 10.0);
}
double fade_slope(double t) {
  return 30.0 * t * t * (1.0 - t) * (1.0 - t);
}

std::array<double, 2> lattice_gradient(std::uint64_t key, double i, double j) {
  const std::uint64_t k =
      mix64(mix64(mix64(key) ^ static_cast<std::uint64_t>(static_cast<std::int64_t>(i))) ^
            static_cast<std::uint64_t>(static_cast<std::int64_t>(j)));
  const double angle = 2.0 * std::numbers::pi * uniform_open(random_word(k, 0));
  return {math::cos(angle), math::sin(angle)};
}
}  // namespace

// Perlin 2002, in 2-D with unit gradients.
NoiseSample gradient_noise(std::uint64_t key, double x, double z) {
  const double i = std::floor(x), j = std::floor(z);
  const double u = x - i, v = z - j;
  const double su = fade(u), sv = fade(v), du = fade_slope(u), dv = fade_slope(v);
  NoiseSample n;
  for (int b = 0; b < 2; ++b) {
    for (int a = 0; a < 2; ++a) {
      const std::array<double, 2> g = lattice_gradient(key, i + a, j + b);
      const double dx = u - a, dz = v - b;
      const double dot = g[0] * dx + g[1] * dz;
      const double wx = a == 0 ? 1.0 - su : su, wz = b == 0 ? 1.0 - sv : sv;
      const double dwx = a == 0 ? -du : du, dwz = b == 0 ? -dv : dv;
      n.value += wx * wz * dot;
      n.d_dx += dwx * wz * dot + wx * wz * g[0];
      n.d_dz += wx * dwz * dot + wx * wz * g[1];
    }
  }
  return n;
}

NoiseBlend make_noise_blend(std::uint64_t seed, double weight, double cell,
                            const std::array<double, 3>& mean_squares) {
  constexpr std::uint64_t kNoiseTag = 0x6e6f;  // "no"
  NoiseBlend b;
  b.weight = weight;
  b.cell = cell;
  for (std::size_t c = 0; c < 3; ++c) {
    b.amplitude[c] = std::sqrt(mean_squares[c] / kGradientNoiseMeanSquare);
    b.keys[c] = mix64(mix64(mix64(seed) ^ kNoiseTag) ^ c);
  }
  return b;
}

PointFields noise_fields(const NoiseBlend& b, double x, double z) {
  const auto at = [](Field f) { return static_cast<std::size_t>(f); };
  const double px = x / b.cell, pz = z / b.cell;
  const NoiseSample dx = gradient_noise(b.keys[0], px, pz);
  const NoiseSample eta = gradient_noise(b.keys[1], px, pz);
  const NoiseSample dz = gradient_noise(b.keys[2], px, pz);
  const double ax = b.amplitude[0], ae = b.amplitude[1], az = b.amplitude[2];
  PointFields n;
  n.raw[at(Field::height)] = ae * eta.value;
  n.raw[at(Field::slope_x)] = ae * eta.d_dx / b.cell;
  n.raw[at(Field::slope_z)] = ae * eta.d_dz / b.cell;
  n.raw[at(Field::displacement_x)] = ax * dx.value;
  n.raw[at(Field::displacement_z)] = az * dz.value;
  n.raw[at(Field::ddx_dx)] = ax * dx.d_dx / b.cell;
  n.raw[at(Field::ddx_dz)] = ax * dx.d_dz / b.cell;
  n.raw[at(Field::ddz_dz)] = az * dz.d_dz / b.cell;
  n.ddz_dx = az * dz.d_dx / b.cell;
  return n;
}

// Lutz eq. 2: D = (1 − w_P)D_S + w_P D_P.
void mix_noise(PointFields& exemplar, const PointFields& noise, double weight) {
  for (std::size_t f = 0; f < exemplar.raw.size(); ++f) {
    exemplar.raw[f] = (1.0 - weight) * exemplar.raw[f] + weight * noise.raw[f];
  }
  exemplar.ddz_dx = (1.0 - weight) * exemplar.ddz_dx + weight * noise.ddz_dx;
}

}  // namespace oceanref
