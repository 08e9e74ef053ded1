// The positions of an adaptive pixel's samples (`render.pixel_pattern`, README "Converged
// pixels"): Owen-scrambled Sobol' points, in independent replicates, in place of the nested grid.
//
// The Sobol' (0,2)-sequence (Sobol' 1967; Joe & Kuo 2008): point i's first coordinate is the
// radical inverse of i in base 2 (van der Corput), its second the product of i's bits with the
// upper-triangular Pascal matrix mod 2 (direction numbers v_1 = 2³¹, v_{j+1} = v_j ⊕ (v_j ≫ 1)).
// The first 2^m points put one point in every elementary interval [a·2^−k, (a+1)·2^−k) ×
// [b·2^−(m−k), (b+1)·2^−(m−k)), and every further 2^m points do it again: a pixel refined by
// doubling keeps its samples.
//
// Owen's nested uniform scrambling (Owen 1995), exact to 32 digits: digit d of a coordinate is
// flipped when a hash of the replicate's key, the coordinate, d and the d digits above it says
// so, so every replicate is a (0,2)-sequence again, each of its points uniform in the pixel, and
// replicates with different keys are independent. Their means are then independent unbiased
// estimates of the pixel, and the spread of R replicate means is an honest standard error of
// their mean (Owen 1997: the variance of a scrambled net's mean falls as o(1/N), N^−3/2 for a
// smooth integrand). The hash is the counter hash of waves/random.h: the same bits everywhere.
#pragma once

#include <array>
#include <cstdint>

namespace oceanref {

// The unscrambled coordinate `dimension` (0 or 1) of Sobol' point i, as a 32-bit binary
// fraction (the value is coordinate / 2³²).
std::uint32_t sobol_coordinate(int dimension, std::uint32_t i);

// The 32-digit binary fraction x with Owen's nested uniform scrambling keyed by `key`.
std::uint32_t owen_scrambled(std::uint32_t x, std::uint64_t key);

// Point i in [0, 1)² of the replicate keyed by `key`: each coordinate scrambled by its own key,
// the centre of its 2⁻³² cell ((x + ½)·2⁻³²: never 0 or 1).
std::array<double, 2> scrambled_sobol_point(std::uint64_t key, std::uint32_t i);

// The key of replicate r of pixel (x, y) of the image: the same for any band, tile or thread.
std::uint64_t pixel_replicate_key(int x, int y, int replicate);

}  // namespace oceanref
