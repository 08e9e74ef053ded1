// The Sobol' pattern of adaptive pixels (raster/pixel_pattern.h): the unscrambled points against
// an independent construction (Pascal's matrix mod 2), the (0,m,2)-net property of every
// scrambled replicate and of each further block of 2^m points, the scrambled points' uniformity
// over keys, and the variance of a replicate's mean falling faster than Monte Carlo's 1/N on a
// smooth integrand (what the pattern is for).
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "raster/pixel_pattern.h"
#include "waves/random.h"

using namespace oceanref;

namespace {
// Coordinate 1 of Sobol' point i from its definition: digit j (from the top, 1-based) is
// Σ_k C(k−1, j−1)·i_k mod 2 over i's bits i_k (k = 1 the lowest): the upper-triangular Pascal
// matrix, with the binomial coefficients mod 2 from Lucas' theorem ((j−1) & ~(k−1)) == 0.
std::uint32_t pascal_coordinate(std::uint32_t i) {
  std::uint32_t x = 0;
  for (int j = 1; j <= 32; ++j) {
    std::uint32_t digit = 0;
    for (int k = j; k <= 32; ++k) {
      const bool odd = ((static_cast<unsigned>(j - 1)) & ~static_cast<unsigned>(k - 1)) == 0;
      if (odd) digit ^= (i >> (k - 1)) & 1u;
    }
    x |= digit << (32 - j);
  }
  return x;
}

// Whether points [first, first + 2^m) put exactly one point in every elementary interval of
// volume 2^−m: 2^k × 2^(m−k) cells for k = 0…m.
bool is_net(const std::vector<std::array<double, 2>>& points, std::size_t first, int m) {
  const std::size_t n = std::size_t{1} << m;
  for (int k = 0; k <= m; ++k) {
    std::vector<int> count(n, 0);
    for (std::size_t i = first; i < first + n; ++i) {
      const auto a = static_cast<std::size_t>(std::floor(points[i][0] * std::ldexp(1.0, k)));
      const auto b = static_cast<std::size_t>(std::floor(points[i][1] * std::ldexp(1.0, m - k)));
      ++count[(a << (m - k)) | b];
    }
    for (const int c : count) {
      if (c != 1) return false;
    }
  }
  return true;
}
}  // namespace

TEST_CASE("pixel pattern: Sobol' points are the van der Corput and Pascal-matrix coordinates") {
  // The first points of the second coordinate (Joe & Kuo's listing, natural order).
  const double expected[] = {0.0, 0.5, 0.75, 0.25, 0.625, 0.125, 0.375, 0.875};
  for (std::uint32_t i = 0; i < 8; ++i) {
    CHECK(sobol_coordinate(1, i) * 0x1p-32 == expected[i]);
  }
  for (std::uint32_t i = 0; i < 70000; i += 7) {
    std::uint32_t reversed = 0;
    for (int b = 0; b < 32; ++b) reversed |= ((i >> b) & 1u) << (31 - b);
    REQUIRE(sobol_coordinate(0, i) == reversed);
    REQUIRE(sobol_coordinate(1, i) == pascal_coordinate(i));
  }
}

TEST_CASE("pixel pattern: every scrambled replicate is a (0,m,2)-net, block after block") {
  for (int replicate = 0; replicate < 8; ++replicate) {
    const std::uint64_t key = pixel_replicate_key(17, 5, replicate);
    std::vector<std::array<double, 2>> points;
    for (std::uint32_t i = 0; i < 1024; ++i) points.push_back(scrambled_sobol_point(key, i));
    for (int m = 0; m <= 8; ++m) {
      for (std::size_t first = 0; first + (std::size_t{1} << m) <= points.size();
           first += std::size_t{1} << m) {
        REQUIRE(is_net(points, first, m));
      }
    }
    for (const auto& p : points) REQUIRE((p[0] > 0.0 && p[0] < 1.0 && p[1] > 0.0 && p[1] < 1.0));
  }
  // A point is the centre of its scrambled 2⁻³² cell, each coordinate scrambled by its own key:
  // point 5 of replicate 3 of pixel (17, 5), digit by digit.
  const std::uint64_t key = pixel_replicate_key(17, 5, 3);
  const auto p = scrambled_sobol_point(key, 5);
  for (int d = 0; d < 2; ++d) {
    const std::uint32_t x =
        owen_scrambled(sobol_coordinate(d, 5), mix64(key ^ static_cast<std::uint64_t>(d + 1)));
    CHECK(p[static_cast<std::size_t>(d)] == (static_cast<double>(x) + 0.5) / 4294967296.0);
  }
  // The scramble is a bijection of [0, 2³²) that keeps the nets: a key changes the points.
  CHECK(scrambled_sobol_point(pixel_replicate_key(0, 0, 0), 3) !=
        scrambled_sobol_point(pixel_replicate_key(0, 0, 1), 3));
  CHECK(pixel_replicate_key(1, 0, 0) != pixel_replicate_key(0, 1, 0));
}

TEST_CASE("pixel pattern: a scrambled point is uniform over keys, its coordinates independent") {
  // Point 5 of 16384 replicates: per coordinate 16 bins (χ² with 15 degrees of freedom; 40 is
  // beyond its 99.95th percentile), and the correlation of the coordinates (standard deviation
  // 1/√n = 0.008: at most 0.04).
  const int n = 16384;
  std::array<std::array<int, 16>, 2> bins{};
  double sum_u = 0.0, sum_v = 0.0, sum_uv = 0.0;
  for (int r = 0; r < n; ++r) {
    const auto p = scrambled_sobol_point(pixel_replicate_key(3, 9, r), 5);
    for (std::size_t d = 0; d < 2; ++d) ++bins[d][static_cast<std::size_t>(p[d] * 16.0)];
    sum_u += p[0];
    sum_v += p[1];
    sum_uv += p[0] * p[1];
  }
  for (const auto& b : bins) {
    double chi2 = 0.0;
    for (const int c : b) chi2 += (c - n / 16.0) * (c - n / 16.0) / (n / 16.0);
    CHECK(chi2 < 40.0);
  }
  const double mu = sum_u / n, mv = sum_v / n;
  const double correlation = (sum_uv / n - mu * mv) * 12.0;  // each variance 1/12
  CHECK(std::fabs(mu - 0.5) < 0.01);
  CHECK(std::fabs(mv - 0.5) < 0.01);
  CHECK(std::fabs(correlation) < 0.04);
}

TEST_CASE("pixel pattern: a replicate's error falls faster than Monte Carlo's on a smooth pixel") {
  // ∫∫ e^u sin(πv) du dv = (e − 1)·2/π over [0,1)². The RMS error over 64 replicates at N = 16
  // and N = 1024 points: Monte Carlo's falls by √64 = 8, a scrambled net's by 64^(3/2) = 512
  // for a smooth integrand (Owen 1997); at least 64 (the rate of N^−1) is asked.
  const double exact = (std::exp(1.0) - 1.0) * 2.0 / 3.141592653589793;
  const auto rms = [&](std::uint32_t n) {
    double squares = 0.0;
    for (int r = 0; r < 64; ++r) {
      const std::uint64_t key = pixel_replicate_key(40, 2, r);
      double sum = 0.0;
      for (std::uint32_t i = 0; i < n; ++i) {
        const auto p = scrambled_sobol_point(key, i);
        sum += std::exp(p[0]) * std::sin(3.141592653589793 * p[1]);
      }
      squares += (sum / n - exact) * (sum / n - exact);
    }
    return std::sqrt(squares / 64.0);
  };
  const double coarse = rms(16), fine = rms(1024);
  MESSAGE("RMS error at N = 16: " << coarse << ", at N = 1024: " << fine << " (ratio "
                                  << coarse / fine << ")");
  CHECK(coarse / fine > 64.0);
}
