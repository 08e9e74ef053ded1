#include "waves/random.h"

#include <cmath>
#include <numbers>

#include "core/math.h"

namespace oceanref {

std::uint64_t mix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

std::uint64_t component_key(std::uint64_t seed, std::uint32_t cascade, std::int32_t alpha,
                            std::int32_t beta) {
  const std::uint64_t indices = static_cast<std::uint64_t>(static_cast<std::uint32_t>(alpha)) |
                                static_cast<std::uint64_t>(static_cast<std::uint32_t>(beta)) << 32;
  return mix64(mix64(mix64(seed) ^ cascade) ^ indices);
}

std::uint64_t random_word(std::uint64_t key, std::uint64_t n) {
  return mix64(key + n * 0xD1B54A32D192ED03ULL);
}

double uniform_open(std::uint64_t word) {
  return (static_cast<double>(word >> 11) + 0.5) * 0x1.0p-53;
}

NormalPair standard_normal_pair(std::uint64_t key) {
  const double u1 = uniform_open(random_word(key, 0));
  const double u2 = uniform_open(random_word(key, 1));
  const double radius = std::sqrt(-2.0 * math::log(u1));
  const double angle = 2.0 * std::numbers::pi * u2;
  return {radius * math::cos(angle), radius * math::sin(angle)};
}

}  // namespace oceanref
