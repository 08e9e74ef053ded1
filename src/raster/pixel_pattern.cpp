#include "raster/pixel_pattern.h"

#include "waves/random.h"

namespace oceanref {

std::uint32_t sobol_coordinate(int dimension, std::uint32_t i) {
  std::uint32_t x = 0;
  std::uint32_t v = 1u << 31;  // v_1
  for (; i != 0; i >>= 1) {
    if ((i & 1u) != 0) x ^= v;
    v = dimension == 0 ? v >> 1 : v ^ (v >> 1);
  }
  return x;
}

std::uint32_t owen_scrambled(std::uint32_t x, std::uint64_t key) {
  std::uint32_t out = 0;
  for (int d = 0; d < 32; ++d) {
    // The node of the binary tree of digits: 1 followed by the d digits above digit d.
    const std::uint64_t above = d == 0 ? 0u : x >> (32 - d);
    const std::uint64_t node = (std::uint64_t{1} << d) | above;
    const std::uint32_t flip = static_cast<std::uint32_t>(random_word(key, node) >> 63);
    const std::uint32_t digit = ((x >> (31 - d)) & 1u) ^ flip;
    out |= digit << (31 - d);
  }
  return out;
}

std::array<double, 2> scrambled_sobol_point(std::uint64_t key, std::uint32_t i) {
  std::array<double, 2> p{};
  for (int d = 0; d < 2; ++d) {
    const std::uint32_t x =
        owen_scrambled(sobol_coordinate(d, i), mix64(key ^ static_cast<std::uint64_t>(d + 1)));
    p[static_cast<std::size_t>(d)] = (static_cast<double>(x) + 0.5) * 0x1p-32;
  }
  return p;
}

std::uint64_t pixel_replicate_key(int x, int y, int replicate) {
  constexpr std::uint64_t kPixelPatternTag = 0x50495845'4C534F42u;  // "PIXELSOB"
  const std::uint64_t pixel =
      static_cast<std::uint32_t>(x) | std::uint64_t{static_cast<std::uint32_t>(y)} << 32;
  return mix64(mix64(mix64(kPixelPatternTag) ^ pixel) ^ static_cast<std::uint32_t>(replicate));
}

}  // namespace oceanref
