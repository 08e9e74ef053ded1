// Counter-based random numbers: every draw is a pure function of its key, never of a generator
// state, so a wave component gets the same numbers at every resolution, in every iteration
// order and on every thread count (DESIGN.md, determinism contract; Gamper §4.4, Fig. 4.11).
//
// Bit-exact mapping (documented so that other implementations can reproduce it):
//   mix(x)         = SplitMix64 finalizer of x + 0x9E3779B97F4A7C15 (Steele et al. 2014)
//   component_key  = mix(mix(mix(seed) ^ cascade) ^ (uint32(α) | uint64(uint32(β)) << 32))
//   word(key, n)   = mix(key + n·0xD1B54A32D192ED03)                  n = 0, 1, ...
//   uniform(word)  = ((word >> 11) + 0.5) · 2⁻⁵³                      ∈ (0, 1), never 0 or 1
//   normals        = Box–Muller on u1 = uniform(word(key, 0)), u2 = uniform(word(key, 1)):
//                    ξ_r = √(−2 ln u1) cos(2π u2),  ξ_i = √(−2 ln u1) sin(2π u2)
// The normals use the portable log, cos and sin of core/math.h: the same bits on every
// compiler, CPU and architecture; they are correctly rounded for all but a handful of
// arguments in 10^7 (reference/ACCURACY.md), so a correctly rounded libm reproduces them.
#pragma once

#include <cstdint>

namespace oceanref {

struct NormalPair {
  double real;  // ξ_r
  double imag;  // ξ_i
};

std::uint64_t mix64(std::uint64_t x);
// The key of the component with integer wavevector indices (α, β) of one cascade.
std::uint64_t component_key(std::uint64_t seed, std::uint32_t cascade, std::int32_t alpha,
                            std::int32_t beta);
// The n-th 64-bit word of a key's stream.
std::uint64_t random_word(std::uint64_t key, std::uint64_t n);
// A uniform number in the open interval (0, 1) with 53 random bits.
double uniform_open(std::uint64_t word);
// Two independent standard normals from a key (Box–Muller).
NormalPair standard_normal_pair(std::uint64_t key);

}  // namespace oceanref
